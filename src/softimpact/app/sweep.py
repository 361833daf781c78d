"""``softimpact sweep``: grids and Monte Carlo of a case, locally or on a Dask cluster.

The spec (:mod:`softimpact.input.sweep_spec`) lists the runs; runs sharing a
structure (same mesh, laminate, support, solver: everything but the load
history, as the case's adapter says, :mod:`softimpact.app.sweep_cases`) form
a group whose expensive part (factorisation, impulse responses) is built once
and shared by its chunks. Chunks run as Dask tasks (a LocalCluster of
``workers`` processes, or the cluster at ``scheduler``), or in a plain loop
(``workers = 0``). Each finished chunk is checkpointed in
``OUT/checkpoints/<spec fingerprint>/``: a killed sweep started again computes
only the chunks missing there, so every run is computed once.
"""

from __future__ import annotations

import functools
import json
import math
import os
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import units
from ..errors import InputError
from ..input.sweep_spec import Level, SweepSpec, load_sweep_spec
from ..units import INCH
from . import Outcome, Progress, no_progress
from .sweep_cases import ADAPTERS, adapter_for, flatten

__all__ = [
    "SweepPlan",
    "plan_sweep",
    "run_sweep",
    "sweep",
    "statistics",
    "sensitivity",
    "sobol_first_order",
    "thresholds",
    "paper_thresholds",
    "paper_plate_case",
    "paper_plate_thresholds",
    "threshold_section",
]

CHECKPOINTS = "checkpoints"  # folder in OUT holding one JSON file per finished chunk


@dataclass(frozen=True)
class Chunk:
    """Runs ``items`` [(run index, case dict)] of group ``group`` (of ``group_size`` runs)."""

    name: str
    group: int
    group_size: int
    items: tuple


@dataclass(frozen=True)
class SweepPlan:
    spec: SweepSpec
    kind: str
    runs: tuple
    chunks: tuple[Chunk, ...]
    groups: int


def plan_sweep(spec: SweepSpec) -> SweepPlan:
    """Runs, grouped by structure and cut into chunks; checks the first run's case and the outputs."""
    adapter = adapter_for(spec.case_data, "sweep.case")
    runs = spec.runs()
    cases = [spec.case_for(r, adapter.expand) for r in runs]
    base = spec.case_path.parent
    # Bad specs fail at once: with the draws at their medians, the first run and the first run
    # taking each level value must parse (a run failing on an unlucky draw is only recorded).
    central = spec.runs(central=True)
    probe = {0}
    for p in spec.parameters:
        if isinstance(p, Level):
            for value in p.values:
                probe.add(next(r.index for r in central if (p.key, value) in r.sets))
    for i in sorted(probe):
        try:
            checked = adapter.problem(spec.case_for(central[i], adapter.expand), base)
        except InputError as exc:
            raise InputError(f"sweep: {spec.case_path.name}: {exc}") from None
        if i == 0:
            problem = checked
    known = adapter.output_keys(problem)
    for o in spec.outputs:
        if o not in known:
            raise InputError(f"sweep.outputs: {o!r} is not an output of a {adapter.name} case (known: {', '.join(known)})")
    groups: dict[str, list[int]] = {}
    for r, data in zip(runs, cases):
        groups.setdefault(adapter.structure(data), []).append(r.index)
    chunks = []
    for g, members in enumerate(groups.values()):
        for k in range(0, len(members), spec.chunk):
            part = members[k : k + spec.chunk]
            chunks.append(Chunk(f"chunk-{g:05d}-{k // spec.chunk:05d}", g, len(members), tuple((i, cases[i]) for i in part)))
    return SweepPlan(spec, adapter.name, tuple(runs), tuple(chunks), len(groups))


def _one_line(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    return f"{type(exc).__name__}: {text[0] if text else ''}".strip().rstrip(":")


class _Failed:
    """A group whose shared part could not be built: each of its runs fails with ``reason``."""

    def __init__(self, reason: str):
        self.reason = reason


def prepare_group(kind: str, candidates, base: str, runs: int, outputs=()):
    """The shared part of a group (a Dask task: plain arguments, picklable result), from the
    first of the group's ``candidates`` (case dicts) that builds: a run's own load may be bad.
    ``outputs``: the spec's, so the adapter may leave out what none of them needs."""
    first = None
    for data in candidates:
        try:
            return ADAPTERS[kind].prepare(data, Path(base), runs, tuple(outputs))
        except Exception as exc:  # a drawn structure can be invalid: its runs fail, the sweep goes on
            first = first or _Failed(_one_line(exc))
            if runs == 1:
                break
    return first


def run_chunk(kind: str, prepared, items, base: str, outputs) -> list[dict]:
    """Runs of one chunk → rows {run, outputs (dict or None), error (None or one line)}."""
    adapter = ADAPTERS[kind]
    rows = []
    for run, data in items:
        if isinstance(prepared, _Failed):
            rows.append({"run": run, "outputs": None, "error": prepared.reason})
            continue
        try:
            flat = flatten(adapter.run(prepared, data, Path(base), tuple(outputs)))
            rows.append({"run": run, "outputs": {o: float(flat[o]) for o in outputs}, "error": None})
        except Exception as exc:  # recorded with its reason; the sweep goes on
            rows.append({"run": run, "outputs": None, "error": _one_line(exc)})
    return rows


def group_chunk(kind: str, base: str, runs: int, items, outputs) -> list[dict]:
    """A group of one chunk as one task: prepare and run where the data is."""
    return run_chunk(kind, prepare_group(kind, [d for _, d in items], base, runs, outputs), items, base, outputs)


def _checkpoint_dir(out: Path, spec: SweepSpec) -> Path:
    return Path(out) / CHECKPOINTS / spec.fingerprint


def _save(folder: Path, chunk: Chunk, rows) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    tmp = folder / f".{chunk.name}.tmp"
    tmp.write_text(json.dumps(rows), encoding="utf-8")
    os.replace(tmp, folder / f"{chunk.name}.json")  # atomic: a chunk is checkpointed whole or not at all


def _load(folder: Path, chunk: Chunk):
    path = folder / f"{chunk.name}.json"
    if not path.is_file():
        return None
    try:
        rows = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return rows if sorted(r["run"] for r in rows) == sorted(i for i, _ in chunk.items) else None


def _client(workers: int, scheduler: str | None):
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise InputError("--workers/--scheduler: Dask is not installed (pip install 'softimpact[sweep]'), or use --workers 0") from None
    if scheduler:
        try:
            return Client(scheduler, timeout="10s"), None
        except (OSError, TimeoutError) as exc:
            raise InputError(f"--scheduler: cannot reach {scheduler} ({_one_line(exc)})") from None
    import dask

    # Dask's statistical profiler samples the task thread every 10 ms and, holding the GIL,
    # doubles the cost of a millisecond-sized run: off for the local cluster.
    with dask.config.set({"distributed.worker.profile.enabled": False}):
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None)
    return Client(cluster), cluster


def execute(plan: SweepPlan, out: Path | None, workers: int = 0, scheduler: str | None = None, progress: Progress = no_progress) -> tuple[dict, int]:
    """Run the plan's missing chunks; returns ({run: row}, runs computed now).

    With ``out``, finished chunks are read from and written to its checkpoints.
    ``workers = 0`` without ``scheduler`` runs a plain loop in this process.
    """
    spec, kind = plan.spec, plan.kind
    base = str(spec.case_path.parent)
    folder = None if out is None else _checkpoint_dir(out, spec)
    rows: dict[int, dict] = {}
    pending = []
    for c in plan.chunks:
        done = None if folder is None else _load(folder, c)
        if done is None:
            pending.append(c)
        else:
            rows.update({r["run"]: r for r in done})
    total = len(plan.runs)
    progress(len(rows), total, "runs")

    def finish(chunk, result):
        if folder is not None:
            _save(folder, chunk, result)
        rows.update({r["run"]: r for r in result})
        progress(len(rows), total, "runs")

    by_group: dict[int, list[Chunk]] = {}
    for c in pending:
        by_group.setdefault(c.group, []).append(c)
    if workers == 0 and not scheduler:
        for chunks in by_group.values():
            prepared = prepare_group(kind, [d for _, d in chunks[0].items], base, chunks[0].group_size, spec.outputs)
            for c in chunks:
                finish(c, run_chunk(kind, prepared, c.items, base, spec.outputs))
        return rows, sum(len(c.items) for c in pending)
    client, cluster = _client(workers, scheduler)
    try:
        from distributed import as_completed

        futures = {}
        for chunks in by_group.values():
            first = chunks[0]
            if len(chunks) == 1 and first.group_size == len(first.items):
                f = client.submit(group_chunk, kind, base, first.group_size, first.items, spec.outputs, pure=False)
                futures[f] = first
                continue
            prepared = client.submit(prepare_group, kind, [d for _, d in first.items], base, first.group_size, spec.outputs, pure=False)
            for c in chunks:
                futures[client.submit(run_chunk, kind, prepared, c.items, base, spec.outputs, pure=False)] = c
        for f in as_completed(list(futures)):
            finish(futures[f], f.result())
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    return rows, sum(len(c.items) for c in pending)


def statistics(values: np.ndarray) -> dict:
    """Mean, standard deviation, extremes and percentiles (2.5, 5, 50, 95, 97.5) of the finite values."""
    v = np.asarray(values, float)
    v = v[np.isfinite(v)]
    if v.size == 0:
        return {"count": 0}
    p = np.percentile(v, [2.5, 5, 50, 95, 97.5])
    return {
        "count": int(v.size),
        "mean": float(v.mean()),
        "std": float(v.std(ddof=1)) if v.size > 1 else 0.0,
        "min": float(v.min()),
        "p05": float(p[1]),
        "median": float(p[2]),
        "p95": float(p[3]),
        "max": float(v.max()),
        "interval95": [float(p[0]), float(p[4])],
    }


def sensitivity(columns: dict[str, np.ndarray], y: np.ndarray) -> list[dict]:
    """Varied inputs ranked by |Spearman rank correlation| with output ``y`` (finite runs only)."""
    from scipy.stats import spearmanr

    out = []
    ok = np.isfinite(y)
    for name, x in columns.items():
        x = np.asarray(x)
        if x.dtype.kind not in "fiu" or ok.sum() < 3:
            continue
        xs, ys = x[ok].astype(float), y[ok]
        if np.ptp(xs) == 0 or np.ptp(ys) == 0:
            continue
        rho = float(spearmanr(xs, ys).statistic)
        out.append({"parameter": name, "spearman": rho})
    return sorted(out, key=lambda d: -abs(d["spearman"]))


def sobol_first_order(columns: dict[str, np.ndarray], y: np.ndarray) -> list[dict]:
    """First-order Sobol indices S_i = Var(E[Y | X_i]) / Var(Y) of the varied inputs, from the runs
    already made (a given-data estimate: no extra design), ranked largest first.

    E[Y | X_i] is estimated by the mean of Y over bins of X_i: its distinct values when
    there are few (levels), else ⌈√n⌉ bins of equal count by rank. The between-bin share of
    the variance, S_raw, is biased up by (M − 1)/(n − 1) for M bins when Y does not depend
    on X_i; that bias is removed, S = (S_raw − b)/(1 − b), and S clipped at 0. Assumes the
    inputs independent (the α's of a scaling.json are not: their indices share the
    variance their correlation carries). Finite runs only; needs 10 or more.
    """
    y = np.asarray(y, float)
    ok = np.isfinite(y)
    n = int(ok.sum())
    if n < 10 or np.ptp(y[ok]) == 0:
        return []
    yk = y[ok]
    total = float(np.sum((yk - yk.mean()) ** 2))
    out = []
    for name, x in columns.items():
        x = np.asarray(x)
        if x.dtype.kind not in "fiu":
            continue
        xk = x[ok].astype(float)
        if np.ptp(xk) == 0:
            continue
        levels = np.unique(xk)
        M = math.ceil(math.sqrt(n))
        if levels.size <= M:
            labels = np.searchsorted(levels, xk)
            M = levels.size
        else:
            labels = np.minimum((np.argsort(np.argsort(xk, kind="stable"), kind="stable") * M) // n, M - 1)
        counts = np.bincount(labels, minlength=M)
        means = np.bincount(labels, weights=yk, minlength=M) / np.maximum(counts, 1)
        raw = float(np.sum(counts * (means - yk.mean()) ** 2)) / total
        bias = (M - 1) / (n - 1)
        out.append({"parameter": name, "S1": max(0.0, (raw - bias) / (1 - bias)), "bins": int(M)})
    return sorted(out, key=lambda d: -d["S1"])


def _table(plan: SweepPlan, rows: dict) -> dict[str, np.ndarray | list]:
    spec = plan.spec
    names = []
    for p in spec.parameters:
        names += [c for c in p.columns if c not in names]
    cols: dict = {"run": np.array([r.index for r in plan.runs], dtype=np.int64)}
    for n in names:
        vals = [r.row.get(n) for r in plan.runs]
        cols[n] = np.array(vals, float) if all(isinstance(v, (int, float)) for v in vals) else [None if v is None else str(v) for v in vals]
    for o in spec.outputs:
        cols[o] = np.array([np.nan if rows[r.index]["outputs"] is None else rows[r.index]["outputs"][o] for r in plan.runs])
    cols["error"] = [rows[r.index]["error"] or "" for r in plan.runs]
    return cols


def _velocity_key(spec: SweepSpec) -> str | None:
    keys = [p.key for p in spec.parameters if isinstance(p, Level) and p.key.endswith("velocity") and all(isinstance(v, float) for v in p.si)]
    return keys[0] if keys else None


def thresholds(plan: SweepPlan, cols: dict) -> list[dict]:
    """Threshold velocities: per combination of the other levels and per damage output,
    the velocity [m/s] where the index first reaches 1 (linear between levels), over the
    draws: median and 5–95 % band, and how many draws reach 1 within the swept range."""
    spec = plan.spec
    vkey = _velocity_key(spec)
    damage = [o for o in spec.outputs if o.startswith("damage.") and o != "damage.threshold_force_N"]
    if vkey is None or not damage:
        return []
    others = [p.key for p in spec.parameters if isinstance(p, Level) and p.key != vkey]
    draws = np.array([r.draw for r in plan.runs])
    velocity = np.asarray(cols[vkey], float)
    labels = [" ".join(str(cols[k][i]) for k in others) for i in range(len(plan.runs))]
    out = []
    for label in dict.fromkeys(labels):
        sel = np.array([lab == label for lab in labels])
        for o in damage:
            found = []
            for d in np.unique(draws[sel]):
                m = sel & (draws == d)
                order = np.argsort(velocity[m])
                v, idx = velocity[m][order], np.asarray(cols[o], float)[m][order]
                k = np.flatnonzero(np.nan_to_num(idx, nan=-np.inf) >= 1.0)
                if k.size == 0:
                    found.append(np.nan)
                elif k[0] == 0:
                    found.append(float(v[0]))
                else:
                    j = k[0]
                    found.append(float(v[j - 1] + (1.0 - idx[j - 1]) * (v[j] - v[j - 1]) / (idx[j] - idx[j - 1])))
            f = np.array(found)
            ok = f[np.isfinite(f)]
            q = np.percentile(ok, [5, 50, 95]) if ok.size else [np.nan] * 3
            out.append(
                {
                    "levels": label,
                    "index": o.removeprefix("damage."),
                    "threshold_velocity_median_m_s": float(q[1]),
                    "threshold_velocity_p05_m_s": float(q[0]),
                    "threshold_velocity_p95_m_s": float(q[2]),
                    "draws": int(f.size),
                    "draws_reaching_1": int(ok.size),
                }
            )
    return out


def _parquet(cols: dict) -> bytes:
    import io

    import pyarrow as pa
    import pyarrow.parquet as pq

    buf = io.BytesIO()
    pq.write_table(pa.table({k: pa.array(v) for k, v in cols.items()}), buf)
    return buf.getvalue()


def sweep_files(plan: SweepPlan, rows: dict, computed: int, figures: bool, system: str = "in-lbf-s") -> tuple[dict, dict]:
    """runs.parquet, summary.json, thresholds.csv (+ figure) from the finished rows."""
    from .. import __version__
    from ..output.files import csv_text, figure_bytes, json_text

    spec = plan.spec
    cols = _table(plan, rows)
    varied = {k: v for k, v in cols.items() if k not in spec.outputs and k not in ("run", "error")}
    failures = [{"run": int(cols["run"][i]), "reason": e} for i, e in enumerate(cols["error"]) if e]
    summary = {
        "softimpact_version": __version__,
        "case": str(spec.case_path),
        "case_type": plan.kind,
        "method": spec.method,
        "seed": spec.seed,
        "fingerprint": spec.fingerprint,
        "runs": len(plan.runs),
        "succeeded": len(plan.runs) - len(failures),
        "failed": len(failures),
        "groups": plan.groups,
        "computed_now": computed,
        "from_checkpoints": len(plan.runs) - computed,
        "failures": failures,
        "statistics": {o: statistics(cols[o]) for o in spec.outputs},
        "sensitivity_spearman": {o: sensitivity(varied, np.asarray(cols[o], float)) for o in spec.outputs},
        "sensitivity_sobol_first_order": {o: sobol_first_order(varied, np.asarray(cols[o], float)) for o in spec.outputs},
    }
    files = {"runs.parquet": _parquet(cols)}
    th = thresholds(plan, cols)
    if th:
        summary["thresholds"] = th
        keys = list(th[0])
        files["thresholds.csv"] = csv_text({k: np.array([t[k] for t in th], dtype=object if k in ("levels", "index") else float) for k in keys})
        if figures:
            files["thresholds.png"] = figure_bytes(_threshold_figure(th, system))
    files["summary.json"] = json_text(summary)
    return files, summary


def _threshold_figure(th: list[dict], system: str, title: str = "Threshold velocity (index reaches 1): median and 5-95 % band"):
    import matplotlib.pyplot as plt

    from ..units import display

    vu = display(system, "velocity")
    fig, ax = plt.subplots(figsize=(7, 4))
    labels = list(dict.fromkeys(t["levels"] for t in th))
    indices = list(dict.fromkeys(t["index"] for t in th))
    width = 0.8 / max(len(indices), 1)
    for j, name in enumerate(indices):
        xs, ys, lo, hi = [], [], [], []
        for i, lab in enumerate(labels):
            t = next(t for t in th if t["levels"] == lab and t["index"] == name)
            xs.append(i + (j - (len(indices) - 1) / 2) * width)
            ys.append(t["threshold_velocity_median_m_s"] * vu.factor)
            lo.append(ys[-1] - t["threshold_velocity_p05_m_s"] * vu.factor)
            hi.append(t["threshold_velocity_p95_m_s"] * vu.factor - ys[-1])
        ax.errorbar(xs, ys, yerr=[np.nan_to_num(lo), np.nan_to_num(hi)], fmt="o", capsize=3, label=name)
        for x, y in zip(xs, ys):
            if not np.isfinite(y):  # no draw reached 1 within the swept velocities
                ax.annotate("not reached", (x, 0.02), xycoords=("data", "axes fraction"), rotation=90, fontsize=7, ha="center")
    ax.set_xlim(-0.5, len(labels) - 0.5)
    ax.set_xticks(range(len(labels)), [lab or "all runs" for lab in labels], fontsize=8)
    ax.set_ylabel(f"threshold velocity [{vu.label}]")
    ax.set_title(title, fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def run_sweep(
    spec: SweepSpec, out: Path | None, workers: int = 0, scheduler: str | None = None, figures: bool = True, progress: Progress = no_progress, plan=None
):
    """Plan, execute (resuming from ``out``'s checkpoints) and make the files; returns (files, summary)."""
    plan = plan or plan_sweep(spec)
    rows, computed = execute(plan, out, workers, scheduler, progress)
    system = spec.case_data.get("units", "in-lbf-s") if spec.case_data.get("units") in ("in-lbf-s", "SI") else "in-lbf-s"
    return sweep_files(plan, rows, computed, figures, system)


def sweep(spec: str, out_dir: str, workers: int | None = None, scheduler: str | None = None, figures: bool = True, progress: Progress = no_progress) -> Outcome:
    """``softimpact sweep SPEC --out DIR``: the spec is checked whole before anything is written."""
    t0 = time.perf_counter()
    s = load_sweep_spec(spec)
    if workers is None:
        workers = os.cpu_count() or 1
    if workers < 0:
        raise InputError(f"--workers: expected 0 (plain loop) or more, got {workers}")
    plan = plan_sweep(s)  # bad specs fail here, before the checkpoints folder exists
    files, summary = run_sweep(s, Path(out_dir), workers, scheduler, figures, progress, plan)
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


PAPER_BEAMS = ("paper-long-beam", "paper-short-beam")
PAPER_PROJECTILES = {"rubber-3/8in": "0.375 in", "rubber-1/2in": "0.5 in"}  # projectile → its group in the fit


PAPER_PLATE = "plate-ss-8in"
PAPER_PLATE_ELEMENTS = 32  # per side of the quarter: 1/8-in elements (discretisation error in paper_plate_case)
PAPER_PLATE_MESHES = (16, 32, 64)  # the report's plate thresholds: on the finest, with the error over the three
PAPER_DRAWS = 16  # α draws (Latin hypercube) per ball for the report's thresholds
PAPER_PLATE_DURATION = "400 us"  # the index peaks under the load by 250 us at 1000 in/s, by 80 us at 3000 in/s
PAPER_DAMAGE = ["damage.max_strain", "damage.tsai_wu", "damage.hashin", "damage.delamination"]


def paper_plate_case(elements: int = PAPER_PLATE_ELEMENTS, duration: str = PAPER_PLATE_DURATION) -> dict:
    """The built-in 8 × 8 in simply supported [90/0]5s plate as the quarter x, y ≤ 4 in with
    symmetry edges on the centre lines, struck at the centre (the quarter's corner) by a ball
    whose contact disc (r0 0.25 in, as the beams') grows with the force by eq (10); no gauges
    (damage under the impact point only, where it peaks: the case's gauges 1 and 2 in away
    see under half of it).

    Discretisation error (measured on :func:`paper_plate_thresholds`, quarter meshes of 16,
    24, 32, 48 and 64 elements a side): the Tsai–Wu threshold of the 3/8-in ball is 6349,
    5801, 5570, 5396 and 5336 in/s, converging at order ≈ 2 in the element size from 32
    on toward ≈ 5260 in/s; the 32-element quarter's first-ply thresholds are 5–6 % high
    (its indices ≈ 9 % low: Tsai–Wu at 4000 in/s, 1/2-in ball, 1.097, 1.150 and 1.170 on
    32, 48 and 64 elements, extrapolating to ≈ 1.20; the index grows about like V^1.6). Halving the
    1 µs step moves no threshold by 1 in/s. The delamination threshold depends on the
    force alone: no mesh error.

    The element is MITC4, named in the case: its thresholds converge monotonically (the three
    meshes give a Richardson estimate). MITC9, the default element, converges faster in
    the gauge strains of the Navier check but not in the point strain at the corner node
    under the load that the damage indices use: its quarters of 8, 16 and 32 elements give
    5287, 5091 and 5169 in/s (oscillating, ≈ 2 % below MITC4's extrapolation).
    """
    from ..input.toml import load_toml, locate

    data = load_toml(locate(PAPER_PLATE))
    half_x, half_y = (f"{units.parse(data['plate'][k], 'length', k) / 2 / INCH!r} in" for k in ("length", "width"))
    data["title"] = "Quarter of " + data.get("title", PAPER_PLATE)
    data["plate"].update(length=half_x, width=half_y, elements=[elements, elements], element="mitc4")
    data["plate"]["support"] = dict(data["plate"]["support"], x1="symmetry", y1="symmetry")
    data["load"].update(position=[half_x, half_y], contact_radius="0.25 in", grow=True)
    data["solver"]["duration"] = duration
    data.pop("gauges", None)
    return data


def paper_plate_thresholds(draws: int = PAPER_DRAWS, levels: int = 10, meshes: tuple[int, ...] = PAPER_PLATE_MESHES) -> list[dict]:
    """Threshold velocities of :func:`paper_plate_case` for both balls, as :func:`paper_thresholds`
    does for the beams (one plate model and one set of impulse responses for both), with
    their discretisation error.

    The thresholds are computed on each of ``meshes`` (elements a side of the quarter,
    coarse → fine, ratio 2) and reported on the finest, with Richardson's observed order
    and GCI over the last three (:func:`softimpact.workflows.convergence.richardson`,
    safety factor 1.25; an oscillating sequence gets half its range, a diverging one the
    whole of its last change): ``discretisation_error_m_s`` is that GCI in m/s, and the
    5–95 % band of the α draws is widened by it on both sides, so the band covers the
    mesh's error too.
    """
    from ..workflows.convergence import richardson

    per_mesh = [_ball_thresholds(PAPER_PLATE, "8-in plate", draws, levels, paper_plate_case(elements)) for elements in meshes]
    out = []
    for i, row in enumerate(per_mesh[-1]):
        values = np.array([rows[i]["threshold_velocity_median_m_s"] for rows in per_mesh], dtype=float)
        error, order = math.nan, math.nan
        if len(values) >= 3 and np.all(np.isfinite(values[-3:])):
            conv = richardson(values[-3:], 2.0, formal_order=2.0, name=f"{row['levels']} {row['index']}")
            order = conv.order
            gci = conv.gci_fine if math.isfinite(conv.gci_fine) else abs(values[-1] - values[-2]) / abs(values[-1])
            error = gci * abs(values[-1])
        widen = error if math.isfinite(error) else 0.0
        out.append(
            row
            | {
                "threshold_velocity_p05_m_s": row["threshold_velocity_p05_m_s"] - widen,
                "threshold_velocity_p95_m_s": row["threshold_velocity_p95_m_s"] + widen,
                "discretisation_error_m_s": error,
                "observed_order": order,
                "elements": meshes[-1],
            }
        )
    return out


@functools.lru_cache(maxsize=1)
def _paper_fit() -> dict:
    """The scaling.json contents of the built-in rubber series' fit (computed once per process; not to be changed)."""
    from ..input.series import load_series
    from ..input.series_records import read_series_records
    from ..output.scaling_json import scaling_summary
    from ..studies.series import fit_series, reduce_series

    series = load_series("paper-rubber-series")
    return scaling_summary(fit_series(reduce_series(series, *read_series_records(series))))


def _paper_spec(case: str, projectile: str, draws: int, levels: int) -> dict:
    return {
        "sweep": {
            "case": case,
            "method": "latin-hypercube",
            "runs": draws,
            "seed": 1,
            "outputs": list(PAPER_DAMAGE),
            "parameter": [
                {"key": "load.history", "value": {"shape": "empirical", "projectile": projectile, "velocity": "1000 in/s"}},
                {"key": "load.history.velocity", "range": ["1000 in/s", "8000 in/s", levels]},
            ],
        }
    }


def paper_thresholds(draws: int = PAPER_DRAWS, levels: int = 10) -> list[dict]:
    """Threshold velocities of the paper's beams for both balls: the α's drawn from the
    covariance of the built-in rubber series' fit, velocity 1000–8000 in/s (a plain loop)."""
    return [row for beam in PAPER_BEAMS for row in _ball_thresholds(beam, f"{beam.removeprefix('paper-').removesuffix('-beam')} beam", draws, levels)]


def _ball_thresholds(case: str, label: str, draws: int, levels: int, case_data: dict | None = None) -> list[dict]:
    """Threshold velocities of one structure (built-in ``case``, or ``case_data`` in its place) for
    each of the paper's balls, the α's drawn from the covariance of the built-in rubber series'
    fit; one model and one set of impulse responses serve both balls. Rows labelled "label, ball"."""
    import dataclasses

    from ..input.sweep_spec import Scaling, read_sweep_spec, scaling_covariance

    fit = _paper_fit()
    rows, prepared = [], None
    for proj, group in PAPER_PROJECTILES.items():
        spec = read_sweep_spec(_paper_spec(case, proj, draws, levels), Path("."))
        mean, cov = scaling_covariance(fit, group)
        parameters = spec.parameters + (Scaling("load.history", mean, cov, f"paper-rubber-series:{group}"),)
        spec = dataclasses.replace(spec, parameters=parameters, case_data=spec.case_data if case_data is None else case_data)
        plan = plan_sweep(spec)
        base = str(spec.case_path.parent)
        if prepared is None:
            prepared = prepare_group(plan.kind, [plan.chunks[0].items[0][1]], base, len(PAPER_PROJECTILES) * len(plan.runs), spec.outputs)
        done = {r["run"]: r for c in plan.chunks for r in run_chunk(plan.kind, prepared, c.items, base, spec.outputs)}
        rows += [{**t, "levels": f"{label}, {proj}"} for t in thresholds(plan, _table(plan, done))]
    return rows


def threshold_section(figures: bool, files: dict, prefix: str = "thresholds/"):
    """The report section: threshold velocity curves of the paper's beams and of a plate
    (first-ply failure, delamination), each as a CSV and a figure."""
    from ..output.files import csv_text, figure_bytes
    from ..output.report import Section
    from ..units import display

    system = "in-lbf-s"
    vu = display(system, "velocity")
    beams, plate = paper_thresholds(), paper_plate_thresholds()
    figs = []
    for name, th, title, caption in (
        (
            "thresholds",
            beams,
            "Paper's beams: velocity at which a damage index first reaches 1",
            "Threshold velocity by criterion: median and 5-95 % band over the α draws",
        ),
        (
            "plate-thresholds",
            plate,
            "8 x 8 in simply supported [90/0]5s plate, struck at the centre: velocity at which a damage index first reaches 1",
            "The plate's threshold velocity by criterion and ball: median and 5-95 % band over the α draws, widened by the mesh's discretisation error",
        ),
    ):
        keys = list(th[0])
        files[f"{prefix}{name}.csv"] = csv_text({k: np.array([t[k] for t in th], dtype=object if k in ("levels", "index") else float) for k in keys})
        if figures:
            files[f"{prefix}{name}.png"] = figure_bytes(_threshold_figure(th, system, title))
            figs.append((f"{prefix}{name}.png", caption))

    def cell(t):
        if not t["draws_reaching_1"]:
            return "above 8000"
        m, lo, hi = (t[f"threshold_velocity_{q}_m_s"] * vu.factor for q in ("median", "p05", "p95"))
        part = "" if t["draws_reaching_1"] == t["draws"] else f" ({t['draws_reaching_1']}/{t['draws']} draws)"
        return f"{m:.0f} [{lo:.0f}-{hi:.0f}]{part}"

    plate_h = f"{PAPER_PLATE_MESHES[-1]} × {PAPER_PLATE_MESHES[-1]}"
    first_ply = [t for t in plate if t["index"] != "delamination" and math.isfinite(t["discretisation_error_m_s"])]
    plate_err = (
        "first-ply thresholds ± "
        + ", ".join(f"{t['discretisation_error_m_s'] / t['threshold_velocity_median_m_s']:.1%} ({t['index']}, {t['levels'].split(', ')[1]})" for t in first_ply)
        + f", observed orders {min(t['observed_order'] for t in first_ply):.2g}-{max(t['observed_order'] for t in first_ply):.2g}"
        if first_ply
        else "not estimable (a threshold above the range on a mesh)"
    )
    th = beams + plate
    labels = list(dict.fromkeys(t["levels"] for t in th))
    indices = list(dict.fromkeys(t["index"] for t in th))
    rows = [[lab] + [cell(next(t for t in th if t["levels"] == lab and t["index"] == i)) for i in indices] for lab in labels]
    return Section(
        "Damage thresholds of the paper's beams and of a plate",
        [
            "Velocity at which each damage index first reaches 1 (first-ply failure by maximum strain, Tsai-Wu and Hashin; "
            "Davies-Zhang delamination force against the peak force), for the two rubber balls under the empirical "
            f"law, with α1-α4 drawn (Latin hypercube, {PAPER_DRAWS} draws) from the covariance of the built-in rubber series' fit; velocity "
            "levels 1000-8000 in/s (the law is fitted on 1000-5000 in/s: above, an extrapolation). Strengths: T300/5208 values "
            "of Tsai & Hahn standing in for T300/934 (docs/modelling-notes.md). Beams: first-ply failure at the gauge sections.",
            "Plate: the built-in 8 × 8 in simply supported [90/0]5s T300/934 plate (plate-ss-8in) struck at its centre, the "
            "ball's contact disc (0.25 in, growing with the force by eq 10) as on the beams; FSDT on the quarter with symmetry "
            f"edges, 1 µs, through the response engine, on {', '.join(f'{n} × {n}' for n in PAPER_PLATE_MESHES)} elements; "
            f"the thresholds are those of the finest ({plate_h}), and their band is widened on both sides by the "
            "discretisation error estimated from the three meshes (Richardson's observed order, GCI with safety factor 1.25): "
            f"{plate_err}. First-ply failure under the impact point, where it peaks: ply stresses at both faces of every ply "
            "from the top- and bottom-face strains in x, y and 45°. Halving the step changes no threshold by 1 in/s; the "
            "delamination threshold depends on the force alone and has no mesh error. The beams' rows are on the paper's "
            "meshes, whose gauge strains are 1-3 % from converged (section 'Discretisation error'); their bands are the α "
            "draws' only.",
        ],
        [(f"Threshold velocity [{vu.label}]: median [5-95 %]", ["structure, ball"] + indices, rows)],
        figs,
    )
