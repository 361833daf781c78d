"""Calibration of a beam's force history on models whose discretisation error is checked
(paper "Impact force history", steps 1–3; Tables II, III; Figs 21–25).

The calibration itself is :mod:`softimpact.workflows.calibration`; this module composes it with
the beam model (:mod:`softimpact.workflows.beam_impact`), its refinements
(:mod:`softimpact.workflows.refinement`), Richardson extrapolation of the calibrated parameters
(:mod:`softimpact.workflows.convergence`) and the scaling fit of a series' calibrated histories
(:mod:`softimpact.workflows.scaling`): a ladder of models refined within a time budget, every
test of a series calibrated on it, and the quality gates of the answers.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from ..errors import InputError
from ..gates import Gate, at_most, passed_if, pulse_skew
from ..input.records import read_strains
from ..input.scaling_constants import start_pulse
from ..models.empirical import PROJECTILES
from ..workflows.beam_impact import BeamModel
from ..workflows.calibration import MAIN, Calibration, Measured, calibrate, calibrate_checked
from ..workflows.convergence import MIN_RISE_STEPS, ROUNDOFF, richardson
from ..workflows.refinement import coarsen_beam, refine_beam
from ..workflows.scaling import ScalingFit, TestPoint, fit_groups

__all__ = [
    "DEFAULT_BUDGET",
    "SOLVE_RATE",
    "MAX_RESIDUAL_TO_NOISE",
    "CalibratedTest",
    "ModelLadder",
    "calibration_model",
    "discretisation_uncertainty",
    "parameter_convergence",
    "with_parameter_convergence",
    "calibrate_tests",
    "calibration_gates",
    "scaling_points",
    "series_fits",
]

DEFAULT_BUDGET = 20.0  # s: what refining the calibration model may cost (building the refined response engines)
# flop/s of banded back-substitutions assumed in cost predictions: conservative for one core
# (the standard machine does about 5.7e9 on the beam meshes).
SOLVE_RATE = 2e9
MAX_RESIDUAL_TO_NOISE = 2.0  # RMS residual / noise σ at any gauge: above, the model does not describe the record


def _silent(done: int, total: int, label: str) -> None:
    """The default progress callback: silent."""


@dataclass(frozen=True)
class CalibratedTest:
    """A calibration test with its result (and the deconvolved history beside it), or its error."""

    test: object  # softimpact.input.series.CalibrationTest
    calibration: Calibration | None
    deconvolved: Calibration | None = None
    error: str = ""


class ModelLadder:
    """The case's beam model (level 0) and its refinements by ``ratio``^k, each built on
    first use and kept, with a contact patch that covers every r0 to be used.

    :meth:`affordable` is the highest level whose response engine the time budget
    allows (:meth:`engine_seconds`).
    """

    def __init__(self, problem, radii, fit_radius: bool = False, ratio: int = 2):
        reach = max(radii) * (1.5 if fit_radius else 1.0)
        x, L = problem.load.position, problem.beam.length
        self.problem, self.ratio, self.reach = problem, ratio, min(reach, x, L - x)
        self.models: dict[int, BeamModel] = {}

    def __call__(self, level: int) -> BeamModel:
        """Level ``level``: refined by ratio^level (coarsened for a negative level, when the
        element counts divide; InputError otherwise)."""
        if level not in self.models:
            if level < 0:
                problem = coarsen_beam(self.problem, self.ratio**-level)
            else:
                problem = self.problem if level == 0 else refine_beam(self.problem, self.ratio**level)
            self.models[level] = BeamModel(problem, patch_radius=self.reach, outputs="strain")
        return self.models[level]

    def one_factor(self, level: int) -> tuple[BeamModel, BeamModel]:
        """Level ``level`` with its mesh only, and with its time step only, refined by ``ratio``
        (the one-factor refinements that tell whether mesh and step errors cancel along the ladder)."""
        key = ("one-factor", level)
        if key not in self.models:
            base = self(level).problem
            self.models[key] = tuple(
                BeamModel(refine_beam(base, self.ratio, space=space, time=not space), patch_radius=self.reach, outputs="strain") for space in (True, False)
            )
        return self.models[key]

    def engine_seconds(self, level: int) -> float:
        """Predicted cost of level's response engine [s]: its back-substitutions (steps × gauges)
        at SOLVE_RATE; a level above 0 scales level 0's by ratio⁴ (DOFs ratio², band ratio,
        steps ratio). A prediction from the problem's size, not a timing, so that the choice
        of model does not depend on what else the machine is running."""
        m = self(0)
        work = m.stepper.solve_flops() * m.steps * len(m.problem.gauges)
        return work * self.ratio ** (4 * level) / SOLVE_RATE

    def affordable(self, budget: float) -> int:
        """The highest level whose engine fits in ``budget`` seconds (at least 0, at most 3)."""
        level = 0
        while level < 3 and self.engine_seconds(level + 1) <= budget:
            level += 1
        return level

    def finest(self) -> BeamModel:
        """The finest level built so far."""
        return self(max((k for k in self.models if isinstance(k, int) and k >= 0), default=0))

    def describe(self, level: int) -> dict:
        """Mesh and step of a level (SI)."""
        b, s = self(level).problem.beam, self(level).problem.solver
        return {"level": level, "factor": self.ratio**level, "elements": [b.nx, b.nz], "time_step_s": s.time_step}


def calibration_model(problem, radii, fit_radius: bool) -> ModelLadder:
    """The ladder of calibration models for a case (level 0: its own mesh)."""
    return ModelLadder(problem, radii, fit_radius)


def discretisation_uncertainty(conv, name: str, rise_steps: float) -> float:
    """The standard uncertainty (k = 1) of a calibrated parameter's discretisation error at the finest
    level, from its convergence over three levels f1, f2, f3 (coarse → fine; ``conv``: :func:`richardson`'s
    record; ``rise_steps``: time steps of the coarsest level in the pulse rise t_F0).

    The Richardson estimate of the error is taken as one standard uncertainty:

    - monotone ("asymptotic" or not): |f3 − f_ext|, f_ext extrapolated at the order ``richardson`` used
      (the observed one when asymptotic, at most the formal one otherwise);
    - alternating: |f3 − f2| (the limit lies between the two finest levels; ``converge`` reports
      half the range of all three, which the first level's larger change dominates);
    - for t_F0 when the coarsest level resolves the rise with fewer than MIN_RISE_STEPS steps (or the
      rise is unknown): at least |f3 − f2| (the observed order is then not the fine levels' own:
      the first-order bound is kept). F0 and T describe the whole pulse, not its rise;
    - diverging: the whole range of the three levels (at least the last change);
    - "converged to round-off": 0 only when f1, f2 and f3 all agree to round-off; two finest levels that
      agree exactly after a larger first change (a fit stuck, e.g. on a bound) keep |f2 − f1|;
    - not finite (a level without a value): NaN.

    The GCI (Fs·estimate, Fs = 1.25 or 3 by the asymptotic rule) stays the reported conservative bound;
    this uncertainty is the one combined with the noise's, and its coverage is measured in
    benchmarks/bench_coverage.py (BENCHMARKS.md)."""
    v = np.asarray(conv.values, float)[-3:]
    if not np.all(np.isfinite(v)) or conv.status == "undefined":
        return math.nan
    last, first = abs(float(v[-1] - v[-2])), abs(float(v[-2] - v[0]))
    if conv.status == "converged to round-off":
        return 0.0 if first <= ROUNDOFF * max(abs(float(v[-1])), 1e-300) else first
    if conv.status == "oscillatory":
        return last
    if conv.status in ("asymptotic", "monotone", "two levels"):
        estimate = abs(float(v[-1] - conv.extrapolated))
        if name == "time_of_peak" and not rise_steps >= MIN_RISE_STEPS:  # NaN: unknown, kept conservative
            return max(estimate, last)
        return estimate
    return float(np.max(v) - np.min(v))  # diverging


def _gci(conv) -> float:
    """The GCI of the finest level in the parameter's units (Fs·|f3 − f_ext|, half the range × Fs when
    alternating); NaN where ``richardson`` gives none (diverging)."""
    return float(conv.gci_fine * abs(float(conv.values[-1]))) if math.isfinite(conv.gci_fine) else math.nan


def parameter_convergence(models: ModelLadder, measured, start, cal, contact_time, fit_radius) -> dict:
    """How the calibrated parameters themselves converge: the least-squares fits on the level
    used and the two below it (those the check made are reused; cheap engines: the data, and so
    the noise, are the same in all three fits, so their differences are discretisation), then
    Richardson on each parameter (workflows/convergence), with the fits on the coarsest of the
    three refined in mesh only and in time step only, and the steps of its time grid in the
    rise t_F0 fitted on the finest level: the same rule of the asymptotic range as ``converge`` (Fs = 1.25 only when
    the order is near 2, the one-factor refinements agree in sign and the rise has ≥ 10 steps;
    Fs = 3 otherwise). Returns name → (standard uncertainty of the value at the level used
    (:func:`discretisation_uncertainty`), the convergence record); {} when fewer than three levels exist."""
    level = cal.check.level
    ladder = (level - 2, level - 1, level) if level >= 1 else (-2, -1, 0)
    if math.isfinite(cal.check.contact_time):  # the check's first contact: every fit sees the same samples
        contact_time = cal.check.contact_time
    fits = dict(cal.check.level_fits)
    fits[level] = tuple(getattr(cal, n) for n in MAIN)
    for k in ladder:
        if k in fits:
            continue
        try:
            c = calibrate(models(k), measured, cal.pulse, "least-squares", contact_time=contact_time, radius=cal.contact_radius, fit_radius=fit_radius)
        except InputError:  # a mesh that cannot be coarsened, or a level too coarse to fit
            return {}
        fits[k] = tuple(getattr(c, n) for n in MAIN)
    sides = []
    for m in models.one_factor(ladder[0]):
        try:
            c = calibrate(m, measured, cal.pulse, "least-squares", contact_time=contact_time, radius=cal.contact_radius, fit_radius=fit_radius)
        except InputError:
            sides = []
            break
        sides.append(tuple(getattr(c, n) for n in MAIN))
    # the rise as the finest fit sees it (a coarse level's own t_F0 is inflated by its error), in the coarsest level's steps
    rise_steps = fits[ladder[-1]][1] / models(ladder[0]).problem.solver.time_step
    out = {}
    for i, name in enumerate(MAIN):
        values = [fits[k][i] for k in ladder]
        space, time = (sides[0][i], sides[1][i]) if sides else (None, None)
        conv = richardson(values, float(models.ratio), 2.0, name, space=space, time=time, rise_steps=rise_steps)
        out[name] = (discretisation_uncertainty(conv, name, rise_steps), conv)
    return out


def with_parameter_convergence(models, measured, start, cal, contact_time, fit_radius):
    """The calibration with its standard errors those of the noise and of the parameters' own
    discretisation error together, √(SE_noise² + u²) (:func:`parameter_convergence`; they replace the
    check's estimate, which rests on an assumed order); unchanged when fewer than three levels exist."""
    conv = parameter_convergence(models, measured, start, cal, contact_time, fit_radius)
    if not conv:
        return cal
    se = dict(cal.standard_errors)
    noise = cal.check.noise_errors
    for name, (u, _) in conv.items():
        if name in se and name in noise:
            se[name] = math.hypot(noise[name], u)
    check = replace(
        cal.check,
        parameter_orders={name: c.order for name, (_, c) in conv.items()},
        parameter_uncertainty_95={name: 1.96 * u for name, (u, _) in conv.items()},
        parameter_gci={name: _gci(c) for name, (_, c) in conv.items()},
        parameter_levels={name: [float(x) for x in c.values] for name, (_, c) in conv.items()},
        parameter_status={name: c.status for name, (_, c) in conv.items()},
        parameter_safety={name: c.safety_factor for name, (_, c) in conv.items()},
    )
    return replace(cal, standard_errors=se, check=check)


def calibrate_tests(
    models: ModelLadder,
    tests,
    projectile,
    constants,
    method,
    fit_radius=False,
    deconvolve=True,
    budget: float = DEFAULT_BUDGET,
    progress: Callable[[int, int, str], None] = _silent,
    units: str = "in-lbf-s",
) -> list[CalibratedTest]:
    """Calibrate each test on a model whose discretisation error is checked (and refined within
    ``budget`` seconds); a bad test (unreadable record, velocity out of the constants' range, no
    fit) is reported and the others go on (``units``: the display system of those reports)."""
    out = []
    problem = models.problem
    max_level = models.affordable(budget)
    for i, test in enumerate(tests):
        try:
            start = start_pulse(projectile, constants, test.velocity, units)
            t, strains = read_strains(test.measured)
            measured = Measured(test.measured.name, t, strains)
            r0 = test.contact_radius or problem.load.contact_radius
            cal = calibrate_checked(
                models,
                measured,
                start,
                method,
                max_level=max_level,
                contact_time=test.contact_time,
                radius=r0,
                fit_radius=fit_radius,
                progress=lambda label, i=i, name=test.name: progress(i, len(tests), f"{name}: {label}"),
            )
            if method == "least-squares":
                cal = with_parameter_convergence(models, measured, start, cal, test.contact_time, fit_radius)
            dec = None
            if deconvolve and method != "deconvolve":
                dec = calibrate(
                    models(cal.check.level),
                    measured,
                    start,
                    "deconvolve",
                    contact_time=cal.prepared.contact_time,
                    radius=r0,
                    error_to_noise=cal.check.error_to_noise,
                )
            out.append(CalibratedTest(test, cal, dec))
        except InputError as exc:
            out.append(CalibratedTest(test, None, None, str(exc)))
        progress(i + 1, len(tests), "calibrating")
    return out


def calibration_gates(items: list[CalibratedTest]) -> tuple[Gate, ...]:
    """Quality checks of each calibrated test: residual against the noise, a pulse that is
    not degenerate (:func:`softimpact.gates.pulse_skew`), the optimiser's own status, and no
    parameter on a bound of the least-squares search (``bounds[name]``, naming it)."""
    gates = []
    for item in items:
        c, name = item.calibration, item.test.name
        if c is None:
            continue
        ratio = float(np.max(c.residual_rms / c.prepared.noise))
        gates.append(
            at_most(
                f"residual[{name}]",
                ratio,
                MAX_RESIDUAL_TO_NOISE,
                f"{name}: the computed strains miss the record by {{value:.3g}} × its noise (RMS; limit {{limit:g}}): "
                "the model does not describe it (gauge polarity, gauge names, case?)",
            )
        )
        gates.append(pulse_skew(name, c.time_of_peak, c.duration))
        gates.append(passed_if(f"optimiser[{name}]", c.converged, f"{name}: the {c.method} fit did not converge ({c.message})"))
        gates.append(
            passed_if(
                f"bounds[{name}]",
                not c.at_bounds,
                f"{name}: the fit ended on the bound of {', '.join(c.at_bounds)}: the estimate is the edge of the search, not a minimum "
                "(the data do not fix it; check the velocity, the gauges and the contact time)",
            )
        )
    return tuple(gates)


def scaling_points(rows, projectile: str) -> list[TestPoint]:
    """(name, V [m/s], F0 [N], tF0 [s], T [s]) rows as scaling test points of the named projectile
    (its m, d; I of eq 15: 2F0T/π)."""
    P = PROJECTILES[projectile]
    return [TestPoint(n, V, P.mass, P.diameter, F0, tp, T, 2 * F0 * T / math.pi) for n, V, F0, tp, T in rows]


def series_fits(series, items: list[CalibratedTest]) -> dict[str, ScalingFit] | None:
    """The scaling fit (eqs 4–7) of a series' calibrated histories (None for fewer than two)."""
    rows = [
        (i.test.name, i.test.velocity, i.calibration.peak_force, i.calibration.time_of_peak, i.calibration.duration) for i in items if i.calibration is not None
    ]
    return fit_groups(scaling_points(rows, series.projectile)) if len(rows) >= 2 else None
