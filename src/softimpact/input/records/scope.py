"""Oscilloscope binaries (.isf, .wfm Tektronix; .trc LeCroy), read with RigolWFM (optional:
``pip install softimpact[scope]``): time base from the scope's own header (XINCR, XZERO, …)."""

from __future__ import annotations

from ._common import _fail, _finish, _lib_error, _pick

__all__ = ["channels", "read"]


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


def read(path, channel):
    w = _scope_open(path)
    chans = {str(ch.name): ch for ch in _scope_channels(w)}
    name = _pick(path, list(chans), channel)
    ch = chans[name]
    unit = getattr(getattr(ch, "unit", None), "name", None)
    header = {"parser": getattr(w, "parser_name", None), "seconds_per_point": getattr(ch, "seconds_per_point", None)}
    return _finish(path, "scope", name, ch.times, ch.volts, "V" if unit in (None, "v") else unit, header, None, None)


def channels(path) -> list[str]:
    """Names of the enabled channels holding data."""
    return [str(ch.name) for ch in _scope_channels(_scope_open(path))]
