"""Files: CSV and JSON writing, and atomic output into a chosen folder.

:func:`write_outputs` is the only way results reach the disk: every file is
first written into a hidden staging folder inside DIR, then moved into place
with :func:`os.replace`, so a run that fails leaves no half-written file that
looks complete, and an input file is never overwritten.
"""

from __future__ import annotations

import io
import json
import math
import os
import shutil
import tempfile
from dataclasses import asdict, is_dataclass
from pathlib import Path

import numpy as np

from . import __version__
from .errors import InputError

__all__ = ["read_strains", "csv_text", "json_text", "write_outputs", "figure_bytes", "jsonable", "read_record", "read_columns"]

# Record headers understood, and their factor to SI.
TIME_COLUMNS = {"time_s": 1.0, "time_ms": 1e-3, "time_us": 1e-6}
SIGNAL_COLUMNS = {"strain": ("strain", 1.0), "microstrain": ("strain", 1e-6), "voltage_V": ("voltage", 1.0)}


def csv_text(columns: dict[str, np.ndarray]) -> str:
    """CSV text of equal-length columns, full precision (repr of float64)."""
    names = list(columns)
    data = [np.asarray(columns[n]) for n in names]
    lengths = {len(d) for d in data}
    if len(lengths) != 1:
        raise ValueError(f"columns of unequal length: {dict(zip(names, map(len, data)))}")
    buf = io.StringIO()
    buf.write(",".join(names) + "\n")
    for row in zip(*data):
        buf.write(",".join(_cell(v) for v in row) + "\n")
    return buf.getvalue()


def _cell(v) -> str:
    if isinstance(v, (str, np.str_)):
        return str(v)
    f = float(v)
    return "" if math.isnan(f) else repr(f)


def jsonable(obj):
    """Dataclasses, numpy scalars and arrays, NaN → JSON-ready values (NaN → null)."""
    if is_dataclass(obj) and not isinstance(obj, type):
        return jsonable(asdict(obj))
    if isinstance(obj, dict):
        return {str(k): jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return jsonable(obj.tolist())
    if isinstance(obj, (np.floating, float)):
        f = float(obj)
        return f if math.isfinite(f) else None
    if isinstance(obj, (np.integer,)):
        return int(obj)
    if isinstance(obj, (np.bool_,)):
        return bool(obj)
    return obj


def json_text(obj) -> str:
    """Indented JSON with ``softimpact_version`` added to a top-level dict."""
    data = jsonable(obj)
    if isinstance(data, dict):
        data = {**data, "softimpact_version": __version__}
    return json.dumps(data, indent=2, allow_nan=False) + "\n"


def figure_bytes(fig, fmt: str = "png") -> bytes:
    """Render a matplotlib figure to bytes and close it."""
    import matplotlib.pyplot as plt

    buf = io.BytesIO()
    fig.savefig(buf, format=fmt, dpi=120, bbox_inches="tight")
    plt.close(fig)
    return buf.getvalue()


def write_outputs(out_dir, files: dict[str, bytes | str], inputs=()) -> list[Path]:
    """Write ``files`` (relative name → content) into ``out_dir`` atomically.

    All files are staged in a hidden folder inside ``out_dir`` and moved into
    place only once all are written. Refuses to overwrite any of ``inputs``.
    Returns the paths written.
    """
    out = Path(out_dir)
    protected = {Path(p).resolve() for p in inputs}
    targets = {name: (out / name) for name in files}
    for name, target in targets.items():
        if target.resolve() in protected:
            raise InputError(f"--out: writing {name} would overwrite the input {target}")
    if out.exists() and not out.is_dir():
        raise InputError(f"--out: {out} exists and is not a folder")
    out.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=".softimpact-", dir=out))
    try:
        for name, content in files.items():
            path = staging / name
            path.parent.mkdir(parents=True, exist_ok=True)
            if isinstance(content, str):
                path.write_text(content, encoding="utf-8")
            else:
                path.write_bytes(content)
        for name, target in targets.items():
            target.parent.mkdir(parents=True, exist_ok=True)
            os.replace(staging / name, target)
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    return list(targets.values())


def read_columns(path) -> tuple[list[str], np.ndarray]:
    """A CSV file with a header row: (names, data of shape (n_rows, n_columns)).

    Empty cells and 'nan' read as NaN (callers decide whether that is an error);
    text that is not a number is an error naming the row and column.
    """
    import csv

    path = Path(path)
    try:
        with open(path, newline="", encoding="utf-8") as fh:
            rows = [r for r in csv.reader(fh) if r and not r[0].lstrip().startswith("#")]
    except OSError as exc:
        raise InputError(f"{path}: cannot read ({exc.strerror})") from None
    except UnicodeDecodeError:
        raise InputError(f"{path}: not a text (CSV) file") from None
    if not rows:
        raise InputError(f"{path}: empty file")
    names = [c.strip() for c in rows[0]]
    data = np.full((len(rows) - 1, len(names)), np.nan)
    for i, row in enumerate(rows[1:]):
        if len(row) != len(names):
            raise InputError(f"{path}: row {i + 2} has {len(row)} cells, the header {len(names)}")
        for j, cell in enumerate(row):
            cell = cell.strip()
            if cell == "":
                continue
            try:
                data[i, j] = float(cell)
            except ValueError:
                raise InputError(f"{path}: row {i + 2}, column {names[j]!r}: {cell!r} is not a number") from None
    return names, data


def _time_column(path, names, data) -> np.ndarray:
    """The record's one time column (time_s, time_ms or time_us), in seconds."""
    tcols = [n for n in names if n in TIME_COLUMNS]
    if len(tcols) != 1:
        raise InputError(f"{path}: needs one time column ({', '.join(TIME_COLUMNS)}), header is {','.join(names)!r}")
    return data[:, names.index(tcols[0])] * TIME_COLUMNS[tcols[0]]


def read_record(path) -> tuple[np.ndarray, np.ndarray, str]:
    """A gauge record: (time [s], signal, kind) with kind 'strain' (SI) or 'voltage' [V].

    The header names the units: a time column (time_s, time_ms, time_us) and a
    signal column (strain, microstrain, voltage_V).
    """
    names, data = read_columns(path)
    t = _time_column(path, names, data)
    scols = [n for n in names if n in SIGNAL_COLUMNS]
    if len(scols) != 1:
        raise InputError(f"{path}: needs one signal column ({', '.join(SIGNAL_COLUMNS)}), header is {','.join(names)!r}")
    kind, factor = SIGNAL_COLUMNS[scols[0]]
    return t, data[:, names.index(scols[0])] * factor, kind


def read_strains(path) -> tuple[np.ndarray, dict]:
    """Measured gauge strains: a time column (time_s, time_ms, time_us) and
    ``strain_<gauge>`` (or ``microstrain_<gauge>``) columns. Returns (time [s], {gauge: strain})."""
    names, data = read_columns(path)
    t = _time_column(path, names, data)
    strains = {}
    for j, n in enumerate(names):
        if n.startswith("strain_"):
            strains[n[len("strain_"):]] = data[:, j]
        elif n.startswith("microstrain_"):
            strains[n[len("microstrain_"):]] = data[:, j] * 1e-6
        elif n not in TIME_COLUMNS:
            raise InputError(f"{path}: column {n!r} is neither time nor strain_<gauge>")
    if not strains:
        raise InputError(f"{path}: no strain_<gauge> columns")
    bad = ~np.isfinite(t) | np.any([~np.isfinite(v) for v in strains.values()], axis=0)
    if bad.any():
        raise InputError(f"{path}: {int(bad.sum())} NaN or empty values (first at row {int(np.argmax(bad)) + 2})")
    return t, strains
