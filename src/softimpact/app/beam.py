"""``softimpact beam``: transverse impact of a laminated beam (paper Figs 16–22)."""

from __future__ import annotations

import time

import numpy as np

from ..cases.run import execute
from ..extras import require
from ..input.beam_case import load_beam_case
from ..input.sweep_spec import case_files
from ..input.toml import case_units
from ..output.beam import beam_files
from ..output.fields import field_files
from ..units import display
from . import Outcome, Progress, no_progress
from .options import display_system

__all__ = ["beam"]


def beam(
    *, case: str, history: int | None = None, units: str | None = None, figures: bool = True, fields: bool = False, progress: Progress = no_progress
) -> Outcome:
    """Run a beam case (file or built-in name), optionally with row ``history`` of its [[load.table]];
    ``fields``: also fields.xdmf/.h5, the displacement and strain fields (:mod:`softimpact.output.fields`); ``units``: the display system of the line and figures (None: the case's)."""
    if fields:  # before any work: the extra's modules, or exit 2 with the install line
        require("fields", "--fields (fields.xdmf/.h5)")
    problem, path = load_beam_case(case, history)
    system = display_system(units, case_units(path))
    t0 = time.perf_counter()
    steps = problem.solver.steps
    run = execute(problem, figures=figures, fields=fields, progress=lambda k: progress(k, steps, "stepping"))
    model, result = run.model, run.result
    progress(steps, steps, "stepping")
    files = beam_files(model, result, figures, summary=run.summary, units=system)
    if fields:
        kept = run.kept
        files.update(field_files(model, (kept, result.time[kept], result.displacement[:, kept])))
    su = display(system, "strain")
    peaks = ", ".join(f"{g.name} {eps[np.argmax(np.abs(eps))] * su.factor:.0f} {su.label}" for g, eps in zip(problem.gauges, result.strain))
    line = f"{model.plane.n} DOF, {steps} steps ({time.perf_counter() - t0:.1f} s)" + (f"; peak strains {peaks}" if peaks else "")  # no empty field
    return Outcome(files, line, case_files(path), run.warnings.flags)
