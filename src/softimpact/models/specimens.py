"""Specimens: the parameter objects of test articles and instruments (SI).

A bar (:class:`BarSpec`, with an optional :class:`EndCap`), a sphere striking
it (:class:`Projectile`) and a strain gauge on it (:class:`Gauge`); the bridge
that turns its resistance change into volts is :class:`softimpact.models.bridge.Bridge`.
Positions on a bar are measured from the struck end. Every workflow that needs one takes it
from here, so workflows never import each other for their inputs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import InputError
from ..units import INCH
from .materials import Material, sphere_mass

__all__ = ["EndCap", "BarSpec", "Projectile", "Gauge", "Impactor", "GAUGE_LENGTH"]

GAUGE_LENGTH = 0.031 * INCH  # m: the paper's strain gauges, 0.031 in (docs/modelling-notes.md); the default of beam and plate gauges


@dataclass(frozen=True)
class EndCap:
    """A cylindrical cap on the struck end, modelled as a lumped mass."""

    material: Material
    diameter: float
    length: float

    @property
    def mass(self) -> float:
        """ρ·π d²/4·L [kg]."""
        return self.material.density * math.pi * self.diameter**2 / 4.0 * self.length


@dataclass(frozen=True)
class BarSpec:
    """A uniform circular bar; positions are measured from the struck end."""

    material: Material
    length: float
    diameter: float
    elements: int = 39
    end_cap: EndCap | None = None

    @property
    def area(self) -> float:
        return math.pi * self.diameter**2 / 4.0


@dataclass(frozen=True)
class Projectile:
    """A sphere: material, diameter [m], impact velocity [m/s], mass [kg]."""

    material: Material
    diameter: float
    velocity: float
    mass: float

    def __post_init__(self):
        Impactor(self.mass, self.diameter, self.velocity)  # the same rule on every path: positive, velocity toward the target

    @classmethod
    def solid(cls, material: Material, diameter: float, velocity: float) -> Projectile:
        """A solid sphere whose mass follows from density and diameter."""
        return cls(material, diameter, velocity, sphere_mass(material, diameter))


@dataclass(frozen=True)
class Gauge:
    """A strain gauge at ``position`` [m] from the struck end."""

    name: str
    position: float


@dataclass(frozen=True)
class Impactor:
    """A rigid impactor: mass [kg], diameter [m], velocity [m/s] toward the structure."""

    mass: float
    diameter: float
    velocity: float

    def __post_init__(self):
        for name in ("mass", "diameter", "velocity"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise InputError(f"impactor.{name} must be positive, got {v!r}", name)

    @property
    def momentum(self) -> float:
        return self.mass * self.velocity

    @property
    def kinetic_energy(self) -> float:
        return 0.5 * self.mass * self.velocity**2
