"""``softimpact calibrate``: the force history that makes computed gauge strains match measured ones.

One beam case with one measured file, or a calibration series (a beam case and
several measured tests, laid out as the paper's Tables II and III).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from .. import units
from ..errors import InputError
from ..gates import Gate, at_most, passed_if
from ..input.beam_case import load_beam_case
from ..input.records import read_strains
from ..input.series import CalibrationSeries, CalibrationTest, is_calibration_series, load_calibration_series
from ..models.empirical import PRESETS, PROJECTILES
from ..models.pulses import SkewedPulse
from ..output.calibration import SeriesComparison, calibration_files, series_calibration_files
from ..workflows.beam_impact import BeamModel
from ..workflows.calibration import ASSUMED_ORDER_SAFETY, MAIN, METHODS, Calibration, Measured, calibrate, calibrate_checked
from ..workflows.convergence import richardson
from ..workflows.refinement import coarsen_beam, refine_beam
from ..workflows.scaling import TestPoint, fit_groups
from . import Outcome, Progress, no_progress
from .predict import scaling_law

__all__ = [
    "CalibratedTest",
    "ModelLadder",
    "calibration_gates",
    "start_pulse",
    "calibration_model",
    "calibrate_tests",
    "series_fits",
    "comparison",
    "calibrate_command",
]


@dataclass(frozen=True)
class CalibratedTest:
    """A calibration test with its result (and the deconvolved history beside it), or its error."""

    test: CalibrationTest
    calibration: Calibration | None
    deconvolved: Calibration | None = None
    error: str = ""


def start_pulse(projectile: str, constants: str | None, velocity: float, system: str = "in-lbf-s") -> SkewedPulse:
    """The bar-model history at ``velocity``: eqs (4)–(6) with eq (15); refuses velocities out of the constants' range."""
    if projectile not in PROJECTILES:
        raise InputError(f"--projectile: unknown {projectile!r} (known: {', '.join(PROJECTILES)})")
    P = PROJECTILES[projectile]
    law = scaling_law(constants, "pooled", P)
    if not law.in_range(velocity):
        lo, hi = law.velocity_range
        vu = units.display(system, "velocity")
        raise InputError(
            f"velocity: {velocity * vu.factor:.0f} {vu.label} is outside the range of the bar model {law.name} "
            f"({lo * vu.factor:.0f}-{hi * vu.factor:.0f} {vu.label})"
        )
    return law.pulse(P.mass, P.diameter, velocity)


DEFAULT_BUDGET = 20.0  # s: what refining the calibration model may cost (building the refined response engines)
# flop/s of banded back-substitutions assumed in cost predictions: conservative for one core
# (the standard machine does about 5.7e9 on the beam meshes).
SOLVE_RATE = 2e9


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
        return self(max((k for k in self.models if k >= 0), default=0))

    def describe(self, level: int) -> dict:
        """Mesh and step of a level (SI)."""
        b, s = self(level).problem.beam, self(level).problem.solver
        return {"level": level, "factor": self.ratio**level, "elements": [b.nx, b.nz], "time_step_s": s.time_step}


def parameter_convergence(models: ModelLadder, measured, start, cal, contact_time, fit_radius) -> dict:
    """How the calibrated parameters themselves converge: the least-squares fits on the level
    used and the two below it (those the check made are reused; cheap engines: the data, and so
    the noise, are the same in all three fits, so their differences are discretisation), then
    Richardson on each parameter (workflows/convergence). Returns name → (95 % discretisation
    uncertainty of the value at the level used, the convergence record); {} when fewer than
    three levels exist."""
    level = cal.check.level
    ladder = (level - 2, level - 1, level) if level >= 1 else (-2, -1, 0)
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
    out = {}
    for i, name in enumerate(MAIN):
        values = [fits[k][i] for k in ladder]
        conv = richardson(values, float(models.ratio), 2.0, name)
        if conv.status == "converged to round-off":
            u95 = 0.0
        elif conv.status == "asymptotic":
            u95 = conv.safety_factor * abs(values[-1] - conv.extrapolated)
        else:  # oscillatory, diverging: half the range, with the assumed order's safety
            u95 = ASSUMED_ORDER_SAFETY * 0.5 * (max(values) - min(values))
        out[name] = (float(u95), conv)
    return out


def calibration_model(problem, radii, fit_radius: bool) -> ModelLadder:
    """The ladder of calibration models for a case (level 0: its own mesh)."""
    return ModelLadder(problem, radii, fit_radius)


def calibrate_tests(
    models: ModelLadder,
    tests,
    projectile,
    constants,
    method,
    fit_radius=False,
    deconvolve=True,
    budget: float = DEFAULT_BUDGET,
    progress: Progress = no_progress,
) -> list[CalibratedTest]:
    """Calibrate each test on a model whose discretisation error is checked (and refined within
    ``budget`` seconds); a bad test is reported and the others go on."""
    out = []
    problem = models.problem
    max_level = models.affordable(budget)
    for i, test in enumerate(tests):
        try:
            start = start_pulse(projectile, constants, test.velocity, problem.units)
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


MAX_RESIDUAL_TO_NOISE = 2.0  # RMS residual / noise σ at any gauge: above, the model does not describe the record
MAX_SKEW = 0.95  # tF0/T at or above: a degenerate pulse (tF0 ≈ T)


def calibration_gates(items: list[CalibratedTest]) -> tuple[Gate, ...]:
    """Quality checks of each calibrated test: residual against the noise, a pulse that is
    not degenerate, the optimiser's own status."""
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
        skew = c.time_of_peak / c.duration if c.duration > 0 else float("nan")
        gates.append(at_most(f"pulse-skew[{name}]", skew, MAX_SKEW, f"{name}: degenerate pulse, tF0/T = {{value:.2f}} (limit {{limit:.2f}})"))
        gates.append(passed_if(f"optimiser[{name}]", c.converged, f"{name}: the {c.method} fit did not converge ({c.message})"))
    return tuple(gates)


def with_parameter_convergence(models, measured, start, cal, contact_time, fit_radius):
    """The calibration with its standard errors widened, where the parameters' own convergence
    (:func:`parameter_convergence`) shows a larger discretisation error than the check's estimate."""
    conv = parameter_convergence(models, measured, start, cal, contact_time, fit_radius)
    if not conv:
        return cal
    se = dict(cal.standard_errors)
    noise = cal.check.noise_errors
    for name, (u95, _) in conv.items():
        if name in se and name in noise:
            se[name] = max(se[name], math.hypot(noise[name], u95 / 1.96))
    orders = {name: c.order for name, (_, c) in conv.items()}
    check = replace(
        cal.check,
        parameter_orders=orders,
        parameter_uncertainty_95={name: u for name, (u, _) in conv.items()},
        parameter_status={name: c.status for name, (_, c) in conv.items()},
    )
    return replace(cal, standard_errors=se, check=check)


def _points(rows, projectile) -> list[TestPoint]:
    """(name, V, F0, tF0, T) rows as scaling test points of the series' projectile (I of eq 15: 2F0T/π)."""
    P = PROJECTILES[projectile]
    return [TestPoint(n, V, P.mass, P.diameter, F0, tp, T, 2 * F0 * T / math.pi) for n, V, F0, tp, T in rows]


def series_fits(series: CalibrationSeries, items: list[CalibratedTest]):
    """The scaling fit of the calibrated histories (None for fewer than two)."""
    rows = [
        (i.test.name, i.test.velocity, i.calibration.peak_force, i.calibration.time_of_peak, i.calibration.duration) for i in items if i.calibration is not None
    ]
    return fit_groups(_points(rows, series.projectile)) if len(rows) >= 2 else None


def comparison(model: BeamModel, series: CalibrationSeries, items: list[CalibratedTest], fits) -> SeriesComparison:
    """The bar law's histories, the strains under the paper's histories and both scaling fits."""
    P = PROJECTILES[series.projectile]
    law = PRESETS[P.law]
    ref = {round(r[0], 6): r for r in series.reference}
    bar_models, strains = [], []
    for item in items:
        V = item.test.velocity
        bar_models.append(law.parameters(P.mass, P.diameter, V))
        r = ref.get(round(V, 6))
        if r is None:
            strains.append(None)
        else:
            res = model.respond(SkewedPulse(r[1], r[2], r[3]), r[4])
            strains.append(tuple(float(np.max(np.abs(s))) for s in res.strain))
    groups = {}
    if len(series.reference) >= 2:
        paper_rows = [(str(i), r[0], r[1], r[2], r[3]) for i, r in enumerate(series.reference)]
        groups["paper's table"] = next(iter(fit_groups(_points(paper_rows, series.projectile)).values()))
    if fits is not None:
        groups["calibrated"] = next(iter(fits.values()))
    return SeriesComparison(tuple(bar_models), tuple(strains), groups, law)


def calibrate_command(
    case: str,
    measured: str | None = None,
    velocity: str | None = None,
    method: str = "least-squares",
    contact_radius: str | None = None,
    contact_time: str | None = None,
    fit_radius: bool = False,
    projectile: str = "rubber-1/2in",
    constants: str | None = None,
    figures: bool = True,
    budget: float = DEFAULT_BUDGET,
    progress: Progress = no_progress,
) -> Outcome:
    """Calibrate a beam case against one measured file, or every test of a calibration series.
    ``budget`` [s]: what refining the model (to bound its discretisation error) may cost."""
    if not (isinstance(budget, (int, float)) and math.isfinite(budget) and budget >= 0):
        raise InputError(f"--budget: must be a non-negative number of seconds, got {budget!r}")
    if method not in METHODS:
        raise InputError(f"--method: {method!r} is not one of {', '.join(METHODS)}")
    if projectile not in PROJECTILES:
        raise InputError(f"--projectile: unknown {projectile!r} (known: {', '.join(PROJECTILES)})")
    t0 = time.perf_counter()
    if is_calibration_series(case):
        if measured or velocity:
            raise InputError("--measured/--velocity: not used with a series file (its [[test]] entries give them)")
        series = load_calibration_series(case)
        problem, case_path = load_beam_case(series.case)
        radii = [t.contact_radius or problem.load.contact_radius for t in series.tests]
        models = calibration_model(problem, radii, fit_radius)
        items = calibrate_tests(models, series.tests, series.projectile, series.constants, method, fit_radius, budget=budget, progress=progress)
        warnings = tuple(i.error for i in items if i.calibration is None)
        if len(warnings) == len(items):
            raise InputError("no test of the series could be calibrated")
        gates = calibration_gates(items)
        files = series_calibration_files(models, series, items, series_fits(series, items), figures, gates=gates)
        line = f"{len(items) - len(warnings)} of {len(items)} tests calibrated ({time.perf_counter() - t0:.1f} s); calibration.json"
        return Outcome(files, line, (series.path, case_path, *(t.measured for t in series.tests)), warnings, gates)
    if not measured or not velocity:
        raise InputError("--measured and --velocity are required with a beam case")
    V = units.parse(velocity, "velocity", "--velocity")
    r0 = units.parse(contact_radius, "length", "--contact-radius") if contact_radius else None
    tc = units.parse(contact_time, "time", "--contact-time") if contact_time else None
    problem, case_path = load_beam_case(case)
    test = CalibrationTest(Path(measured).stem, Path(measured), V, r0, tc)
    models = calibration_model(problem, [r0 or problem.load.contact_radius], fit_radius)
    items = calibrate_tests(models, [test], projectile, constants, method, fit_radius, budget=budget, progress=progress)
    if items[0].calibration is None:
        raise InputError(items[0].error)
    gates = calibration_gates(items)
    files = calibration_files(models, items, figures, single=True, gates=gates)
    c = items[0].calibration
    fu, tu = units.display(problem.units, "force"), units.display(problem.units, "time")
    se = c.standard_errors.get("peak_force")
    line = (
        f"{c.method}: F0 {c.peak_force * fu.factor:.1f} {fu.label}{f' ± {se * fu.factor:.2g}' if se else ''}, "
        f"tF0 {c.time_of_peak * tu.factor:.1f} {tu.label}, T {c.duration * tu.factor:.1f} {tu.label} ({c.message}); "
        f"{c.check.message if c.check else ''}; {time.perf_counter() - t0:.1f} s"
    )
    return Outcome(files, line, (case_path, Path(measured)), gates=gates)
