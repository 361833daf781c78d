"""``softimpact bar``: a sphere on the instrumented bar (paper Figs 4–6)."""

from __future__ import annotations

import time

import numpy as np

from ..cases.run import execute
from ..input.bar_case import load_bar_case
from ..input.bar_file import bar_file_of
from ..input.sweep_spec import case_files
from ..input.toml import case_units
from ..models.validity import warn
from ..output.bar import bar_files
from ..units import display
from . import Outcome, Progress, no_progress
from .options import display_system

__all__ = ["bar"]


def gauge_lag(result, inferred) -> tuple[float, float] | None:
    """(peak ratio, time lag [s]) of the gauge-derived force against the contact force."""
    if inferred is None:
        return None
    t, f, _ = inferred
    k = int(np.nanargmax(f))
    return float(f[k] / result.peak_force), float(t[k] - result.time_of_peak)


def bar(*, case: str, units: str | None = None, figures: bool = True, progress: Progress = no_progress) -> Outcome:
    """Run a bar case (file or built-in name); ``units``: the display system of the line and figures (None: the case's)."""
    problem, path = load_bar_case(case)
    system = display_system(units, case_units(path))
    t0 = time.perf_counter()
    run = execute(problem)
    result = run.result
    files = bar_files(result, run.plain, run.inferred, figures, summary=run.summary, units=system)
    warn(run.warnings)
    fu, tu = display(system, "force"), display(system, "time")
    contact = (
        f"contact {result.contact_duration * tu.factor:.1f} {tu.label}" if np.isfinite(result.contact_duration) else "contact not ended by the end of the run"
    )
    line = (
        f"peak force {result.peak_force * fu.factor:.1f} {fu.label} at {result.time_of_peak * tu.factor:.1f} {tu.label}, "
        f"{contact} ({time.perf_counter() - t0:.2f} s)"
    )
    inputs = case_files(path)
    return Outcome(files, line, (*inputs, *(f for f in filter(None, (bar_file_of(path),)) if f not in inputs)))
