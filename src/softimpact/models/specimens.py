"""Specimens: the parameter objects of test articles and instruments (SI).

A bar (:class:`BarSpec`, with an optional :class:`EndCap`), a sphere striking
it (:class:`Projectile`), a strain gauge on it (:class:`Gauge`) and the bridge
that turns its resistance change into volts (:class:`Bridge`). Positions on a
bar are measured from the struck end. Every workflow that needs one takes it
from here, so workflows never import each other for their inputs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..fem.bar import Rod
from .materials import Material, sphere_mass

__all__ = ["EndCap", "BarSpec", "Projectile", "Gauge", "Bridge"]


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


@dataclass(frozen=True)
class Bridge:
    """Wheatstone bridge of strain gauges: V_out = gain·V_exc·(arms/4)·GF·ε (small strain).

    ``active_arms``: 1 quarter, 2 half, 4 full bridge. ``polarity`` −1 for a
    bridge wired so that compression reads positive.
    """

    gauge_factor: float
    active_arms: int
    excitation: float  # V
    gain: float = 1.0
    polarity: float = 1.0

    ARMS = {"quarter": 1, "half": 2, "full": 4}

    def __post_init__(self):
        if not self.gauge_factor > 0:
            raise InputError(f"gauge_factor must be positive, got {self.gauge_factor!r}")
        if self.active_arms not in (1, 2, 4):
            raise InputError(f"bridge: active arms must be 1, 2 or 4, got {self.active_arms!r}")
        if not self.excitation > 0 or self.gain == 0:
            raise InputError(f"excitation must be positive and gain non-zero, got {self.excitation!r}, {self.gain!r}")
        if self.polarity not in (1.0, -1.0):
            raise InputError(f"polarity must be 1 or -1, got {self.polarity!r}")

    def strain(self, volts):
        """ε = polarity·4·V/(arms·GF·V_exc·gain)."""
        return self.polarity * 4.0 * np.asarray(volts) / (self.active_arms * self.gauge_factor * self.excitation * self.gain)
