"""What every lab-record reader shares: the :class:`LabRecord`, channel choice, units, and the final checks."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

import numpy as np

from ...errors import InputError
from ...models.sampling import series_problem

__all__ = ["LabRecord", "MIN_SAMPLES", "TIME_NAMES", "DT_NAMES", "RATE_NAMES", "T0_NAMES", "UNIT_ATTRS"]

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
    problem = series_problem(t, y, min_samples=MIN_SAMPLES, what=f"channel {name!r}")
    if problem is not None:
        _fail(path, problem)
    unit, factor, stated = _unit(written_unit)
    dt = float(np.median(np.diff(t)))
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
