"""``softimpact sweep``: grids and Monte Carlo of a case, locally or on a Dask cluster.

The spec is read and checked whole (:mod:`softimpact.input.sweep_spec`), the runs
planned, grouped by structure and run, resuming from ``OUT/checkpoints``
(:mod:`softimpact.cases.sweep`), their statistics computed
(:mod:`softimpact.workflows.sweep_stats`) and the files made
(:mod:`softimpact.output.sweep`). Any kind of case sweeps: bar, beam, plate and impact.
Thresholds (an index reaching 1, an output its ``[sweep.limits]`` limit) and onsets of sizes are printed
against the spec's ``threshold_against`` level (the velocity level by default) in the display units.
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
    if th or summary.get("onsets"):
        line = threshold_lines(th, system, summary.get("onsets", [])) + "\n" + line  # the command line ends the last line with the files written
    # validity flags raised here (the probes' reading of their cases) are the runs' own, counted per run
    found = [str(w.message).strip() for w in caught.held if not (isinstance(w.message, ValidityWarning) and w.message.flag)]
    read = (s.path, s.case_path, *(Path(f) for f, _ in s.inputs))  # every file the runs read: never replaced nor removed
    return Outcome(files, line, read, tuple(sweep_warnings(summary, found)))


MAX_THRESHOLDS = 6  # threshold rows printed (all of them in thresholds.csv and summary.json)


_KIND_OF_SUFFIX = {"m_s": "velocity", "J": "energy", "m": "length", "kg": "mass", "N": "force", "Pa": "stress", "s": "time", "N_s": "impulse"}


def _shown(t: dict, system: str):
    """(quantity, SI suffix of its columns, display unit or None) of a threshold or onset row (velocity when the row
    does not say: a paper's or an older row)."""
    from ..units import display

    quantity, suffix = t.get("quantity", "velocity"), t.get("unit", "m_s")
    kind = _KIND_OF_SUFFIX.get(suffix)
    return quantity, suffix, None if kind is None else display(system, kind)


def _level_text(x: float, du) -> str:
    return f"{x:.4g}" if du is None else f"{x * du.factor:.4g} {du.label}"


def _quantile_text(t: dict, prefix: str, q: str, suffix: str, du) -> str:
    """A quantile in display units, or its bound in words with the level it is beyond."""
    tail = f"_{suffix}" if suffix else ""
    bound = t.get(f"{prefix}_{q}_bound", "")
    if not bound:
        return _level_text(t[f"{prefix}_{q}{tail}"], du)
    if bound.startswith("below") and "others" not in bound:
        return f"{bound} ({_level_text(t[f'lowest_level{tail}'], du)})"
    if bound.startswith("above"):
        return f"{bound} ({_level_text(t[f'highest_level{tail}'], du)})"
    return bound


def _validity_text(t: dict) -> str:
    n = t.get("runs_outside_validity", 0)
    return f"; {n} of its {t['runs_used']} runs outside validity ({', '.join(t['validity_flags'])})" if n else ""


def threshold_lines(th: list[dict], system: str, onsets: list[dict] = ()) -> str:
    """The thresholds (and the onsets of sizes) as printed lines: per output and level combination, the median and
    5-95 % band of the level they are against (velocity, energy, diameter, ...) in display units, a quantile outside
    the swept levels as its bound in words (never a bare value), a limit as written, the runs outside validity."""
    lines = []
    for t in th[:MAX_THRESHOLDS]:
        quantity, suffix, du = _shown(t, system)
        prefix = f"threshold_{quantity}"
        where = f" ({t['levels']})" if t["levels"] else ""
        what = f"{t['index']} reaching {t['limit']}" if t.get("limit") else t["index"]
        band = f"{_quantile_text(t, prefix, 'p05', suffix, du)} to {_quantile_text(t, prefix, 'p95', suffix, du)}"
        lines.append(
            f"threshold {quantity.replace('_', ' ')} {what}{where}: median {_quantile_text(t, prefix, 'median', suffix, du)}, 5-95 % {band}{_validity_text(t)}"
        )
    if len(th) > MAX_THRESHOLDS:
        lines.append(f"... and {len(th) - MAX_THRESHOLDS} more in thresholds.csv")
    for t in onsets[:MAX_THRESHOLDS]:
        quantity, suffix, du = _shown(t, system)
        prefix = f"onset_{quantity}"
        tail = f"_{suffix}" if suffix else ""
        where = f" ({t['levels']})" if t["levels"] else ""
        lo, hi = t[f"{prefix}_last_zero{tail}"], t[f"{prefix}_first_positive{tail}"]
        bracket = f" (zero at {_level_text(lo, du)}, positive at {_level_text(hi, du)})" if math.isfinite(lo) and math.isfinite(hi) else ""
        lines.append(
            f"onset {quantity.replace('_', ' ')} {t['index']}{where}: median {_quantile_text(t, prefix, 'median', suffix, du)}{bracket}{_validity_text(t)}"
        )
    if len(onsets) > MAX_THRESHOLDS:
        lines.append(f"... and {len(onsets) - MAX_THRESHOLDS} more in onsets.csv")
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
