"""``softimpact calibrate``: the force history that makes computed gauge strains match measured ones.

One beam case with one measured file, or a calibration series (a beam case and
several measured tests, laid out as the paper's Tables II and III), calibrated on
models refined within a time budget (:mod:`softimpact.studies.calibration`).
"""

from __future__ import annotations

import math
import time
from pathlib import Path

from ..errors import InputError
from ..input.beam_case import load_beam_case
from ..input.series import CalibrationTest, is_calibration_series, load_calibration_series
from ..input.sweep_spec import case_files
from ..input.toml import case_units
from ..models.empirical import PROJECTILES
from ..output.calibration import calibration_files, series_calibration_files
from ..studies.calibration import DEFAULT_BUDGET, calibrate_tests, calibration_gates, calibration_model, series_fits
from ..units import display, parse
from ..workflows.calibration import METHODS
from . import Outcome, Progress, no_progress
from .options import display_system

__all__ = ["calibrate_command"]


def _linear_only(problem, case) -> None:
    """Calibration fits the force history on the beam's linear response (impulse responses convolved with the
    history, :mod:`softimpact.workflows.calibration`): a large-deflection beam would be calibrated as a linear one
    without a word, so it is refused, naming its key."""
    if problem.kinematics != "linear":
        raise InputError(
            f"beam.kinematics = {problem.kinematics!r} ({case}): calibrate fits the force history on the beam's linear response "
            "(its impulse responses), so a large-deflection beam cannot be calibrated; set beam.kinematics = 'linear' (and check "
            "the linear beam's deflection over thickness in its warnings)"
        )


def calibrate_command(
    *,
    case: str,
    measured: str | None = None,
    velocity: str | None = None,
    method: str = "least-squares",
    contact_radius: str | None = None,
    contact_time: str | None = None,
    fit_radius: bool = False,
    projectile: str = "rubber-1/2in",
    constants: str | None = None,
    units: str | None = None,
    figures: bool = True,
    budget: float = DEFAULT_BUDGET,
    progress: Progress = no_progress,
) -> Outcome:
    """Calibrate a beam case against one measured file, or every test of a calibration series.
    ``budget`` [s]: what refining the model (to bound its discretisation error) may cost; ``units``: the display system of the line and
    figures (None: the beam case's)."""
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
        _linear_only(problem, case_path)
        system = display_system(units, case_units(series.case))
        radii = [t.contact_radius or problem.load.contact_radius for t in series.tests]
        models = calibration_model(problem, radii, fit_radius)
        items = calibrate_tests(models, series.tests, series.projectile, series.constants, method, fit_radius, budget=budget, progress=progress, units=system)
        warnings = tuple(i.error for i in items if i.calibration is None)
        if len(warnings) == len(items):
            raise InputError("no test of the series could be calibrated")
        gates = calibration_gates(items)
        files = series_calibration_files(models, series, items, series_fits(series, items), figures, gates=gates, units=system)
        line = f"{len(items) - len(warnings)} of {len(items)} tests calibrated ({time.perf_counter() - t0:.1f} s); calibration.json"
        return Outcome(files, line, (series.path, *case_files(case_path), *(t.measured for t in series.tests)), warnings, gates)
    if not measured or not velocity:
        raise InputError("--measured and --velocity are required with a beam case")
    V = parse(velocity, "velocity", "--velocity")
    r0 = parse(contact_radius, "length", "--contact-radius") if contact_radius else None
    tc = parse(contact_time, "time", "--contact-time") if contact_time else None
    problem, case_path = load_beam_case(case)
    _linear_only(problem, case_path)
    system = display_system(units, case_units(case))
    test = CalibrationTest(Path(measured).stem, Path(measured), V, r0, tc)
    models = calibration_model(problem, [r0 or problem.load.contact_radius], fit_radius)
    items = calibrate_tests(models, [test], projectile, constants, method, fit_radius, budget=budget, progress=progress, units=system)
    if items[0].calibration is None:
        raise InputError(items[0].error)
    gates = calibration_gates(items)
    files = calibration_files(models, items, figures, single=True, gates=gates, units=system)
    c = items[0].calibration
    fu, tu = display(system, "force"), display(system, "time")
    se = c.standard_errors.get("peak_force")
    parts = (
        f"{c.method}: F0 {c.peak_force * fu.factor:.1f} {fu.label}{f' ± {se * fu.factor:.2g}' if se else ''}, "
        f"tF0 {c.time_of_peak * tu.factor:.1f} {tu.label}, T {c.duration * tu.factor:.1f} {tu.label} ({c.message})",
        c.check.message if c.check else "",
        f"{time.perf_counter() - t0:.1f} s",
    )
    line = "; ".join(p for p in parts if p)  # no empty field
    return Outcome(files, line, (*case_files(case_path), Path(measured)), gates=gates)
