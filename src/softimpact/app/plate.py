"""``softimpact plate``: transverse impact of a laminated plate (FSDT, MITC9 or MITC4)."""

from __future__ import annotations

import time

import numpy as np

from ..cases.run import execute
from ..errors import InputError
from ..extras import require
from ..input.plate_case import load_plate_case
from ..input.sweep_spec import case_files
from ..input.toml import case_units
from ..output.fields import field_files, kept_frames, select_kept
from ..output.plate import plate_files, plate_static_files
from ..units import display
from . import Outcome, Progress, no_progress
from .options import display_system

__all__ = ["plate"]


def plate(
    *, case: str, history: int | None = None, units: str | None = None, figures: bool = True, fields: bool = False, progress: Progress = no_progress
) -> Outcome:
    """Run a plate case (file or built-in name), optionally with row ``history`` of its [[load.table]];
    ``fields``: also fields.xdmf/.h5, the displacement fields (:mod:`softimpact.output.fields`); ``units``: the display system of the line and figures (None: the case's)."""
    if fields:  # before any work: the extra's modules, or exit 2 with the install line
        require("fields", "--fields (fields.xdmf/.h5)")
    problem, path = load_plate_case(case, history)
    system = display_system(units, case_units(path))
    t0 = time.perf_counter()
    if problem.analysis == "static":
        if fields:  # an option the run cannot honour is refused, never dropped
            raise InputError("--fields: a static plate run has no time steps to write as fields (summary.json holds its deflection): leave --fields out")
        run = execute(problem)
        s, lu = run.summary, display(system, "length")
        its = s["newton"]["iterations"]
        line = (
            f"{s['dofs']} DOF, {problem.kinematics}, {len(its)} load steps ({sum(its)} Newton iterations, "
            f"{time.perf_counter() - t0:.1f} s); max deflection {s['max_deflection_m'] * lu.factor:.4g} {lu.label}"
        )
        return Outcome(plate_static_files(s, system), line, case_files(path), run.warnings.flags)
    steps = problem.solver.steps
    run = execute(problem, figures=figures, fields=fields, progress=lambda k: progress(k, steps, "stepping"))
    model, result = run.model, run.result
    progress(steps, steps, "stepping")
    files = plate_files(model, select_kept(result, run.shown) if fields else result, figures, run.summary, units=system)
    if fields:
        files.update(field_files(model, kept_frames(result, run.kept)))
    su, lu = display(system, "strain"), display(system, "length")
    peaks = "".join(f", {g.name} {eps[np.argmax(np.abs(eps))] * su.factor:.0f} {su.label}" for g, eps in zip(problem.gauges, result.strain))
    w = result.deflection[0]
    line = f"{model.size} DOF, {steps} steps ({time.perf_counter() - t0:.1f} s); peak deflection {w[np.argmax(np.abs(w))] * lu.factor:.3g} {lu.label}{peaks}"
    return Outcome(files, line, case_files(path), run.warnings.flags)
