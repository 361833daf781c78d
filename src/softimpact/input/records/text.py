"""Delimited text (.csv .txt .tsv .dat) with vendor metadata lines (Tektronix, LeCroy, PicoScope,
Excel exports): ``key<delimiter>value`` lines, a header row (units as "Time (s)", "CH1 [mV]" or on a
units row "(us),(mV)"), then numbers; time from a time column, else a sample interval among the
metadata lines. Delimiters , ; and tab are sniffed; a UTF-8 byte-order mark and decimal commas
(European Excel) are accepted."""

from __future__ import annotations

import re

import numpy as np

from ._common import _TIME_UNITS, TIME_NAMES, _fail, _finish, _norm, _pick, _time_factor, _uniform_time

__all__ = ["channels", "read"]


_NUMBER = re.compile(r"^[+-]?(\d+([.,]\d*)?|[.,]\d+)([eE][+-]?\d+)?$")
_UNIT_IN_NAME = re.compile(r"^(.*?)[\s_]*[\(\[]\s*([^\)\]]*)\s*[\)\]]\s*$")
# softimpact's own record columns carry their unit in the name (input/records/softimpact_csv.py)
_OWN_COLUMNS = {"time_s": ("time", "s"), "time_ms": ("time", "ms"), "time_us": ("time", "us"), "strain": ("strain", "strain")}
_OWN_COLUMNS |= {"microstrain": ("strain", "microstrain"), "voltage_V": ("voltage", "V")}
_DT_KEYS = ("sample interval", "sampling interval", "sample period", "horizontal interval", "xincr", "dt", "time interval")
_T0_KEYS = ("horizontal offset", "trigger offset", "xzero", "t0", "start time", "time offset")
_DATE_KEYS = ("date", "trigger date", "time stamp", "timestamp", "trigtime", "date/time", "created")


def _read_lines(path):
    raw = path.read_bytes()
    for enc in ("utf-8-sig", "cp1252", "latin-1"):
        try:
            text = raw.decode(enc)
            break
        except UnicodeDecodeError:
            continue
    return text.splitlines()


def _split(line, delim):
    import csv

    return [c.strip() for c in next(csv.reader([line], delimiter=delim))] if line.strip() else []


def _is_num(cell, decimal_comma):
    c = cell.strip()
    if decimal_comma:
        c = c.replace(",", ".")
    return bool(_NUMBER.match(c)) or c.lower() in ("nan", "inf", "-inf", "+inf")


def _text_table(path):
    """(metadata pairs, column names, column units, data rows as strings, decimal_comma, their line numbers)."""
    lines = [ln for ln in _read_lines(path)]
    body = [ln for ln in lines if ln.strip()]
    if not body:
        _fail(path, "empty file")
    tail = body[-min(20, len(body)) :]
    best = None
    for delim in (",", ";", "\t"):
        split = [_split(ln, delim) for ln in tail]
        counts = [len(r) for r in split]
        width = max(set(counts), key=counts.count)
        dc = delim != "," and any(re.search(r"\d,\d", ln) for ln in tail)
        numeric = sum(all(_is_num(c, dc) for c in r) for r in split)
        score = (numeric, width > 1, counts.count(width), width)
        if best is None or score > best[0]:
            best = (score, delim, width)
    _, delim, width = best
    decimal_comma = delim != "," and any(re.search(r"\d,\d", ln) for ln in tail) and not any(re.search(r"\d\.\d", ln) for ln in tail)
    rows = [_split(ln, delim) for ln in lines]

    def data_like(r):  # most of its cells are numbers: a data row, even with a bad cell
        cells = [c for c in r[:width]]
        return bool(cells) and 2 * sum(_is_num(c, decimal_comma) for c in cells) >= len(cells) and any(cells)

    # The data block: the run of data-like rows (blank lines allowed) that ends the file.
    end = len(rows)
    while end > 0 and not rows[end - 1]:
        end -= 1
    start = end
    while start > 0 and (not rows[start - 1] or data_like(rows[start - 1])):
        start -= 1
    while start < end and not rows[start]:
        start += 1
    line_numbers = [k + 1 for k in range(start, end) if rows[k]]
    data = [r for r in rows[start:end] if r]
    if not data:
        _fail(path, "no numeric data rows found")
    # Rows above the data: a units row like "(us),(mV)", the header row, metadata lines.
    above = [r for r in rows[:start] if r and any(c for c in r)]
    units = [None] * width
    if above and all(re.fullmatch(r"[\(\[].*[\)\]]", c) or c == "" for c in above[-1][:width]):
        units = [c.strip("()[] ") or None for c in (above[-1] + [""] * width)[:width]]
        above = above[:-1]
    names = None
    if above and len(above[-1]) >= width and not all(c == "" for c in above[-1][:width]):
        names = above[-1][:width]
        above = above[:-1]
    metadata = {}
    for r in above:
        key = r[0].strip().lstrip("#").strip()
        if key:
            metadata[key] = ", ".join(c for c in r[1:] if c)
    if names is None:
        names = [f"column {j + 1}" for j in range(width)]
    clean = []
    for j, n in enumerate(names):
        m = _UNIT_IN_NAME.match(n)
        if m and units[j] is None:
            units[j] = m.group(2).strip() or None
            n = m.group(1).strip() or n
        elif units[j] is None and n.strip() in _OWN_COLUMNS:
            n, units[j] = _OWN_COLUMNS[n.strip()]
        clean.append(n or f"column {j + 1}")
    # Rows shorter than the header are unequal lengths, not blanks.
    for i, r in enumerate(data):
        if len(r) < width:
            _fail(path, f"line {line_numbers[i]} has {len(r)} cells, the header {width}: columns of unequal length")
    return metadata, clean, units, data, decimal_comma, line_numbers


def _is_time_name(name, unit):
    n = _norm(name)
    if n in TIME_NAMES or n.startswith("time") or n in ("zeit", "temps"):
        return True
    return unit is not None and unit.strip().lower().replace("μ", "µ") in _TIME_UNITS and n in ("", "x", "column_1")


def _meta_value(metadata, keys):
    for k, v in metadata.items():
        if _norm(k).replace("_", " ") in keys:
            return v
    return None


def _header_time(path, text: str, what: str) -> float:
    """A time in the header [s]: its number and the unit written after it in the same or the next cell
    ("0.5 us", "0.5,us", "5E-07 s"; none: seconds, as the vendors write them); a unit that is not a time
    unit is refused naming it, never read as seconds."""
    cells = [c.strip() for c in str(text).split(",") if c.strip()]
    words = cells[0].split() if cells else []
    try:
        value = float(words[0])
    except (ValueError, IndexError):
        _fail(path, f"{what} {text!r} in the header is not a number")
    unit = " ".join(words[1:]) or (cells[1] if len(cells) > 1 else None)
    return value * _time_factor(path, unit)


def _read_text(path, channel, list_only=False):
    metadata, names, units, data, decimal_comma, line_numbers = _text_table(path)
    tcols = [j for j, n in enumerate(names) if _is_time_name(n, units[j])]
    tcol = tcols[0] if tcols else None
    chans = [n for j, n in enumerate(names) if j != tcol]
    if list_only:
        return chans
    name = _pick(path, chans, channel)
    j = names.index(name)

    def column(k):
        out = np.empty(len(data))
        for i, r in enumerate(data):
            cell = r[k].strip()
            if cell == "":
                _fail(path, f"line {line_numbers[i]}, column {names[k]!r}: empty cell (columns of unequal length?)")
            try:
                out[i] = float(cell.replace(",", ".") if decimal_comma else cell)
            except ValueError:
                _fail(path, f"line {line_numbers[i]}, column {names[k]!r}: {cell!r} is not a number")
        return out

    y = column(j)
    if tcol is not None:
        t = column(tcol) * _time_factor(path, units[tcol])
    else:
        dt_text = _meta_value(metadata, _DT_KEYS)
        t0_text = _meta_value(metadata, _T0_KEYS)
        dt = _header_time(path, dt_text, "sample interval") if dt_text else None
        t0 = _header_time(path, t0_text, "start time") if t0_text else 0.0
        t = _uniform_time(path, y.size, dt=dt, t0=t0)
        if t is None:
            _fail(path, "no time base: no time column and no sample interval in the header")
    date = _meta_value(metadata, _DATE_KEYS)
    return _finish(path, "text", name, t, y, units[j], metadata, date, None)


def channels(path) -> list[str]:
    """Column names other than the time column."""
    return _read_text(path, None, list_only=True)


def read(path, channel):
    return _read_text(path, channel)
