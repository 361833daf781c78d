"""Isotropic elastic materials and the built-in catalogue.

All values SI: Young's modulus in Pa, density in kg/m³.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import InputError
from ..units import INCH, POUND_MASS, PSI

__all__ = ["Material", "CATALOGUE", "lookup", "sphere_mass"]


def _positive(name: str, value: float) -> None:
    if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
        raise InputError(f"{name} must be a positive finite number, got {value!r}")


@dataclass(frozen=True)
class Material:
    """Linear elastic isotropic material.

    Attributes: ``youngs_modulus`` E [Pa], ``poisson_ratio`` ν [-],
    ``density`` ρ [kg/m³], and where the values come from.
    """

    name: str
    youngs_modulus: float
    poisson_ratio: float
    density: float
    source: str = "user input"

    def __post_init__(self):
        _positive(f"{self.name}: youngs_modulus", self.youngs_modulus)
        _positive(f"{self.name}: density", self.density)
        if not (-1.0 < self.poisson_ratio < 0.5):
            raise InputError(f"{self.name}: poisson_ratio must lie in (-1, 0.5), got {self.poisson_ratio!r}")

    @property
    def wave_speed(self) -> float:
        """Bar (one-dimensional) wave speed c = sqrt(E/ρ) [m/s]."""
        return math.sqrt(self.youngs_modulus / self.density)

    @property
    def plane_modulus(self) -> float:
        """k = E / (1 − ν²) [Pa], the modulus of eq (2)."""
        return self.youngs_modulus / (1.0 - self.poisson_ratio**2)


_LB_PER_IN3 = POUND_MASS / INCH**3  # kg/m³

CATALOGUE = {
    m.name: m
    for m in (
        Material(
            "Al 6061-T6",
            10.0e6 * PSI,
            0.33,
            0.0975 * _LB_PER_IN3,
            "handbook values (MIL-HDBK-5), as in docs/modelling-notes.md",
        ),
        Material(
            "steel",
            30.0e6 * PSI,
            0.29,
            0.283 * _LB_PER_IN3,
            "handbook values for carbon/bearing steel, as in docs/modelling-notes.md",
        ),
        Material(
            "silicone rubber",
            5.0e6,
            0.49,
            # 1.1 g for a 1/2-in ball (the paper's text) gives 1025.6 kg/m³.
            1.1e-3 / (math.pi / 6 * 0.0127**3),
            "density from the paper (1/2-in ball weighs 1.1 g); modulus and ν representative of silicone rubber",
        ),
    )
}


def lookup(name: str, key: str = "material") -> Material:
    """Catalogue material by name (case-insensitive)."""
    for known, material in CATALOGUE.items():
        if known.lower() == str(name).strip().lower():
            return material
    raise InputError(f"{key}: unknown material {name!r} (catalogue: {', '.join(CATALOGUE)})")


def sphere_mass(material: Material, diameter: float) -> float:
    """Mass of a solid sphere of ``diameter`` [m] in [kg]."""
    return material.density * math.pi / 6.0 * diameter**3
