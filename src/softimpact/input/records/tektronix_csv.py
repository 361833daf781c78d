"""Tektronix TDS1000/TDS2000-series (and TPS2000/TBS1000) CSV: the header beside the data.

Each line holds a header item in columns 1–3 (name, value, an empty cell) and a sample in
columns 4–5 (time [Horizontal Units], value [Vertical Units]), with a trailing comma; the 18 header
rows are Record Length, Sample Interval, Trigger Point, three empty rows, Source, Vertical Units,
Vertical Scale, Vertical Offset, Horizontal Units, Horizontal Scale, Pt Fmt, Yzero, Probe Atten,
Model Number, Serial Number, Firmware Version; later lines have columns 1–3 empty.

Time base: t_k = t_0 + k·Δt with Δt the header's Sample Interval and t_0 the first time stamp;
the time column must agree with it within half a sample (the column is printed rounded, so
stamps may repeat where Δt is below its last digit). The channel is named by Source, the unit
by Vertical Units; Trigger Point (the trigger's sample index) goes to ``metadata["trigger"]`` as a whole number.
"""

from __future__ import annotations

import numpy as np

from ._common import _fail, _finish, _pick, _time_factor

__all__ = ["channels", "read", "looks_like", "HEADER_ITEMS"]

HEADER_ITEMS = 18  # header rows the TDS1000/2000 series writes beside the first samples
FIRST_ITEM = "Record Length"


def looks_like(head: bytes) -> bool:
    """The file starts (after a byte-order mark) with ``Record Length,`` on a line of 5 or more cells."""
    first = head.decode("latin-1").lstrip("\ufeff\xef\xbb\xbf").splitlines()[0] if head.strip() else ""
    return first.startswith(FIRST_ITEM + ",") and first.count(",") >= 4


def _table(path):
    """(header {name: value}, times, values) as written."""
    from .text import _read_lines

    header, t, y = {}, [], []
    for number, line in enumerate(_read_lines(path), start=1):
        if not line.strip():
            continue
        cells = [c.strip() for c in line.split(",")]
        if len(cells) < 5:
            _fail(path, f"line {number} has {len(cells)} cells; a Tektronix TDS CSV line has 5 (header item in columns 1-3, time and value in 4-5)")
        if cells[0]:
            header[cells[0]] = cells[1]
        try:
            t.append(float(cells[3]))
            y.append(float(cells[4]))
        except ValueError:
            _fail(path, f"line {number}: time {cells[3]!r} and value {cells[4]!r} (columns 4-5) must be numbers")
    return header, np.array(t), np.array(y)


def _number(path, header, key):
    try:
        return float(header[key])
    except KeyError:
        _fail(path, f"Tektronix TDS CSV without {key!r} in its header")
    except ValueError:
        _fail(path, f"header item {key!r} = {header[key]!r} is not a number")


def channels(path) -> list[str]:
    """The one channel of the file: its Source (CH1, MATH, …)."""
    header, _, _ = _table(path)
    return [header.get("Source") or "CH1"]


def read(path, channel):
    header, t_col, y = _table(path)
    name = _pick(path, [header.get("Source") or "CH1"], channel)
    dt = _number(path, header, "Sample Interval") * _time_factor(path, header.get("Horizontal Units"))
    if not dt > 0:
        _fail(path, f"Sample Interval {header['Sample Interval']!r} is not positive")
    t_col = t_col * _time_factor(path, header.get("Horizontal Units"))
    t = t_col[0] + dt * np.arange(t_col.size)
    worst = int(np.argmax(np.abs(t - t_col)))
    if abs(t[worst] - t_col[worst]) > 0.5 * dt:
        _fail(
            path,
            f"time column departs from the header's Sample Interval {dt:.6g} s at line {worst + 1} ({t_col[worst]:.9g} s written, {t[worst]:.9g} s expected)",
        )
    n = header.get("Record Length")
    if n is not None and _number(path, header, "Record Length") != t.size:
        _fail(path, f"Record Length {n} in the header, but {t.size} samples in the file (truncated?)")
    trigger = None
    if "Trigger Point" in header:
        k = _number(path, header, "Trigger Point")
        trigger = f"{k:.0f}"  # the trigger's sample index, as the other Tektronix exports give it
    return _finish(path, "tektronix-csv", name, t, y, header.get("Vertical Units"), header, None, trigger)
