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
from dataclasses import dataclass

from .errors import InputError

__all__ = ["registry", "parse", "display", "DisplayUnit", "DISPLAY_SYSTEMS", "DIMENSIONS"]

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
    "voltage": "[mass] * [length] ** 2 / [time] ** 3 / [current]",
    "frequency": "1 / [time]",
    "dimensionless": "dimensionless",
}


@functools.cache
def registry():
    """The package's single pint registry (built on first use, not at import)."""
    import pint

    return pint.UnitRegistry()


def parse(value, kind: str, key: str) -> float:
    """Parse ``value`` (a string with a unit) as a quantity of ``kind``; return SI.

    ``key`` names the case entry for the error message. Plain numbers are
    accepted only for ``kind == "dimensionless"``.
    """
    if kind not in DIMENSIONS:
        raise ValueError(f"unknown kind of quantity {kind!r}")
    if isinstance(value, bool) or not isinstance(value, (str, int, float)):
        raise InputError(f"{key}: expected a quantity with a unit, got {value!r}")
    if isinstance(value, (int, float)):
        if kind == "dimensionless":
            return float(value)
        raise InputError(f"{key}: missing unit in {value!r} (expected a {kind}, e.g. \"{_EXAMPLE[kind]}\")")
    ureg = registry()
    try:
        q = ureg.Quantity(value.strip())
    except Exception as exc:  # pint raises several unrelated types for bad text
        raise InputError(f"{key}: cannot read {value!r} as a quantity ({exc.__class__.__name__})") from None
    if not hasattr(q, "dimensionality") or q.unitless and kind != "dimensionless":
        raise InputError(f"{key}: missing unit in {value!r} (expected a {kind}, e.g. \"{_EXAMPLE[kind]}\")")
    if q.dimensionality != ureg.Quantity(1, _SI[kind]).dimensionality:
        raise InputError(f"{key}: {value!r} is not a {kind} (its dimension is {q.dimensionality})")
    return float(q.to(_SI[kind]).magnitude)


_SI = {
    "length": "m",
    "mass": "kg",
    "time": "s",
    "velocity": "m/s",
    "stress": "Pa",
    "density": "kg/m^3",
    "force": "N",
    "impulse": "N*s",
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
        "strain": "microstrain",
    },
}

_LABELS = {"us": "µs", "microstrain": "µε", "lbf*s": "lbf·s", "N*s": "N·s", "lb/in^3": "lb/in³", "kg/m^3": "kg/m³"}


@functools.cache
def display(system: str, kind: str) -> DisplayUnit:
    """Factor from SI and label for showing a quantity of ``kind`` in ``system``."""
    if system not in DISPLAY_SYSTEMS:
        raise InputError(f"units: unknown display system {system!r} (choose from {', '.join(DISPLAY_SYSTEMS)})")
    unit = DISPLAY_SYSTEMS[system][kind]
    ureg = registry()
    si = "dimensionless" if kind == "strain" else _SI[kind]
    factor = float(ureg.Quantity(1.0, si).to(unit).magnitude)
    return DisplayUnit(factor, _LABELS.get(unit, unit))
