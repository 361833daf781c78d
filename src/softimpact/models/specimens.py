"""Specimens: the parameter objects of test articles and instruments (SI).

A bar (:class:`BarSpec`, with an optional :class:`EndCap`), the sphere striking
it or a beam or plate (:class:`Impactor`) and a strain gauge on it (:class:`Gauge`); the bridge
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

__all__ = ["EndCap", "BarSpec", "Impactor", "Gauge", "GAUGE_LENGTH"]

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
class Gauge:
    """A strain gauge at ``position`` [m] from the struck end."""

    name: str
    position: float


@dataclass(frozen=True)
class Impactor:
    """A sphere striking a structure: mass [kg], diameter [m], velocity [m/s] toward the structure, and
    its ``material`` where a contact law needs one (Hertz on a bar's end, ice, gelatin); None for a rigid
    impactor whose law is given whole (a coupled impact case carries its material beside it).

    The one sphere of every path: the ``projectile`` of bar cases and series, the ``impactor`` of impact
    cases (docs/naming.md)."""

    mass: float
    diameter: float
    velocity: float
    material: Material | None = None

    def __post_init__(self):
        for name in ("mass", "diameter", "velocity"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise InputError(f"impactor.{name} must be positive, got {v!r}", name)

    @classmethod
    def solid(cls, material: Material, diameter: float, velocity: float) -> Impactor:
        """A solid sphere of ``material`` whose mass follows from density and diameter."""
        return cls(sphere_mass(material, diameter), diameter, velocity, material)

    @property
    def momentum(self) -> float:
        return self.mass * self.velocity

    @property
    def kinetic_energy(self) -> float:
        return 0.5 * self.mass * self.velocity**2
