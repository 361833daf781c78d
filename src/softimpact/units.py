"""Units: one pint registry, used at the edges only.

Case files give quantities as strings with units (``"0.5 in"``, ``"1.1 g"``,
``"62.1 in/s"``, ``"0.5 us"``, ``"10.0e6 psi"``, ``"0.0975 lb/in^3"``).
:func:`parse` turns them into SI floats; everything inside the package is SI.
Display units (``units = "in-lbf-s"`` or ``"SI"`` in a case) are a presentation
choice: :func:`display` gives the factor from SI and the label for a kind of
quantity.
"""

from __future__ import annotations

import functools
import hashlib
import json
import math
import os
import re
import tempfile
from dataclasses import dataclass
from pathlib import Path

from .errors import InputError

__all__ = ["registry", "parse", "display", "DisplayUnit", "DISPLAY_SYSTEMS", "DIMENSIONS", "SI_UNITS", "INCH", "POUND_FORCE", "POUND_MASS", "PSI"]

# Exact definitions (NIST SP 811), for catalogue data written in US customary units
# without building the unit registry; nothing else in the package converts units.
INCH = 0.0254  # m
POUND_MASS = 0.45359237  # kg
POUND_FORCE = POUND_MASS * 9.80665  # N
PSI = POUND_FORCE / INCH**2  # Pa

# Dimension of each kind of quantity a case may hold, in pint's notation.
DIMENSIONS = {
    "length": "[length]",
    "mass": "[mass]",
    "time": "[time]",
    "velocity": "[length] / [time]",
    "stress": "[mass] / [length] / [time] ** 2",
    "density": "[mass] / [length] ** 3",
    "force": "[length] * [mass] / [time] ** 2",
    "impulse": "[length] * [mass] / [time]",
    "energy": "[length] ** 2 * [mass] / [time] ** 2",
    "moment": "[length] ** 2 * [mass] / [time] ** 2",
    "toughness": "[mass] / [time] ** 2",  # energy per area (fracture toughness G_c)
    "interface_stiffness": "[mass] / [length] ** 2 / [time] ** 2",  # traction per opening (a cohesive law's penalty)
    "voltage": "[mass] * [length] ** 2 / [time] ** 3 / [current]",
    "frequency": "1 / [time]",
    "dimensionless": "dimensionless",
}


def _import_pint():
    """Import pint without its optional array integrations.

    At import, pint looks for dask (and babel, uncertainties) and imports dask
    whole if it is installed (about 0.15 s, for pint's dask-array support, which
    units of a case file never need). The ``sweep`` extra installs dask, so the
    lookup is made to miss for the duration of pint's import: a ``None`` entry
    in ``sys.modules`` is how ``importlib.util.find_spec`` reports a module as
    absent. The entry is removed afterwards, so dask imports normally later.
    """
    import sys

    blocked = [name for name in ("dask",) if name not in sys.modules]
    for name in blocked:
        sys.modules[name] = None
    try:
        import pint
    finally:
        for name in blocked:
            if sys.modules.get(name, 0) is None:
                del sys.modules[name]
    return pint


class _FactorCache:
    """pint's conversion factors, remembered between runs.

    Importing pint costs about 0.12 s of CPU, more than a whole beam run's
    stepping; a case names the same few units every time. So the factor pint
    computes for a unit (to SI for a kind of quantity, or from SI to a display
    unit) is kept in ``units-<hash>.json`` in the user's cache folder
    (``$SOFTIMPACT_CACHE_DIR``, else ``$XDG_CACHE_HOME/softimpact``, else
    ``~/.cache/softimpact``), and pint is imported only for a unit not seen before.
    pint stays the only source of the numbers: the cache holds nothing pint did
    not compute, and its name carries the hash of ``data/units.txt``, so a change
    of the definitions starts a new cache. Only accepted units are cached
    (errors always come from pint); a cache that cannot be read is ignored, one
    that cannot be written is not written (``SOFTIMPACT_CACHE_DIR=""`` turns it off).
    """

    def __init__(self):
        self._factors: dict[str, float] | None = None

    @functools.cached_property
    def path(self) -> Path | None:
        root = os.environ.get("SOFTIMPACT_CACHE_DIR")
        if root is None:
            base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
            root = os.path.join(base, "softimpact")
        if not root:
            return None
        digest = hashlib.sha256(_DEFINITIONS.read_bytes()).hexdigest()[:16]
        return Path(root) / f"units-{digest}.json"

    def _load(self) -> dict[str, float]:
        if self._factors is None:
            self._factors = {}
            try:
                data = json.loads(self.path.read_text(encoding="utf-8")) if self.path else {}
                if isinstance(data, dict) and all(isinstance(v, float) and math.isfinite(v) and v > 0 for v in data.values()):
                    self._factors = data
            except (OSError, ValueError):
                pass
        return self._factors

    def factor(self, kind: str, unit: str, compute) -> float:
        """The cached factor of ``unit`` for ``kind``, or ``compute()`` (pint's; it may raise) remembered."""
        factors = self._load()
        key = f"{kind}|{unit}"
        if key in factors:
            return factors[key]
        factor = factors[key] = compute()
        if self.path is not None:
            tmp = None
            try:  # atomically: a concurrent reader sees the old file or the new one
                self.path.parent.mkdir(parents=True, exist_ok=True)
                fd, tmp = tempfile.mkstemp(dir=self.path.parent, prefix=".units-", suffix=".tmp")
                with os.fdopen(fd, "w", encoding="utf-8") as f:
                    json.dump(factors, f, sort_keys=True)
                os.replace(tmp, self.path)
            except OSError:
                if tmp is not None and os.path.exists(tmp):
                    os.unlink(tmp)
        return factor


_DEFINITIONS = Path(__file__).resolve().parent / "data" / "units.txt"
_FACTORS = _FactorCache()


@functools.cache
def registry():
    """The package's single pint registry (built on first use, not at import).

    It holds only the units of ``data/units.txt`` (SI, US customary, their
    prefixes): it builds in milliseconds, and a name that is not a unit is an error.
    """
    pint = _import_pint()
    ureg = pint.UnitRegistry(None)
    ureg.load_definitions(str(_DEFINITIONS))
    return ureg


# A quantity is a number and a unit expression: unit names joined by * or /, each
# with an optional one-digit power. Nothing else is evaluated (no 9**9**9).
_NUMBER = re.compile(r"^\s*(?P<number>[+-]?(\d+(\.\d*)?|\.\d+)([eE][+-]?\d+)?)\s*(?P<unit>.*?)\s*$")
_NAME = r"[^\W\d]+"
_POWER = r"(\^|\*\*)[+-]?\d"
_UNIT = re.compile(rf"^{_NAME}({_POWER})?(\s*[*/]\s*{_NAME}({_POWER})?)*$")


def a_or_an(word: str) -> str:
    """``word`` with its indefinite article: "an energy", "a length" (by its first letter)."""
    return f"{'an' if word[:1].lower() in 'aeiou' else 'a'} {word}"


def parse(value, kind: str, key: str) -> float:
    """Parse ``value`` (a number and a unit, ``"0.5 in"``) as a quantity of ``kind``; return SI.

    ``key`` names the case entry for the error message, which echoes the value
    as typed. Plain numbers are accepted only for ``kind == "dimensionless"``.
    Infinite, NaN and overflowing values are refused.
    """
    if kind not in DIMENSIONS:
        raise ValueError(f"unknown kind of quantity {kind!r}")
    if isinstance(value, bool) or not isinstance(value, (str, int, float)):
        raise InputError(f"{key}: expected a quantity with a unit, got {value!r}")
    example = f'(expected {a_or_an(kind)}, e.g. "{_EXAMPLE[kind]}")'
    if isinstance(value, (int, float)):
        if kind != "dimensionless":
            raise InputError(f"{key}: missing unit in {value!r} {example}")
        if not math.isfinite(value):
            raise InputError(f"{key}: {value!r} is not a finite number")
        return float(value)
    m = _NUMBER.match(value)
    if m is None:
        raise InputError(f"{key}: cannot read {value!r} as a number and a unit {example}")
    number, unit = float(m["number"]), m["unit"]
    if not math.isfinite(number):
        raise InputError(f"{key}: {value!r} is not a finite number")
    if not unit:
        if kind == "dimensionless":
            return number
        raise InputError(f"{key}: missing unit in {value!r} {example}")
    if not _UNIT.match(unit.replace(" ", "")):
        raise InputError(f"{key}: cannot read the unit {unit!r} of {value!r} (unit names joined by * and /, powers as ^2) {example}")
    unit = unit.replace(" ", "").replace("**", "^")

    def to_si() -> float:
        ureg = registry()
        try:
            q = ureg.Quantity(1.0, ureg.parse_units(unit))
        except Exception:  # pint raises several unrelated types for unknown names
            raise InputError(f"{key}: unknown unit {m['unit']!r} in {value!r} {example}") from None
        if q.dimensionality != ureg.Quantity(1, SI_UNITS[kind]).dimensionality:
            raise InputError(f"{key}: {value!r} is not {a_or_an(kind)} (its dimension is {q.dimensionality})")
        return float(q.to(SI_UNITS[kind]).magnitude)

    si = number * _FACTORS.factor(kind, unit, to_si)
    if not math.isfinite(si):
        raise InputError(f"{key}: {value!r} is not a finite {kind}")
    return si


SI_UNITS = {
    "length": "m",
    "mass": "kg",
    "time": "s",
    "velocity": "m/s",
    "stress": "Pa",
    "density": "kg/m^3",
    "force": "N",
    "impulse": "N*s",
    "energy": "J",
    "moment": "N*m",  # a moment, or a bending stiffness per unit width (N·m²/m)
    "toughness": "J/m^2",
    "interface_stiffness": "N/m^3",
    "voltage": "V",
    "frequency": "Hz",
    "dimensionless": "dimensionless",
}

_EXAMPLE = {
    "length": "0.5 in",
    "mass": "1.1 g",
    "time": "0.5 us",
    "velocity": "62.1 in/s",
    "stress": "10.0e6 psi",
    "density": "0.0975 lb/in^3",
    "force": "44 lbf",
    "impulse": "0.01 N*s",
    "energy": "1 J",
    "moment": "10 lbf*in",
    "toughness": "0.5 kJ/m^2",
    "interface_stiffness": "1e6 N/mm^3",
    "voltage": "5 V",
    "frequency": "1 kHz",
    "dimensionless": "0.3",
}


@dataclass(frozen=True)
class DisplayUnit:
    """How a kind of quantity is shown: ``shown = factor * si_value``."""

    factor: float
    label: str


# Display units of each system (for tables and plots only).
DISPLAY_SYSTEMS = {
    "in-lbf-s": {
        "length": "in",
        "mass": "g",
        "time": "us",
        "velocity": "in/s",
        "stress": "psi",
        "density": "lb/in^3",
        "force": "lbf",
        "impulse": "lbf*s",
        "energy": "in*lbf",
        "moment": "lbf*in",
        "strain": "microstrain",
    },
    "SI": {
        "length": "mm",
        "mass": "g",
        "time": "us",
        "velocity": "m/s",
        "stress": "GPa",
        "density": "kg/m^3",
        "force": "N",
        "impulse": "N*s",
        "energy": "mJ",
        "moment": "N*m",
        "strain": "microstrain",
    },
}

_LABELS = {
    "in*lbf": "in·lbf",
    "lbf*in": "lbf·in",
    "N*m": "N·m",
    "us": "µs",
    "microstrain": "µε",
    "lbf*s": "lbf·s",
    "N*s": "N·s",
    "lb/in^3": "lb/in³",
    "kg/m^3": "kg/m³",
}


@functools.cache
def display(system: str, kind: str) -> DisplayUnit:
    """Factor from SI and label for showing a quantity of ``kind`` in ``system``."""
    if system not in DISPLAY_SYSTEMS:
        raise InputError(f"units: unknown display system {system!r} (choose from {', '.join(DISPLAY_SYSTEMS)})")
    unit = DISPLAY_SYSTEMS[system][kind]
    si = "dimensionless" if kind == "strain" else SI_UNITS[kind]
    factor = _FACTORS.factor(f"display {kind}", unit, lambda: float(registry().Quantity(1.0, si).to(unit).magnitude))
    return DisplayUnit(factor, _LABELS.get(unit, unit))
