"""A channel out of a dict of named arrays (MATLAB v5 variables and structs, HDF5 datasets)."""

from __future__ import annotations

import numpy as np

from ._common import DT_NAMES, RATE_NAMES, T0_NAMES, TIME_NAMES, UNIT_ATTRS, _fail, _finish, _norm, _pick, _time_factor, _uniform_time

__all__ = ["arrays_record", "array_channels"]


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


def arrays_record(path, fmt, groups, channel, header):
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


def array_channels(groups) -> list[str]:
    """Names of the 1-D numeric arrays longer than one sample, time arrays excluded, in file order."""
    return [
        (f"{g}/{n}" if g else n)
        for g, items in groups.items()
        for n, v in items.items()
        if v["data"].dtype.kind in "fiu" and v["data"].size > 1 and v["data"].squeeze().ndim == 1 and _norm(n) not in TIME_NAMES
    ]
