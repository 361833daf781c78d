"""Projectile materials that crush or flow: ice (hail) and gelatin (the bird substitute), SI.

A :class:`ProjectileMaterial` is the catalogue's elastic :class:`~softimpact.models.materials.Material`
(density, and E, ν for the Hertz estimates) with what the non-elastic contact laws need:

- ice: a rate-dependent compressive strength σ_c(ε̇) (:class:`PowerLawStrength`), used by the crushing law
  (:mod:`softimpact.models.crushing_law`);
- gelatin: a linear Hugoniot U_s = c0 + k·u_p (:class:`LinearHugoniot`), used by the hydrodynamic law
  (:mod:`softimpact.models.hydrodynamic_law`).

Each record carries its sources and its validity envelope (the range the published law was measured on).

Sources (retrieved; see docs/hail-and-bird.md for the readings):

- Jones S.J. 1997, "High strain-rate compression tests on ice", J. Phys. Chem. B 101(32):6099-6101
  (doi:10.1021/jp963162j): uniaxial compression of freshwater ice at −11 °C, ε̇ = 1e-1 … 1e1 s⁻¹,
  σ = A·ε̇^m with A = 8.9, m = 0.15 (the abstract gives A without units; MPa with ε̇ in s⁻¹ is the reading
  consistent with its "1.3 times stronger than sea ice at 10 s⁻¹": 8.9·10^0.15 / (6.0·10^0.19) = 1.36).
- Wilbeck's bird-substitute constants (ρ = 950 kg/m³, c0 = 1482.9 m/s, k = 2) as transcribed in
  saullocastro/birdpressure (birdpressure/Bird.py, "all parameters are taken from Wilbeck"); Wilbeck 1978,
  AFML-TR-77-134, was not retrieved, nor the substitute's porosity (reported missing, ``porosity=None``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import InputError
from .materials import CATALOGUE, GELATIN_HUGONIOT, Material

__all__ = [
    "PowerLawStrength",
    "LinearHugoniot",
    "ProjectileMaterial",
    "JONES_1997_FRESHWATER",
    "WILBECK_GELATIN",
    "PROJECTILES",
    "projectile_material",
]


@dataclass(frozen=True)
class PowerLawStrength:
    """Compressive strength σ_c(ε̇) = A·(ε̇/ε̇_ref)^m [Pa] for ε̇ ≥ ε̇_lo, measured over ``rate_range`` (ε̇_lo, ε̇_hi) [1/s].

    Below ε̇_lo the strength is brought linearly to zero, σ_c = σ_c(ε̇_lo)·ε̇/ε̇_lo (a regularisation, not a
    measurement: a rigid-plastic crush stops with a force jump, which a Newton iteration on F(α, α̇) cannot
    bracket; the ramp acts only below the measured range, where the crush has all but stopped). σ_c = 0 for ε̇ ≤ 0.
    ``ramp_below``: the ε̇_lo of that ramp where it is not the measured range's lower end (an identified law's: its
    fit used the catalogue law's floor, while its tests' rates, its validity range, start far above it).
    """

    coefficient: float  # A [Pa]
    exponent: float  # m [-]
    rate_range: tuple[float, float]  # the measured range of ε̇ [1/s]: the validity envelope's
    reference_rate: float = 1.0  # ε̇_ref [1/s]
    source: str = ""
    ramp_below: float | None = None  # ε̇ [1/s] below which σ_c ramps to 0 (None: rate_range's lower end)

    def __post_init__(self):
        lo, hi = self.rate_range
        if not (self.coefficient > 0 and math.isfinite(self.coefficient)):
            raise InputError(f"strength coefficient must be positive, got {self.coefficient!r}")
        if not (0.0 <= self.exponent < 1.0):
            raise InputError(f"strength exponent must lie in [0, 1), got {self.exponent!r}")
        if not (0.0 < lo < hi):
            raise InputError(f"strength rate range must be 0 < lo < hi, got {self.rate_range!r}")
        if self.ramp_below is not None and not (0.0 < self.ramp_below <= hi and math.isfinite(self.ramp_below)):
            raise InputError(f"strength ramp_below must lie in (0, {hi!r}], got {self.ramp_below!r}")

    def __call__(self, rate: float) -> tuple[float, float]:
        """(σ_c [Pa], dσ_c/dε̇ [Pa·s]) at the strain rate ``rate`` [1/s]."""
        lo = self.rate_range[0] if self.ramp_below is None else self.ramp_below
        if rate <= 0.0:
            return 0.0, 0.0
        if rate < lo:
            floor = self.coefficient * (lo / self.reference_rate) ** self.exponent
            return floor * rate / lo, floor / lo
        s = self.coefficient * (rate / self.reference_rate) ** self.exponent
        return s, self.exponent * s / rate


@dataclass(frozen=True)
class LinearHugoniot:
    """Shock speed U_s = c0 + k·u_p [m/s] of a material at rest struck at particle velocity u_p; the
    Hugoniot (shock) pressure P_H = ρ·U_s·u_p = ρ·(c0 + k·u_p)·u_p [Pa] (Wilbeck 1978)."""

    c0: float  # bulk sound speed [m/s]
    k: float  # slope [-]

    def __post_init__(self):
        if not (self.c0 > 0 and self.k >= 0):
            raise InputError(f"Hugoniot: c0 must be positive and k non-negative, got c0={self.c0!r}, k={self.k!r}")

    def shock_speed(self, particle_velocity: float) -> float:
        return self.c0 + self.k * particle_velocity

    def pressure(self, density: float, particle_velocity: float) -> float:
        """P_H = ρ·(c0 + k·u)·u [Pa]."""
        return density * self.shock_speed(particle_velocity) * particle_velocity


# Jones 1997, freshwater ice at −11 °C: σ = 8.9 MPa·(ε̇ / 1 s⁻¹)^0.15 over 0.1 … 10 s⁻¹ (module docstring).
JONES_1997_FRESHWATER = PowerLawStrength(8.9e6, 0.15, (1e-1, 1e1), 1.0, "Jones 1997, J. Phys. Chem. B 101:6099, freshwater ice, -11 C")

WILBECK_GELATIN = LinearHugoniot(GELATIN_HUGONIOT[1], GELATIN_HUGONIOT[2])


@dataclass(frozen=True)
class ProjectileMaterial:
    """A catalogue material with its crushing strength or its Hugoniot, and its sources.

    ``strength``: the crushing strength law (ice), or None; ``hugoniot``: the shock EOS (gelatin), or None;
    ``porosity``: the volume fraction of voids [-] where published, None where it was not retrieved.
    """

    material: Material
    strength: PowerLawStrength | None = None
    hugoniot: LinearHugoniot | None = None
    porosity: float | None = None
    source: str = ""

    @property
    def name(self) -> str:
        return self.material.name

    @property
    def density(self) -> float:
        return self.material.density


PROJECTILES = {
    "ice": ProjectileMaterial(CATALOGUE["ice"], strength=JONES_1997_FRESHWATER, source=JONES_1997_FRESHWATER.source),
    "gelatin": ProjectileMaterial(
        CATALOGUE["gelatin"],
        hugoniot=WILBECK_GELATIN,
        porosity=None,
        source="Wilbeck 1978 (AFML-TR-77-134) constants via saullocastro/birdpressure; porosity not retrieved",
    ),
}


def projectile_material(material: Material | ProjectileMaterial | str) -> ProjectileMaterial:
    """The :class:`ProjectileMaterial` of a catalogue material (a name, a :class:`Material` of the catalogue, or a
    record itself); InputError (``material``) for a material with no crushing or flow data."""
    if isinstance(material, ProjectileMaterial):
        return material
    name = material.name if isinstance(material, Material) else str(material).strip()
    for known, record in PROJECTILES.items():
        if known.lower() == name.lower():
            return record
    raise InputError(f"material {name!r} has no crushing or flow data (known: {', '.join(PROJECTILES)})", "material")
