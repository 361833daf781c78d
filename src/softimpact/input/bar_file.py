"""Bar files: a lab's own bar and its gauge, kept in one TOML file (``softimpact calibrate-bar`` writes one) that
bar cases, bar series (``reduce``, ``fit``, ``identify``) and two-bar series (``shpb``) read.

A bar file holds a ``[bar]`` table (the keys of a case's ``[bar]``: ``material``, ``length``, ``diameter``, …)
and a ``[gauge]`` table (the keys of a series' ``[gauge]``: ``position``, ``bridge``, ``gauge_factor``, …);
what else it holds (``[calibration]``: each constant's interval and residual) is for people and is not read.
A case or series names it by ``file`` in its bar's table::

    [bar]
    file = "lab-bar.toml"     # relative to the case or series file
    elements = 60             # a key given beside it replaces the file's

The file's tables are the defaults; the keys the case or series gives beside ``file`` (and in its own ``[gauge]``)
replace them one by one.
"""

from __future__ import annotations

from pathlib import Path

from ..errors import InputError
from .toml import Table, load_toml

__all__ = ["BAR_FILE_KEY", "load_bar_file", "bar_tables"]

BAR_FILE_KEY = "file"


def load_bar_file(path: Path, key: str) -> dict:
    """The TOML data of a bar file, with its ``[bar]`` table checked to be one; InputError naming ``key``."""
    if not path.is_file():
        raise InputError(f"{key}: no bar file at {path}")
    data = load_toml(path)
    if not isinstance(data.get("bar"), dict):
        raise InputError(f"{key}: {path.name} is not a bar file (no [bar] table)")
    if "gauge" in data and not isinstance(data["gauge"], dict):
        raise InputError(f"{key}: {path.name}: [gauge] must be a table")
    return data


def bar_tables(top: Table, base: Path, bar_key: str = "bar", gauge_key: str | None = "gauge") -> tuple[Table, Table | None, Path | None]:
    """(the bar's table, its gauge's table or None, the bar file read or None) of a case or series (module docstring):
    the tables as written, or a bar file's with the keys written beside ``file`` (and in ``[gauge_key]``) on top."""
    bar = top.table(bar_key)
    gauge_raw = top.raw(gauge_key, None) if gauge_key is not None else None
    if gauge_raw is not None and not isinstance(gauge_raw, dict):
        raise InputError(f"{gauge_key}: expected a table, got {gauge_raw!r}")
    name = bar.string(BAR_FILE_KEY, "")
    if not name:
        return bar, (Table(gauge_raw, gauge_key) if gauge_raw is not None else None), None
    path = Path(name) if Path(name).is_absolute() else base / name
    data = load_bar_file(path, bar.key(BAR_FILE_KEY))
    merged = {**data["bar"], **{k: v for k, v in bar.data.items() if k != BAR_FILE_KEY}}
    gauge = None
    if gauge_key is not None and ("gauge" in data or gauge_raw is not None):
        gauge = Table({**data.get("gauge", {}), **(gauge_raw or {})}, gauge_key)
    return Table(merged, bar.path), gauge, path


def bar_file_of(case_path: Path, bar_key: str = "bar") -> Path | None:
    """The bar file a case or series file names (its ``[bar] file``), or None: an input of the run for its manifest."""
    data = load_toml(case_path)
    name = data.get(bar_key, {}).get(BAR_FILE_KEY) if isinstance(data.get(bar_key), dict) else None
    if not isinstance(name, str):
        return None
    return Path(name) if Path(name).is_absolute() else case_path.parent / name


__all__ += ["bar_file_of"]
