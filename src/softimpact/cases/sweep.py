"""Sweeps planned and run: the runs of a spec grouped by structure, cut into chunks, and run
in a plain loop or as Dask tasks, each finished chunk checkpointed.

The spec (:mod:`softimpact.input.sweep_spec`) lists the runs; runs sharing a
structure (same mesh, laminate, support, solver: everything but the load, as the
case's kind says, :meth:`softimpact.cases.CaseKind.structure_key`) form a group
whose expensive part (factorisation, impulse responses) is built once and shared
by its chunks. Chunks run as Dask tasks (a LocalCluster of ``workers`` processes,
or the cluster at ``scheduler``), or in a plain loop (``workers = 0``). Each
finished chunk is checkpointed in ``OUT/checkpoints/<spec fingerprint>/`` through
output's atomic writer (:func:`softimpact.output.sweep.save_checkpoint`): a killed
sweep started again computes only the chunks missing there, so every run is
computed once. Nothing here parses arguments or writes the sweep's files.
"""

from __future__ import annotations

import hashlib
import math
import re
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import HeldWarnings, InputError, SoftimpactWarning
from ..input.sweep_spec import SIZES, Level, SweepSpec, output_unit
from ..models.validity import ValidityWarning
from ..output.sweep import earlier_inputs, load_checkpoint, save_checkpoint, save_inputs
from ..workflows import sweep_stats
from . import KINDS, kind_of
from ._common import flatten

__all__ = [
    "SweepPlan",
    "Chunk",
    "plan_sweep",
    "execute",
    "prepare_group",
    "run_chunk",
    "check_scheduler",
    "run_table",
    "plan_thresholds",
    "plan_onsets",
    "threshold_axis",
    "threshold_outputs",
    "onset_outputs",
    "Axis",
    "sweep_results",
    "CHECKPOINTS",
    "FLAG_COLUMN",
    "validity_counts",
    "warning_counts",
]

Progress = Callable[[int, int, str], None]  # progress(done, total, label)
CHECKPOINTS = "checkpoints"  # folder in OUT holding one JSON file per finished chunk
FLAG_COLUMN = "flag."  # runs.parquet: one boolean column flag.<name> per validity flag raised by any run
BLAS_THREADS = 1  # BLAS threads of a sweep's runs, in the plain loop and in each Dask task (why: _blas_limited)
_ADDRESS = re.compile(r"^(?:(tcp|tls|inproc|ucx|ws|wss)://)?(\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9_.-]+):([0-9]{1,5})$")


def check_scheduler(address: str | None) -> None:
    """Refuse, before anything runs, a --scheduler that is not ``[protocol://]host:port``."""
    if address is None:
        return
    m = _ADDRESS.match(address.strip())
    if not m or not 0 < int(m.group(3)) < 65536:
        raise InputError(f"--scheduler: {address!r} is not an address [tcp://]host:port (port 1-65535), e.g. tcp://127.0.0.1:8786")


@dataclass(frozen=True)
class Chunk:
    """Runs ``items`` [(run index, case dict)] of group ``group`` (of ``group_size`` runs)."""

    name: str
    group: int
    group_size: int
    items: tuple


@dataclass(frozen=True)
class SweepPlan:
    """The runs of ``spec`` (a case of kind ``kind``), in ``groups`` structure groups cut into ``chunks``."""

    spec: SweepSpec
    kind: str
    runs: tuple
    chunks: tuple[Chunk, ...]
    groups: int
    unchecked: tuple[str, ...] = ()  # envelopes its runs do not check (the outputs asked for leave out what they need)


def plan_sweep(spec: SweepSpec) -> SweepPlan:
    """Runs, grouped by structure and cut into chunks; checks the first run's case and the outputs."""
    kind = kind_of(spec.case_data, f"sweep.case ({spec.case_path.name})")
    _check_threshold_keys(spec)
    runs = spec.runs()
    cases = [spec.case_for(r, kind.expand) for r in runs]
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
            checked = kind.problem(spec.case_for(central[i], kind.expand), base)
            kind.check(checked)  # the command's discretisation floors and resource guards, before any run
            why = kind.refusal(checked, "a sweep")  # a kind of run a sweep does not take: refused now, not run by run
            if why is not None:
                raise InputError(why)
        except InputError as exc:
            raise InputError(f"sweep: {spec.case_path.name}: {exc}") from None
        if i == 0:
            problem = checked
    known = kind.output_keys(problem)
    for o in spec.outputs:
        if o not in known and o.startswith("damage."):
            why = kind.damage_refusal(problem)
            if why is not None:
                raise InputError(f"sweep.outputs: {o!r}: {why}")
        if o not in known:
            import difflib

            near = difflib.get_close_matches(o, known, n=1, cutoff=0.75)
            hint = f"did you mean {near[0]!r}? " if near else ""
            raise InputError(
                f"sweep.outputs: {o!r} is not an output of {'an' if kind.name[:1] in 'aeiou' else 'a'} {kind.name} case ({hint}known: {', '.join(known)})"
            )
    groups: dict[str, list[int]] = {}
    for r, data in zip(runs, cases):
        groups.setdefault(kind.structure_key(data), []).append(r.index)
    chunks = []
    for g, members in enumerate(groups.values()):
        for k in range(0, len(members), spec.chunk):
            part = members[k : k + spec.chunk]
            chunks.append(Chunk(f"chunk-{g:05d}-{k // spec.chunk:05d}", g, len(members), tuple((i, cases[i]) for i in part)))
    # An impact's strains are checked against the ply allowables only on its damage output group, which its
    # runs carry when a damage output (or the index itself) is asked for.
    unchecked = ()
    if "validity.max_strain_index" in known and not any(o.startswith("damage.") or o == "validity.max_strain_index" for o in spec.outputs):
        unchecked = ("strains against the ply allowables (ask for validity.max_strain_index or a damage.* output)",)
    return SweepPlan(spec, kind.name, tuple(runs), tuple(chunks), len(groups), unchecked)


def _check_threshold_keys(spec: SweepSpec) -> None:
    """Limits and onsets need a level to be found against, and threshold_against something to find: refused, not ignored."""
    if threshold_axis(spec) is None and (spec.limits or spec.onset):
        key = "sweep.limits" if spec.limits else "sweep.onset"
        raise InputError(f"{key}: a threshold or onset is found against a level: give a velocity level or sweep.threshold_against (levels of a quantity)")
    if spec.threshold_against and not threshold_outputs(spec) and not onset_outputs(spec):
        raise InputError(
            f"sweep.threshold_against = {spec.threshold_against!r}: no output has a threshold or an onset "
            "(a damage.* index, an output with a limit in [sweep.limits], or a damage.* size)"
        )


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
    ``outputs``: the spec's, so the kind may leave out what none of them needs."""
    first = None
    for data in candidates:
        try:
            with _Caught():  # the runs read their cases again and keep their warnings (run_chunk)
                # the shared part covers every run of the group (an impact's kernels: the widest contact)
                return KINDS[kind].prepare(data, Path(base), runs, tuple(outputs), tuple(candidates))
        except Exception as exc:  # a drawn structure can be invalid: its runs fail, the sweep goes on
            first = first or _Failed(_one_line(exc))
            if runs == 1:
                break
    return first


class _Caught(HeldWarnings):
    """The :class:`~softimpact.errors.SoftimpactWarning` s raised inside the block, none shown
    (:class:`~softimpact.errors.HeldWarnings`): the validity flags among them by kind (``flags``:
    :class:`~softimpact.models.validity.ValidityWarning`'s names, e.g. a law extrapolated in velocity), the
    others as one-line texts (``texts``; each once, in order)."""

    def __exit__(self, *exc):
        super().__exit__(*exc)
        self.texts: list[str] = []
        self.flags: list[str] = []
        for w in self.held:
            if isinstance(w.message, ValidityWarning) and w.message.flag:
                if w.message.flag not in self.flags:
                    self.flags.append(w.message.flag)
            else:
                text = _one_line_text(w.message)
                if text not in self.texts:
                    self.texts.append(text)
        return False


def _one_line_text(message) -> str:
    lines = str(message).strip().splitlines()
    return lines[0] if lines else ""


def run_chunk(kind: str, prepared, items, base: str, outputs) -> list[dict]:
    """Runs of one chunk → rows {run, outputs (dict or None), error (None or one line), flags, warnings}:
    ``flags`` the names of the run's validity flags (the kind's ``validity_flags``, :mod:`softimpact.models.validity`),
    and those its case raised when read (a law's fitted ranges, :func:`softimpact.models.validity.warn`), ``warnings``
    the texts of the other warnings its case raised: kept with the run (they travel back from Dask workers and into
    the checkpoints) and shown by the sweep once each, not once per run."""
    case_kind = KINDS[kind]
    rows = []
    for run, data in items:
        if isinstance(prepared, _Failed):
            rows.append({"run": run, "outputs": None, "error": prepared.reason, "flags": [], "warnings": []})
            continue
        with _Caught() as caught:
            try:
                flat = flatten(case_kind.run(prepared, data, Path(base), tuple(outputs)))
                row = {"run": run, "outputs": {o: float(flat[o]) for o in outputs}, "error": None}
                row["flags"] = list(flat.get("validity_flags", ()))
            except Exception as exc:  # recorded with its reason; the sweep goes on
                row = {"run": run, "outputs": None, "error": _one_line(exc), "flags": []}
        # the flags raised while its case was read (a law's fitted range), then the run's own
        rows.append({**row, "flags": list(dict.fromkeys(caught.flags + row["flags"])), "warnings": caught.texts})
    return rows


def group_chunk(kind: str, base: str, runs: int, items, outputs) -> list[dict]:
    """A group of one chunk as one task: prepare and run where the data is."""
    return run_chunk(kind, prepare_group(kind, [d for _, d in items], base, runs, outputs), items, base, outputs)


def _blas_limited():
    """The BLAS thread pools held to :data:`BLAS_THREADS` (threadpoolctl) while a sweep's chunks run. A run's products
    are small, and OpenBLAS splits those past ~10 000 terms (a kernel run's history dot product) over its threads,
    which spin waiting for a core another process holds: beside one busy process on a 2-core machine a 20 000-term
    dot product took 1.6 ms on two threads against 55 µs on one, and a 50-run chunk of the plate's Monte Carlo
    minutes instead of seconds (benchmarks/bench_sweep_busy.py). Dask's nanny already starts its workers with one
    BLAS thread (its ``pre-spawn-environ``); the plain loop runs in the user's process, which had the default."""
    from threadpoolctl import threadpool_limits

    return threadpool_limits(BLAS_THREADS, user_api="blas")


def _limited(fn, *args):
    """``fn(*args)`` under :func:`_blas_limited`: a Dask task of the sweep (whatever the worker's environment)."""
    with _blas_limited():
        return fn(*args)


def _local_workers(workers: int) -> int:
    """At most the cores this process may run on: each worker runs one run at a time, and more workers than cores
    only share them (with the scheduler's and the nanny's processes besides)."""
    import os

    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1
    return max(1, min(workers, cores))


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
        cluster = LocalCluster(n_workers=_local_workers(workers), threads_per_worker=1, processes=True, dashboard_address=None)
    return Client(cluster), cluster


def execute(plan: SweepPlan, out: Path | None, workers: int = 0, scheduler: str | None = None, progress: Progress | None = None) -> tuple[dict, int]:
    """Run the plan's missing chunks; returns ({run: row}, runs computed now).

    With ``out``, finished chunks are read from and written to its checkpoints.
    ``workers = 0`` without ``scheduler`` runs a plain loop in this process.
    """
    spec, kind = plan.spec, plan.kind
    progress = progress or (lambda done, total, label: None)
    base = str(spec.case_path.parent)
    folder = None if out is None else Path(out) / CHECKPOINTS / spec.fingerprint
    if folder is not None:
        _check_inputs(folder, spec)
    rows: dict[int, dict] = {}
    pending = []
    for c in plan.chunks:
        done = None if folder is None else load_checkpoint(folder, c.name, [i for i, _ in c.items])
        if done is None:
            pending.append(c)
        else:
            rows.update({r["run"]: r for r in done})
    total = len(plan.runs)
    progress(len(rows), total, "runs")

    def finish(chunk, result):
        if folder is not None:
            save_checkpoint(folder, chunk.name, result)
        rows.update({r["run"]: r for r in result})
        progress(len(rows), total, "runs")

    by_group: dict[int, list[Chunk]] = {}
    for c in pending:
        by_group.setdefault(c.group, []).append(c)
    if workers == 0 and not scheduler:
        with _blas_limited():
            for chunks in by_group.values():
                prepared = prepare_group(kind, [d for c in chunks for _, d in c.items], base, chunks[0].group_size, spec.outputs)
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
                f = client.submit(_limited, group_chunk, kind, base, first.group_size, first.items, spec.outputs, pure=False)
                futures[f] = first
                continue
            group = [d for c in chunks for _, d in c.items]
            prepared = client.submit(_limited, prepare_group, kind, group, base, first.group_size, spec.outputs, pure=False)
            for c in chunks:
                futures[client.submit(_limited, run_chunk, kind, prepared, c.items, base, spec.outputs, pure=False)] = c
        for f in as_completed(list(futures)):
            finish(futures[f], f.result())
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    return rows, sum(len(c.items) for c in pending)


def _inputs(spec: SweepSpec) -> tuple[str, dict]:
    """The spec's file and {file: sha256} of it and of every file its runs read (:attr:`SweepSpec.inputs`)."""
    name = str(Path(spec.path).resolve())
    files = dict(spec.inputs)
    if Path(spec.path).is_file():
        files[name] = hashlib.sha256(Path(spec.path).read_bytes()).hexdigest()
    return name, files


def _check_inputs(folder: Path, spec: SweepSpec) -> None:
    """A sweep whose inputs changed since checkpoints were made in the same --out starts afresh in its own
    fingerprint folder (the old one is kept: undoing the edit resumes it) and warns naming the files that changed."""
    name, files = _inputs(spec)
    if not folder.is_dir():
        before = earlier_inputs(folder.parent, name, folder.name)
        if before is not None:
            changed = sorted(f for f in set(files) | set(before) if files.get(f) != before.get(f))
            if changed:
                words = "; ".join(f"{f} ({'new' if f not in before else 'gone' if f not in files else 'edited'})" for f in changed)
                warnings.warn(
                    SoftimpactWarning(
                        f"sweep: inputs changed since the checkpoints in {folder.parent}: {words}; every run is computed afresh (checkpoints {folder.name})"
                    ),
                    stacklevel=2,
                )
    save_inputs(folder, name, files)


def run_table(plan: SweepPlan, rows: dict) -> dict[str, np.ndarray | list]:
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
    # Validity (models.validity): the run's flags by name, and one boolean column per flag any run raised, to filter on.
    flags = [rows[r.index].get("flags", []) for r in plan.runs]
    cols["validity_flags"] = [", ".join(f) for f in flags]
    for name in dict.fromkeys(n for f in flags for n in f):
        cols[f"{FLAG_COLUMN}{name}"] = np.array([name in f for f in flags], dtype=bool)
    cols["warnings"] = [" | ".join(rows[r.index].get("warnings", [])) for r in plan.runs]
    return cols


def validity_counts(plan: SweepPlan, rows: dict) -> dict:
    """summary.json's ``validity``: how many runs raised any validity flag and, per flag
    (:data:`softimpact.models.validity.FLAG_LABELS`), how many runs raised it, with its words."""
    from ..models.validity import FLAG_LABELS

    flags = [rows[r.index].get("flags", []) for r in plan.runs]
    per = {name: sum(name in f for f in flags) for name in dict.fromkeys(n for f in flags for n in f)}
    return {
        "runs_outside_envelope": sum(bool(f) for f in flags),
        "runs_per_flag": per,
        "labels": {name: FLAG_LABELS.get(name, name) for name in per},
        "note": f"per run in runs.parquet: validity_flags (names) and one boolean column {FLAG_COLUMN}<name> per flag",
    }


def warning_counts(plan: SweepPlan, rows: dict) -> list[dict]:
    """summary.json's ``run_warnings``: each distinct warning the runs' cases raised, with how many runs raised it."""
    counts: dict[str, int] = {}
    for r in plan.runs:
        for text in rows[r.index].get("warnings", []):
            counts[text] = counts.get(text, 0) + 1
    return [{"warning": text, "runs": n} for text, n in counts.items()]


def _velocity_key(spec: SweepSpec) -> str | None:
    keys = [p.key for p in spec.parameters if isinstance(p, Level) and p.key.endswith("velocity") and all(isinstance(v, float) for v in p.si)]
    return keys[0] if keys else None


_QUANTITY_OF = {"hail": "diameter", "bird": "mass"}  # a threat's key names the threat; its value is its size
_UNIT_SUFFIX = {"m/s": "m_s", "N*s": "N_s", "kg/m^3": "kg_m3", "J/m^2": "J_m2", "N*m": "N_m", "N/m^3": "N_m3"}  # others: as written


@dataclass(frozen=True)
class Axis:
    """The level thresholds and onsets are found against: its case ``key``, the ``quantity`` it names (the key's last
    part: ``velocity``, ``energy``, ``diameter``; a hail threat's ``diameter``, a bird's ``mass``), its SI ``unit`` and
    the ``suffix`` of its columns (``m_s``, ``J``, ``m``)."""

    key: str
    quantity: str
    unit: str
    suffix: str

    def columns(self) -> dict:
        """The names a threshold row carries to say what it is against (summary.json, thresholds.csv)."""
        return {"against": self.key, "quantity": self.quantity, "unit": self.suffix}


def threshold_axis(spec: SweepSpec) -> Axis | None:
    """The spec's ``threshold_against`` level, else its velocity level (None: neither)."""
    key = spec.threshold_against or _velocity_key(spec)
    if key is None:
        return None
    level = next(p for p in spec.parameters if isinstance(p, Level) and p.key == key)
    last = key.split(".")[-1]
    quantity = re.sub(r"[^a-z0-9]+", "_", _QUANTITY_OF.get(last, last).lower()).strip("_") or "level"
    unit = level.unit or ""
    if key.endswith("velocity") and not unit:
        unit = "m/s"  # levels given as case values written back in SI
    return Axis(key, quantity, unit, _UNIT_SUFFIX.get(unit, unit.replace("^", "").replace("/", "_").replace("*", "_")))


def threshold_outputs(spec: SweepSpec) -> dict[str, float]:
    """The outputs with a threshold, each with the value its index divides by: every ``damage.*`` index (no unit
    suffix, :func:`~softimpact.input.sweep_spec.output_unit`: 1 at onset) by 1, and every output with a limit
    (``[sweep.limits]``) by its limit [SI], in the order of ``outputs``. Forces, stresses and sizes have a threshold
    only with a limit (a force of 1 N, a dent of 1 m mean nothing)."""
    limits = {lim.output: lim.value for lim in spec.limits}
    return {o: limits.get(o, 1.0) for o in spec.outputs if o in limits or (o.startswith("damage.") and not output_unit(o))}


def onset_outputs(spec: SweepSpec) -> tuple[str, ...]:
    """The outputs whose onset is reported: ``[sweep] onset`` when given, else every ``damage.*`` size (a length,
    area or volume: zero until the damage starts, as a dent's depth or a delaminated area)."""
    if spec.onset is not None:
        return spec.onset
    return tuple(o for o in spec.outputs if o.startswith("damage.") and output_unit(o) in SIZES)


def _against(plan: SweepPlan, cols: dict) -> tuple[Axis, list[str], np.ndarray, list] | None:
    """The axis, each run's label of the other levels, each run's draw and each run's validity flags."""
    spec = plan.spec
    axis = threshold_axis(spec)
    if axis is None:
        return None
    others = [p.key for p in spec.parameters if isinstance(p, Level) and p.key != axis.key]
    labels = [" ".join(str(cols[k][i]) for k in others) for i in range(len(plan.runs))]
    draws = np.array([r.draw for r in plan.runs])
    flags = [[f for f in text.split(", ") if f] for text in cols.get("validity_flags", [""] * len(plan.runs))]
    return axis, labels, draws, flags


def plan_thresholds(plan: SweepPlan, cols: dict) -> list[dict]:
    """Thresholds of the plan's damage indices and limited outputs (:func:`threshold_outputs`) against its
    ``threshold_against`` level, else its velocity level (:func:`threshold_axis`;
    :func:`softimpact.workflows.sweep_stats.thresholds`), per combination of the other levels; each row says what it is
    against (``against``, ``quantity``, ``unit``), its limit (``limit`` as written, ``limit_si``; empty for an index)
    and the validity of the runs it rests on. [] without such a level or such an output."""
    spec = plan.spec
    found = _against(plan, cols)
    outputs = threshold_outputs(spec)
    if found is None or not outputs:
        return []
    axis, labels, draws, flags = found
    given = {lim.output: lim for lim in spec.limits}
    rows = sweep_stats.thresholds(
        np.asarray(cols[axis.key], float),
        labels,
        draws,
        {o: np.asarray(cols[o], float) / by for o, by in outputs.items()},
        quantity=axis.quantity,
        unit=axis.suffix,
        flags=flags,
    )
    names = list(outputs)
    for k, row in enumerate(rows):  # the rows run over the outputs, in order, for each combination of the other levels
        lim = given.get(names[k % len(names)])
        row.update(axis.columns())
        row.update({"limit": "" if lim is None else str(lim.given), "limit_si": math.nan if lim is None else lim.value})
    return rows


def plan_onsets(plan: SweepPlan, cols: dict) -> list[dict]:
    """Onsets of the plan's sizes (:func:`onset_outputs`) against the same level as its thresholds
    (:func:`softimpact.workflows.sweep_stats.onsets`), per combination of the other levels; [] without them."""
    found = _against(plan, cols)
    sizes = onset_outputs(plan.spec)
    if found is None or not sizes:
        return []
    axis, labels, draws, flags = found
    rows = sweep_stats.onsets(
        np.asarray(cols[axis.key], float), labels, draws, {o: cols[o] for o in sizes}, quantity=axis.quantity, unit=axis.suffix, flags=flags
    )
    for row in rows:
        row.update(axis.columns())
    return rows


def sweep_results(plan: SweepPlan, rows: dict, computed: int) -> tuple[dict, dict, list[dict]]:
    """The run table (columns), the summary (counts, failures, statistics, Spearman and Sobol
    sensitivities per output; ``thresholds`` and ``onsets`` when there are any) and the thresholds of finished
    ``rows``; ``computed``: runs computed now."""
    from .. import __version__

    spec = plan.spec
    cols = run_table(plan, rows)
    varied = {k: cols[k] for k in cols if k not in spec.outputs and k not in ("run", "error", "validity_flags", "warnings") and not k.startswith(FLAG_COLUMN)}
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
        "validity": {**validity_counts(plan, rows), "not_checked": list(plan.unchecked)},
        "run_warnings": warning_counts(plan, rows),
        "statistics": {o: sweep_stats.statistics(cols[o]) for o in spec.outputs},
        "sensitivity_spearman": {o: sweep_stats.sensitivity(varied, np.asarray(cols[o], float)) for o in spec.outputs},
        "sensitivity_sobol_first_order": {o: sweep_stats.sobol_first_order(varied, np.asarray(cols[o], float)) for o in spec.outputs},
    }
    th = plan_thresholds(plan, cols)
    if th:
        summary["thresholds"] = th
    onsets = plan_onsets(plan, cols)
    if onsets:
        summary["onsets"] = onsets
    return cols, summary, th
