"""Case files: TOML in, validated problem objects out.

Every quantity is a string with a unit, parsed once here (:mod:`softimpact.units`).
Unknown keys, missing units, out-of-range values: an :class:`InputError` naming
the key and the value. Built-in cases (``softimpact cases``) are addressed by
name as well as by path.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

from . import units
from .errors import InputError
from .fem.newmark import NewmarkParameters
from .models.materials import Material, lookup, sphere_mass
from .workflows.bar_impact import BarImpactProblem, BarSpec, EndCap, Gauge, Projectile, SolverSpec
from .workflows.reduction import Bridge

__all__ = ["Series", "SeriesTest", "load_series", "Table", "builtin_cases", "locate", "load_toml", "read_material", "read_bar", "bar_problem", "load_bar_case"]

_MISSING = object()


class Table:
    """A TOML table read key by key; :meth:`done` rejects keys nobody asked for."""

    def __init__(self, data: dict, path: str = ""):
        if not isinstance(data, dict):
            raise InputError(f"{path or 'case'}: expected a table, got {data!r}")
        self.data, self.path, self._used = data, path, set()

    def key(self, name: str) -> str:
        return f"{self.path}.{name}" if self.path else name

    def __contains__(self, name: str) -> bool:
        return name in self.data

    def raw(self, name: str, default=_MISSING):
        self._used.add(name)
        if name not in self.data:
            if default is _MISSING:
                raise InputError(f"{self.key(name)}: missing (required)")
            return default
        return self.data[name]

    def quantity(self, name: str, kind: str, default=_MISSING, positive: bool = True) -> float:
        value = self.raw(name, default)
        if value is default and default is not _MISSING:
            return value
        q = units.parse(value, kind, self.key(name))
        if positive and not q > 0:
            raise InputError(f"{self.key(name)}: must be positive, got {value!r}")
        return q

    def number(self, name: str, default=_MISSING) -> float:
        value = self.raw(name, default)
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise InputError(f"{self.key(name)}: expected a number, got {value!r}")
        return float(value)

    def integer(self, name: str, default=_MISSING, minimum: int = 1) -> int:
        value = self.raw(name, default)
        if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
            raise InputError(f"{self.key(name)}: expected an integer >= {minimum}, got {value!r}")
        return value

    def string(self, name: str, default=_MISSING, choices=None) -> str:
        value = self.raw(name, default)
        if not isinstance(value, str):
            raise InputError(f"{self.key(name)}: expected text, got {value!r}")
        if choices is not None and value not in choices:
            raise InputError(f"{self.key(name)}: {value!r} is not one of {', '.join(map(str, choices))}")
        return value

    def table(self, name: str, optional: bool = False) -> "Table | None":
        value = self.raw(name, None if optional else _MISSING)
        return None if value is None else Table(value, self.key(name))

    def tables(self, name: str, optional: bool = False) -> list["Table"]:
        value = self.raw(name, [] if optional else _MISSING)
        if not isinstance(value, list):
            raise InputError(f"{self.key(name)}: expected an array of tables ([[{name}]]), got {value!r}")
        return [Table(v, f"{self.key(name)}[{i}]") for i, v in enumerate(value)]

    def done(self) -> None:
        unknown = sorted(set(self.data) - self._used)
        if unknown:
            raise InputError(f"{self.key(unknown[0])}: unknown key (value {self.data[unknown[0]]!r})")


def builtin_cases() -> dict[str, Path]:
    """Built-in case and series files by name (file stem)."""
    found = {}
    root = resources.files("softimpact") / "data"
    for folder in ("cases", "series"):
        d = root / folder
        if d.is_dir():
            for entry in d.iterdir():
                if entry.name.endswith(".toml"):
                    found[entry.name[: -len(".toml")]] = Path(str(entry))
    return dict(sorted(found.items()))


def locate(case: str) -> Path:
    """A case argument as a path: an existing file, or a built-in name."""
    path = Path(case)
    if path.is_file():
        return path
    known = builtin_cases()
    if case in known:
        return known[case]
    raise InputError(f"CASE: {case!r} is neither a file nor a built-in case (built-ins: {', '.join(known)})")


def load_toml(path: Path) -> dict:
    try:
        with open(path, "rb") as fh:
            return tomllib.load(fh)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{path}: not valid TOML ({exc})") from None
    except OSError as exc:
        raise InputError(f"{path}: cannot read ({exc.strerror})") from None


def read_material(tbl: Table, name: str = "material") -> Material:
    """A catalogue name, or an inline table of E, ν, ρ."""
    value = tbl.raw(name)
    if isinstance(value, str):
        return lookup(value, tbl.key(name))
    inline = Table(value, tbl.key(name))
    mat = Material(
        inline.string("name", "inline material"),
        inline.quantity("youngs_modulus", "stress"),
        inline.number("poisson_ratio"),
        inline.quantity("density", "density"),
        inline.string("source", "user input"),
    )
    inline.done()
    return mat


def read_bar(tbl: Table, default_elements: int = 39) -> BarSpec:
    """The ``[bar]`` table (with its optional ``[bar.end_cap]``)."""
    cap_tbl = tbl.table("end_cap", optional=True)
    cap = None
    if cap_tbl is not None:
        cap = EndCap(read_material(cap_tbl), cap_tbl.quantity("diameter", "length"), cap_tbl.quantity("length", "length"))
        cap_tbl.done()
    bar = BarSpec(
        read_material(tbl),
        tbl.quantity("length", "length"),
        tbl.quantity("diameter", "length"),
        tbl.integer("elements", default_elements),
        cap,
    )
    tbl.done()
    return bar


def read_solver(tbl: Table) -> SolverSpec:
    spec = SolverSpec(
        tbl.quantity("time_step", "time"),
        tbl.quantity("duration", "time"),
        NewmarkParameters(tbl.number("beta", 0.25), tbl.number("gamma", 0.5)),
    )
    tbl.done()
    return spec


def read_gauges(top: Table, length: float) -> tuple[Gauge, ...]:
    gauges = []
    for g in top.tables("gauges", optional=True):
        gauge = Gauge(g.string("name"), g.quantity("position", "length", positive=False))
        if not 0.0 <= gauge.position <= length:
            raise InputError(f"{g.key('position')}: {g.raw('position')!r} is outside the bar (0 to {length:.6g} m)")
        g.done()
        gauges.append(gauge)
    names = [g.name for g in gauges]
    if len(set(names)) != len(names):
        raise InputError(f"gauges: names must be unique, got {names}")
    return tuple(gauges)


def bar_problem(data: dict) -> BarImpactProblem:
    """A bar case (already parsed TOML) as a :class:`BarImpactProblem`."""
    top = Table(data)
    title = top.string("title", "")
    system = top.string("units", "in-lbf-s", choices=tuple(units.DISPLAY_SYSTEMS))
    bar = read_bar(top.table("bar"))
    p = top.table("projectile")
    material = read_material(p)
    diameter = p.quantity("diameter", "length")
    mass = p.quantity("mass", "mass", default=None)
    projectile = Projectile(
        material, diameter, p.quantity("velocity", "velocity"), sphere_mass(material, diameter) if mass is None else mass
    )
    p.done()
    contact_tbl = top.table("contact", optional=True)
    law = "hertz"
    if contact_tbl is not None:
        law = contact_tbl.string("law", "hertz", choices=("hertz",))
        contact_tbl.done()
    solver = read_solver(top.table("solver"))
    gauges = read_gauges(top, bar.length)
    top.done()
    return BarImpactProblem(bar, projectile, solver, gauges, law, title, system)


def load_bar_case(case: str) -> tuple[BarImpactProblem, Path]:
    """Read a bar case by path or built-in name; returns the problem and its file."""
    path = locate(case)
    return bar_problem(load_toml(path)), path


@dataclass(frozen=True)
class SeriesTest:
    """One test of a bar series: its record file, V [m/s], d [m], m [kg]."""

    name: str
    record: Path
    velocity: float
    diameter: float
    mass: float


@dataclass(frozen=True)
class Series:
    """A series of bar tests: the bar, the gauge (and its bridge, for voltage records), the tests."""

    title: str
    units: str
    bar: BarSpec
    gauge_position: float
    bridge: Bridge | None
    tests: tuple[SeriesTest, ...]
    path: Path
    synthetic: str = ""


def load_series(arg: str) -> Series:
    """Read a bar test series (path or built-in name); record paths are relative to the file."""
    path = locate(arg)
    top = Table(load_toml(path))
    title = top.string("title", path.stem)
    system = top.string("units", "in-lbf-s", choices=tuple(units.DISPLAY_SYSTEMS))
    synthetic = top.string("synthetic", "")
    bar = read_bar(top.table("bar"))
    g = top.table("gauge")
    position = g.quantity("position", "length", positive=False)
    if not 0 <= position < bar.length:
        raise InputError(f"gauge.position: {g.raw('position')!r} is not on the bar (0 to {bar.length:.6g} m)")
    bridge = None
    if "gauge_factor" in g:
        arms = g.raw("bridge", "quarter")
        if arms not in Bridge.ARMS:
            raise InputError(f"gauge.bridge: {arms!r} is not one of {', '.join(Bridge.ARMS)}")
        bridge = Bridge(
            g.number("gauge_factor"), Bridge.ARMS[arms], g.quantity("excitation", "voltage"), g.number("gain", 1.0), g.number("polarity", 1.0)
        )
    g.done()
    tests = []
    for t in top.tables("test"):
        record = t.string("record")
        tests.append(
            SeriesTest(
                t.string("name", Path(record).stem),
                (path.parent / record),
                t.quantity("velocity", "velocity"),
                t.quantity("diameter", "length"),
                t.quantity("mass", "mass"),
            )
        )
        t.done()
    if not tests:
        raise InputError(f"{path}: no [[test]] entries")
    names = [t.name for t in tests]
    if len(set(names)) != len(names):
        raise InputError(f"test: names must be unique, got duplicates in {names}")
    top.done()
    return Series(title, system, bar, position, bridge, tuple(tests), path, synthetic)
