"""Record files: CSV with a header row, read into SI arrays.

A bar record holds a time column (``time_s``, ``time_ms`` or ``time_us``) and a
signal column (``strain``, ``microstrain`` or ``voltage_V``); measured beam
strains hold a time column and ``strain_<gauge>`` columns. Errors name the
file, the row and the column. A UTF-8 byte-order mark (Excel's "CSV UTF-8") is
accepted; the delimiter is a comma, or a semicolon or tab found in the header
row (spreadsheets in many locales write those, with a decimal comma, also read).
"""

from __future__ import annotations

import math
import re
import warnings
from pathlib import Path

import numpy as np

from ...errors import InputError, SoftimpactWarning

__all__ = ["TIME_COLUMNS", "SIGNAL_COLUMNS", "read_columns", "read_record", "read_strains"]

# Record headers understood, and their factor to SI.
TIME_COLUMNS = {"time_s": 1.0, "time_ms": 1e-3, "time_us": 1e-6}
SIGNAL_COLUMNS = {"strain": ("strain", 1.0), "microstrain": ("strain", 1e-6), "voltage_V": ("voltage", 1.0)}


DELIMITERS = {",": "comma", ";": "semicolon", "\t": "tab"}
_DECIMAL_COMMA = re.compile(r"^[+-]?\d*,\d+([eE][+-]?\d+)?$")


def _delimiter(header: str) -> str:
    """The delimiter of a header row: the one of DELIMITERS it holds most of (comma when none)."""
    counts = {d: header.count(d) for d in DELIMITERS}
    best = max(counts, key=counts.get)
    return best if counts[best] else ","


def read_columns(path) -> tuple[list[str], np.ndarray]:
    """A CSV file with a header row: (names, data of shape (n_rows, n_columns)).

    Empty cells and 'nan' read as NaN (callers decide whether that is an error);
    text that is not a number is an error naming the row, the column and the
    delimiter used. Infinite values are refused.
    """
    import csv

    path = Path(path)
    try:
        with open(path, newline="", encoding="utf-8-sig") as fh:
            lines = [line for line in fh if line.strip() and not line.lstrip().startswith("#")]
    except OSError as exc:
        raise InputError(f"{path}: cannot read ({exc.strerror})") from None
    except UnicodeDecodeError:
        raise InputError(f"{path}: not a text (CSV) file (UTF-8 expected)") from None
    if not lines:
        raise InputError(f"{path}: empty file")
    delim = _delimiter(lines[0])
    try:
        rows = [r for r in csv.reader(lines, delimiter=delim) if r]
    except csv.Error as exc:
        raise InputError(f"{path}: not a CSV file ({exc})") from None
    names = [c.strip() for c in rows[0]]
    data = np.full((len(rows) - 1, len(names)), np.nan)
    for i, row in enumerate(rows[1:]):
        if len(row) != len(names):
            raise InputError(f"{path}: row {i + 2} has {len(row)} cells, the header {len(names)} ({DELIMITERS[delim]}-separated)")
        for j, cell in enumerate(row):
            cell = cell.strip()
            if cell == "":
                continue
            if delim != "," and _DECIMAL_COMMA.match(cell):
                cell = cell.replace(",", ".")  # ';'- and tab-separated files of many locales write 1,5
            try:
                value = float(cell)
            except ValueError:
                raise InputError(f"{path}: row {i + 2}, column {names[j]!r}: {cell!r} is not a number ({DELIMITERS[delim]}-separated)") from None
            if math.isinf(value):
                raise InputError(f"{path}: row {i + 2}, column {names[j]!r}: {cell!r} is not finite")
            data[i, j] = value
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
    ``strain_<gauge>`` (or ``microstrain_<gauge>``) columns. Returns (time [s], {gauge: strain}).

    Other columns (the ``contact_force_N`` of a history.csv that softimpact
    itself wrote) are ignored, with a :class:`SoftimpactWarning` naming them.
    """
    names, data = read_columns(path)
    t = _time_column(path, names, data)
    strains, ignored = {}, []
    for j, n in enumerate(names):
        if n.startswith("strain_"):
            strains[n[len("strain_") :]] = data[:, j]
        elif n.startswith("microstrain_"):
            strains[n[len("microstrain_") :]] = data[:, j] * 1e-6
        elif n not in TIME_COLUMNS:
            ignored.append(n)
    if not strains:
        raise InputError(f"{path}: no strain_<gauge> columns (header is {','.join(names)!r})")
    if ignored:
        warnings.warn(f"{path}: ignored column(s) {', '.join(ignored)} (neither time nor strain_<gauge>)", SoftimpactWarning, stacklevel=2)
    bad = ~np.isfinite(t) | np.any([~np.isfinite(v) for v in strains.values()], axis=0)
    if bad.any():
        raise InputError(f"{path}: {int(bad.sum())} NaN or empty values (first at row {int(np.argmax(bad)) + 2})")
    return t, strains
