"""Calibration files (``softimpact calibrate-bar``): a lab's bar, its gauge and its records.

::

    title = "The 20-mm steel bar, gauge A"
    units = "SI"

    [bar]
    material = "steel"                 # nominal: the first guess of the wave speed and of ν (or an inline table)
    length = "1.000 m"
    length_uncertainty = "0.5 mm"      # standard uncertainties (one σ), each optional (default 0: exact)
    diameter = "20.00 mm"
    diameter_uncertainty = "0.01 mm"
    density = "7850 kg/m^3"            # default: the material's
    density_uncertainty = "5 kg/m^3"
    dispersion_unknown = "poisson_ratio"   # what the echoes' dispersion gives: poisson_ratio (the radius measured),
                                           # radius (ν given: the material's), or none

    [gauge]                            # a bar series' [gauge]: position (nominal) and the bridge, its gauge factor nominal
    position = "0.5 m"
    bridge = "quarter"
    gauge_factor = 2.0
    excitation = "5 V"
    gain = 500

    [[shot]]                           # one record of an impact on the struck end
    record = "ball-1.csv"              # or { file = ..., channel = ..., unit = ... } (any lab format)
    ball = { mass = "2.104 g", velocity = "3.00 m/s", rebound = "2.88 m/s", rebound_uncertainty = "0.03 m/s" }
    # or rebound_max = "3 m/s" (only bounded), and mass_uncertainty, velocity_uncertainty; no ball: its echoes only

Records in volts go through the bridge with its nominal gauge factor (the calibration gives the true one);
records in strain need no bridge (the calibration then gives a strain scale, not a gauge factor). Paths are
relative to the file.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace

from ..errors import InputError
from ..models.bridge import Bridge
from ..models.specimens import BarSpec
from ..workflows.bar_calibration import BarGeometry, KnownImpact, Shot
from .series import RECORD_UNITS, read_bridge, read_test_record
from .toml import Table, load_toml, locate, naming, read_material, read_units

__all__ = ["UNKNOWNS", "CalibrationFile", "load_calibration_file", "read_record_key"]

UNKNOWNS = ("poisson_ratio", "radius", "none")


@dataclass(frozen=True)
class CalibrationFile:
    """A calibration file read: the bar as known (:class:`~softimpact.workflows.bar_calibration.BarGeometry`), its
    catalogue ``material`` name or inline table as written, the nominal ``bridge`` (None: records in strain), the
    shots with their records as strain, the record paths, and what the bar file will repeat."""

    title: str
    units: str
    path: Path
    geometry: BarGeometry
    material_name: str
    bridge: Bridge | None
    gauge_keys: dict
    shots: tuple[Shot, ...]
    records: tuple[Path, ...]
    metadata: tuple[dict, ...]
    synthetic: str = ""


def read_record_key(t: Table, base: Path, key: str = "record") -> tuple[Path, str | int | None, str | None]:
    """A record key: a path, or ``{ file, channel, unit }`` (channel by name or index; unit one of RECORD_UNITS)."""
    raw = t.raw(key)
    if isinstance(raw, str):
        return base / raw, None, None
    if not isinstance(raw, dict):
        raise InputError(f"{t.key(key)}: expected a path or {{ file = ..., channel = ... }}, got {raw!r}")
    r = Table(raw, t.key(key))
    file = r.string("file")
    channel = r.raw("channel", None)
    if channel is not None and (isinstance(channel, bool) or not isinstance(channel, (str, int))):
        raise InputError(f"{r.key('channel')}: expected a channel name or index, got {channel!r}")
    unit = r.string("unit", None) if "unit" in r else None
    if unit is not None and unit not in RECORD_UNITS:
        raise InputError(f"{r.key('unit')}: {unit!r} is not one of {', '.join(RECORD_UNITS)}")
    r.done()
    return base / file, channel, unit


def read_strain_record(path: Path, channel, unit, bridge: Bridge | None, key: str):
    """(time [s], strain, metadata) of a record: volts through ``bridge`` (InputError naming ``key`` without one)."""
    rec = read_test_record(SimpleNamespace(record=path, channel=channel, unit=unit))
    if rec.kind == "voltage":
        if bridge is None:
            raise InputError(f"{key}: {path.name} is in volts: the gauge's bridge is needed (gauge_factor, bridge, excitation in its [gauge])")
        return rec.time, bridge.strain(rec.signal), {**rec.metadata, "bridge": bridge.configuration}
    return rec.time, rec.signal, rec.metadata


def _ball(t: Table) -> KnownImpact | None:
    b = t.table("ball", optional=True)
    if b is None:
        return None
    keys = {n: b.key(n) for n in ("mass", "velocity", "rebound", "rebound_max", "mass_sd", "velocity_sd")}
    keys.update(mass_sd=b.key("mass_uncertainty"), velocity_sd=b.key("velocity_uncertainty"))
    with naming(keys):
        impact = KnownImpact(
            b.quantity("mass", "mass"),
            b.quantity("velocity", "velocity"),
            b.quantity("mass_uncertainty", "mass", default=0.0, positive=False),
            b.quantity("velocity_uncertainty", "velocity", default=0.0, positive=False),
            b.quantity("rebound", "velocity", default=None, positive=False),
            b.quantity("rebound_uncertainty", "velocity", default=0.0, positive=False),
            b.quantity("rebound_max", "velocity", default=None),
        )
    b.done()
    return impact


def load_calibration_file(arg: str) -> CalibrationFile:
    """Read a calibration file (path or built-in name; module docstring); its records read and turned into strain."""
    path = locate(arg)
    top = Table(load_toml(path))
    title = top.string("title", path.stem)
    system = read_units(top)
    synthetic = top.string("synthetic", "")
    b = top.table("bar")
    unknown = b.string("dispersion_unknown", "poisson_ratio", choices=UNKNOWNS)
    sd = {
        k: b.quantity(f"{k}_uncertainty", kind, default=0.0, positive=False)
        for k, kind in (("length", "length"), ("diameter", "length"), ("density", "density"))
    }
    density = b.quantity("density", "density", default=None)
    material_raw = b.raw("material")
    spec = BarSpec(read_material(b), b.quantity("length", "length"), b.quantity("diameter", "length"))
    b.done()
    g = top.table("gauge")
    position = g.quantity("position", "length", positive=False)
    bridge = read_bridge(g, spec) if "gauge_factor" in g else None
    gauge_keys = {k: v for k, v in g.data.items() if k != "position"}
    g.done()
    m = spec.material
    keys = {n: f"bar.{n}" for n in ("length", "diameter", "density", "wave_speed")}
    keys.update(gauge_position="gauge.position", poisson_ratio="bar.material", length_sd="bar.length_uncertainty", diameter_sd="bar.diameter_uncertainty")
    keys["density_sd"] = "bar.density_uncertainty"
    rho = m.density if density is None else density
    with naming(keys):
        geometry = BarGeometry(
            spec.length, spec.diameter, rho, position, m.poisson_ratio, (m.youngs_modulus / rho) ** 0.5, sd["length"], sd["diameter"], sd["density"], unknown
        )
    shots, records, metas = [], [], []
    for t in top.tables("shot"):
        file, channel, unit = read_record_key(t, path.parent)
        name = t.string("name", file.stem if channel is None else f"{file.stem}-{channel}")
        time, strain, meta = read_strain_record(file, channel, unit, bridge, t.key("record"))
        shots.append(Shot(name, time, strain, _ball(t)))
        records.append(file)
        metas.append(meta)
        t.done()
    if not shots:
        raise InputError(f"{path}: no [[shot]] entries")
    names = [s.name for s in shots]
    if len(set(names)) != len(names):
        raise InputError(f"shot: names must be unique, got {names}")
    top.done()
    name = material_raw if isinstance(material_raw, str) else m.name
    return CalibrationFile(title, system, path, geometry, name, bridge, gauge_keys, tuple(shots), tuple(records), tuple(metas), synthetic)
