"""Threat definitions: hail (size, terminal and flight-speed impact velocity) and bird masses, SI.

Hail falls at its terminal velocity, where drag balances weight,

    ½·ρ_air·C_d·(π·D²/4)·V_t² = ρ_h·(π·D³/6)·g   ⇒   V_t = sqrt(4·ρ_h·g·D / (3·C_d·ρ_air)),

with the sphere's drag coefficient C_d = 0.5 (Serway, *Physics for Scientists and Engineers*, as quoted by
HyperPhysics, hyperphysics.phy-astr.gsu.edu/hbase/airfri2.html: "C is 0.5 for a spherical object"; MeteoSwiss,
"Die Energie von Hagel", 2024, writes the same balance). Air at the ISA sea level, ρ_air = 1.225 kg/m³, g =
9.80665 m/s² (aerodynamics4students.com, "Properties of the atmosphere"). Measured fall speeds are lower for
large stones (tumbling, roughness, lower density: Prodi 1970 measured 820-870 kg/m³, quoted in J. Atmos. Sci.
75:3861); the empirical fit V_t ≈ 1.4·D^0.8 (D in mm, V in m/s, sea level; Geerts 2000, "Fall speed of
hydrometeors", as quoted by hypertextbook.com/facts/2005/AliciaKosiba.shtml: an 80 mm stone at 48 m/s) is
:func:`hail_fall_speed_empirical`.

On an aircraft the hail meets the structure at the flight speed combined with its fall:
:func:`flight_hail_velocity` (the magnitude of the relative velocity, airspeed horizontal, fall vertical).

Bird masses of the certification rules (:data:`BIRD_MASSES`): 14 CFR 25.631 (empennage, 8 lb at V_C at sea
level), 14 CFR 25.775 (windshields, 4 lb at V_C), 14 CFR 25.571(e) (damage tolerance, 4 lb at V_C at sea level
or 0.85 V_C at 8000 ft), EASA CS 25.631 (the whole aeroplane, 4 lb = 1.8 kg at V_C at sea level or 0.85 V_C at
2438 m) and 14 CFR 29.631 (rotorcraft, 2.2 lb = 1.0 kg at V_NE or V_H up to 8000 ft); texts as published by
lexbuild.dev (eCFR) and quoted at vimo-tech.com and pprune.org.

The substitute bird (:class:`SubstituteBird`, :func:`substitute_bird`): a bird of a rule's mass becomes a
hemispherical-ended cylinder of gelatin, length over diameter L/D = 2, density 950 kg/m³, striking nose first; its
diameter follows from V = π·D²/4·(L − D) + π·D³/6 = 5·π·D³/12 at L = 2D:

    D = (12·m / (5·π·ρ))^(1/3)        (a 1.8-kg bird: D = 113.1 mm, L = 226.2 mm),

against (6·m/(π·ρ))^(1/3) = 153.5 mm for a sphere of the same mass and density (:func:`sphere_diameter`). What
was retrieved for these numbers (search of public pages, 2026-12):

- L/D = 2 and ρ = 950 kg/m³: saullocastro/birdpressure, ``birdpressure/Bird.py``: "All parameters are taken from
  Wilbeck for most accurate load prediction", ``initial_density ... default: 950``, ``mass ... default: 1.814 ...
  (4lb)``, ``aspect_ratio: float, default: 2 / length/diamter``. (That code sizes a flat-ended cylinder,
  L = (16·m/(π·ρ))^(1/3), and writes the cube root ``** 1 / 3``, which Python reads as (…)¹/3; the project takes
  its numbers, not its geometry.)
- the hemispherical ends: Hedayati & Ziaei-Rad 2013 (Aerosp. Sci. Technol. 28:9-20, abstract): "for the tail side
  impact scenario, a hemispherical-ended cylinder shows the best results"; Yuniarti et al. 2023 (J. Fis. Unand
  12(4):628, abstract): "a hemispherical-ended cylinder bird model with varying length-to-diameter (L/D) ratio,
  namely 1.4; 1.5; 1.6; 1.7; 1.8; 1.9; and 2.0"; Cwiklak 2020 (Facta Univ. Mech. Eng. 18:639, abstract): "one in
  the shape of a cylinder with hemispherical ends (homogeneous model)".
- the gelatin with voids: Wilbeck & Rand 1981 (J. Eng. Power 103:725, abstract): "a projectile fabricated from
  commercial gelatin impregnated with phenolic mircoballoons [sic] most nearly duplicated the impact loading
  history of real birds".
- the test bird: ASTM F330 (2.1.1) "bird—the carcass that is used to impact the test article" (a chicken, not
  gelatin), and its Note 1, "a 4-lb (1.81-kg) bird".

Not retrieved (only the abstracts or first pages were): Wilbeck 1978 (AFML-TR-77-134) itself, Heimbs 2011's
(Comput. Struct. 89:2093) and Airoldi & Cacchione 2006's statements of the substitute's density and shape, the
porosity of the substitute (10 % is the figure usually quoted, not sourced here), and the other densities in use
(938, 900, 1000 kg/m³ are quoted in the literature; the case's ``density`` key takes any of them).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import InputError
from ..units import POUND_MASS
from .materials import CATALOGUE

__all__ = [
    "SPHERE_DRAG_COEFFICIENT",
    "SEA_LEVEL_AIR_DENSITY",
    "STANDARD_GRAVITY",
    "BirdThreat",
    "BIRD_MASSES",
    "hail_terminal_velocity",
    "hail_fall_speed_empirical",
    "flight_hail_velocity",
    "sphere_diameter",
    "BIRD_SUBSTITUTE_DENSITY",
    "BIRD_ASPECT_RATIO",
    "SubstituteBird",
    "substitute_bird",
]

SPHERE_DRAG_COEFFICIENT = 0.5  # C_d of a sphere (Serway, via HyperPhysics)
SEA_LEVEL_AIR_DENSITY = 1.225  # kg/m³, ISA sea level
STANDARD_GRAVITY = 9.80665  # m/s², ISA
BIRD_SUBSTITUTE_DENSITY = 950.0  # kg/m³, Wilbeck's gelatin via saullocastro/birdpressure (module docstring); the catalogue's gelatin
BIRD_ASPECT_RATIO = 2.0  # L/D of the substitute's hemispherical-ended cylinder (birdpressure's aspect_ratio; module docstring)


def _positive(name: str, value: float) -> None:
    if not (math.isfinite(value) and value > 0):
        raise InputError(f"{name} must be positive, got {value!r}", name)


def hail_terminal_velocity(
    diameter: float,
    density: float | None = None,
    drag_coefficient: float = SPHERE_DRAG_COEFFICIENT,
    air_density: float = SEA_LEVEL_AIR_DENSITY,
) -> float:
    """V_t = sqrt(4·ρ_h·g·D / (3·C_d·ρ_air)) [m/s] of a hailstone of ``diameter`` D [m] (module docstring);
    ``density`` ρ_h defaults to the catalogue's ice."""
    rho = CATALOGUE["ice"].density if density is None else density
    for name, v in (("diameter", diameter), ("density", rho), ("drag_coefficient", drag_coefficient), ("air_density", air_density)):
        _positive(name, v)
    return math.sqrt(4.0 * rho * STANDARD_GRAVITY * diameter / (3.0 * drag_coefficient * air_density))


def hail_fall_speed_empirical(diameter: float) -> float:
    """V_t ≈ 1.4·(D/1 mm)^0.8 m/s at sea level (Geerts 2000, module docstring), D [m]."""
    _positive("diameter", diameter)
    return 1.4 * (diameter * 1e3) ** 0.8


def flight_hail_velocity(airspeed: float, diameter: float, **fall) -> float:
    """|V| = sqrt(V_air² + V_t²) [m/s]: hail falling at its terminal velocity (:func:`hail_terminal_velocity`,
    keywords passed on) met by a structure flying level at ``airspeed`` [m/s]; the normal component on an
    inclined surface is the caller's."""
    _positive("airspeed", airspeed)
    return math.hypot(airspeed, hail_terminal_velocity(diameter, **fall))


def sphere_diameter(mass: float, density: float) -> float:
    """D = (6·m/(π·ρ))^(1/3) [m] of a solid sphere of ``mass`` [kg] and ``density`` [kg/m³] (a bird's gelatin
    substitute as a sphere; Wilbeck's substitutes are hemispherical-ended cylinders of length twice the diameter)."""
    _positive("mass", mass)
    _positive("density", density)
    return (6.0 * mass / (math.pi * density)) ** (1.0 / 3.0)


@dataclass(frozen=True)
class BirdThreat:
    """A certification bird: ``mass`` [kg], the rule, the structure it applies to and its speed condition."""

    rule: str
    mass: float
    applies_to: str
    speed: str


BIRD_MASSES = (
    BirdThreat("14 CFR 25.631", 8.0 * POUND_MASS, "empennage", "V_C at sea level"),
    BirdThreat("14 CFR 25.775", 4.0 * POUND_MASS, "windshield panes", "V_C at sea level"),
    BirdThreat("14 CFR 25.571(e)", 4.0 * POUND_MASS, "damage tolerance", "V_C at sea level or 0.85 V_C at 8000 ft"),
    BirdThreat("EASA CS 25.631", 1.8, "the whole aeroplane (4 lb)", "V_C at sea level or 0.85 V_C at 2438 m"),
    BirdThreat("14 CFR 29.631", 1.0, "rotorcraft (2.2 lb)", "V_NE or V_H up to 8000 ft"),
)


@dataclass(frozen=True)
class SubstituteBird:
    """A bird of ``mass`` [kg] as its gelatin substitute (module docstring): a hemispherical-ended cylinder of
    ``density`` [kg/m³] and ``aspect_ratio`` L/D, of ``diameter`` D [m] and ``length`` L [m]."""

    mass: float
    density: float
    aspect_ratio: float
    diameter: float
    length: float

    @property
    def shape(self) -> str:
        return f"hemispherical-ended cylinder, L/D = {self.aspect_ratio:g}"

    def summary(self) -> dict:
        """summary.json's ``threat``: the bird's mass, the substitute's density, shape, diameter and length (SI)."""
        return {
            "bird_mass_kg": self.mass,
            "substitute": "gelatin",
            "substitute_density_kg_m3": self.density,
            "substitute_shape": self.shape,
            "substitute_diameter_m": self.diameter,
            "substitute_length_m": self.length,
        }


def substitute_bird(mass: float, density: float = BIRD_SUBSTITUTE_DENSITY, aspect_ratio: float = BIRD_ASPECT_RATIO) -> SubstituteBird:
    """The :class:`SubstituteBird` of a bird of ``mass`` [kg]: D = (12·m/(π·ρ·(3λ − 1)))^(1/3), L = λ·D (λ = L/D;
    λ = 2: D = (12·m/(5·π·ρ))^(1/3), module docstring). InputError (``bird``, ``density``, ``aspect_ratio``) for a
    non-positive mass or density or λ < 1."""
    from .capsule import capsule_diameter

    _positive("bird", mass)
    _positive("density", density)
    if not (math.isfinite(aspect_ratio) and aspect_ratio >= 1.0):
        raise InputError(f"aspect_ratio must be at least 1 (a sphere), got {aspect_ratio!r}", "aspect_ratio")
    d = capsule_diameter(mass, density, aspect_ratio)
    return SubstituteBird(mass, density, aspect_ratio, d, aspect_ratio * d)
