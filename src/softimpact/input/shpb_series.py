"""Two-bar series files (``softimpact shpb``): the incident and transmitted bars with their gauges, the specimen,
and one ``[[test]]`` per test with its two records.

::

    title = "Ice at -10 C on the aluminium bars"
    units = "SI"
    dispersion = "none"                # or "pochhammer-chree": each wave moved to its face with its bar's dispersion

    [incident_bar]                     # a bar's keys (material, length, diameter), or file = "incident-bar.toml"
    material = "Al 6061-T6"
    length = "1.0 m"
    diameter = "19.05 mm"

    [incident_gauge]                   # position from the bar's struck end; the bridge keys of a series' [gauge]
    position = "0.5 m"
    bridge = "quarter"
    gauge_factor = 2.11
    excitation = "5 V"
    gain = 100

    [transmitted_bar]                  # as the incident one
    ...
    [transmitted_gauge]                # position from the specimen's end of the bar
    position = "0.3 m"

    [specimen]
    material = "ice"                   # optional: a catalogue name (its density is the law's record of the material)
    length = "6.0 mm"
    diameter = "12.7 mm"
    density = "917 kg/m^3"             # optional: default the material's

    [[test]]
    name = "ice-1"
    incident = { file = "ice-1.csv", channel = "incident" }        # or a path (one channel); any lab format
    transmitted = { file = "ice-1.csv", channel = "transmitted" }
    specimen = { length = "6.1 mm" }   # optional: this test's specimen, where it differs
    transmitted_delay = "0 us"         # optional: the transmitted record's clock behind the incident one's

A bar file (``softimpact calibrate-bar``) gives a bar's ``[bar]`` and its gauge's ``[gauge]``: ``[incident_bar]
file = "..."`` (keys beside it, and in ``[incident_gauge]``, replace the file's). Both records of a test must be on
one clock (one recorder and trigger) or ``transmitted_delay`` says by how much they are not. Paths are relative to
the file.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..errors import InputError
from ..models.bridge import Bridge
from ..models.materials import lookup
from ..workflows.shpb import BarSide, Specimen
from .bar_calibration import read_record_key, read_strain_record
from .bar_case import read_bar
from .bar_file import bar_tables
from .series import read_bridge
from .toml import Table, load_toml, locate, read_units

__all__ = ["DISPERSION", "ShpbTestEntry", "ShpbSeries", "load_shpb_series", "read_shpb_records"]

DISPERSION = ("none", "pochhammer-chree")


@dataclass(frozen=True)
class ShpbTestEntry:
    """One test: its two records (file, channel, unit), its specimen and the transmitted record's delay [s]."""

    name: str
    incident: tuple[Path, str | int | None, str | None]
    transmitted: tuple[Path, str | int | None, str | None]
    specimen: Specimen
    transmitted_delay: float = 0.0


@dataclass(frozen=True)
class ShpbSeries:
    """A two-bar series read: the bars as the analysis sees them, their bridges (None: records in strain), the tests."""

    title: str
    units: str
    path: Path
    incident: BarSide
    transmitted: BarSide
    incident_bridge: Bridge | None
    transmitted_bridge: Bridge | None
    specimen_material: str
    tests: tuple[ShpbTestEntry, ...]
    dispersion: str = "none"
    synthetic: str = ""
    bar_files: tuple[Path, ...] = ()


def _bar(top: Table, base: Path, which: str):
    """(BarSide, bridge, bar file) of ``which`` ("incident" or "transmitted")."""
    bar_tbl, g, file = bar_tables(top, base, f"{which}_bar", f"{which}_gauge")
    spec = read_bar(bar_tbl)
    if g is None:
        raise InputError(f"{which}_gauge: missing (required): the gauge's position on the {which} bar")
    position = g.quantity("position", "length", positive=False)
    if not 0.0 < position < spec.length:
        raise InputError(f"{g.key('position')}: {g.raw('position')!r} is not on the bar (0 to {spec.length:.6g} m)")
    bridge = read_bridge(g, spec) if "gauge_factor" in g else None
    g.done()
    m = spec.material
    distance = spec.length - position if which == "incident" else position
    side = BarSide(m.youngs_modulus, m.density, spec.diameter, distance, spec.length, m.poisson_ratio)
    if spec.end_cap is not None:
        raise InputError(f"{which}_bar.end_cap: a two-bar set-up's bars have no end cap")
    return side, bridge, file


def _specimen(t: Table, base_spec: dict, key: str) -> Specimen:
    """A specimen from ``base_spec`` (length, diameter, density) with the keys of table ``t`` on top."""
    length = t.quantity("length", "length", default=base_spec.get("length"))
    diameter = t.quantity("diameter", "length", default=base_spec.get("diameter"))
    density = t.quantity("density", "density", default=base_spec.get("density"))
    if length is None or diameter is None:
        raise InputError(f"{key}: the specimen's length and diameter are needed")
    return Specimen(length, diameter, density)


def load_shpb_series(arg: str) -> ShpbSeries:
    """Read a two-bar series (path or built-in name; module docstring)."""
    path = locate(arg)
    top = Table(load_toml(path))
    title = top.string("title", path.stem)
    system = read_units(top)
    synthetic = top.string("synthetic", "")
    dispersion = top.string("dispersion", "none", choices=DISPERSION)
    incident, bridge_i, file_i = _bar(top, path.parent, "incident")
    transmitted, bridge_t, file_t = _bar(top, path.parent, "transmitted")
    s = top.table("specimen")
    material = s.string("material", "")
    density = None
    if material:
        density = lookup(material, s.key("material")).density
    base = {"length": None, "diameter": None, "density": density}
    specimen = _specimen(s, base, "specimen")
    s.done()
    base = {"length": specimen.length, "diameter": specimen.diameter, "density": specimen.density}
    tests = []
    for t in top.tables("test"):
        incident_rec = read_record_key(t, path.parent, "incident")
        transmitted_rec = read_record_key(t, path.parent, "transmitted")
        spec_t = t.table("specimen", optional=True)
        this = specimen
        if spec_t is not None:
            this = _specimen(spec_t, base, spec_t.path)
            spec_t.done()
        delay = t.quantity("transmitted_delay", "time", default=0.0, positive=False)
        tests.append(ShpbTestEntry(t.string("name", incident_rec[0].stem), incident_rec, transmitted_rec, this, delay))
        t.done()
    if not tests:
        raise InputError(f"{path}: no [[test]] entries")
    names = [t.name for t in tests]
    if len(set(names)) != len(names):
        raise InputError(f"test: names must be unique, got {names}")
    top.done()
    files = tuple(f for f in (file_i, file_t) if f is not None)
    return ShpbSeries(title, system, path, incident, transmitted, bridge_i, bridge_t, material, tuple(tests), dispersion, synthetic, files)


def read_shpb_records(series: ShpbSeries):
    """Each test's :class:`softimpact.workflows.shpb.ShpbRecord` (strain through each bar's bridge) and its records' metadata."""
    from ..workflows.shpb import ShpbRecord

    out = []
    for i, t in enumerate(series.tests):
        ti, yi, mi = read_strain_record(*t.incident, series.incident_bridge, f"test[{i}].incident")
        tt, yt, mt = read_strain_record(*t.transmitted, series.transmitted_bridge, f"test[{i}].transmitted")
        out.append((ShpbRecord(t.name, ti, yi, tt, yt), {"incident": mi, "transmitted": mt}))
    return out
