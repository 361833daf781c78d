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

from ..fem.bar import Rod
from .materials import Material, sphere_mass

__all__ = ["EndCap", "BarSpec", "Projectile", "Gauge"]


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

    def rod(self) -> Rod:
        """The FE rod, with the end cap's mass lumped at x = 0."""
        return Rod(
            self.length,
            self.area,
            self.material.youngs_modulus,
            self.material.density,
            self.elements,
            0.0 if self.end_cap is None else self.end_cap.mass,
        )


@dataclass(frozen=True)
class Projectile:
    """A sphere: material, diameter [m], impact velocity [m/s], mass [kg]."""

    material: Material
    diameter: float
    velocity: float
    mass: float

    @classmethod
    def solid(cls, material: Material, diameter: float, velocity: float) -> Projectile:
        """A solid sphere whose mass follows from density and diameter."""
        return cls(material, diameter, velocity, sphere_mass(material, diameter))


@dataclass(frozen=True)
class Gauge:
    """A strain gauge at ``position`` [m] from the struck end."""

    name: str
    position: float
