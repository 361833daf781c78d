"""``softimpact bar``: a sphere on the instrumented bar (paper Figs 4–6)."""

from __future__ import annotations

import time

import numpy as np

from ..input.bar_case import load_bar_case
from ..models.validity import warn
from ..output.bar import bar_files, bar_validity
from ..units import display
from ..workflows.bar_impact import force_from_gauge, simulate_impact, without_end_cap
from . import Outcome, Progress, no_progress

__all__ = ["bar", "run_bar"]


def run_bar(problem):
    """The run, the same run without the end cap (None without one), and the force
    read from the first gauge as (time, force, gauge name) (None without a gauge)."""
    result = simulate_impact(problem)
    plain = simulate_impact(without_end_cap(problem)) if problem.bar.end_cap is not None else None
    inferred = None
    if problem.gauges:
        t, f = force_from_gauge(result, 0)
        inferred = (t, f, problem.gauges[0].name)
    return result, plain, inferred


def gauge_lag(result, inferred) -> tuple[float, float] | None:
    """(peak ratio, time lag [s]) of the gauge-derived force against the contact force."""
    if inferred is None:
        return None
    t, f, _ = inferred
    k = int(np.nanargmax(f))
    return float(f[k] / result.peak_force), float(t[k] - result.time_of_peak)


def bar(*, case: str, figures: bool = True, progress: Progress = no_progress) -> Outcome:
    """Run a bar case (file or built-in name)."""
    problem, path = load_bar_case(case)
    t0 = time.perf_counter()
    result, plain, inferred = run_bar(problem)
    files = bar_files(result, plain, inferred, figures)
    warn(bar_validity(result))
    fu, tu = display(problem.units, "force"), display(problem.units, "time")
    line = (
        f"peak force {result.peak_force * fu.factor:.1f} {fu.label} at {result.time_of_peak * tu.factor:.1f} {tu.label}, "
        f"contact {result.contact_duration * tu.factor:.1f} {tu.label} ({time.perf_counter() - t0:.2f} s)"
    )
    return Outcome(files, line, (path,))
