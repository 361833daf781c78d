"""What every result of the notebook API offers on top of its numbers: its command's files, written or parsed;
its histories as a DataFrame; its arrays read-only."""

from __future__ import annotations

import json
from pathlib import Path

from .._edge import _write


class _Written:
    """What every result offers on top of its numbers: the command's files, written or parsed."""

    command = "softimpact"
    warnings: tuple[str, ...] = ()  # the SoftimpactWarnings of the run, one line each (as manifest.json lists them)

    def files(self, figures: bool = True) -> dict[str, bytes | str]:  # pragma: no cover - each result has its own
        raise NotImplementedError

    def inputs(self) -> tuple[Path, ...]:
        return ()

    def summary(self) -> dict:
        """The numbers of the command's summary.json (SI, unit-suffixed keys), as the command line writes them."""
        return json.loads(self.files(figures=False)["summary.json"])

    def write(self, out, *, figures: bool = True, force: bool = False) -> list[Path]:
        """Write the command's files into ``out`` with their manifest.json (the command line's contract).

        Parameters
        ----------
        out : str or Path
            Folder (created if needed); files of an earlier softimpact run there that this run
            does not rewrite are removed, anything else is left alone.
        figures : bool
            Draw the PNG figures too.
        force : bool
            Replace files in ``out`` that no softimpact run wrote.

        Returns
        -------
        list of Path
            The files written (manifest.json not included).
        """
        from ...gates import status

        manifest = {
            "status": status((), False),
            "accept_poor": False,
            "command": f"{self.command} (Python API)",
            "arguments": {},
            "warnings": list(self.warnings),
            "gates": [],
        }
        return _write(out, self.files(figures), self.inputs(), manifest, force)


def _frame(columns: dict, units_of: dict, index: str = "time_s"):
    """A DataFrame of ``columns`` indexed by the column ``index`` (time, ``time_s``, by default), with ``df.attrs["units"]``.

    pandas, not xarray: every history has one dimension (time), which a DataFrame index holds
    exactly, and pandas is what users of lab data know (the ``table`` extra)."""
    try:
        import pandas as pd
    except ImportError:  # pragma: no cover - depends on the environment
        raise ImportError("to_frame needs pandas: pip install 'softimpact[table]'") from None
    cols = dict(columns)
    key = cols.pop(index)
    df = pd.DataFrame(cols, index=pd.Index(key, name=index))
    df.attrs["units"] = {index: units_of.get(index, "s" if index == "time_s" else "1"), **{k: units_of.get(k, "") for k in cols}}
    return df


def _unit_of(column: str) -> str:
    """The SI unit a contract column name ends in (``contact_force_N`` → ``N``)."""
    for suffix, unit in (("_m_s", "m/s"), ("_N_s", "N*s"), ("_N", "N"), ("_J", "J"), ("_m", "m"), ("_s", "s")):
        if column.endswith(suffix):
            return unit
    return "1"  # strains and other ratios


def _read_only(value, depth: int = 3) -> None:
    """Every numpy array reachable from ``value`` (through dataclass fields, tuples, lists and dict values,
    ``depth`` levels down) made read-only in place: a result is frozen, its arrays too (``res.force *= 2``
    raises instead of changing what ``write`` would write)."""
    import dataclasses

    if depth < 0 or value is None or isinstance(value, (str, bytes, int, float)):
        return
    if type(value).__module__ == "numpy" and hasattr(value, "setflags") and hasattr(value, "shape"):
        value.setflags(write=False)
    elif dataclasses.is_dataclass(value) and not isinstance(value, type):
        for f in dataclasses.fields(value):
            _read_only(getattr(value, f.name), depth - 1)
    elif isinstance(value, (tuple, list)):
        for v in value:
            _read_only(v, depth - 1)
    elif isinstance(value, dict):
        for v in value.values():
            _read_only(v, depth - 1)


def _axes(ax):
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots()
    return ax
