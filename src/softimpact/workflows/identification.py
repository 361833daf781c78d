"""A soft projectile's contact law identified from bar tests.

Input per test: the contact force history F(t) at the struck end (the output of
the record reduction: time from first contact, force [N]), the projectile's mass
m, diameter d and velocity V; and the bar as a :class:`~softimpact.fem.bar.Rod`
(Hermite rod, end-cap mass lumped at the struck end).

1. Approach. The impactor moves by momentum, m·ẍ = −F: ẋ = V − ∫F/m, x = ∫ẋ.
   The struck end's displacement u_end(t) comes from driving the same Hermite
   rod FE that produced the records with the measured force (Newmark, dt of the
   force samples): this includes the end cap and every reflection (for a
   non-dispersive bar with no cap it is u̇_end = (F(t) + 2·Σ_k F(t − 2kL/c))/(ρcA)).
   α = x − u_end, α̇ = ẋ − u̇_end.
2. Fit. ONE :class:`~softimpact.models.contact_laws.SoftProjectileLaw` for all
   tests, F = (mV²/d)·k·(α/d)^n·(1 + c·α̇/V), k = k_ref·(d/d_ref)^{q_k},
   c = c_ref·(d/d_ref)^{q_c}, optionally n = p·(d/d_ref)^{q_p} (else n = p; with
   one diameter the q's are 0): nonlinear least squares of F(α, α̇) against the
   measured F over each test's main pulse (until F falls to 15 % of F0 after
   the peak), residuals scaled by each test's F0 so every test weighs the same.
   95 % intervals from the Jacobian at the optimum, ±1.96·sqrt(diag(s²(JᵀJ)⁻¹)).
3. Closure. The identified law in a coupled impactor–bar simulation
   (:func:`softimpact.fem.impact.integrate_impact` on the same rod) gives a force
   history per test; F0 (peak), T (duration of the eq-15 fit of the main pulse, as
   in the reduction) and the impulse I (whole history) are compared with the
   measured ones.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..fem.bar import Rod, assemble_rod
from ..fem.impact import ContactStructure, integrate_impact
from ..fem.newmark import NewmarkStepper
from ..models.contact_laws import SoftProjectileLaw

__all__ = [
    "BarTest",
    "Approach",
    "IdentifiedLaw",
    "Closure",
    "reconstruct_approach",
    "identify",
    "closure",
    "pulse_figures",
    "refine",
    "PARAMETERS",
]

MAIN_PULSE_CUTOFF = 0.15  # the main pulse ends where F falls to this fraction of F0 (as in the reduction)
STEPS_PER_PULSE = 400  # closure simulation: steps per measured main-pulse duration
PARAMETERS = ("k_ref", "p", "c_ref", "q_k", "q_c", "q_p")  # the order of IdentifiedLaw.values
LOWER = np.array([1e-6, 0.2, 0.0, -5.0, -5.0, -5.0])  # bounds of the fits: k > 0, an exponent from 0.2 to 6,
UPPER = np.array([1e6, 6.0, 50.0, 5.0, 5.0, 5.0])  # a non-negative rate term, size powers within ±5
Z95 = 1.959963984540054  # two-sided 95 % normal quantile (hundreds of samples: t ≈ z)


@dataclass(frozen=True)
class BarTest:
    """One bar test: force history (time [s] from first contact, F [N]), m [kg], d [m], V [m/s]."""

    name: str
    time: np.ndarray
    force: np.ndarray
    mass: float
    diameter: float
    velocity: float

    def __post_init__(self):
        if np.shape(self.time) != np.shape(self.force) or np.ndim(self.time) != 1:
            raise InputError(f"test {self.name}: time and force must be 1-D arrays of one length")
        dt = np.diff(self.time)
        if not np.allclose(dt, dt[0], rtol=1e-6):
            raise InputError(f"test {self.name}: force samples must be evenly spaced")
        for k in ("mass", "diameter", "velocity"):
            if not getattr(self, k) > 0:
                raise InputError(f"test {self.name}: {k} must be positive, got {getattr(self, k)!r}")


@dataclass(frozen=True)
class Approach:
    """Reconstructed histories of one test, shape (n,): α, α̇, impactor x, ẋ, bar end u, u̇."""

    time: np.ndarray
    force: np.ndarray
    approach: np.ndarray
    rate: np.ndarray
    impactor_displacement: np.ndarray
    impactor_velocity: np.ndarray
    end_displacement: np.ndarray
    end_velocity: np.ndarray
    main_pulse: np.ndarray  # bool mask: the samples used in the fit


@dataclass(frozen=True)
class IdentifiedLaw:
    """Parameters (k_ref, p, c_ref, q_k, q_c) at d_ref, their 95 % half-widths, and fit quality."""

    names: tuple[str, ...]
    values: np.ndarray
    half_widths: np.ndarray
    d_ref: float
    rms_per_test: np.ndarray  # rms(F_model − F)/F0 over each main pulse
    cost: float

    def law(self, mass: float, diameter: float, velocity: float) -> SoftProjectileLaw:
        k, p, c, qk, qc, qp = _six(self.values)
        return SoftProjectileLaw.scaled(mass, diameter, velocity, k, p, c, self.d_ref, qk, qc, qp)


@dataclass(frozen=True)
class Closure:
    """Per test: measured and simulated F0 [N], T [s], I [N·s], and relative errors."""

    names: tuple[str, ...]
    measured: np.ndarray  # (n_tests, 3): F0, T, I
    simulated: np.ndarray  # (n_tests, 3)
    time: tuple[np.ndarray, ...]
    force: tuple[np.ndarray, ...]  # simulated histories

    @property
    def errors(self) -> np.ndarray:
        return self.simulated / self.measured - 1.0


def _end_response(rod: Rod, dt: float, force: np.ndarray):
    """u_end, u̇_end of the Hermite rod driven by ``force`` at its struck end."""
    model = assemble_rod(rod)
    st = NewmarkStepper(model.M, model.K, dt)
    f = np.zeros((model.n, force.size))
    f[model.end_dof] = force
    u, v, _ = st.run(f)
    return u[model.end_dof], v[model.end_dof]


def reconstruct_approach(test: BarTest, rod: Rod) -> Approach:
    """α(t) = x(t) − u_end(t) from the measured force (module docstring, step 1)."""
    t, F = np.asarray(test.time, float), np.asarray(test.force, float)
    dt = t[1] - t[0]
    # average acceleration on the impactor too: trapezoid for ẋ, and x from the mean of ẋ
    xv = test.velocity - np.concatenate(([0.0], np.cumsum(0.5 * (F[1:] + F[:-1])))) * dt / test.mass
    x = np.concatenate(([0.0], np.cumsum(0.5 * (xv[1:] + xv[:-1])))) * dt
    u, ud = _end_response(rod, dt, F)
    k_pk = int(np.argmax(F))
    F0 = F[k_pk]
    below = np.flatnonzero((np.arange(F.size) > k_pk) & (F < MAIN_PULSE_CUTOFF * F0))
    end = int(below[0]) if below.size else F.size
    mask = np.zeros(F.size, bool)
    mask[:end] = True
    return Approach(t, F, x - u, xv - ud, x, xv, u, ud, mask)


def _six(values) -> np.ndarray:
    """(k_ref, p, c_ref, q_k, q_c, q_p); a law of five parameters has q_p = 0."""
    v = np.zeros(6)
    v[: len(values)] = values
    return v


def _model_force(params, d_ref, approaches, tests):
    k, p, c, qk, qc, qp = _six(params)
    out = []
    for a, tst in zip(approaches, tests):
        s = tst.diameter / d_ref
        scale = tst.mass * tst.velocity**2 / tst.diameter
        al = np.maximum(a.approach[a.main_pulse], 0.0) / tst.diameter
        g = 1.0 + c * s**qc * a.rate[a.main_pulse] / tst.velocity
        out.append(np.maximum(scale * k * s**qk * al ** (p * s**qp) * g, 0.0))
    return out


def _free(tests, size_exponent: bool) -> list[int]:
    """Indices of the parameters a fit may move: with one diameter the q's stay 0."""
    if len({t.diameter for t in tests}) == 1:
        return [0, 1, 2]
    return [0, 1, 2, 3, 4, 5] if size_exponent else [0, 1, 2, 3, 4]


def identify(tests, rod: Rod, d_ref: float | None = None, size_exponent: bool = False) -> tuple[IdentifiedLaw, tuple[Approach, ...]]:
    """Fit one soft-projectile law to all tests (module docstring, step 2).

    ``size_exponent``: let the exponent p scale with the diameter too (q_p), so each
    diameter has three size-dependent shape parameters (k, p, c) for its three
    independent pulse figures (F0·d/(mV²), T·V/d, I/(mV)). Off by default: on the
    built-in rubber series it does not close the 3/8-in gap (measured: the 3/8-in
    tests alone, k, p, c all free, still close at T +4 %, I −4 to −6 %; the gap is
    the family's, see :func:`refine`).
    """
    from scipy.optimize import least_squares

    tests = tuple(tests)
    if len(tests) < 2:
        raise InputError("identify: need at least two tests")
    approaches = tuple(reconstruct_approach(t, rod) for t in tests)
    d_ref = d_ref or max(t.diameter for t in tests)
    F0s = [a.force.max() for a in approaches]
    meas = [a.force[a.main_pulse] for a in approaches]
    weights = [1.0 / (F0 * math.sqrt(m.size)) for F0, m in zip(F0s, meas)]
    free = _free(tests, size_exponent)

    def full(z):
        v = np.zeros(6)
        v[free] = z
        return v

    def residual(z):
        return np.concatenate([w * (f - m) for w, f, m in zip(weights, _model_force(full(z), d_ref, approaches, tests), meas)])

    z0 = np.array([2.0, 1.0, 1.0, 0.0, 0.0, 0.0])[free]
    sol = least_squares(residual, z0, bounds=(LOWER[free], UPPER[free]), x_scale="jac")
    J = sol.jac
    dof = max(sol.fun.size - sol.x.size, 1)
    # residuals carry weights 1/(F0·sqrt(n_i)): s² from the unweighted scale of the fit
    s2 = float(sol.fun @ sol.fun) / dof
    cov = s2 * np.linalg.pinv(J.T @ J)
    half = np.zeros(6)
    half[free] = Z95 * np.sqrt(np.maximum(np.diag(cov), 0.0))
    values = full(sol.x)
    fits = _model_force(values, d_ref, approaches, tests)
    rms = np.array([math.sqrt(np.mean((f - m) ** 2)) / F0 for f, m, F0 in zip(fits, meas, F0s)])
    law = IdentifiedLaw(PARAMETERS, values, half, d_ref, rms, float(sol.cost))
    return law, approaches


def pulse_figures(t: np.ndarray, F: np.ndarray) -> tuple[float, float, float]:
    """(F0, T, I): peak, duration of the eq-15 fit to the main pulse (until F falls to 15 % of F0
    after the peak), impulse of the whole history (trapezoid)."""
    from scipy.optimize import least_squares

    k_pk = int(np.argmax(F))
    F0, tF0 = float(F[k_pk]), float(t[k_pk])
    below = np.flatnonzero((np.arange(F.size) > k_pk) & (F < MAIN_PULSE_CUTOFF * F0))
    end = int(below[0]) if below.size else F.size - 1
    ts, Fs = t[: end + 1], F[: end + 1]
    T_guess = max(t[end] * 1.1, 2 * tF0)

    def residual(p):
        f0, tp, dur = p[0] * F0, p[1] * T_guess, p[2] * T_guess
        rise = f0 * np.sin(np.pi * ts / (2 * tp))
        fall = f0 * np.cos(np.pi * (ts - tp) / (2 * (dur - tp)))
        m = np.where(ts < tp, rise, np.where(ts < dur, fall, 0.0))
        return (m - Fs) / F0

    sol = least_squares(residual, [1.0, max(tF0 / T_guess, 1e-3), 1.0], bounds=([0.5, 1e-3, 0.2], [2.0, 0.95, 5.0]))
    I = float(np.sum(0.5 * (F[1:] + F[:-1])) * (t[1] - t[0]))
    return F0, float(sol.x[2] * T_guess), I


def _rod_structure(rod: Rod) -> ContactStructure:
    model = assemble_rod(rod)
    e = np.zeros(model.n)
    e[model.end_dof] = 1.0
    return ContactStructure(
        M=model.M,
        K=model.K,
        surface_x=np.array([0.0]),
        surface_dofs=np.array([model.end_dof]),
        load_sign=1.0,
        center=0.0,
        approach_row=e,
        outputs=np.zeros((0, model.n)),
    )


def closure(law: IdentifiedLaw, tests, rod: Rod, steps_per_pulse: int = STEPS_PER_PULSE) -> Closure:
    """Simulate each test with the identified law on the rod; compare F0, T, I (module docstring, step 3)."""
    structure = _rod_structure(rod)
    names, meas, sim, ts, fs = [], [], [], [], []
    for tst in tests:
        t, F = np.asarray(tst.time, float), np.asarray(tst.force, float)
        fig = pulse_figures(t, F)
        dt = fig[1] / steps_per_pulse
        steps = int(math.ceil(t[-1] / dt))
        h = integrate_impact(
            structure,
            law.law(tst.mass, tst.diameter, tst.velocity),
            tst.mass,
            tst.velocity,
            dt,
            steps,
            energy=False,
            stop_after=0.5 * fig[1],
        )
        names.append(tst.name)
        meas.append(fig)
        sim.append(pulse_figures(h.time, h.contact_force))
        ts.append(h.time)
        fs.append(h.contact_force)
    return Closure(tuple(names), np.array(meas), np.array(sim), tuple(ts), tuple(fs))


def refine(
    law: IdentifiedLaw,
    tests,
    rod: Rod,
    max_evaluations: int = 40,
    size_exponent: bool = False,
    steps_per_pulse: int = STEPS_PER_PULSE,
    bounded: bool = False,
) -> IdentifiedLaw:
    """Second stage: adjust the parameters so the coupled bar simulations reproduce each test's
    (F0, T, I) — least squares on the 3·n_tests relative errors, from the F(α, α̇) fit.

    Each evaluation runs every test once (closure); intervals from this Jacobian.
    ``bounded``: keep the parameters within LOWER–UPPER (always with the size
    exponent). Few tests leave the problem ill-conditioned and an unbounded step
    can make k negative; on all 13 rubber tests the unbounded path lands at a
    lower cost (max closure error 6.5 %, bounded 7.4 %, measured).

    What limits the closure on the built-in rubber series is the law family: the
    rate term cuts the force off during the rebound, so no slow low tail follows
    the main pulse, while the series' impulse carries one: 1 − 2F0T/(πI), the share
    of I beyond the eq-15 pulse, is 0–3 % for the 1/2-in tests and 4–11 % for the
    3/8-in ones (Table I's α4 against α1·α2), against −1 to −3 % for the law's pulses.
    The 1/2-in tests close within 2 %; the 3/8-in tests are left at T ≈ +4 %,
    I ≈ −4 % (−6.5 % on the noisiest). A memory element (viscoelastic recovery)
    would carry the tail.
    """
    from scipy.optimize import least_squares

    tests = tuple(tests)
    free = _free(tests, size_exponent)
    start = _six(law.values)

    def with_values(z):
        v = start.copy()
        v[free] = z
        return IdentifiedLaw(PARAMETERS, v, law.half_widths, law.d_ref, law.rms_per_test, law.cost)

    def residual(z):
        return closure(with_values(z), tests, rod, steps_per_pulse).errors.ravel()

    z0 = np.clip(start[free], LOWER[free], UPPER[free])
    bounds = (LOWER[free], UPPER[free]) if bounded or len(free) == 6 else (-np.inf, np.inf)
    sol = least_squares(residual, z0, bounds=bounds, diff_step=1e-3, max_nfev=max_evaluations, x_scale=np.maximum(np.abs(z0), 0.1))
    dof = max(sol.fun.size - sol.x.size, 1)
    cov = float(sol.fun @ sol.fun) / dof * np.linalg.pinv(sol.jac.T @ sol.jac)
    half = np.zeros(6)
    half[free] = Z95 * np.sqrt(np.maximum(np.diag(cov), 0.0))
    out = with_values(sol.x)
    return IdentifiedLaw(PARAMETERS, out.values, half, law.d_ref, law.rms_per_test, float(sol.cost))
