"""Format name → reader, and the detection that picks one: by the file's first bytes, then its extension.

Each reader module has ``channels(path) -> list[str]`` and ``read(path, channel) -> LabRecord``.
A new format is one module and one line in :data:`READERS` (and a rule in :func:`detect`).
"""

from __future__ import annotations

from pathlib import Path
from types import ModuleType

from . import hdf5, mat, scope, tdms, tektronix_csv, text
from ._common import _fail

__all__ = ["READERS", "FORMATS", "detect"]

READERS: dict[str, ModuleType] = {
    "tdms": tdms,
    "mat": mat,
    "hdf5": hdf5,
    "tektronix-csv": tektronix_csv,
    "text": text,
    "scope": scope,
}
FORMATS = tuple(READERS)


def detect(path: Path) -> str:
    """The format name (a key of READERS) of the file at ``path``; unreadable or unknown files fail with one line."""
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
    return "tektronix-csv" if tektronix_csv.looks_like(head) else "text"


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
