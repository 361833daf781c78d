"""JSON text as every softimpact file writes it: numpy values made plain, NaN as null, the version added."""

from __future__ import annotations

import json
import math
from dataclasses import asdict, is_dataclass

import numpy as np

from .. import __version__

__all__ = ["jsonable", "json_text"]


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


def check_si(data, path, argument: str) -> None:
    """Refuse a file whose ``units`` field says anything but SI (absent: SI, as every file softimpact writes).

    law.json and scaling.json name their keys with SI suffixes (``d_ref_m``, ``velocity_m_s``); a file
    that says ``"units": "in-lbf-s"`` was written by hand or another tool, and reading its numbers as SI
    would silently scale the law (a diameter in inches read as metres). An :class:`InputError` naming
    ``argument`` instead."""
    from ..errors import InputError

    units = data.get("units", "SI") if isinstance(data, dict) else "SI"
    if not isinstance(units, str) or units.strip().upper() != "SI":
        raise InputError(
            f"{argument}: {path} says units {units!r}: only SI files are read (the keys carry SI suffixes: _m, _m_s, _kg); "
            'convert its lengths, velocities and masses to SI and set "units": "SI"'
        )
