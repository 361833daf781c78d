"""The optional extras (pyproject.toml's ``[project.optional-dependencies]``) and the check a command makes
before any work: every module an extra brings, looked for without importing it (``importlib.util.find_spec``),
so a command that needs one that is missing stops at once with the install line (exit 2, nothing computed or
written) instead of computing and then failing on the import.

A leaf module: it imports nothing of softimpact but its errors.
"""

from __future__ import annotations

import importlib.util
import sys

from .errors import InputError

__all__ = ["EXTRAS", "FORMAT_EXTRAS", "MissingExtra", "missing", "require"]

# extra → the modules it brings (import names), as declared in pyproject.toml
EXTRAS: dict[str, tuple[str, ...]] = {
    "sweep": ("dask", "distributed", "pyarrow"),
    "fields": ("meshio", "h5py"),
    "lab": ("nptdms", "h5py"),
    "scope": ("RigolWFM",),
    "table": ("pandas",),
}

# a record format (softimpact.input.records.registry's names) → (its extra, the modules it reads with)
FORMAT_EXTRAS: dict[str, tuple[str, tuple[str, ...]]] = {
    "tdms": ("lab", ("nptdms",)),
    "hdf5": ("lab", ("h5py",)),
    "scope": ("scope", ("RigolWFM",)),
}


class MissingExtra(InputError, ImportError):
    """An optional dependency a command or method needs is not installed: bad input of the environment (exit 2,
    nothing written); an ImportError too, as Python code expects of a missing module."""


def _absent(module: str) -> bool:
    """Whether ``module`` cannot be imported (not installed, or blocked by ``sys.modules[module] = None``)."""
    if module in sys.modules:
        return sys.modules[module] is None
    try:
        return importlib.util.find_spec(module) is None
    except (ImportError, ValueError):
        return True


def missing(extra: str, modules: tuple[str, ...] | None = None) -> list[str]:
    """The modules of ``extra`` (or only ``modules`` of it) that are not installed, in the table's order."""
    return [m for m in (EXTRAS[extra] if modules is None else modules) if _absent(m)]


def require(extra: str, what: str, modules: tuple[str, ...] | None = None) -> None:
    """Raise :class:`MissingExtra` naming ``what`` needs it and the install line when a module of ``extra`` (or of
    ``modules`` only: a command that needs part of an extra) is missing; nothing otherwise."""
    gone = missing(extra, modules)
    if gone:
        raise MissingExtra(f"{what} needs {', '.join(gone)}, not installed: pip install 'softimpact[{extra}]'")
