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
from .fem.newmark import SolverSpec
from .workflows.bar_impact import BarImpactProblem, BarSpec, EndCap, Gauge, Projectile
from .workflows.reduction import Bridge

__all__ = ["CalibrationSeries", "CalibrationTest", "load_calibration_series", "is_calibration_series", "load_beam_case", "beam_problem", "Series", "SeriesTest", "load_series", "Table", "builtin_cases", "locate", "load_toml", "read_material", "read_bar", "bar_problem", "load_bar_case"]

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
    snapshots = ()
    output = top.table("output", optional=True)
    if output is not None:
        raw = output.raw("snapshots", [])
        if not isinstance(raw, list):
            raise InputError(f"output.snapshots: expected a list of times, got {raw!r}")
        snapshots = tuple(units.parse(v, "time", f"output.snapshots[{i}]") for i, v in enumerate(raw))
        for i, t in enumerate(snapshots):
            if not 0 <= t <= solver.duration:
                raise InputError(f"output.snapshots[{i}]: {raw[i]!r} is outside the run (0 to {solver.duration * 1e6:.6g} us)")
        output.done()
    top.done()
    return BarImpactProblem(bar, projectile, solver, gauges, law, title, system, snapshots)


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


def read_ply(tbl: Table, name: str = "ply"):
    from .models.laminate import PLIES, Ply

    value = tbl.raw(name)
    if isinstance(value, str):
        if value not in PLIES:
            raise InputError(f"{tbl.key(name)}: unknown ply {value!r} (catalogue: {', '.join(PLIES)})")
        return PLIES[value]
    p = Table(value, tbl.key(name))
    mods = {k: p.quantity(k, "stress") for k in ("E1", "E2", "E3", "G12", "G13", "G23")}
    ply = Ply(
        p.string("name", "inline ply"), mods["E1"], mods["E2"], mods["E3"], mods["G12"], mods["G13"], mods["G23"],
        p.number("nu12"), p.number("nu13"), p.number("nu23"), p.quantity("density", "density"), p.quantity("thickness", "length"),
        p.string("source", "user input"),
    )
    p.done()
    return ply


def read_history(tbl: Table, name: str, base: Path):
    """A force history: eq (15) ('skewed'), a CSV table ('table'), or the empirical model ('empirical')."""
    from .models.empirical import PRESETS, PROJECTILES
    from .models.pulses import SkewedPulse, TabulatedPulse

    h = tbl.table(name)
    shape = h.string("shape", "skewed", choices=("skewed", "table", "empirical"))
    if shape == "skewed":
        pulse = SkewedPulse(h.quantity("peak_force", "force"), h.quantity("time_of_peak", "time"), h.quantity("duration", "time"))
    elif shape == "table":
        from .io import read_columns

        path = base / h.string("file")
        names, data = read_columns(path)
        if "time_s" not in names or "force_N" not in names:
            raise InputError(f"{h.key('file')}: {path} needs columns time_s and force_N")
        pulse = TabulatedPulse(data[:, names.index("time_s")], data[:, names.index("force_N")])
    else:
        proj = h.string("projectile", choices=tuple(PROJECTILES))
        P = PROJECTILES[proj]
        law = PRESETS[h.string("constants", P.law, choices=tuple(PRESETS))]
        pulse = law.pulse(P.mass, P.diameter, h.quantity("velocity", "velocity"))
    h.done()
    return pulse


def beam_problem(data: dict, base: Path = Path("."), history: int | None = None):
    """A beam case (parsed TOML) as a BeamProblem; ``history`` picks a row of [[load.table]] (1-based)."""
    from .models.laminate import Blend, Stack, parse_layup
    from .models.pulses import SkewedPulse
    from .workflows.beam_impact import BeamGauge, BeamLoad, BeamProblem, BeamSpec

    top = Table(data)
    title = top.string("title", "")
    system = top.string("units", "in-lbf-s", choices=tuple(units.DISPLAY_SYSTEMS))
    b = top.table("beam")
    elements = b.raw("elements", [200, 6])
    if not (isinstance(elements, list) and len(elements) == 2 and all(isinstance(e, int) and not isinstance(e, bool) and e >= 1 for e in elements)):
        raise InputError(f"beam.elements: expected [along the length, through the thickness], got {elements!r}")
    lam = b.table("laminate", optional=True)
    mat = b.table("material", optional=True)
    if (lam is None) == (mat is None):
        raise InputError("beam: give exactly one of [beam.laminate] and [beam.material]")
    stack = material = None
    thickness = 0.0
    model = "smeared"
    if lam is not None:
        ply = read_ply(lam)
        model = lam.string("model", "smeared", choices=("smeared", "layered"))
        if "fractions" in lam:
            fr = lam.raw("fractions")
            if not isinstance(fr, dict) or not fr:
                raise InputError(f"beam.laminate.fractions: expected a table of angle = fraction, got {fr!r}")
            try:
                pairs = tuple((float(k), float(v)) for k, v in fr.items())
            except ValueError:
                raise InputError(f"beam.laminate.fractions: angles and fractions must be numbers, got {fr!r}") from None
            stack = Blend(ply, pairs, lam.quantity("thickness", "length"))
        else:
            stack = Stack(ply, parse_layup(lam.string("layup")))
        lam.done()
    else:
        if "material" in mat:
            material = read_material(mat)
        else:
            material = Material(mat.string("name", "inline material"), mat.quantity("youngs_modulus", "stress"), mat.number("poisson_ratio"), mat.quantity("density", "density"))
        thickness = mat.quantity("thickness", "length")
        mat.done()
    damping = (0.0, 0.0)
    d = b.table("damping", optional=True)
    if d is not None:
        ratio = d.number("ratio")
        freqs = d.raw("frequencies")
        if not (isinstance(freqs, list) and len(freqs) == 2):
            raise InputError(f"beam.damping.frequencies: expected two frequencies, got {freqs!r}")
        w1, w2 = (2 * 3.141592653589793 * units.parse(f, "frequency", "beam.damping.frequencies") for f in freqs)
        # ζ(ω) = α/(2ω) + βω/2 equal to the ratio at both frequencies.
        damping = (2 * ratio * w1 * w2 / (w1 + w2), 2 * ratio / (w1 + w2))
        d.done()
    spec = BeamSpec(
        b.quantity("length", "length"), b.quantity("width", "length"), elements[0], elements[1],
        b.string("support", "clamped-free", choices=("clamped-free", "clamped-clamped", "simply-supported")),
        stack, model, material, thickness, b.string("plane", "strain", choices=("strain", "stress")),
        b.string("mass", "consistent", choices=("consistent", "lumped")) == "lumped", damping,
    )
    b.done()
    ld = top.table("load")
    position = ld.quantity("position", "length")
    radius = ld.quantity("contact_radius", "length")
    pulse = read_history(ld, "history", base)
    rows = ld.tables("table", optional=True)
    if history is not None:
        if not 1 <= history <= len(rows):
            raise InputError(f"--history: {history} is not a row of [[load.table]] (1 to {len(rows)})")
        row = rows[history - 1]
        pulse = SkewedPulse(row.quantity("peak_force", "force"), row.quantity("time_of_peak", "time"), row.quantity("duration", "time"))
        radius = row.quantity("contact_radius", "length", default=radius)
        row.quantity("velocity", "velocity", default=None)
        row.done()
    else:
        for row in rows:
            row._used.update(row.data)
    ld.done()
    solver = read_solver(top.table("solver"))
    gauges = []
    for g in top.tables("gauges", optional=True):
        gauges.append(BeamGauge(g.string("name"), g.quantity("position", "length", positive=False), g.string("surface", "bottom", choices=("top", "bottom")), g.quantity("length", "length", default=0.031 * 0.0254)))
        g.done()
    if len({g.name for g in gauges}) != len(gauges):
        raise InputError("gauges: names must be unique")
    top.done()
    return BeamProblem(spec, BeamLoad(position, radius, pulse), solver, tuple(gauges), title, system)


def load_beam_case(case: str, history: int | None = None):
    path = locate(case)
    return beam_problem(load_toml(path), path.parent, history), path


def table_rows(case: str) -> list[dict]:
    """The [[load.table]] rows of a beam case, in SI: velocity, F0, tF0, T, r0."""
    path = locate(case)
    out = []
    for i, row in enumerate(Table(load_toml(path)).table("load").tables("table", optional=True)):
        out.append({
            "velocity": row.quantity("velocity", "velocity"), "peak_force": row.quantity("peak_force", "force"),
            "time_of_peak": row.quantity("time_of_peak", "time"), "duration": row.quantity("duration", "time"),
            "contact_radius": row.quantity("contact_radius", "length"),
        })
    return out


@dataclass(frozen=True)
class CalibrationTest:
    """One test of a calibration series: measured file, velocity [m/s], r0 [m] (None: the case's)."""

    name: str
    measured: Path
    velocity: float
    contact_radius: float | None
    contact_time: float | None = None


@dataclass(frozen=True)
class CalibrationSeries:
    title: str
    case: str  # path or built-in name of the beam case
    projectile: str
    constants: str | None
    tests: tuple[CalibrationTest, ...]
    path: Path
    synthetic: str = ""
    reference: tuple = ()  # the paper's rows (Tables II/III): (V, F0, tF0, T, r0) in SI, if given


def is_calibration_series(arg: str) -> bool:
    try:
        data = load_toml(locate(arg))
    except InputError:
        return False
    return "case" in data and "test" in data


def load_calibration_series(arg: str) -> CalibrationSeries:
    """Read a calibration series: a beam case and its measured tests (paths relative to the file)."""
    from .models.empirical import PRESETS, PROJECTILES

    path = locate(arg)
    top = Table(load_toml(path))
    title = top.string("title", path.stem)
    case = top.string("case")
    case_path = path.parent / case
    case_ref = str(case_path) if case_path.is_file() else case
    locate(case_ref)
    projectile = top.string("projectile", "rubber-1/2in", choices=tuple(PROJECTILES))
    constants = top.raw("constants", None)
    if constants is not None and constants not in PRESETS and not (path.parent / str(constants)).is_file():
        raise InputError(f"constants: {constants!r} is neither a preset ({', '.join(PRESETS)}) nor a file")
    synthetic = top.string("synthetic", "")
    tests, reference = [], []
    for t in top.tables("test"):
        measured = t.string("measured")
        tests.append(CalibrationTest(
            t.string("name", Path(measured).stem), path.parent / measured, t.quantity("velocity", "velocity"),
            t.quantity("contact_radius", "length", default=None), t.quantity("contact_time", "time", default=None, positive=False),
        ))
        ref = t.table("reference", optional=True)
        if ref is not None:
            reference.append((tests[-1].velocity, ref.quantity("peak_force", "force"), ref.quantity("time_of_peak", "time"), ref.quantity("duration", "time"), ref.quantity("contact_radius", "length")))
            ref.done()
        t.done()
    top.done()
    if not tests:
        raise InputError(f"{path}: no [[test]] entries")
    return CalibrationSeries(title, case_ref, projectile, constants if constants is None or constants in PRESETS else str(path.parent / constants), tuple(tests), path, synthetic, tuple(reference))
