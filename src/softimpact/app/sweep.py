"""``softimpact sweep``: grids and Monte Carlo of a case, locally or on a Dask cluster.

The spec is read and checked whole (:mod:`softimpact.input.sweep_spec`), the runs
planned, grouped by structure and run, resuming from ``OUT/checkpoints``
(:mod:`softimpact.cases.sweep`), their statistics computed
(:mod:`softimpact.workflows.sweep_stats`) and the files made
(:mod:`softimpact.output.sweep`). Any kind of case sweeps: bar, beam, plate and impact.
"""

from __future__ import annotations

import os
import time
from pathlib import Path

from ..cases.sweep import check_scheduler, execute, plan_sweep, sweep_results
from ..errors import InputError
from ..input.sweep_spec import load_sweep_spec
from ..output.sweep import sweep_files
from . import Outcome, Progress, no_progress

__all__ = ["sweep"]


def sweep(
    *, spec: str, out_dir: str, workers: int | None = None, scheduler: str | None = None, figures: bool = True, progress: Progress = no_progress
) -> Outcome:
    """``softimpact sweep SPEC --out DIR``: the spec and the scheduler's address are checked whole before anything is written."""
    t0 = time.perf_counter()
    check_scheduler(scheduler)
    s = load_sweep_spec(spec)
    if workers is None:
        workers = os.cpu_count() or 1
    if workers < 0:
        raise InputError(f"--workers: expected 0 (plain loop) or more, got {workers}")
    plan = plan_sweep(s)  # bad specs fail here, before the checkpoints folder exists
    rows, computed = execute(plan, Path(out_dir), workers, scheduler, progress)
    cols, summary, th = sweep_results(plan, rows, computed)
    system = s.case_data.get("units") if s.case_data.get("units") in ("in-lbf-s", "SI") else "in-lbf-s"
    files = sweep_files(cols, summary, th, figures, system)
    dt = time.perf_counter() - t0
    line = (
        f"{summary['runs']} runs in {summary['groups']} structure group(s): {summary['succeeded']} done, {summary['failed']} failed, "
        f"{summary['from_checkpoints']} from checkpoints ({dt:.1f} s, {summary['computed_now'] / dt:.0f} runs/s)"
    )
    warnings = []
    if summary["failed"]:
        first = summary["failures"][0]
        warnings.append(
            f"{summary['failed']} of {summary['runs']} runs failed (run {first['run']}: {first['reason']}; all in summary.json): "
            f"the statistics, correlations and thresholds are over the {summary['succeeded']} that ran, which may bias them"
        )
    return Outcome(files, line, (s.path, s.case_path), tuple(warnings))
