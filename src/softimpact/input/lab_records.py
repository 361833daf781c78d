"""Laboratory gauge records from data-acquisition and oscilloscope files.

:func:`read_lab_record` returns one channel as a :class:`LabRecord` (time [s],
signal, unit, metadata); :func:`list_channels` names what a file holds. The
format is chosen by extension and confirmed by the file's first bytes:

========================  ====================  =========================================
format                    read with             time base
========================  ====================  =========================================
.tdms (NI LabVIEW)        npTDMS                wf_increment, wf_start_offset (waveform
                                                properties), else a time channel in the group
.mat v4–v7 (MATLAB)       scipy.io.loadmat      a time vector (t, time, …), else dt/fs and t0
.mat v7.3, .h5, .hdf5     h5py                  a time dataset beside the signal, else dt/fs
                                                and t0 attributes (or scalar datasets)
.csv .txt .tsv .dat       csv (stdlib)          a time column, else a sample interval among
                                                the metadata lines
.isf .wfm (Tektronix),    RigolWFM (optional:   the scope's own header (XINCR, XZERO, …)
.trc (LeCroy)             pip install RigolWFM)
========================  ====================  =========================================

Delimited text may carry vendor metadata lines (Tektronix, LeCroy, PicoScope,
Excel exports): ``key<delimiter>value`` lines, then a header row (names, with
units as "Time (s)", "CH1 [mV]" or on a PicoScope units row "(us),(mV)"), then
numbers. Delimiters ``,`` ``;`` and tab are sniffed; a UTF-8 byte-order mark is
accepted; a semicolon file with decimal commas (European Excel) is read too.

Units: time is converted to seconds; mV/µV to V; "strain", "m/m" → ``strain``;
"µε", "microstrain", "um/m" → ``microstrain``; other units are kept as written;
none stated → ``V``, and ``metadata["unit_stated"]`` is False.

Every problem (unreadable or truncated file, unknown channel, no time base,
text among the numbers, unequal lengths, NaN) raises
:class:`softimpact.errors.InputError` with one line naming the file.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import InputError

__all__ = ["LabRecord", "read_lab_record", "list_channels", "FORMATS"]

FORMATS = ("tdms", "mat", "hdf5", "text", "scope")
MIN_SAMPLES = 2
TIME_NAMES = ("time", "t", "time_s", "time_ms", "time_us", "times", "x", "zeit", "temps", "tiempo", "seconds")
DT_NAMES = ("dt", "ts", "sample_interval", "sampling_interval", "sample_period", "sampling_period", "xincr", "wf_increment", "increment", "delta_t")
RATE_NAMES = ("fs", "sample_rate", "sampling_rate", "samplerate", "sampling_frequency", "rate")
T0_NAMES = ("t0", "start_time", "time_offset", "xzero", "wf_start_offset", "trigger_offset", "horizontal_offset", "start")
UNIT_ATTRS = ("unit", "units", "unit_string", "yunit", "nx_unit")

_TIME_UNITS = {"s": 1.0, "sec": 1.0, "ms": 1e-3, "us": 1e-6, "µs": 1e-6, "μs": 1e-6, "ns": 1e-9}
_SIGNAL_UNITS = {  # written unit → (LabRecord unit, factor)
    "v": ("V", 1.0),
    "volt": ("V", 1.0),
    "volts": ("V", 1.0),
    "mv": ("V", 1e-3),
    "uv": ("V", 1e-6),
    "µv": ("V", 1e-6),
    "strain": ("strain", 1.0),
    "m/m": ("strain", 1.0),
    "ε": ("strain", 1.0),
    "µε": ("microstrain", 1.0),
    "με": ("microstrain", 1.0),
    "ue": ("microstrain", 1.0),
    "microstrain": ("microstrain", 1.0),
    "um/m": ("microstrain", 1.0),
    "µm/m": ("microstrain", 1.0),
}


@dataclass(frozen=True)
class LabRecord:
    """One channel: ``time`` [s] (1-D, increasing), ``signal`` (same shape) in ``unit``.

    ``metadata``: ``file``, ``source_format``, ``channel``, ``unit`` (as written
    in the file), ``unit_stated``, ``sample_rate`` [Hz], ``time_start`` [s]
    (negative: pre-trigger), ``pretrigger_samples``, ``date`` (ISO text or
    None), ``trigger`` (the header's trigger item as text, or None), and the
    format's own header items under ``header``.
    """

    time: np.ndarray
    signal: np.ndarray
    unit: str
    metadata: dict = field(default_factory=dict)


def _one_line(text) -> str:
    return " ".join(str(text).split())


def _fail(path, msg):
    raise InputError(f"{path}: {_one_line(msg)}")


def _lib_error(path, fmt, exc):
    first = _one_line(exc)[:160] or type(exc).__name__
    raise InputError(f"{path}: not a readable {fmt} file ({first})") from None


# ---------------------------------------------------------------- detection


def _detect(path: Path) -> str:
    try:
        with open(path, "rb") as fh:
            head = fh.read(1024)
    except FileNotFoundError:
        _fail(path, "no such file")
    except IsADirectoryError:
        _fail(path, "is a folder, not a record file")
    except OSError as exc:
        _fail(path, f"cannot read ({exc.strerror})")
    if not head:
        _fail(path, "empty file")
    ext = path.suffix.lower()
    if head.startswith(b"TDSm"):
        return "tdms"
    if head.startswith(b"\x89HDF\r\n\x1a\n") or (head[:19] == b"MATLAB 7.3 MAT-file") or _hdf5_at_userblock(path):
        return "hdf5"
    if head.startswith(b"MATLAB 5.0 MAT-file") or ext == ".mat":
        return "mat"
    if ext in (".isf", ".wfm", ".trc"):
        return "scope"
    if ext == ".tdms":
        _fail(path, "not a TDMS file (no 'TDSm' tag at the start): truncated or mislabelled?")
    if ext in (".h5", ".hdf5", ".hdf"):
        _fail(path, "not an HDF5 file (no HDF5 signature): truncated or mislabelled?")
    if b"\x00" in head:
        _fail(path, f"unknown binary format (extension {ext or 'none'!r}); readable: .tdms, .mat, .h5/.hdf5, .csv/.txt, .isf/.wfm/.trc")
    return "text"


def _hdf5_at_userblock(path) -> bool:
    """HDF5 signature at 512, 1024, … (a userblock, as MATLAB v7.3 files have)."""
    try:
        with open(path, "rb") as fh:
            for offset in (512, 1024, 2048, 4096):
                fh.seek(offset)
                if fh.read(8) == b"\x89HDF\r\n\x1a\n":
                    return True
    except OSError:
        return False
    return False


# ---------------------------------------------------------------- common helpers


def _norm(name: str) -> str:
    return re.sub(r"[\s\-]+", "_", str(name).strip().lower())


def _unit(written):
    """(LabRecord unit, factor, stated) for a unit string from a file."""
    if written is None or str(written).strip() == "":
        return "V", 1.0, False
    w = str(written).strip().strip("()[]").strip()
    key = w.lower().replace("μ", "µ")
    if key in _SIGNAL_UNITS:
        unit, factor = _SIGNAL_UNITS[key]
        return unit, factor, True
    return w, 1.0, True


def _time_factor(path, unit) -> float:
    if unit is None or str(unit).strip() == "":
        return 1.0
    key = str(unit).strip().strip("()[]").strip().lower().replace("μ", "µ")
    if key not in _TIME_UNITS:
        _fail(path, f"time unit {unit!r} not understood (s, ms, us, ns)")
    return _TIME_UNITS[key]


def _pick(path, names: list[str], channel) -> str:
    """The channel asked for: None (the only one), an index, or a name (exact, then unique suffix, any case)."""
    if not names:
        _fail(path, "no signal channels found")
    listing = ", ".join(repr(n) for n in names)
    if channel is None:
        if len(names) == 1:
            return names[0]
        _fail(path, f"{len(names)} channels, choose one: {listing}")
    if isinstance(channel, (int, np.integer)) and not isinstance(channel, bool):
        if -len(names) <= channel < len(names):
            return names[int(channel)]
        _fail(path, f"channel index {channel} out of range; channels are {listing}")
    if not isinstance(channel, str):
        _fail(path, f"channel must be a name or an index, got {channel!r}")
    if channel in names:
        return channel
    for match in (
        [n for n in names if n.split("/")[-1] == channel],
        [n for n in names if n.lower() == channel.lower()],
        [n for n in names if n.split("/")[-1].lower() == channel.lower()],
    ):
        if len(match) == 1:
            return match[0]
        if len(match) > 1:
            _fail(path, f"channel {channel!r} is ambiguous: {', '.join(map(repr, match))}")
    _fail(path, f"no channel {channel!r}; channels are {listing}")


def _finish(path, fmt, name, t, y, written_unit, header=None, date=None, trigger=None) -> LabRecord:
    """Validate (1-D, equal lengths, finite, increasing time) and build the record."""
    t = np.asarray(t, dtype=float).squeeze()
    try:
        y = np.asarray(y, dtype=float).squeeze()
    except (TypeError, ValueError):
        _fail(path, f"channel {name!r} is not numeric")
    if t.ndim != 1 or y.ndim != 1:
        _fail(path, f"channel {name!r}: expected 1-D data, got shape {y.shape}")
    if t.size != y.size:
        _fail(path, f"channel {name!r} has {y.size} samples but the time base {t.size}")
    if y.size < MIN_SAMPLES:
        _fail(path, f"channel {name!r} holds {y.size} sample(s)")
    for what, arr in (("time", t), (f"channel {name!r}", y)):
        bad = ~np.isfinite(arr)
        if bad.any():
            _fail(path, f"{what}: {int(bad.sum())} NaN or infinite values (first at sample {int(np.argmax(bad))})")
    d = np.diff(t)
    if np.any(d <= 0):
        k = int(np.argmax(d <= 0))
        _fail(path, f"time is not increasing at sample {k + 1} ({t[k]!r} then {t[k + 1]!r})")
    unit, factor, stated = _unit(written_unit)
    dt = float(np.median(d))
    if trigger is None:  # the header's own trigger item (Tektronix "Trigger Point", LeCroy "Trigger Time", ...)
        trigger = next((_one_line(v) for k, v in (header or {}).items() if "trig" in str(k).lower() and "date" not in str(k).lower()), None)
    meta = {
        "file": str(path),
        "source_format": fmt,
        "channel": name,
        "unit": None if not stated else str(written_unit),
        "unit_stated": stated,
        "sample_rate": 1.0 / dt,
        "time_start": float(t[0]),
        "pretrigger_samples": int(np.count_nonzero(t < -0.5 * dt)),  # rounding of t0 + k·dt near 0
        "date": date,
        "trigger": trigger,
        "header": dict(header or {}),
    }
    return LabRecord(t, y * factor, unit, meta)


def _uniform_time(path, n, dt=None, rate=None, t0=0.0):
    if dt is None and rate is not None:
        if not (math.isfinite(rate) and rate > 0):
            _fail(path, f"sample rate {rate!r} is not positive")
        dt = 1.0 / rate
    if dt is None:
        return None
    if not (math.isfinite(dt) and dt > 0):
        _fail(path, f"sample interval {dt!r} is not positive")
    t0 = 0.0 if t0 is None else float(t0)
    return t0 + dt * np.arange(n)


# ---------------------------------------------------------------- TDMS


def _tdms_check_segments(path):
    """Walk the TDMS segment lead-ins (NI, "TDMS File Format Internal Structure").

    Each segment starts with 28 bytes: 'TDSm', ToC mask (uint32; bit 14 = big
    endian), version (uint32), next-segment offset and raw-data offset (uint64)
    counted from the end of the lead-in. npTDMS reads a cut file quietly, with
    fewer samples; a record cut short must not pass as a complete one.
    """
    import struct

    size = path.stat().st_size
    pos = 0
    with open(path, "rb") as fh:
        while pos < size:
            fh.seek(pos)
            lead = fh.read(28)
            if len(lead) < 28 or lead[:4] != b"TDSm":
                _fail(path, f"TDMS file damaged or truncated: no segment lead-in at byte {pos} of {size}")
            big = struct.unpack("<I", lead[4:8])[0] & (1 << 14)
            next_offset = struct.unpack(">Q" if big else "<Q", lead[12:20])[0]
            if next_offset == 0xFFFFFFFFFFFFFFFF:
                _fail(path, f"TDMS file incomplete: the segment at byte {pos} was never closed (acquisition interrupted?)")
            pos += 28 + next_offset
            if pos > size:
                _fail(path, f"TDMS file truncated: a segment ends at byte {pos} but the file has {size}")


def _tdms_open(path):
    try:
        from nptdms import TdmsFile
    except ImportError:
        _fail(path, "reading .tdms needs npTDMS (pip install npTDMS)")
    _tdms_check_segments(path)
    try:
        return TdmsFile.read(path)
    except Exception as exc:  # npTDMS raises ValueError, struct.error, EOFError… on damaged files
        _lib_error(path, "TDMS", exc)


def _tdms_channels(f):
    return [f"{g.name}/{c.name}" for g in f.groups() for c in g.channels()]


def _read_tdms(path, channel):
    f = _tdms_open(path)
    names = [n for n in _tdms_channels(f) if _norm(n.split("/", 1)[1]) not in TIME_NAMES]
    name = _pick(path, names, channel)
    gname, cname = name.split("/", 1)
    ch = f[gname][cname]
    props = dict(ch.properties)
    try:
        y = ch[:]
    except Exception as exc:
        _lib_error(path, "TDMS", exc)
    if "wf_increment" in props:
        t = _uniform_time(path, len(y), dt=float(props["wf_increment"]), t0=float(props.get("wf_start_offset", 0.0)))
    else:
        tch = [c for c in f[gname].channels() if _norm(c.name) in TIME_NAMES]
        if not tch:
            _fail(path, f"channel {name!r} has no time base (no wf_increment property, no time channel in group {gname!r})")
        tc = tch[0]
        t = tc[:] * _time_factor(path, tc.properties.get("unit_string") or ("ms" if _norm(tc.name) == "time_ms" else None))
    date = props.get("wf_start_time")
    date = None if date is None else str(np.datetime64(date, "us"))
    header = {k: (v.item() if hasattr(v, "item") else v) for k, v in props.items()}
    return _finish(path, "tdms", name, t, y, props.get("unit_string"), header, date, None)


# ---------------------------------------------------------------- MAT v5 and HDF5 (a dict of arrays)


def _scalar(v):
    a = np.asarray(v)
    if a.dtype.kind in "fiu" and a.size == 1:
        return float(a.ravel()[0])
    return None


def _text(v):
    a = np.asarray(v)
    if a.dtype.kind in "US":
        return str(a.ravel()[0]) if a.size else ""
    return None


def _arrays_record(path, fmt, groups, channel, header):
    """Pick a channel from ``groups``: {group: {name: array, name+'@attrs': attrs}}.

    Within a group: 1-D numeric arrays of length > 1 are channels, unless named
    as time; scalars named dt/fs/t0 (or attributes of the array) give the time
    base; a text variable ``<name>_unit`` or ``unit`` (or attribute) the unit.
    """
    channels = {}
    for g, items in groups.items():
        for n, v in items.items():
            a = v["data"]
            if a.dtype.kind in "fiu" and a.size > 1 and a.squeeze().ndim == 1 and _norm(n) not in TIME_NAMES:
                channels[f"{g}/{n}" if g else n] = (g, n)
    name = _pick(path, list(channels), channel)
    g, n = channels[name]
    items = groups[g]
    entry = items[n]
    y = entry["data"].squeeze()
    attrs = {_norm(k): v for k, v in entry["attrs"].items()}
    scalars = {_norm(k): _scalar(v["data"]) for k, v in items.items()}
    texts = {_norm(k): _text(v["data"]) for k, v in items.items()}

    def find(names):
        for key in names:
            if key in attrs and _scalar(attrs[key]) is not None:
                return _scalar(attrs[key])
        for key in names:
            if scalars.get(key) is not None:
                return scalars[key]
        return None

    time_vars = [k for k, v in items.items() if _norm(k) in TIME_NAMES and v["data"].size > 1]
    if time_vars:
        tv = items[time_vars[0]]
        tunit = next((_text(tv["attrs"][k]) for k in tv["attrs"] if _norm(k) in UNIT_ATTRS), None)
        if tunit is None:
            tunit = {"time_ms": "ms", "time_us": "us"}.get(_norm(time_vars[0]))
        t = tv["data"].squeeze().astype(float) * _time_factor(path, tunit)
    else:
        t = _uniform_time(path, y.size, dt=find(DT_NAMES), rate=find(RATE_NAMES), t0=find(T0_NAMES))
        if t is None:
            _fail(path, f"channel {name!r} has no time base (no time vector, no dt/fs variable or attribute)")
    unit = next((_text(attrs[k]) for k in UNIT_ATTRS if k in attrs and _text(attrs[k]) is not None), None)
    if unit is None:
        unit = texts.get(_norm(f"{n}_unit")) or texts.get(_norm(f"{n}_units")) or texts.get("unit") or texts.get("units")
    date = next((_text(v) for k, v in attrs.items() if k in ("date", "datetime", "start_date")), None)
    if date is None:
        date = texts.get("date")
    return _finish(path, fmt, name, t, y, unit, header, date, None)


def _mat_groups(path):
    import scipy.io

    try:
        raw = scipy.io.loadmat(path, squeeze_me=False, struct_as_record=True, chars_as_strings=True)
    except NotImplementedError:  # v7.3 without the HDF5 signature where we looked
        _fail(path, "MATLAB v7.3 file: read as HDF5 failed (damaged userblock?)")
    except Exception as exc:
        _lib_error(path, "MAT", exc)
    header = {k: (v.decode("latin-1") if isinstance(v, bytes) else str(v)) for k, v in raw.items() if k.startswith("__")}
    groups = {"": {}}
    for k, v in raw.items():
        if k.startswith("__"):
            continue
        a = np.asarray(v)
        if a.dtype.names:  # a struct: its fields form a group
            s = a.ravel()[0] if a.size else None
            if s is None:
                continue
            groups[k] = {f: {"data": np.asarray(s[f]), "attrs": {}} for f in a.dtype.names if np.asarray(s[f]).dtype.kind in "fiuUS"}
        elif a.dtype.kind in "fiuUS":
            groups[""][k] = {"data": a, "attrs": {}}
    return groups, header


def _h5_groups(path):
    try:
        import h5py
    except ImportError:
        _fail(path, "reading HDF5 and MATLAB v7.3 files needs h5py (pip install h5py)")
    groups: dict = {}
    header = {}
    try:
        with h5py.File(path, "r") as f:
            header = {k: _h5_attr(v) for k, v in f.attrs.items()}
            if f.userblock_size:
                with open(path, "rb") as fh:
                    header["userblock"] = fh.read(116).decode("latin-1").rstrip("\x00 ")

            def visit(name, obj):
                if not isinstance(obj, h5py.Dataset) or name.startswith(("#refs#", "#subsystem#")):
                    return
                g, _, n = name.rpartition("/")
                attrs = {k: _h5_attr(v) for k, v in obj.attrs.items()}
                data = obj[()]
                data = np.asarray(data)
                if _h5_attr(obj.attrs.get("MATLAB_class")) == "char" and data.dtype.kind in "iu":
                    data = np.asarray("".join(map(chr, data.ravel())))  # MATLAB v7.3 char: UTF-16 code units
                elif data.dtype.kind == "O" or data.dtype.kind == "S":
                    data = np.asarray(_h5_attr(data.ravel()[0]) if data.size else "")
                groups.setdefault(g, {})[n] = {"data": data, "attrs": attrs}

            f.visititems(visit)
    except InputError:
        raise
    except Exception as exc:
        _lib_error(path, "HDF5", exc)
    return groups, header


def _h5_attr(v):
    if v is None or isinstance(v, str):
        return v
    if isinstance(v, bytes):
        return v.decode("utf-8", "replace")
    a = np.asarray(v)
    if a.dtype.kind == "S":
        return a.ravel()[0].decode("utf-8", "replace") if a.size else ""
    if a.dtype.kind == "O" and a.size == 1:
        item = a.ravel()[0]
        return item if isinstance(item, (str, bytes)) and not isinstance(item, bytes) else _h5_attr(item) if isinstance(item, bytes) else str(item)
    if a.size == 1 and a.dtype.kind in "fiub":
        return a.ravel()[0].item()
    return a


# ---------------------------------------------------------------- delimited text

_NUMBER = re.compile(r"^[+-]?(\d+([.,]\d*)?|[.,]\d+)([eE][+-]?\d+)?$")
_UNIT_IN_NAME = re.compile(r"^(.*?)[\s_]*[\(\[]\s*([^\)\]]*)\s*[\)\]]\s*$")
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
        try:
            dt = float(dt_text.split(",")[0].split()[0]) if dt_text else None
            t0 = float(t0_text.split(",")[0].split()[0]) if t0_text else 0.0
        except (ValueError, IndexError):
            _fail(path, f"sample interval {dt_text!r} or start time {t0_text!r} in the header is not a number")
        t = _uniform_time(path, y.size, dt=dt, t0=t0)
        if t is None:
            _fail(path, "no time base: no time column and no sample interval in the header")
    date = _meta_value(metadata, _DATE_KEYS)
    return _finish(path, "text", name, t, y, units[j], metadata, date, None)


# ---------------------------------------------------------------- oscilloscope binaries (optional)


def _scope_open(path):
    try:
        from RigolWFM import wfm
    except ImportError:
        _fail(path, "reading Tektronix .isf/.wfm and LeCroy .trc files needs RigolWFM (pip install RigolWFM, or softimpact[scope])")
    model = {".isf": "ISF", ".wfm": "Tek", ".trc": "LeCroy"}[path.suffix.lower()]
    try:
        return wfm.Wfm.from_file(str(path), model)
    except Exception as exc:
        _lib_error(path, f"{model} scope", exc)


def _scope_channels(w):
    return [ch for ch in w.channels if getattr(ch, "enabled", True) and getattr(ch, "volts", None) is not None]


def _read_scope(path, channel):
    w = _scope_open(path)
    chans = {str(ch.name): ch for ch in _scope_channels(w)}
    name = _pick(path, list(chans), channel)
    ch = chans[name]
    unit = getattr(getattr(ch, "unit", None), "name", None)
    header = {"parser": getattr(w, "parser_name", None), "seconds_per_point": getattr(ch, "seconds_per_point", None)}
    return _finish(path, "scope", name, ch.times, ch.volts, "V" if unit in (None, "v") else unit, header, None, None)


# ---------------------------------------------------------------- public API


def _groups(path, kind):
    return _h5_groups(path) if kind == "hdf5" else _mat_groups(path)


def list_channels(path) -> list[str]:
    """Names of the signal channels in a record file (time columns excluded), in file order."""
    path = Path(path)
    kind = _detect(path)
    if kind == "tdms":
        f = _tdms_open(path)
        return [n for n in _tdms_channels(f) if _norm(n.split("/", 1)[1]) not in TIME_NAMES]
    if kind in ("mat", "hdf5"):
        groups, _ = _groups(path, kind)
        return [
            (f"{g}/{n}" if g else n)
            for g, items in groups.items()
            for n, v in items.items()
            if v["data"].dtype.kind in "fiu" and v["data"].size > 1 and v["data"].squeeze().ndim == 1 and _norm(n) not in TIME_NAMES
        ]
    if kind == "scope":
        return [str(ch.name) for ch in _scope_channels(_scope_open(path))]
    return _read_text(path, None, list_only=True)


def read_lab_record(path, channel: str | int | None = None) -> LabRecord:
    """One channel of a record file as a :class:`LabRecord` (module docstring for formats).

    ``channel``: a name (``"group/channel"`` or just ``"channel"`` when unique,
    any case), an index into :func:`list_channels`, or None when the file holds
    one channel.
    """
    path = Path(path)
    kind = _detect(path)
    if kind == "tdms":
        return _read_tdms(path, channel)
    if kind in ("mat", "hdf5"):
        groups, header = _groups(path, kind)
        fmt = "mat-v7.3" if kind == "hdf5" and "MATLAB 7.3" in str(header.get("userblock", "")) else ("mat" if kind == "mat" else "hdf5")
        return _arrays_record(path, fmt, groups, channel, header)
    if kind == "scope":
        return _read_scope(path, channel)
    return _read_text(path, channel)
