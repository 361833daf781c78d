"""Output files: CSV and JSON text, figures as bytes, and atomic writes into a folder.

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

from .. import __version__
from ..errors import InputError

__all__ = ["csv_text", "json_text", "jsonable", "figure_bytes", "write_outputs"]


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
