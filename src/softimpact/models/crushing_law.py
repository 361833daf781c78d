"""A crushing contact law for ice spheres (hail): the crushed area times the crushing strength, plus the
momentum flux of the crushed ice; no elastic rebound.

The sphere (diameter d, density ρ, mass m = ρ·π·d³/6) is crushed against the target from its front pole:
after a crushed length s the section at the crushing front has the area

    A(s) = π·s·(d − s),

the uncrushed remainder (mass m_r = m·φ(u), φ(u) = (1 − u)²·(1 + 2u), u = s/d) moves at ṡ, and the crushed
ice has stopped at the target. Mass and momentum balances over the remainder and the crushing front (the
soft-missile equations of Riera for aircraft on rigid walls; his paper was not retrieved, the equations are
derived here) give the force on the target and the motion of the remainder:

    F = A(s)·[σ_c(ε̇) + ρ·ṡ²],      m_r·s̈ = −A(s)·σ_c(ε̇),      ε̇ = ṡ/d,

the first term the crushing front's strength over the crushed area, the second the momentum flux of the ice
brought to rest (ρ·A·ṡ per second, each with momentum ṡ). Energy: the crushing dissipates A·σ_c per unit of s
and the stopped ice its kinetic energy; nothing is stored, nothing rebounds.

The coupled stepper integrates a rigid impactor of mass m with m·ẍ = −F and hands the law the approach α and
its rate. Here that impactor is the projectile's CENTRE OF MASS: the total momentum is m_r·ṡ (the crushed ice
is at rest), so m·Ẋ = m_r·ṡ and m·Ẍ = −A·σ_c − ρ·A·ṡ² = −F, exactly the equations above. The centre of mass has
advanced (crushed ice at rest at the target, the remainder advanced by s)

    X(s) = s − s³/d² + s⁴/(2·d³),     dX/ds = φ(s/d),

so α = X fixes s (X is monotone on [0, d], X(d) = d/2: the whole sphere deposited), and α̇ = φ·ṡ fixes
ṡ = α̇/φ. The law is therefore a memoryless F(α, α̇) (:class:`softimpact.models.protocols.ContactLaw`) that
every structure, sweep and map can take, and on a rigid target the impactor's history IS the soft-missile solution. The
impactor's kinetic energy ½·m·Ẋ² is less than the remainder's ½·m_r·ṡ² while the crush goes on; the
stepper's contact work ∫F dα ends equal to the initial kinetic energy (all of it dissipated, ``energy`` = 0).

The strength's strain rate is the sphere's nominal rate ṡ/d; the published strength laws are measured far
below impact rates (:func:`softimpact.models.validity.ice_strength_validity`).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

from ..errors import InputError
from .projectiles import PowerLawStrength, projectile_material

__all__ = ["SphereFlowLaw", "CrushingLaw", "sphere_crush_depth", "sphere_crush_depths", "crushed_area", "centre_of_mass_advance", "rigid_target_pulse"]

DEPTH_TOL = 1e-14  # relative tolerance on u = s/d in the inversion of X(s)
CONSUMED = 1.0 - 1e-9  # u beyond which the sphere is all crushed: no section, no force


def centre_of_mass_advance(u: float) -> float:
    """X/d = u − u³ + u⁴/2 of a sphere crushed to the depth u = s/d (module docstring)."""
    return u - u**3 + 0.5 * u**4


def _phi(u: float) -> float:
    """φ(u) = dX/ds = (1 − u)²·(1 + 2u): the remaining fraction of the sphere's mass."""
    return (1.0 - u) ** 2 * (1.0 + 2.0 * u)


@functools.lru_cache(maxsize=256)  # a coupled step asks for the same depth several times (radius, force, stiffness at one α)
def sphere_crush_depth(x: float) -> float:
    """u = s/d of a sphere whose centre of mass has advanced x = X/d ∈ [0, ½] (the inverse of
    :func:`centre_of_mass_advance`): Newton safeguarded by bisection; 0 for x ≤ 0, 1 for x ≥ ½."""
    if x <= 0.0:
        return 0.0
    if x >= 0.5:
        return 1.0
    lo, hi = 0.0, 1.0
    u = min(x, 0.999)  # X ≈ s for a shallow crush
    for _ in range(100):
        r = centre_of_mass_advance(u) - x
        if r > 0.0:
            hi = u
        else:
            lo = u
        step = r / max(_phi(u), 1e-300)
        nxt = u - step
        if abs(step) <= DEPTH_TOL * max(u, 1e-300):
            return nxt  # converged: a step at round-off may land on the bracket's end (no bisection then)
        if not lo < nxt < hi:
            nxt = 0.5 * (lo + hi)
        if abs(nxt - u) <= DEPTH_TOL * max(u, 1e-300) or hi - lo <= DEPTH_TOL:
            return nxt
        u = nxt
    return u


def sphere_crush_depths(x):
    """:func:`sphere_crush_depth` of an array x = X/d (any shape): Newton from u = x on X(u) − x, which is
    monotone (φ ≥ 0) and convex-concave; each step clipped to [0, 1] and a bisection step taken where
    Newton leaves the bracket, to DEPTH_TOL. 0 where x ≤ 0, 1 where x ≥ ½."""
    import numpy as np

    x = np.asarray(x, float)
    xc = np.clip(x, 0.0, 0.5)
    lo, hi = np.zeros_like(xc), np.ones_like(xc)
    u = np.minimum(xc, 0.999)
    for _ in range(100):
        r = u - u**3 + 0.5 * u**4 - xc
        hi = np.where(r > 0.0, u, hi)
        lo = np.where(r > 0.0, lo, u)
        phi = (1.0 - u) ** 2 * (1.0 + 2.0 * u)
        nxt = u - r / np.maximum(phi, 1e-300)
        nxt = np.where((nxt > lo) & (nxt < hi), nxt, 0.5 * (lo + hi))
        done = np.all((np.abs(nxt - u) <= DEPTH_TOL * np.maximum(u, 1e-300)) | (hi - lo <= DEPTH_TOL))
        u = nxt
        if done:
            break
    return np.where(x <= 0.0, 0.0, np.where(x >= 0.5, 1.0, u))


def crushed_area(s: float, d: float) -> float:
    """A(s) = π·s·(d − s) [m²], the sphere's section at the depth s from its pole."""
    return math.pi * s * (d - s) if 0.0 < s < d else 0.0


@dataclass(frozen=True)
class SphereFlowLaw:
    """A sphere crushed or flowing against the target, in its centre-of-mass approach (module docstring).

    Subclasses give the mean pressure on the crushed section, ``pressure_terms(s, ṡ) -> (p, ∂p/∂s, ∂p/∂ṡ)`` [Pa];
    the force is F = A(s)·p. ``mass`` m [kg] and ``diameter`` d [m]; the density is m/(π·d³/6), so the geometry
    holds the given mass.
    """

    mass: float
    diameter: float

    def __post_init__(self):
        for name in ("mass", "diameter"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise InputError(f"contact: {name} must be positive, got {v!r}", name)

    @property
    def density(self) -> float:
        """ρ = m/(π·d³/6) [kg/m³]."""
        return self.mass / (math.pi / 6.0 * self.diameter**3)

    @property
    def extent(self) -> float:
        """The body's length along the impact [m]: the sphere's diameter (a longer body's own length); the centre of
        mass has advanced half of it when the whole body is deposited."""
        return self.diameter

    def geometry(self, alpha: float) -> tuple[float, float, float, float, float]:
        """(s [m], φ, dφ/ds [1/m], A [m²], dA/ds [m]) at the centre-of-mass approach α > 0 [m]: the depth crushed, the
        remaining fraction of the mass and the section at the front (module docstring); φ = 0 once the body is
        consumed. A body of another shape overrides this (and :attr:`density`, :attr:`extent`)."""
        d = self.diameter
        u = sphere_crush_depth(alpha / d)
        if u >= CONSUMED:
            return d, 0.0, 0.0, 0.0, 0.0
        s = u * d
        return s, _phi(u), -6.0 * u * (1.0 - u) / d, math.pi * s * (d - s), math.pi * (d - 2.0 * s)

    def pressure_terms(self, s: float, rate: float) -> tuple[float, float, float]:  # pragma: no cover - abstract
        raise NotImplementedError

    def state(self, alpha: float, rate: float) -> tuple[float, float, float]:
        """(s [m], ṡ [m/s], φ) of the centre-of-mass approach α [m] and its rate α̇ [m/s]."""
        s, phi = self.geometry(alpha)[:2] if alpha > 0.0 else (0.0, 1.0)
        return s, (rate / phi if phi > 0.0 else math.inf), phi

    def response(self, alpha: float, rate: float = 0.0) -> tuple[float, float, float]:
        """(F [N], ∂F/∂α [N/m], ∂F/∂α̇ [N·s/m]) at once. F = A(s)·p(s, ṡ) with s(α), ṡ = α̇/φ(s):
        ∂s/∂α = 1/φ, ∂ṡ/∂α̇ = 1/φ, ∂ṡ/∂α = −ṡ·(dφ/ds)/φ² (for the sphere dφ/ds = −6u(1 − u)/d)."""
        if alpha <= 0.0 or rate <= 0.0:
            return 0.0, 0.0, 0.0
        s, phi, dphi, area, darea = self.geometry(alpha)
        if phi <= 0.0:
            return 0.0, 0.0, 0.0
        sdot = rate / phi
        p, dp_ds, dp_dv = self.pressure_terms(s, sdot)
        if p <= 0.0:
            return 0.0, 0.0, 0.0
        ds_da = 1.0 / phi
        dv_da = -sdot * dphi / (phi * phi)
        stiffness = darea * ds_da * p + area * (dp_ds * ds_da + dp_dv * dv_da)
        return area * p, stiffness, area * dp_dv / phi

    def force(self, alpha: float, rate: float = 0.0) -> float:
        return self.response(alpha, rate)[0]

    def stiffness(self, alpha: float, rate: float = 0.0) -> float:
        return self.response(alpha, rate)[1]

    def damping(self, alpha: float, rate: float = 0.0) -> float:
        return self.response(alpha, rate)[2]

    def radius(self, alpha: float) -> float:
        """The crushed section's radius a = sqrt(A/π) [m] (the sphere's sqrt(s·(d − s)))."""
        if alpha <= 0.0:
            return 0.0
        return math.sqrt(max(self.geometry(alpha)[3], 0.0) / math.pi)

    def energy(self, alpha: float) -> float:
        """Nothing is stored: crushed or flowing material does not spring back [J]."""
        return 0.0

    def pressure(self, alpha: float, rate: float) -> float:
        """The mean pressure F/A on the crushed section [Pa] (0 where nothing presses)."""
        if alpha <= 0.0 or rate <= 0.0:
            return 0.0
        s, sdot, phi = self.state(alpha, rate)
        if phi <= 0.0:
            return 0.0
        return max(self.pressure_terms(s, sdot)[0], 0.0)


@dataclass(frozen=True)
class CrushingLaw(SphereFlowLaw):
    """Ice crushing (module docstring): F = A(s)·[σ_c(ṡ/d) + ρ·ṡ²] while the sphere crushes, 0 otherwise.

    ``strength``: the crushing strength law σ_c(ε̇) (:class:`~softimpact.models.projectiles.PowerLawStrength`);
    None is the fragment-flow limit (no strength: the momentum flux alone, the crush lasting d/V exactly).
    """

    source = "ice crushing strength of Jones 1997 (J. Phys. Chem. B 101:6099) with the momentum flux rho*V^2 (models/crushing_law.py)"  # where the law comes from (softimpact catalogue); a class attribute, not a field

    strength: PowerLawStrength | None = None

    @classmethod
    def of(cls, material, diameter: float, mass: float, velocity: float) -> CrushingLaw:
        """The law of a sphere of ``material`` (a catalogue name, Material or ProjectileMaterial with a crushing
        strength: ice), ``diameter`` [m], ``mass`` [kg]; ``velocity`` [m/s] is not needed (the table's signature)."""
        record = projectile_material(material)
        if record.strength is None:
            raise InputError(f"material {record.name!r} has no crushing strength: the crushing law is for ice", "material")
        return cls(mass, diameter, record.strength)

    def validity(self, velocity: float):
        """The strength law's envelope at the impact ``velocity`` [m/s]: the crush's strain rate V/d against the
        rates it was measured on (:func:`~softimpact.models.validity.ice_strength_validity`); nothing to check
        in the fragment-flow limit (no strength)."""
        from .validity import Validity, ice_strength_validity

        return Validity({}) if self.strength is None else ice_strength_validity(self.diameter, velocity, self.strength)

    def pressure_terms(self, s: float, rate: float) -> tuple[float, float, float]:
        """p = σ_c(ṡ/d) + ρ·ṡ², ∂p/∂s = 0, ∂p/∂ṡ = σ_c'/d + 2ρṡ (ṡ > 0)."""
        if rate <= 0.0:
            return 0.0, 0.0, 0.0
        rho, d = self.density, self.diameter
        sigma, dsigma = self.strength(rate / d) if self.strength is not None else (0.0, 0.0)
        return sigma + rho * rate * rate, 0.0, dsigma / d + 2.0 * rho * rate


def rigid_target_pulse(law: SphereFlowLaw, mass: float, velocity: float, samples: int = 801):
    """The force history [N] of a sphere (``law``, e.g. :class:`CrushingLaw`; ``mass`` [kg] striking at
    ``velocity`` [m/s]) on a rigid target: m·α̈ = −F(α, α̇), α(0) = 0, α̇(0) = V, integrated (scipy's LSODA, a
    step of at most d/V/1000) until the sphere stops or is consumed (α = d/2), and sampled at ``samples``
    instants as a :class:`~softimpact.models.pulses.TabulatedPulse`. On a rigid target this is the soft-missile
    solution of the law (module docstring); its impulse is m·(V − the velocity left when consumed)."""
    import numpy as np
    from scipy.integrate import solve_ivp

    from .pulses import TabulatedPulse

    d = law.extent  # the body's length: the sphere's diameter
    T = d / velocity

    def rhs(t, y):
        return [y[1], -law.force(y[0], y[1]) / mass]

    def stopped(t, y):
        return y[1] - 1e-9 * velocity

    def consumed(t, y):
        return y[0] - 0.5 * d * CONSUMED

    stopped.terminal = consumed.terminal = True
    sol = solve_ivp(
        rhs, (0.0, 5.0 * T), [0.0, velocity], method="LSODA", events=[stopped, consumed], rtol=1e-9, atol=1e-12 * d, max_step=T / 1000, dense_output=True
    )
    t = np.linspace(0.0, sol.t[-1], samples)
    alpha, rate = sol.sol(t)
    force = np.array([law.force(a, r) for a, r in zip(alpha, rate)])
    force[-1] = 0.0  # stopped or consumed: the force ends with the contact
    return TabulatedPulse(t, force)
