"""MATLAB .mat v4–v7 files, read with scipy.io.loadmat: a time vector (t, time, …), else dt/fs and t0
(variables or struct fields). v7.3 files are HDF5 (:mod:`.hdf5`)."""

from __future__ import annotations

import numpy as np

from ._arrays import array_channels, arrays_record
from ._common import _fail, _lib_error

__all__ = ["channels", "read"]


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


def channels(path) -> list[str]:
    """Names of the signal arrays (``struct/field`` inside a struct)."""
    return array_channels(_mat_groups(path)[0])


def read(path, channel):
    groups, header = _mat_groups(path)
    return arrays_record(path, "mat", groups, channel, header)
