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


def test_the_resolved_force_raises_no_zigzag_flag():
    """On this target the stepped force is smooth (the tests above): the step-resolution check stays silent."""
    from softimpact.models.validity import force_step_validity

    assert force_step_validity(_stepped(2e-6)[1], 2e-6).flags == ()


@pytest.mark.slow  # two coupled runs of the plate, ~10 s of CPU each
def test_the_bird_on_the_elastic_plate_is_flagged_and_moves_with_the_step(tmp_path):
    """The same bird on the 4-mm aluminium quarter plate run elastic and linear (the issue's case): its force zigzags
    from step to step at 2 µs and still at 1 µs (flagged force_unresolved_in_time each time), and halving the step moves
    its peak by more than 1 % (measured 2.7 %: 287 to 295 kN), where the resolved spring-mass target's moves by less
    than 0.5 % (test_peak_converges_with_time_step): the flag says what the numbers show."""
    from softimpact.cases import KINDS
    from softimpact.input.impact_case import load_impact_case
    from softimpact.input.toml import builtin_cases

    plate = builtin_cases()["al-skin-4mm"].read_text()
    plate = plate.replace('kinematics = "von-karman"', 'kinematics = "linear"').replace('thickness = "4 mm"', 'thickness = "4 mm"\nplasticity = false')
    (tmp_path / "plate.toml").write_text(plate)
    bird = builtin_cases()["bird-al-skin"].read_text().replace('case = "al-skin-4mm"', 'case = "plate.toml"')
    peaks = []
    for step in ("2 us", "1 us"):
        path = tmp_path / f"bird-{step.split()[0]}.toml"
        path.write_text(bird.replace('time_step = "8 us"', f'time_step = "{step}"'))
        run = KINDS["impact"].execute(load_impact_case(path)[0])
        peaks.append(run.summary["peak_force_N"])
        names = run.summary["validity"]
        assert any("zigzags from step to step" in f for f in names["flags"])
    assert abs(peaks[1] / peaks[0] - 1.0) > 0.01
