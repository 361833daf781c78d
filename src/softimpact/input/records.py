"""Record files: CSV with a header row, read into SI arrays.

A bar record holds a time column (``time_s``, ``time_ms`` or ``time_us``) and a
signal column (``strain``, ``microstrain`` or ``voltage_V``); measured beam
strains hold a time column and ``strain_<gauge>`` columns. Errors name the
file, the row and the column.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..errors import InputError

__all__ = ["TIME_COLUMNS", "SIGNAL_COLUMNS", "read_columns", "read_record", "read_strains"]

# Record headers understood, and their factor to SI.
TIME_COLUMNS = {"time_s": 1.0, "time_ms": 1e-3, "time_us": 1e-6}
SIGNAL_COLUMNS = {"strain": ("strain", 1.0), "microstrain": ("strain", 1e-6), "voltage_V": ("voltage", 1.0)}


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
            strains[n[len("strain_") :]] = data[:, j]
        elif n.startswith("microstrain_"):
            strains[n[len("microstrain_") :]] = data[:, j] * 1e-6
        elif n not in TIME_COLUMNS:
            raise InputError(f"{path}: column {n!r} is neither time nor strain_<gauge>")
    if not strains:
        raise InputError(f"{path}: no strain_<gauge> columns")
    bad = ~np.isfinite(t) | np.any([~np.isfinite(v) for v in strains.values()], axis=0)
    if bad.any():
        raise InputError(f"{path}: {int(bad.sum())} NaN or empty values (first at row {int(np.argmax(bad)) + 2})")
    return t, strains
