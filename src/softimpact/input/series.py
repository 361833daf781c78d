"""Series files: bar test series (``reduce``, ``fit``) and calibration series (``calibrate``).

A bar series names the bar (``dispersion = "none" | "pochhammer-chree"`` among
its keys), its gauge (and bridge, for voltage records) and one ``[[test]]`` per
shot: the record, velocity, diameter and mass. A record is a path, or a table
``{ file = "shot12.tdms", channel = "gauge A" }`` (channel by name or index)
for any file :func:`softimpact.input.records.read_lab_record` reads. With a second gauge
(``[gauge] second_position``) each test names its ``second_record`` too. A calibration series
names a beam case and one ``[[test]]`` per measured strain file. Paths inside
are relative to the series file.

The bridge, in ``[gauge]`` (README "A bar test series"): ``bridge`` (quarter,
half, full, or one of :data:`softimpact.models.bridge.CONFIGURATIONS`; half and
full are the bending types half II and full I), ``gauge_factor``,
``excitation``, ``gain``, ``polarity`` (+1: tension reads positive volts, −1:
negative, NI's wiring), ``poisson_ratio`` (default the bar's, for the Poisson
types), ``gauge_resistance_ohm``, ``lead_resistance_ohm``, and shunt
calibration by ``shunt_resistance_ohm`` with the measured ``shunt_step``.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..models.bridge import CONFIGURATIONS, Bridge
from ..models.empirical import PRESETS, PROJECTILES
from ..models.specimens import BarSpec
from .bar_case import read_bar
from .bar_file import bar_tables
from .toml import Table, load_toml, locate, naming, read_units

__all__ = [
    "SeriesTest",
    "Series",
    "TestRecord",
    "load_series",
    "read_bridge",
    "read_test_record",
    "DISPERSION",
    "CalibrationTest",
    "CalibrationSeries",
    "is_calibration_series",
    "load_calibration_series",
]


DISPERSION = ("none", "pochhammer-chree")
BRIDGE_ALIASES = {"half": "half-bending", "full": "full-bending"}  # the old linear bridge's names: 2 and 4 active arms
RECORD_UNITS = {"V": ("voltage", 1.0), "mV": ("voltage", 1e-3), "strain": ("strain", 1.0), "microstrain": ("strain", 1e-6)}


@dataclass(frozen=True)
class SeriesTest:
    """One test of a bar series: its record file (and channel), V [m/s], d [m], m [kg].

    ``channel``: name or index in a multi-channel file (None: the file's only
    one, or a softimpact CSV record). ``unit``: overrides the channel's unit
    (one of RECORD_UNITS). ``accept_flagged``: fit this test even if its
    record is flagged (double hit, clipping).
    """

    name: str
    record: Path
    velocity: float
    diameter: float
    mass: float
    channel: str | int | None = None
    unit: str | None = None
    accept_flagged: bool = False
    second: tuple[Path, str | int | None, str | None] | None = None  # the second gauge's (file, channel, unit)


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
    dispersion: str = "none"
    second_position: float | None = None  # a second gauge [m]: two-gauge wave separation
    bar_file: Path | None = None  # the bar file its [bar] names (input/bar_file.py), an input of the run


@dataclass(frozen=True)
class TestRecord:
    """A test's record as read: time [s], signal (strain [-] or volts), kind, the file's metadata."""

    time: object
    signal: object
    kind: str  # "strain" or "voltage"
    metadata: dict


def read_bridge(g: Table, bar: BarSpec) -> Bridge:
    """The bridge keys of ``[gauge]`` (module docstring) as a :class:`Bridge`, shunt-calibrated if asked."""
    name = g.string("bridge", "quarter")
    configuration = BRIDGE_ALIASES.get(name, name)
    if configuration not in CONFIGURATIONS:
        raise InputError(f"{g.key('bridge')}: {name!r} is not one of {', '.join(('quarter', 'half', 'full') + CONFIGURATIONS[1:])}")
    polarity = g.number("polarity", 1.0)
    if polarity not in (1.0, -1.0):
        raise InputError(f"{g.key('polarity')}: must be 1 (tension reads positive volts) or -1, got {g.raw('polarity')!r}")
    nu = g.number("poisson_ratio", bar.material.poisson_ratio)
    keys = {
        "gauge_factor": g.key("gauge_factor"),
        "excitation": g.key("excitation"),
        "gain": g.key("gain"),
        "poisson_ratio": g.key("poisson_ratio"),
        "gauge_resistance": g.key("gauge_resistance_ohm"),
        "lead_resistance": g.key("lead_resistance_ohm"),
        "shunt_resistance": g.key("shunt_resistance_ohm"),
        "measured_step": g.key("shunt_step"),
    }
    with naming(keys):
        bridge = Bridge(
            configuration,
            g.number("gauge_factor"),
            g.quantity("excitation", "voltage"),
            g.number("gain", 1.0),
            nu,
            g.number("gauge_resistance_ohm", 350.0),
            g.number("lead_resistance_ohm", 0.0),
            # The Bridge's polarity is NI's (tension reads negative); the file's is the sign tension reads.
            -int(polarity),
        )
        if "shunt_resistance_ohm" in g or "shunt_step" in g:
            bridge = bridge.shunt_calibrated(g.number("shunt_resistance_ohm"), g.quantity("shunt_step", "voltage", positive=False))
    return bridge


def _read_record_key(t: Table, base: Path, key: str = "record") -> tuple[Path, str | int | None, str | None]:
    """``record`` (or ``second_record``): a path, or ``{ file, channel, unit }``."""
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


def _native_csv(path: Path) -> bool:
    """Is this a softimpact CSV record (header with a time_* and a signal column, input/records.py)?"""
    from .records import SIGNAL_COLUMNS, TIME_COLUMNS

    if path.suffix.lower() != ".csv":
        return False
    try:
        with open(path, encoding="utf-8-sig", errors="replace") as fh:
            for line in fh:
                if line.strip() and not line.lstrip().startswith("#"):
                    names = {c.strip() for c in line.split(",")}
                    return bool(names & set(TIME_COLUMNS)) and bool(names & set(SIGNAL_COLUMNS))
    except OSError:
        return True  # let the CSV reader say what is wrong with it
    return False


def read_test_record(test: SeriesTest, second: bool = False) -> TestRecord:
    """The test's record (or its second gauge's): a softimpact CSV or a lab file (input/records/).

    Raises InputError naming the file when it cannot be read, has no such
    channel or no time base, or holds a unit other than volts or strain.
    """
    path, channel, unit = test.second if second else (test.record, test.channel, test.unit)
    if channel is None and unit is None and _native_csv(path):
        from .records import read_record

        t, y, kind = read_record(path)
        meta = {"file": str(path), "source_format": "softimpact-csv", "channel": kind, "unit": "V" if kind == "voltage" else "strain"}
        if t.size > 1:
            meta["sample_rate"] = float(1.0 / np.median(np.diff(t)))
            meta["time_start"] = float(t[0])
            meta["pretrigger_samples"] = int(np.count_nonzero(t < 0))
        return TestRecord(t, y, kind, meta)
    from .records import read_lab_record

    rec = read_lab_record(path, channel)
    if unit is None:
        unit = {"V": "V", "strain": "strain", "microstrain": "microstrain"}.get(rec.unit)
        if unit is None:
            raise InputError(
                f"{path}: channel {rec.metadata.get('channel')!r} is in {rec.unit!r}, not volts or strain "
                "(wrong channel? give record.unit if the file's unit is wrong)"
            )
    kind, factor = RECORD_UNITS[unit]
    meta = {k: v for k, v in rec.metadata.items() if k != "header"}
    meta["header"] = {str(k): (v if isinstance(v, (int, float, str, bool)) or v is None else str(v)) for k, v in rec.metadata.get("header", {}).items()}
    return TestRecord(rec.time, rec.signal * factor, kind, meta)


def load_series(arg: str) -> Series:
    """Read a bar test series (path or built-in name); record paths are relative to the file."""
    path = locate(arg)
    top = Table(load_toml(path))
    title = top.string("title", path.stem)
    system = read_units(top)
    synthetic = top.string("synthetic", "")
    bar_tbl, g, bar_file = bar_tables(top, path.parent)  # the bar's own table, or a bar file's (input/bar_file.py)
    dispersion = bar_tbl.string("dispersion", "none", choices=DISPERSION)
    bar = read_bar(bar_tbl)
    if g is None:
        raise InputError("gauge: missing (required)")
    position = g.quantity("position", "length", positive=False)
    if not 0 <= position < bar.length:
        raise InputError(f"gauge.position: {g.raw('position')!r} is not on the bar (0 to {bar.length:.6g} m)")
    second_position = g.quantity("second_position", "length", default=None)
    if second_position is not None:
        if not position < second_position < bar.length:
            raise InputError(f"gauge.second_position: {g.raw('second_position')!r} must lie beyond position, on the bar (to {bar.length:.6g} m)")
        if dispersion != "none":
            raise InputError("gauge.second_position: two-gauge separation with bar.dispersion is not implemented (use one or the other)")
    bridge = read_bridge(g, bar) if "gauge_factor" in g else None
    g.done()
    tests = []
    for t in top.tables("test"):
        record, channel, unit = _read_record_key(t, path.parent)
        second = None
        if second_position is not None:
            second = _read_record_key(t, path.parent, "second_record")
        elif "second_record" in t:
            raise InputError(f"{t.key('second_record')}: a second record needs gauge.second_position")
        accept = t.raw("accept_flagged", False)
        if not isinstance(accept, bool):
            raise InputError(f"{t.key('accept_flagged')}: expected true or false, got {accept!r}")
        tests.append(
            SeriesTest(
                t.string("name", record.stem),
                record,
                t.quantity("velocity", "velocity"),
                t.quantity("diameter", "length"),
                t.quantity("mass", "mass"),
                channel,
                unit,
                accept,
                second,
            )
        )
        t.done()
    if not tests:
        raise InputError(f"{path}: no [[test]] entries")
    names = [t.name for t in tests]
    if len(set(names)) != len(names):
        raise InputError(f"test: names must be unique, got duplicates in {names}")
    top.done()
    return Series(title, system, bar, position, bridge, tuple(tests), path, synthetic, dispersion, second_position, bar_file)


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
