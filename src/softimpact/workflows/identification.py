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
2. Fit. ONE law for all tests, by default with its Maxwell arm
   (:class:`~softimpact.models.contact_laws.ViscoelasticSoftLaw`):
   F = (mV²/d)·[k·(α/d)^n·(1 + c·α̇/V) + σ], σ̇ = κ·d(α⁺/d)/dt − σ·V/(θ·d),
   k = k_ref·(d/d_ref)^{q_k}, c = c_ref·(d/d_ref)^{q_c}, optionally n = p·(d/d_ref)^{q_p}
   (else n = p; with one diameter the q's are 0), κ = κ_ref·(d/d_ref)^{q_κ},
   θ = θ_ref·(d/d_ref)^{q_θ}, and c = 0 beside the arm (:func:`_free`)
   (``memory=False``: the memoryless family, κ = 0). σ along each test follows from
   the reconstructed α history (:func:`arm_stress`, the solver's own exact step).
   Nonlinear least squares of F(α, α̇, σ) against the measured F over each test's main
   pulse (until F falls to 15 % of F0 after the peak), residuals scaled by each test's
   F0 so every test weighs the same. 95 % intervals from the Jacobian at the optimum,
   ±1.96·sqrt(diag(s²(JᵀJ)⁻¹)). Then :func:`refine` adjusts the parameters on the
   coupled bar simulations themselves (F0, t_F0, T, I of every test).
   The crushing family of ice spheres (``family="crushing"`` of :func:`identify_series`) fits its
   strength law along the same approach instead (:mod:`._identification_crushing`: strength at a
   reference rate and rate exponent, delete-one-test jackknife intervals) and is not refined.
3. Closure. The identified law in a coupled impactor–bar simulation
   (:func:`softimpact.fem.impact.integrate_impact` on the same rod) gives a force
   history per test; F0 (peak), T (duration of the eq-15 fit of the main pulse, as
   in the reduction) and the impulse I (whole history) are compared with the
   measured ones.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import ClassVar

import numpy as np

from ..errors import InputError
from ..fem.bar import Rod, assemble_rod
from ..fem.contact import rod_contact_structure
from ..fem.impact import ContactStructure, integrate_impact
from ..models.pulse_fit import MAIN_PULSE_CUTOFF, fit_main_pulse
from ._identification_crushing import CRUSHING_PARAMETERS, CrushingIdentifiedLaw, identify_crushing  # the crushing family (ice)
from ._identification_fit import (  # steps 1 and 2: the approach and the F(α, α̇) fit
    CLOSURE_SCALE,
    LOWER,
    N_PARAMETERS,
    PARAMETERS,
    REFINE_NORM,
    REFINE_STEPS_PER_PULSE,
    STEPS_PER_PULSE,
    UPPER,
    Z95,
    Approach,
    BarTest,
    IdentifiedLaw,
    _embed,
    _free,
    _full,
    _on_bounds,
    arm_stress,
    fitted_force,
    identify,
    reconstruct_approach,
    unfixed_parameters,
)

__all__ = [
    "BarTest",
    "Approach",
    "IdentifiedLaw",
    "Closure",
    "reconstruct_approach",
    "identify",
    "closure",
    "pulse_figures",
    "pulse_shape",
    "fitted_force",
    "representatives",
    "refine",
    "PARAMETERS",
    "arm_stress",
    "CRUSHING_PARAMETERS",
    "CrushingIdentifiedLaw",
    "identify_crushing",
    "LAW_FAMILIES",
]

LAW_FAMILIES = ("soft", "crushing")  # what identify fits: the visco-elastic soft law, or the crushing law of ice


@dataclass(frozen=True)
class Closure:
    """Per test: measured and simulated F0 [N], T [s], I [N·s], and relative errors."""

    names: tuple[str, ...]
    measured: np.ndarray  # (n_tests, 3): F0, T, I
    simulated: np.ndarray  # (n_tests, 3)
    time: tuple[np.ndarray, ...]
    force: tuple[np.ndarray, ...]  # simulated histories
    peak_times: np.ndarray | None = None  # (n_tests, 2): measured, simulated t_F0 of the eq-15 fits [s]

    @property
    def errors(self) -> np.ndarray:
        return self.simulated / self.measured - 1.0

    @property
    def peak_time_errors(self) -> np.ndarray:
        """Relative error of the simulated t_F0, (n_tests,)."""
        return self.peak_times[:, 1] / self.peak_times[:, 0] - 1.0


def pulse_figures(t: np.ndarray, F: np.ndarray) -> tuple[float, float, float]:
    """(F0, T, I): peak, duration of the eq-15 fit to the main pulse (as in the reduction), impulse of
    the whole history (trapezoid)."""
    F0, _, T, I = pulse_shape(t, F)
    return F0, T, I


def pulse_shape(t: np.ndarray, F: np.ndarray) -> tuple[float, float, float, float]:
    """(F0, t_F0, T, I) as :func:`pulse_figures`: F0 the largest sample; t_F0 and T of the reduction's
    own main-pulse fit (:func:`~softimpact.models.pulse_fit.fit_main_pulse`, cutoff MAIN_PULSE_CUTOFF),
    so a pulse has the same T here as in ``reduce``."""
    fit = fit_main_pulse(t, F, cutoff=MAIN_PULSE_CUTOFF).fit.pulse
    I = float(np.sum(0.5 * (F[1:] + F[:-1])) * (t[1] - t[0]))
    return float(np.max(F)), fit.time_of_peak, fit.duration, I


def _rod_structure(rod: Rod) -> ContactStructure:
    """The rod struck at its end, no outputs (:func:`softimpact.fem.contact.rod_contact_structure`)."""
    return rod_contact_structure(assemble_rod(rod))


def _simulate(law: IdentifiedLaw, tst: BarTest, structure: ContactStructure, steps_per_pulse: int, duration: float):
    """The coupled history of one test simulated with ``law`` on the rod, steps of duration/steps_per_pulse
    (``duration``: the test's measured T)."""
    t = np.asarray(tst.time, float)
    dt = duration / steps_per_pulse
    return integrate_impact(
        structure,
        law.law(tst.mass, tst.diameter, tst.velocity),
        tst.mass,
        tst.velocity,
        dt,
        int(math.ceil(t[-1] / dt)),
        energy=False,
        stop_after=0.5 * duration,
    )


def closure(law: IdentifiedLaw, tests, rod: Rod, steps_per_pulse: int = STEPS_PER_PULSE) -> Closure:
    """Simulate each test with the identified law on the rod; compare F0, T, I and t_F0 (module docstring, step 3)."""
    structure = _rod_structure(rod)
    names, meas, sim, ts, fs = [], [], [], [], []
    for tst in tests:
        measured = pulse_shape(np.asarray(tst.time, float), np.asarray(tst.force, float))
        h = _simulate(law, tst, structure, steps_per_pulse, measured[2])
        names.append(tst.name)
        meas.append(measured)
        sim.append(pulse_shape(h.time, h.force))
        ts.append(h.time)
        fs.append(h.force)
    meas, sim = np.array(meas), np.array(sim)
    three = [0, 2, 3]  # F0, T, I of (F0, t_F0, T, I)
    return Closure(tuple(names), meas[:, three], sim[:, three], tuple(ts), tuple(fs), np.column_stack((meas[:, 1], sim[:, 1])))


def _scaled_shape(shape, test: BarTest) -> np.ndarray:
    """(F0, t_F0, T, I) in the law's scaling: F0·d/(mV²), t_F0·V/d, T·V/d, I/(mV) (Table I's α1/2, α2·α3, α2, 2·α4)."""
    m, d, V = test.mass, test.diameter, test.velocity
    return np.array([shape[0] * d / (m * V * V), shape[1] * V / d, shape[2] * V / d, shape[3] / (m * V)])


def representatives(tests) -> dict[float, int]:
    """Diameter → index of the test at the median velocity of that diameter's tests."""
    groups: dict[float, list[int]] = {}
    for i, t in enumerate(tests):
        groups.setdefault(t.diameter, []).append(i)
    return {d: sorted(ix, key=lambda i: tests[i].velocity)[len(ix) // 2] for d, ix in groups.items()}


class _Errors:
    """The refinement's residuals: for free parameters z, the relative errors of every test's scaled
    (F0, t_F0, T, I) against the coupled bar run of its diameter's representative (:func:`refine`).

    Evaluations are kept by z: the stages and the final Jacobian revisit points.
    """

    def __init__(self, law: IdentifiedLaw, tests: tuple, rod: Rod, free: list[int], steps_per_pulse: int):
        self.law, self.tests, self.free, self.steps_per_pulse = law, tests, free, steps_per_pulse
        self.start = _full(law.values)
        self.reps = representatives(tests)
        self.structure = _rod_structure(rod)
        self.shapes = [pulse_shape(t.time, t.force) for t in tests]
        self.measured = np.array([_scaled_shape(sh, t) for sh, t in zip(self.shapes, tests)])
        self.group = np.array([list(self.reps).index(t.diameter) for t in tests])
        self.known: dict[bytes, np.ndarray] = {}

    def with_values(self, z) -> IdentifiedLaw:
        """The law with its free parameters set to z."""
        law = self.law
        v = self.start.copy()
        v[self.free] = z
        return IdentifiedLaw(PARAMETERS, v, law.half_widths, law.d_ref, law.rms_per_test, law.cost, law.identified_on)

    def __call__(self, z) -> np.ndarray:
        key = np.asarray(z, float).tobytes()
        if key not in self.known:
            trial = self.with_values(z)
            tests, shapes = self.tests, self.shapes
            runs = [(tests[i], _simulate(trial, tests[i], self.structure, self.steps_per_pulse, shapes[i][2])) for i in self.reps.values()]
            sim = np.array([_scaled_shape(pulse_shape(h.time, h.force), t) for t, h in runs])
            self.known[key] = (sim[self.group] / self.measured - 1.0).ravel()
        return self.known[key].copy()

    def high_norm(self, z) -> np.ndarray:
        """Residuals whose sum of squares is Σ r^REFINE_NORM (scaled by the closure target)."""
        r = self(z)
        return r * (np.abs(r) / CLOSURE_SCALE) ** (REFINE_NORM / 2 - 1)


def _covariance(errors: _Errors, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The free parameters' covariance s²·(JᵀJ)⁺ at the optimum x, and the errors there.

    From the errors themselves (their Jacobian by forward differences, one
    evaluation per parameter), not from the Σr⁸ objective, whose Jacobian
    vanishes with the errors.
    """
    r = errors(x)
    J = np.empty((r.size, x.size))
    for j in range(x.size):
        h = 1e-3 * max(abs(x[j]), 0.1)
        z = x.copy()
        z[j] += h
        J[:, j] = (errors(z) - r) / h
    dof = max(r.size - x.size, 1)
    return float(r @ r) / dof * np.linalg.pinv(J.T @ J), r


def refine(
    law: IdentifiedLaw,
    tests,
    rod: Rod,
    max_evaluations: int = 40,
    size_exponent: bool = False,
    steps_per_pulse: int = REFINE_STEPS_PER_PULSE,
    bounded: bool = True,
) -> IdentifiedLaw:
    """Second stage: adjust the parameters so the coupled bar simulations reproduce each test's
    pulse — F0, the time of peak t_F0 and the duration T of its eq-15 fit, and the impulse I —
    from the F(α, α̇) fit.

    Cheap by the law's scaling: on a rigid target the pulse in F·d/(mV²) against t·V/d is the same
    at every velocity of one diameter, so each evaluation runs the coupled bar simulation of ONE test
    per diameter (the median velocity, :func:`representatives`) and compares its scaled figures
    with every test of that diameter (the bar's compliance breaks the similarity by < 0.3 % here:
    the closure runs every test), at ``steps_per_pulse`` = 200 (the figures move by < 1e-4 against
    the closure's 400). Least squares on the 4·n_tests relative errors r, then Σr⁸ from there: the
    closure target is a bound per test (5 %), and Σr⁸ is close to the worst test's error. t_F0 is
    among the figures because F0, T and I alone leave the pulse's skew free: without it the
    refinement met them with a peak 35–55 % late on the 3/8-in tests (measured), which the beams
    then inherit. Intervals from the errors' Jacobian at the optimum; ``cost`` = ½Σr². ``bounded``: keep the parameters
    within LOWER–UPPER.

    What limits the closure on the built-in rubber series is kinematic: the series' slow tail
    (Table I's α4 against α1·α2: 0–3 % of the impulse for the 1/2-in tests, 4–11 % for the 3/8-in
    ones) runs on after the ball has left the bar — the reconstructed approach α is negative — for
    1–2 % (1/2 in) and 7.5–11 % (3/8 in) of the impulse, which no contact law (F = 0 at α ≤ 0)
    can carry. The memoryless family cuts the force off during the rebound (its rate term) and
    closes the 3/8-in tests at T +5 %, I −4 to −7 %; with the Maxwell arm the force falls fast
    and then lingers while α > 0, and every test closes within 5 % (F0 4.1 %, T 3.3 %, I 3.9 %,
    t_F0 2.8 % at worst, measured).
    """
    from scipy.optimize import least_squares

    tests = tuple(tests)
    free = _free(tests, size_exponent, law.has_memory)
    errors = _Errors(law, tests, rod, free, steps_per_pulse)
    z = np.clip(errors.start[free], LOWER[free], UPPER[free])
    bounds = (LOWER[free], UPPER[free]) if bounded else (-np.inf, np.inf)
    # Σr² first (its Jacobian does not vanish where the errors do: it gets there from a rough start),
    # then Σr⁸ from there
    for fun in (errors, errors.high_norm):
        sol = least_squares(fun, z, bounds=bounds, diff_step=1e-3, max_nfev=max_evaluations, x_scale=np.maximum(np.abs(z), 0.1))
        z = sol.x
    cov, r = _covariance(errors, sol.x)
    half = np.zeros(N_PARAMETERS)
    half[free] = Z95 * np.sqrt(np.maximum(np.diag(cov), 0.0))
    out = errors.with_values(sol.x)
    at_bounds = _on_bounds(out.values, free) if bounded else ()
    return IdentifiedLaw(PARAMETERS, out.values, half, law.d_ref, law.rms_per_test, 0.5 * float(r @ r), law.identified_on, _embed(cov, free), at_bounds)


# --- a reduced bar series as identification tests (reduce → identify → refine → closure) ------------

__all__ += ["bar_tests", "identify_series"]


def bar_tests(reduced) -> list[BarTest]:
    """The reduced tests of a series (:class:`softimpact.studies.series.ReducedTest`, read
    duck-typed) as BarTests: force [N] from first contact up to where the record holds it
    (``valid_until``), resampled evenly at the reduction's own (median) step; tests that
    could not be reduced are skipped (InputError when fewer than two remain)."""
    out = []
    for r in reduced:
        if r.reduction is None:
            continue
        red = r.reduction
        dt = float(np.median(np.diff(red.time)))
        t = np.arange(0.0, min(red.valid_until, red.time[-1]) + 0.5 * dt, dt)
        t = t[t <= red.time[-1]]
        out.append(BarTest(r.test.name, t, np.interp(t, red.time, red.force), r.test.mass, r.test.diameter, r.test.velocity))
    if len(out) < 2:
        raise InputError("identify: need at least two reduced tests")
    return out


def _silent(done: int, total: int, label: str) -> None:
    """The default progress callback: silent."""


def identify_series(rod: Rod, reduced, refined: bool = True, progress=_silent, family: str = "soft"):
    """Fit the law on the reconstructed F(α, α̇) of the reduced tests on the bar ``rod``, refine it
    on the coupled bar simulations (:func:`refine`; one run per diameter per evaluation, 200 steps
    per pulse), run the :func:`closure` on every test. ``progress(done, total, label)``.
    ``family`` (:data:`LAW_FAMILIES`): "soft", the visco-elastic soft law, or "crushing", an ice sphere's
    crushing strength law (:func:`identify_crushing`: memoryless and exact along the reconstructed
    approach, so not refined). Returns (tests, law, approaches, closure)."""
    if family not in LAW_FAMILIES:
        raise InputError(f"identify: law family must be one of {', '.join(LAW_FAMILIES)}, got {family!r}", "law")
    tests = bar_tests(reduced)
    progress(0, 3, "fitting F(alpha)")
    if family == "crushing":
        law, approaches = identify_crushing(tests, rod)
        refined = False
    else:
        law, approaches = identify(tests, rod)
    if refined:
        progress(1, 3, "refining on coupled bar runs")
        law = refine(law, tests, rod)
        approaches = tuple(replace(a, fitted_force=fitted_force(law, a, t)) for a, t in zip(approaches, tests))  # the refined law's
    progress(2, 3, "closure")
    cl = closure(law, tests, rod)
    progress(3, 3, "closure")
    # the law's envelope is what it was identified on: with its tests' velocities and diameters, the range of their largest
    # approach over diameter (models.validity.identified_contact_validity checks a run's against it)
    reached = [float(np.max(a.approach[a.main_pulse] if np.any(a.main_pulse) else a.approach)) / t.diameter for a, t in zip(approaches, tests)]
    law = replace(law, identified_on={**(law.identified_on or {}), "approach_over_diameter": [min(reached), max(reached)]})
    return tests, law, approaches, cl


# --- what the data fix: predictive intervals of the pulse, not parameters ± -----------------------

__all__ += ["FIGURES", "PredictedPulse", "unfixed_parameters", "predict_pulses"]

FIGURES = ("peak_force_N", "time_of_peak_s", "duration_s", "impulse_N_s")  # the order of PredictedPulse's arrays


@dataclass(frozen=True)
class PredictedPulse:
    """The pulse the identified law predicts on the bar for one impact (m [kg], d [m], V [m/s]).

    ``values`` (4,): F0 [N], t_F0 [s], T [s], I [N·s] (:data:`FIGURES`; as :func:`pulse_shape`).
    ``half_widths`` (4,): 95 % predictive half-widths, Z95·sqrt(gᵀCg + (s·y)²): g the figure's
    gradient in the free parameters (forward differences at the diameter's median tested
    velocity, relative, carried to every velocity of that diameter: the law's scaling), C their
    covariance, s the RMS relative closure error of that figure over the tests (what the law
    cannot reproduce). ``parameter_half_widths``: the gᵀCg part alone. ``tested``: a (d, V) of the
    tests, not an extrapolation.
    """

    mass: float
    diameter: float
    velocity: float
    tested: bool
    values: np.ndarray
    half_widths: np.ndarray
    parameter_half_widths: np.ndarray
    figures: ClassVar[tuple[str, ...]] = FIGURES  # what ``values`` and the half-widths hold, in order


def _point_test(tests, mass: float, diameter: float, velocity: float) -> tuple[BarTest, float]:
    """A stand-in BarTest for an impact (only m, d, V and the horizon are read) and the expected T:
    the nearest tested diameter's median test, scaled by the law's d/V."""
    ref = min(tests, key=lambda t: (abs(t.diameter - diameter), abs(t.velocity - velocity)))
    scale = (diameter / ref.diameter) * (ref.velocity / velocity)
    T = pulse_shape(np.asarray(ref.time, float), np.asarray(ref.force, float))[2] * scale
    horizon = float(ref.time[-1]) * scale
    return BarTest("point", np.array([0.0, horizon]), np.zeros(2), mass, diameter, velocity), T


def _figures(law, test, structure, steps, T) -> np.ndarray:
    h = _simulate(law, test, structure, steps, T)
    F0, tp, Td, I = pulse_shape(h.time, h.force)
    return np.array([F0, tp, Td, I])


def predict_pulses(
    law: IdentifiedLaw, tests, rod: Rod, closure: Closure, points=(), steps_per_pulse: int = REFINE_STEPS_PER_PULSE
) -> tuple[PredictedPulse, ...]:
    """F0, t_F0, T, I with 95 % predictive intervals (:class:`PredictedPulse`) at every tested
    (m, d, V) and at the requested ``points`` ((mass [kg], diameter [m], velocity [m/s]), ...).
    One coupled bar run per point, plus one per free parameter per diameter for the gradient."""
    tests = tuple(tests)
    structure = _rod_structure(rod)
    C = law.covariance if law.covariance is not None else np.diag((law.half_widths / Z95) ** 2)
    free = [i for i in range(len(law.values)) if C[i, i] > 0]
    Cf = C[np.ix_(free, free)]
    # what the law cannot reproduce, per figure: RMS relative closure error (F0, t_F0, T, I)
    e = closure.errors
    tp_err = closure.peak_time_errors if closure.peak_times is not None else np.zeros(len(closure.names))
    misfit = np.sqrt(np.mean(np.column_stack((e[:, 0], tp_err, e[:, 1], e[:, 2])) ** 2, axis=0))
    tested = [(t.mass, t.diameter, t.velocity, True) for t in tests]
    wanted = tested + [(float(m), float(d), float(V), False) for m, d, V in points]
    gradients: dict[float, np.ndarray] = {}
    out = []
    for m, d, V, is_test in wanted:
        stand_in, T = _point_test(tests, m, d, V)
        y = _figures(law, stand_in, structure, steps_per_pulse, T)
        if d not in gradients:
            # relative gradient at the diameter's median tested velocity (or at this point for a new diameter)
            same = sorted((t for t in tests if t.diameter == d), key=lambda t: t.velocity)
            at, T_at = (_point_test(tests, same[len(same) // 2].mass, d, same[len(same) // 2].velocity)) if same else (stand_in, T)
            y0 = _figures(law, at, structure, steps_per_pulse, T_at)
            G = np.empty((4, len(free)))
            for k, i in enumerate(free):
                step = 1e-3 * max(abs(law.values[i]), 0.1)
                v = law.values.copy()
                v[i] += step
                G[:, k] = (_figures(replace(law, values=v), at, structure, steps_per_pulse, T_at) / y0 - 1.0) / step
            gradients[d] = G
        G = gradients[d]
        rel_par = np.sqrt(np.maximum(np.einsum("ik,kl,il->i", G, Cf, G), 0.0))
        par = Z95 * rel_par * np.abs(y)
        total = Z95 * np.sqrt(rel_par**2 + misfit**2) * np.abs(y)
        out.append(PredictedPulse(m, d, V, is_test, y, total, par))
    return tuple(out)
