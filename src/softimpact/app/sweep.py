"""``softimpact sweep``: grids and Monte Carlo of a case, locally or on a Dask cluster.

The spec is read and checked whole (:mod:`softimpact.input.sweep_spec`), the runs
planned, grouped by structure and run, resuming from ``OUT/checkpoints``
(:mod:`softimpact.cases.sweep`), their statistics computed
(:mod:`softimpact.workflows.sweep_stats`) and the files made
(:mod:`softimpact.output.sweep`). Any kind of case sweeps: bar, beam, plate and impact.
"""

from __future__ import annotations

import math
import os
import time
from pathlib import Path

from ..cases.sweep import check_scheduler, execute, plan_sweep, sweep_results
from ..errors import HeldWarnings, InputError
from ..extras import require
from ..input.sweep_spec import load_sweep_spec
from ..models.validity import ValidityWarning
from ..output.sweep import sweep_files
from . import Outcome, Progress, no_progress
from .options import display_system

__all__ = ["sweep", "sweep_warnings", "threshold_lines"]

MAX_DISTINCT = 8  # distinct run warnings shown (e.g. a Monte Carlo's draws outside a law's fitted range, each with its value)


def sweep(
    *,
    spec: str,
    out_dir: str,
    workers: int | None = None,
    scheduler: str | None = None,
    units: str | None = None,
    figures: bool = True,
    progress: Progress = no_progress,
) -> Outcome:
    """``softimpact sweep SPEC --out DIR``: the spec and the scheduler's address are checked whole before anything is written;
    ``workers`` None: the machine's cores; ``units``: the display system of the lines and figures (None: the case's)."""
    from ..output.files import check_writable

    t0 = time.perf_counter()
    check_writable(out_dir)  # the checkpoints' folder: an empty path (Python's out="") would put them in the working folder
    # before any work (no checkpoints/ yet): runs.parquet needs pyarrow, and Dask runs (workers > 0 or a scheduler) Dask
    require("sweep", "softimpact sweep", None if scheduler or workers != 0 else ("pyarrow",))
    check_scheduler(scheduler)
    with HeldWarnings() as caught:  # the spec's and the probes' warnings: shown once each, below
        s = load_sweep_spec(spec)
        if workers is None:
            workers = os.cpu_count() or 1
        if workers < 0:
            raise InputError(f"--workers: expected 0 (plain loop) or more, got {workers}")
        plan = plan_sweep(s)  # bad specs fail here, before the checkpoints folder exists
        rows, computed = execute(plan, Path(out_dir), workers, scheduler, progress)
    cols, summary, th = sweep_results(plan, rows, computed)
    own = s.case_data.get("units")
    system = display_system(units, own if own in ("in-lbf-s", "SI") else None)
    files = sweep_files(cols, summary, th, figures, system)
    dt = time.perf_counter() - t0
    line = (
        f"{summary['runs']} runs in {summary['groups']} structure group(s): {summary['succeeded']} done, {summary['failed']} failed, "
        f"{summary['from_checkpoints']} from checkpoints ({dt:.1f} s, {_rate(summary['computed_now'] / dt)} runs/s)"
    )
    if th:
        line = threshold_lines(th, system) + "\n" + line  # the command line ends the last line with the files written
    # validity flags raised here (the probes' reading of their cases) are the runs' own, counted per run
    found = [str(w.message).strip() for w in caught.held if not (isinstance(w.message, ValidityWarning) and w.message.flag)]
    read = (s.path, s.case_path, *(Path(f) for f, _ in s.inputs))  # every file the runs read: never replaced nor removed
    return Outcome(files, line, read, tuple(sweep_warnings(summary, found)))


MAX_THRESHOLDS = 6  # threshold rows printed (all of them in thresholds.csv and summary.json)


def _velocity_text(t: dict, q: str, vu) -> str:
    """A threshold quantile in display units, or its bound in words with the level it is beyond."""
    bound = t.get(f"threshold_velocity_{q}_bound", "")
    if not bound:
        return f"{t[f'threshold_velocity_{q}_m_s'] * vu.factor:.4g} {vu.label}"
    if bound.startswith("below") and "others" not in bound:
        return f"{bound} ({t['lowest_level_m_s'] * vu.factor:.4g} {vu.label})"
    if bound.startswith("above"):
        return f"{bound} ({t['highest_level_m_s'] * vu.factor:.4g} {vu.label})"
    return bound


def threshold_lines(th: list[dict], system: str) -> str:
    """The thresholds as printed lines: per index and level combination, the median and 5-95 % band in display
    units, a quantile outside the swept velocities as its bound in words (never a bare value)."""
    from ..units import display

    vu = display(system, "velocity")
    lines = []
    for t in th[:MAX_THRESHOLDS]:
        where = f" ({t['levels']})" if t["levels"] else ""
        band = f"{_velocity_text(t, 'p05', vu)} to {_velocity_text(t, 'p95', vu)}"
        lines.append(f"threshold velocity {t['index']}{where}: median {_velocity_text(t, 'median', vu)}, 5-95 % {band}")
    if len(th) > MAX_THRESHOLDS:
        lines.append(f"... and {len(th) - MAX_THRESHOLDS} more in thresholds.csv")
    return "\n".join(lines)


def _rate(x: float) -> str:
    """A rate with two significant digits, never in exponent form (0.33, 5.6, 123)."""
    if not math.isfinite(x) or x <= 0:
        return "0"
    return f"{x:.{max(0, 1 - math.floor(math.log10(x)))}f}"


def sweep_warnings(summary: dict, found=()) -> list[str]:
    """The sweep's warning lines, each once: the runs' warnings (summary.json's ``run_warnings``; ``found``, those
    raised while the spec was read and checked, counted once when no run raised them), at most
    :data:`MAX_DISTINCT`; ONE line counting the runs outside the models' envelopes per flag (``validity``); and the failures."""
    counts = {w["warning"]: w["runs"] for w in summary.get("run_warnings", [])}
    for text in found:
        counts.setdefault(text.splitlines()[0] if text else text, 0)
    lines = [text if n <= 1 else f"{text} ({n} runs)" for text, n in counts.items()]
    if len(lines) > MAX_DISTINCT:
        lines = lines[:MAX_DISTINCT] + [f"... and {len(lines) - MAX_DISTINCT} more distinct warnings of the runs (summary.json's run_warnings)"]
    v = summary.get("validity", {})
    if v.get("runs_outside_envelope"):
        per = ", ".join(f"{v['labels'][name]} ({n})" for name, n in v["runs_per_flag"].items())
        lines.append(
            f"{v['runs_outside_envelope']} of {summary['runs']} runs outside the models' validity envelopes: {per} "
            "(per run in runs.parquet: validity_flags, flag.<name>; the statistics and thresholds include them)"
            + "".join(f"; not checked: {u}" for u in v.get("not_checked", []))
        )
    elif v.get("not_checked"):
        lines.append(f"the runs' validity envelopes did not check {'; '.join(v['not_checked'])}")
    if summary["failed"]:
        first = summary["failures"][0]
        lines.append(
            f"{summary['failed']} of {summary['runs']} runs failed (run {first['run']}: {first['reason']}; all in summary.json): "
            f"the statistics, correlations and thresholds are over the {summary['succeeded']} that ran, which may bias them"
        )
    return lines
