"""A 1.8-kg gelatin bird (153.5 mm, hydrodynamic law) on a single-degree-of-freedom target.

The coupled stepper's force on a spring-mass target against an independent integration of the same equations
(scipy's solve_ivp: m·Ẍ = −F(X − w, Ẋ − ẇ), m_p·ẅ + k·w = F), and its convergence with the time step. On this
target the coupling is smooth and converges; the step-to-step noise of the same bird on the 4-mm plate comes from
the plate's unresolved modes (undamped by the trapezoidal rule) read through the law's rate ṡ = α̇/φ, whose
sensitivity to the target's velocity grows as 1/φ = m/m_r at the end of the crush.
"""

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.integrate import solve_ivp

from softimpact.fem.impact import ContactStructure, integrate_impact
from softimpact.models.hydrodynamic_law import HydrodynamicLaw

MASS, DIAMETER, VELOCITY = 1.8, 0.1535, 150.0  # the 1.8-kg bird as a 153.5-mm sphere at 150 m/s [kg, m, m/s]
# The target: a plate's first mode stiffened to the 4-mm Al 2024-T3 plate's secant (about 20 mm under 400 kN);
# its period, 2π·sqrt(m_p/k) = 0.47 ms, is shorter than the crush (d/V = 1.0 ms): the target moves during it.
PLATE_MASS, PLATE_STIFFNESS = 0.11, 2.0e7  # [kg, N/m]
DURATION = 1.3e-3  # past the crush [s]
LAW = HydrodynamicLaw.of("gelatin", DIAMETER, MASS, VELOCITY)


def _target():
    """The spring-mass target as a one-DOF structure loaded at its only node."""
    return ContactStructure(
        M=sp.csr_matrix([[PLATE_MASS]]),
        K=sp.csr_matrix([[PLATE_STIFFNESS]]),
        surface_x=np.array([0.0]),
        surface_dofs=np.array([0]),
        load_sign=1.0,
        center=0.0,
        approach_row=np.array([1.0]),
        outputs=np.zeros((0, 1)),
    )


def _stepped(dt):
    """The package's coupled force history at the step ``dt`` [s]: (t, F)."""
    h = integrate_impact(_target(), LAW, MASS, VELOCITY, dt, int(round(DURATION / dt)))
    return np.asarray(h.time), np.asarray(h.force)


def _reference():
    """The same bird and target integrated by scipy (LSODA, rtol 1e-10) on a 0.1-µs grid: (t, F)."""

    def rhs(t, y):
        x, xd, w, wd = y
        f = LAW.force(x - w, xd - wd)
        return [xd, -f / MASS, wd, (f - PLATE_STIFFNESS * w) / PLATE_MASS]

    t = np.linspace(0.0, DURATION, 13001)
    sol = solve_ivp(rhs, (0.0, DURATION), [0.0, VELOCITY, 0.0, 0.0], method="LSODA", rtol=1e-10, atol=1e-13, t_eval=t, max_step=1e-6)
    assert sol.success
    return t, np.array([LAW.force(x - w, xd - wd) for x, xd, w, wd in sol.y.T])


@pytest.fixture(scope="module")
def reference():
    return _reference()


@pytest.mark.parametrize("dt", [2e-6, 1e-6])
def test_peak_against_solve_ivp(reference, dt):
    """The stepped peak force and its time agree with scipy's integration of the same equations (0.5 %, 2 steps)."""
    t_ref, f_ref = reference
    t, f = _stepped(dt)
    assert f.max() == pytest.approx(f_ref.max(), rel=5e-3)
    assert t[f.argmax()] == pytest.approx(t_ref[f_ref.argmax()], abs=2 * dt)


@pytest.mark.parametrize("dt", [2e-6, 1e-6])
def test_peak_converges_with_time_step(dt):
    """Halving the step moves the peak force by less than 0.5 %."""
    f1, f2 = _stepped(dt)[1], _stepped(dt / 2)[1]
    assert f1.max() == pytest.approx(f2.max(), rel=5e-3)


def test_force_history_has_no_step_to_step_noise(reference):
    """The stepped force's total variation is that of scipy's smooth history (one rise, one fall: 2·peak and the
    shock's spike), within 2 %: no period-2 oscillation."""
    t_ref, f_ref = reference
    f = _stepped(1e-6)[1]
    tv, tv_ref = np.abs(np.diff(f)).sum() / f.max(), np.abs(np.diff(f_ref)).sum() / f_ref.max()
    assert tv == pytest.approx(tv_ref, rel=0.02)


def test_impulse_is_the_momentum():
    """The impulse of the stepped force is the bird's momentum m·V to 1 % (all of it brought to rest on the target)."""
    t, f = _stepped(1e-6)
    assert np.trapezoid(f, t) == pytest.approx(MASS * VELOCITY, rel=1e-2)
