"""A hydrodynamic contact law for gelatin (bird-substitute) spheres: Wilbeck's shock, release and steady flow.

Wilbeck (1978, AFML-TR-77-134; the regimes as summarised by the bird-strike literature, e.g. Airoldi &
Cacchione 2006, Int. J. Impact Eng. 32:1651-1677, and the analytical code saullocastro/birdpressure) splits a
soft body's impact on a rigid target into

1. the shock: the material behind the shock front is brought to rest at the Hugoniot pressure
   P_H = ρ·(c0 + k·v)·v (linear Hugoniot U_s = c0 + k·u_p);
2. the release: once the contact edge moves slower than the shock, release waves run in from the free edge
   and bring the pressure down;
3. the steady flow: the material flows radially at the stagnation pressure ½·ρ·v² at the centre, the force
   being the momentum flux ρ·A·v² of the column that arrives (a mean pressure ρ·v² over the section);

lasting the length of the projectile over its velocity.

Here the sphere is treated as in the crushing law (:mod:`softimpact.models.crushing_law`, whose geometry and
centre-of-mass approach it shares): after a flowed length s the section is A(s) = π·s·(d − s), the material
still arriving moves at ṡ, the force is F = A(s)·p(s, ṡ) and the remainder decelerates by (p − ρ·ṡ²)·A (the
shock's excess over the momentum flux). The mean pressure on the section is

    p = ρ·ṡ² + (P_H(ṡ) − ρ·ṡ²)·w(s),   w = 1 for s ≤ s_c,   w = exp(−(s − s_c)/ℓ) beyond,

- s_c = d·V²/(4·U_s²): the contact edge of a sphere, a = sqrt(s·(d − s)), runs at ȧ ≈ (V/2)·sqrt(d/s); it falls
  to the shock speed U_s = c0 + k·V at a_c = R·V/U_s (R = d/2; derived here for a shallow cap, s ≪ d): until
  then the edge outruns the shock, no release reaches the section and the whole of it is at P_H;
- ℓ = V·a_c/U_s = 2·s_c: the crush advanced while a release wave crosses the contact radius a_c. The release
  waves run faster than U_s in the compressed material (Wilbeck's c_r, from an equation of state not
  retrieved here); U_s is a lower bound, so the spike lasts at most this long.

V is the impact velocity the law is built for (the length scales); P_H and ρ·ṡ² follow the current ṡ. Nothing
is stored (``energy`` = 0), nothing rebounds; the impulse is m·V (all the momentum is brought to rest) and the
duration about d/V. Validity: :func:`softimpact.models.validity.hydrodynamic_validity`.

The substitute bird is not a sphere but a hemispherical-ended cylinder (:class:`HydrodynamicCapsuleLaw`, its geometry in
:mod:`softimpact.models.capsule`): the same pressure on its own section, A = π·d²/4 along the cylinder, for the
time L/V the body takes to flow (Wilbeck's steady force ρ·A·V² and "squash-up" time L/V); the shock and its release
are those of its hemispherical nose, the sphere's of the same diameter (s_c ≪ d/2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import InputError
from .capsule import capsule_advance, capsule_depth, capsule_section, capsule_volume
from .crushing_law import CONSUMED, SphereFlowLaw
from .projectiles import WILBECK_GELATIN, LinearHugoniot, projectile_material

__all__ = ["HydrodynamicLaw", "HydrodynamicCapsuleLaw"]


@dataclass(frozen=True)
class HydrodynamicLaw(SphereFlowLaw):
    """Wilbeck's shock, release and steady flow for a sphere (module docstring).

    ``mass`` m [kg], ``diameter`` d [m], ``velocity`` V [m/s] the impact velocity (the shock's length
    scales), ``hugoniot`` the linear Hugoniot (c0, k) of the material.
    """

    source = "Wilbeck 1978 (AFML-TR-77-134) shock, release and steady flow; constants via saullocastro/birdpressure"  # where the law comes from (softimpact catalogue); a class attribute, not a field

    velocity: float = 1.0
    hugoniot: LinearHugoniot = WILBECK_GELATIN

    def __post_init__(self):
        super().__post_init__()
        if not (math.isfinite(self.velocity) and self.velocity > 0):
            raise InputError(f"contact: velocity must be positive, got {self.velocity!r}", "velocity")

    @classmethod
    def of(cls, material, diameter: float, mass: float, velocity: float, length: float | None = None) -> HydrodynamicLaw:
        """The law of a sphere of ``material`` (a catalogue name, Material or ProjectileMaterial with a Hugoniot:
        gelatin), ``diameter`` [m], ``mass`` [kg], striking at ``velocity`` [m/s]; with ``length`` [m] (> diameter),
        that of a hemispherical-ended cylinder of that length striking nose first (:class:`HydrodynamicCapsuleLaw`)."""
        record = projectile_material(material)
        if record.hugoniot is None:
            raise InputError(f"material {record.name!r} has no Hugoniot: the hydrodynamic law is for gelatin", "material")
        if length is None or length == diameter:
            return cls(mass, diameter, velocity, record.hugoniot)
        return HydrodynamicCapsuleLaw(mass, diameter, velocity, record.hugoniot, length)

    def validity(self, velocity: float | None = None):
        """The shock phase's envelope (:func:`~softimpact.models.validity.hydrodynamic_validity`) at the law's own
        impact velocity (the length scales were built for it; ``velocity`` [m/s], the run's, is not needed)."""
        from .validity import hydrodynamic_validity

        return hydrodynamic_validity(self.diameter, self.velocity, self.hugoniot)

    @property
    def hugoniot_pressure(self) -> float:
        """P_H = ρ·(c0 + k·V)·V at the impact velocity [Pa]."""
        return self.hugoniot.pressure(self.density, self.velocity)

    @property
    def stagnation_pressure(self) -> float:
        """½·ρ·V², the steady flow's centre pressure [Pa]."""
        return 0.5 * self.density * self.velocity**2

    @property
    def release_depth(self) -> float:
        """s_c = d·V²/(4·U_s²) [m]: the shock covers the whole section up to this depth."""
        us = self.hugoniot.shock_speed(self.velocity)
        return self.diameter * self.velocity**2 / (4.0 * us * us)

    @property
    def release_length(self) -> float:
        """ℓ = 2·s_c [m]: the depth over which the release brings the shock's excess down by e."""
        return 2.0 * self.release_depth

    def shock_share(self, s: float) -> tuple[float, float]:
        """(w, dw/ds [1/m]) at the depth s [m]."""
        sc, ell = self.release_depth, self.release_length
        if s <= sc:
            return 1.0, 0.0
        w = math.exp(-(s - sc) / ell)
        return w, -w / ell

    def pressure_terms(self, s: float, rate: float) -> tuple[float, float, float]:
        """p = ρṡ² + (P_H(ṡ) − ρṡ²)·w(s) and its partial derivatives (ṡ > 0)."""
        if rate <= 0.0:
            return 0.0, 0.0, 0.0
        rho, h = self.density, self.hugoniot
        flux = rho * rate * rate
        shock = h.pressure(rho, rate)
        w, dw = self.shock_share(s)
        dflux, dshock = 2.0 * rho * rate, rho * (h.c0 + 2.0 * h.k * rate)
        return flux + (shock - flux) * w, (shock - flux) * dw, dflux + (dshock - dflux) * w


@dataclass(frozen=True)
class HydrodynamicCapsuleLaw(HydrodynamicLaw):
    """Wilbeck's shock, release and steady flow for a hemispherical-ended cylinder striking nose first (module
    docstring; its geometry: :mod:`softimpact.models.capsule`).

    ``length`` L [m] ≥ ``diameter`` d, the overall length; the density is m/V with V = π·d²/4·(L − d) + π·d³/6.
    """

    source = "Wilbeck 1978 (AFML-TR-77-134) shock, release and steady flow of a hemispherical-ended cylinder; constants via saullocastro/birdpressure"  # where the law comes from (softimpact catalogue); a class attribute, not a field

    length: float = 0.0

    def __post_init__(self):
        super().__post_init__()
        if not (math.isfinite(self.length) and self.length >= self.diameter):
            raise InputError(f"contact: length must be at least the diameter ({self.diameter!r} m), got {self.length!r}", "length")

    @property
    def density(self) -> float:
        """ρ = m/V [kg/m³], V the capsule's volume."""
        return self.mass / capsule_volume(self.diameter, self.length)

    @property
    def extent(self) -> float:
        """L [m]: the centre of mass has advanced L/2 when the whole body is deposited."""
        return self.length

    def geometry(self, alpha: float) -> tuple[float, float, float, float, float]:
        """(s, φ, dφ/ds = −A/V, A, dA/ds) of the capsule at the centre-of-mass approach α [m]
        (:func:`~softimpact.models.capsule.capsule_depth`); φ = 0 once consumed."""
        d, L = self.diameter, self.length
        s = capsule_depth(alpha, d, L)
        if s >= CONSUMED * L:
            return L, 0.0, 0.0, 0.0, 0.0
        phi = capsule_advance(s, d, L)[1]
        area, darea = capsule_section(s, d, L)
        return s, phi, -area / capsule_volume(d, L), area, darea
