"""NI LabVIEW TDMS files, read with npTDMS: time base from the waveform properties (wf_increment,
wf_start_offset), else a time channel in the group; a file cut short is refused (segment walk)."""

from __future__ import annotations

import numpy as np

from ._common import TIME_NAMES, _fail, _finish, _lib_error, _norm, _pick, _time_factor, _uniform_time

__all__ = ["channels", "read"]


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


def read(path, channel):
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


def channels(path) -> list[str]:
    """``group/channel`` names of the signal channels (time channels excluded)."""
    return [n for n in _tdms_channels(_tdms_open(path)) if _norm(n.split("/", 1)[1]) not in TIME_NAMES]
