"""HDF5 files and MATLAB v7.3 .mat files, read with h5py: a time dataset beside the signal, else dt/fs
and t0 attributes (or scalar datasets)."""

from __future__ import annotations

import numpy as np

from ...errors import InputError
from ._arrays import array_channels, arrays_record
from ._common import _fail, _lib_error

__all__ = ["channels", "read"]


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


def channels(path) -> list[str]:
    """Names of the signal datasets (``group/dataset``)."""
    return array_channels(_h5_groups(path)[0])


def read(path, channel):
    groups, header = _h5_groups(path)
    fmt = "mat-v7.3" if "MATLAB 7.3" in str(header.get("userblock", "")) else "hdf5"
    return arrays_record(path, fmt, groups, channel, header)
