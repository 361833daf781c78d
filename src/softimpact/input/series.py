"""Series files: bar test series (``reduce``, ``fit``) and calibration series (``calibrate``).

A bar series names the bar, its gauge (and bridge, for voltage records) and
one ``[[test]]`` per shot: the record file, velocity, diameter and mass. A
calibration series names a beam case and one ``[[test]]`` per measured strain
file. Paths inside are relative to the series file.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..errors import InputError
from ..models.empirical import PRESETS, PROJECTILES
from ..models.specimens import BarSpec, Bridge
from .bar_case import read_bar
from .toml import Table, load_toml, locate, naming, read_units

__all__ = ["SeriesTest", "Series", "load_series", "CalibrationTest", "CalibrationSeries", "is_calibration_series", "load_calibration_series"]


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
    system = read_units(top)
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
        with naming({None: "gauge"}):
            bridge = Bridge(g.number("gauge_factor"), Bridge.ARMS[arms], g.quantity("excitation", "voltage"), g.number("gain", 1.0), g.number("polarity", 1.0))
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
        tests.append(
            CalibrationTest(
                t.string("name", Path(measured).stem),
                path.parent / measured,
                t.quantity("velocity", "velocity"),
                t.quantity("contact_radius", "length", default=None),
                t.quantity("contact_time", "time", default=None, positive=False),
            )
        )
        ref = t.table("reference", optional=True)
        if ref is not None:
            reference.append(
                (
                    tests[-1].velocity,
                    ref.quantity("peak_force", "force"),
                    ref.quantity("time_of_peak", "time"),
                    ref.quantity("duration", "time"),
                    ref.quantity("contact_radius", "length"),
                )
            )
            ref.done()
        t.done()
    top.done()
    if not tests:
        raise InputError(f"{path}: no [[test]] entries")
    return CalibrationSeries(
        title,
        case_ref,
        projectile,
        constants if constants is None or constants in PRESETS else str(path.parent / constants),
        tuple(tests),
        path,
        synthetic,
        tuple(reference),
    )
