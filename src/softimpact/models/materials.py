"""Isotropic elastic materials and the built-in catalogue.

All values SI: Young's modulus in Pa, density in kg/m³.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import InputError
from ..units import INCH, POUND_MASS, PSI

__all__ = ["Material", "CATALOGUE", "ICE_ELASTIC_CONSTANTS", "GELATIN_HUGONIOT", "hexagonal_isotropic_moduli", "lookup", "sphere_mass"]


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

# Single-crystal ice Ih at −16 °C, c11, c12, c13, c33, c44 [Pa]: Gammon, Kiefte, Clouter & Denner, "Elastic constants
# of artificial and natural ice samples by Brillouin spectroscopy", J. Glaciol. (its abstract: 139.29, 70.82, 57.65,
# 150.10, 30.14 in units of 1e8 N/m², each ± 0.1-0.5).
ICE_ELASTIC_CONSTANTS = (139.29e8, 70.82e8, 57.65e8, 150.10e8, 30.14e8)
ICE_DENSITY = 916.7  # kg/m³ at 0 °C (0.9167 g/cm³; Wikipedia "Ice", as mirrored at altsci.com/3/p/Ice/9)

# Wilbeck's bird-substitute constants (density 950 kg/m³, c0 = 1482.9 m/s, k = 2), as transcribed with
# "all parameters taken from Wilbeck" in saullocastro/birdpressure (birdpressure/Bird.py); Wilbeck 1978,
# AFML-TR-77-134, itself not retrieved. (density [kg/m³], c0 [m/s], k [-])
GELATIN_HUGONIOT = (950.0, 1482.9, 2.0)


def hexagonal_isotropic_moduli(c11: float, c12: float, c13: float, c33: float, c44: float) -> tuple[float, float]:
    """(E [Pa], ν) of an untextured polycrystal of a hexagonal crystal: the Voigt–Reuss–Hill average of the
    bulk and shear moduli of the stiffnesses c_ij [Pa] (c66 = (c11 − c12)/2)."""
    c66 = 0.5 * (c11 - c12)
    C = [[c11, c12, c13, 0, 0, 0], [c12, c11, c13, 0, 0, 0], [c13, c13, c33, 0, 0, 0], [0, 0, 0, c44, 0, 0], [0, 0, 0, 0, c44, 0], [0, 0, 0, 0, 0, c66]]
    import numpy as np

    S = np.linalg.inv(np.array(C, float))
    kv = (2 * c11 + c33 + 2 * (c12 + 2 * c13)) / 9.0
    gv = (2 * c11 + c33 - (c12 + 2 * c13) + 3 * (2 * c44 + c66)) / 15.0
    kr = 1.0 / (S[0, 0] + S[1, 1] + S[2, 2] + 2.0 * (S[0, 1] + S[1, 2] + S[0, 2]))
    gr = 15.0 / (4.0 * (S[0, 0] + S[1, 1] + S[2, 2]) - 4.0 * (S[0, 1] + S[1, 2] + S[0, 2]) + 3.0 * (S[3, 3] + S[4, 4] + S[5, 5]))
    k, g = 0.5 * (kv + kr), 0.5 * (gv + gr)
    return 9.0 * k * g / (3.0 * k + g), (3.0 * k - 2.0 * g) / (2.0 * (3.0 * k + g))


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
        Material(
            "ice",
            *hexagonal_isotropic_moduli(*ICE_ELASTIC_CONSTANTS),
            ICE_DENSITY,
            "E, ν: Voigt-Reuss-Hill average of Gammon et al.'s single-crystal c_ij (J. Glaciol.); density 916.7 kg/m³ at 0 °C "
            "(natural hailstones are lighter, 820-870 kg/m³: Prodi 1970); strength law and envelope: models/projectiles.py",
        ),
        Material(
            "gelatin",
            GELATIN_HUGONIOT[0] * GELATIN_HUGONIOT[1] ** 2,
            0.0,
            GELATIN_HUGONIOT[0],
            "Wilbeck's bird substitute: density 950 kg/m³ and Hugoniot c0 = 1482.9 m/s, k = 2 (Wilbeck 1978 via "
            "saullocastro/birdpressure); its elastic constants were not retrieved: E = ρ·c0² and ν = 0 are stand-ins "
            "(bar wave speed c0) that size the Hertz estimates only; the hydrodynamic law uses ρ, c0, k",
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
