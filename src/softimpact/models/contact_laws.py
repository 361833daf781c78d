"""Contact laws for coupled impact: force, tangent, contact radius, stored energy.

A contact law maps the approach α [m] (positive when the bodies overlap) and its
rate α̇ [m/s] to a compressive force F [N] ≥ 0 (no tension, ever). Every law has

- ``force(alpha, rate)``      F [N]
- ``stiffness(alpha, rate)``  ∂F/∂α [N/m]   (Newton's tangent)
- ``damping(alpha, rate)``    ∂F/∂α̇ [N·s/m] (zero for rate-independent laws; the
  coupled solver needs it because α̇ at the new step is affine in α)
- ``radius(alpha)``           contact radius a [m] (the loaded patch follows it)
- ``energy(alpha)``           the recoverable (elastic) energy stored at α [J]

(:class:`ContactLaw`). Scalars in, scalars out; α ≤ 0 gives zero force.

A law with memory (:class:`HistoryLaw`, e.g. Yang–Sun unloading) keeps its
history in an explicit frozen state: ``initial_state()``; ``branch(state)``
returns a memoryless :class:`ContactLaw` valid within one time step;
``advance(state, alpha, rate)`` returns the state after a converged step. Nothing
is mutated. Memoryless laws are their own branch (:func:`branch_of`). A law whose
memory evolves in time (the Maxwell arm) has ``for_time_step(dt)``, which the
solver calls once before stepping.

Laws
----
:class:`HertzLaw`
    F = K·α^n, n = 3/2 (Hertz 1882; paper eqs 1–3), a = sqrt(R·α). On a laminate,
    Sun's form (Sun 1977, NASA CR-1977; Tan & Sun 1985, J. Appl. Mech. 52:6–12)
    uses the laminate's transverse modulus: K = (4/3)·sqrt(R)·E*,
    1/E* = (1 − ν_s²)/E_s + 1/E_2.
:class:`YangSunLaw`
    Hertz loading with permanent indentation on unloading (Yang & Sun 1982, ASTM
    STP 787:425–449; Tan & Sun 1985): unloading F = F_m·((α − α_p)/(α_m − α_p))^q,
    q = 5/2, with α_p = 0 for α_m < α_cr and α_p = α_m·(1 − (α_cr/α_m)^(2/5))
    otherwise. Reloading follows the unloading curve back up to (α_m, F_m) (the
    elastic reload of the same form; Tan & Sun's exponent-1.5 reload is not used).
:class:`HuntCrossleyLaw`
    F = K·α^n·(1 + D·α̇), clipped at zero: Hunt & Crossley 1975 (J. Appl. Mech.
    42:440–445), D = 3(1 − e)/(2·v⁻), or Lankarani & Nikravesh 1990 (J. Mech.
    Des. 112:369–376), D = 3(1 − e²)/(4·v⁻), with e the coefficient of
    restitution and v⁻ the impact velocity.
:class:`SoftProjectileLaw`
    F = (m·V²/d)·k·(α/d)^p·(1 + c·α̇/V), clipped at zero, a = sqrt(d·α)
    (flattening of a sphere, a² = 2Rα − α² ≈ d·α). Why this family: Table I's
    scaling laws F0 = α1·mV²/(2d) and T = α2·d/V say the pulse, written in
    α/d and t·V/d, is the same at every V; of m·α̈ = −F that is true exactly when
    F·d/(mV²) is a function of α/d and α̇/V only. Physically the ball is in
    the hydrodynamic regime: pressure ∝ ρV² (Wilbeck 1978, AFML-TR-77-134) over a
    flattened area ∝ d·α, which is p = 1; the rate term makes the pulse rise fast
    and fall slowly (tF0/T ≈ 0.25) and dissipates energy (rebound e < 1), the
    role of the Hunt–Crossley term. k and c may scale with the diameter,
    k = k_ref·(d/d_ref)^{q_k}, c = c_ref·(d/d_ref)^{q_c} (and, optionally, the
    exponent p_ref·(d/d_ref)^{q_p}); q = 0 is pure geometric similarity. Its parameters are identified from bar tests
    (:mod:`softimpact.workflows.identification`).
:class:`ViscoelasticSoftLaw`
    The soft-projectile law in parallel with a Maxwell arm (spring in series with a
    dashpot; with the equilibrium branch, the standard linear solid of Zener 1948,
    *Elasticity and Anelasticity of Metals*; contact of viscoelastic bodies: Lee &
    Radok 1960, J. Appl. Mech. 27:438–444; Ting 1966, J. Appl. Mech. 33:845–854):

        F = (m·V²/d)·[k·(α/d)^p·(1 + c·α̇/V) + σ] ≥ 0 for α > 0,
        dσ/dt = κ·d(α⁺/d)/dt − σ·V/(θ·d),   α⁺ = max(α, 0).

    Why: a memoryless F(α, α̇) unloads along one curve, so the rate term that makes the
    pulse rise fast also cuts the force off as soon as the ball rebounds, and the
    measured pulses fall fast to a low force that lingers while the ball is still in
    contact (the tail, Fig 7). The arm is stiff on the fast loading, relaxes near the
    peak and pulls the force down on the fast unloading; once it has relaxed, the
    equilibrium branch carries the lingering force. The arm's stress, like the rest,
    is in units of m·V²/d and its relaxation time θ·d/V in units of the transit time:
    only then is F·d/(mV²) a function of α/d, α̇/V and t·V/d, as Table I's scaling
    laws (one pulse shape at every velocity) require. A fixed material relaxation time
    would change the tail's share by the series' 5:1 velocity range; in the
    hydrodynamic regime the flowing material's response time is the transit time
    (Wilbeck 1978). κ, θ may scale with the diameter as k and c do. Out of contact
    (α ≤ 0) the arm's strain α⁺ stays 0 and σ relaxes. Over one time step Δt the arm
    is integrated exactly for a strain rate constant over the step (the branch is
    affine in α⁺), so the law is a :class:`HistoryLaw` bound to the solver's step
    (``for_time_step``). Recoverable energy: the equilibrium branch's plus the arm
    spring's ½·(mV²/d)·d·σ²/κ; the dashpots dissipate.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from .materials import Material
from .protocols import ContactLaw, HistoryLaw

__all__ = [
    "CONTACT_LAWS",
    "HERTZ_DURATION",
    "HertzLaw",
    "YangSunLaw",
    "YangSunState",
    "YangSunBranch",
    "HuntCrossleyLaw",
    "SoftProjectileLaw",
    "ViscoelasticSoftLaw",
    "MaxwellState",
    "MaxwellBranch",
    "laminate_modulus",
    "effective_modulus",
    "branch_of",
    "resolve_law",
    "law_name",
]

# Rigid-wall Hertz impact lasts HERTZ_DURATION·α_max/V: (4/5)·B(2/5, 1/2) = 2·∫₀¹(1 − s^(5/2))^(-1/2) ds.
HERTZ_DURATION = 2.9432752


def branch_of(law, state) -> ContactLaw:
    """The memoryless law to use in a step: ``law.branch(state)`` or ``law`` itself."""
    return law.branch(state) if isinstance(law, HistoryLaw) else law


def _positive(name: str, value: float) -> None:
    if not (math.isfinite(value) and value > 0):
        raise InputError(f"contact: {name} must be positive, got {value!r}")


def effective_modulus(a: Material, b: Material) -> float:
    """E* = k1·k2/(k1 + k2), k = E/(1 − ν²), the modulus factor of eq (2) [Pa]."""
    k1, k2 = a.plane_modulus, b.plane_modulus
    return k1 * k2 / (k1 + k2)


def laminate_modulus(sphere: Material, transverse_modulus: float) -> float:
    """E* of a sphere on a laminate, 1/E* = (1 − ν_s²)/E_s + 1/E_2 [Pa] (Sun's form)."""
    _positive("transverse modulus E2", transverse_modulus)
    return 1.0 / ((1.0 - sphere.poisson_ratio**2) / sphere.youngs_modulus + 1.0 / transverse_modulus)


@dataclass(frozen=True)
class HertzLaw:
    """F = K·α^n, eq (1), n = 3/2; a = sqrt(R·α); K [N/m^n], R the sphere radius [m].

    Build it from geometry with :meth:`sphere_on_flat` (eq 3), :meth:`sphere_on_sphere`
    (eq 2) or :meth:`sphere_on_laminate` (Sun's form). ``force``, ``stiffness`` and
    ``energy`` take a scalar (the stepping loop's fast path) or an array of α.
    """

    radius_power = 0.5  # the contact radius a = sqrt(c·α) ∝ α^½ (the contact iteration's da/dα = ½·a/α)

    K: float
    R: float
    exponent: float = 1.5

    def __post_init__(self):
        _positive("Hertz constant K", self.K)
        _positive("sphere radius R", self.R)
        if not self.exponent >= 1.0:
            raise InputError(f"contact: exponent must be >= 1, got {self.exponent!r}")

    @classmethod
    def sphere_on_sphere(cls, r1: float, r2: float, m1: Material, m2: Material) -> HertzLaw:
        """Eq (2): K = (4/3)·sqrt(R1R2/(R1+R2))·k1k2/(k1+k2); radii in m (R: the effective radius)."""
        if r1 <= 0 or r2 <= 0:
            raise InputError(f"contact: radii must be positive, got {r1!r}, {r2!r}")
        radius = r1 * r2 / (r1 + r2)
        return cls(4.0 / 3.0 * math.sqrt(radius) * effective_modulus(m1, m2), radius)

    @classmethod
    def sphere_on_flat(cls, radius: float, sphere: Material, flat: Material) -> HertzLaw:
        """Eq (3) for an isotropic flat target (R2 → ∞): K = (4/3)·sqrt(R)·E*."""
        _positive("sphere radius", radius)
        k1, k2 = sphere.plane_modulus, flat.plane_modulus
        return cls(4.0 / 3.0 * math.sqrt(radius) * k1 * k2 / (k1 + k2), radius)

    @classmethod
    def sphere_on_laminate(cls, radius: float, sphere: Material, transverse_modulus: float) -> HertzLaw:
        """Sun's form on a laminate: K = (4/3)·sqrt(R)·E*, 1/E* = (1 − ν_s²)/E_s + 1/E_2."""
        _positive("sphere radius", radius)
        return cls(4.0 / 3.0 * math.sqrt(radius) * laminate_modulus(sphere, transverse_modulus), radius)

    def force(self, alpha, rate: float = 0.0):
        """F(α) = K·max(α, 0)^n [N]."""
        if isinstance(alpha, float):
            return self.K * alpha**self.exponent if alpha > 0.0 else 0.0
        return self.K * np.maximum(alpha, 0.0) ** self.exponent

    def stiffness(self, alpha, rate: float = 0.0):
        """dF/dα = n·K·max(α, 0)^(n−1) [N/m]."""
        if isinstance(alpha, float):
            return self.exponent * self.K * alpha ** (self.exponent - 1.0) if alpha > 0.0 else 0.0
        return self.exponent * self.K * np.maximum(alpha, 0.0) ** (self.exponent - 1.0)

    def damping(self, alpha: float, rate: float = 0.0) -> float:
        return 0.0

    def radius(self, alpha: float) -> float:
        """Hertz contact radius a = sqrt(R·α) [m]."""
        return math.sqrt(self.R * alpha) if alpha > 0.0 else 0.0

    def energy(self, alpha):
        """Stored energy ∫₀^α F dα = K·α^(n+1)/(n+1) [J]."""
        if isinstance(alpha, float):
            return self.K * alpha ** (self.exponent + 1.0) / (self.exponent + 1.0) if alpha > 0.0 else 0.0
        return self.K * np.maximum(alpha, 0.0) ** (self.exponent + 1.0) / (self.exponent + 1.0)

    def rigid_impact(self, mass: float, velocity: float) -> tuple[float, float, float]:
        """(α_max, F_max, duration) on a rigid immovable flat, n = 3/2 (Hertz 1882).

        α_max = (5mV²/(4K))^(2/5); duration = 2·(α_max/V)·∫₀¹(1 − s^(5/2))^(-1/2) ds
        = :data:`HERTZ_DURATION`·α_max/V, the same as 3.2181·(m/K)^(2/5)·V^(-1/5).
        """
        if self.exponent != 1.5:
            raise ValueError("closed form exists for n = 3/2 only")
        a = (5.0 * mass * velocity**2 / (4.0 * self.K)) ** 0.4
        return a, self.force(a), HERTZ_DURATION * a / velocity


@dataclass(frozen=True)
class YangSunState:
    """Memory of the Yang–Sun law: the largest approach reached so far, α_m [m]."""

    alpha_max: float = 0.0


@dataclass(frozen=True)
class YangSunBranch:
    """The Yang–Sun law at a fixed α_m: loading above α_m, the unloading curve below."""

    radius_power = 0.5  # the contact radius a = sqrt(c·α) ∝ α^½ (the contact iteration's da/dα = ½·a/α)

    law: YangSunLaw
    alpha_max: float

    def _unload(self):
        am = self.alpha_max
        return self.law.force_loading(am), self.law.permanent(am), am

    def force(self, alpha: float, rate: float = 0.0) -> float:
        if alpha >= self.alpha_max:
            return self.law.force_loading(alpha)
        Fm, ap, am = self._unload()
        if alpha <= ap:
            return 0.0
        return Fm * ((alpha - ap) / (am - ap)) ** self.law.unloading_exponent

    def stiffness(self, alpha: float, rate: float = 0.0) -> float:
        if alpha >= self.alpha_max:
            return self.law.hertz.stiffness(alpha)
        Fm, ap, am = self._unload()
        if alpha <= ap:
            return 0.0
        q = self.law.unloading_exponent
        return q * Fm / (am - ap) * ((alpha - ap) / (am - ap)) ** (q - 1.0)

    def damping(self, alpha: float, rate: float = 0.0) -> float:
        return 0.0

    def radius(self, alpha: float) -> float:
        return self.law.hertz.radius(max(alpha, 0.0))

    def energy(self, alpha: float) -> float:
        """Recoverable energy: the integral of the unloading curve from α_p up to α."""
        am = max(alpha, self.alpha_max)
        Fm, ap = self.law.force_loading(am), self.law.permanent(am)
        if alpha <= ap or am <= 0.0:
            return 0.0
        q = self.law.unloading_exponent
        return Fm * (am - ap) / (q + 1.0) * ((alpha - ap) / (am - ap)) ** (q + 1.0)


@dataclass(frozen=True)
class YangSunLaw:
    """Hertz loading, Yang–Sun unloading with permanent indentation (module docstring).

    ``hertz``: the loading law; ``critical_indentation`` α_cr [m] (Yang & Sun
    report ≈ 0.08 mm for graphite/epoxy with a 12.7 mm steel ball);
    ``unloading_exponent`` q = 5/2.
    """

    hertz: HertzLaw
    critical_indentation: float
    unloading_exponent: float = 2.5

    def __post_init__(self):
        _positive("critical indentation", self.critical_indentation)
        if not self.unloading_exponent >= 1.0:
            raise InputError(f"contact: unloading exponent must be >= 1, got {self.unloading_exponent!r}")

    def force_loading(self, alpha: float) -> float:
        return self.hertz.force(alpha)

    def permanent(self, alpha_max: float) -> float:
        """α_p = 0 below α_cr, else α_m·(1 − (α_cr/α_m)^(2/5)) [m]."""
        if alpha_max <= self.critical_indentation:
            return 0.0
        return alpha_max * (1.0 - (self.critical_indentation / alpha_max) ** 0.4)

    def initial_state(self) -> YangSunState:
        return YangSunState()

    def branch(self, state: YangSunState) -> YangSunBranch:
        return YangSunBranch(self, state.alpha_max)

    def advance(self, state: YangSunState, alpha: float, rate: float) -> YangSunState:
        return state if alpha <= state.alpha_max else YangSunState(alpha)


@dataclass(frozen=True)
class HuntCrossleyLaw:
    """F = K·α^n·(1 + D·α̇) ≥ 0 with D from the restitution e (module docstring).

    ``form``: ``"lankarani-nikravesh"`` (D = 3(1 − e²)/(4v⁻)) or ``"hunt-crossley"``
    (D = 3(1 − e)/(2v⁻)). ``impact_velocity`` v⁻ > 0 [m/s].
    """

    radius_power = 0.5  # the contact radius a = sqrt(c·α) ∝ α^½ (the contact iteration's da/dα = ½·a/α)

    K: float
    R: float
    restitution: float
    impact_velocity: float
    exponent: float = 1.5
    form: str = "lankarani-nikravesh"

    def __post_init__(self):
        _positive("Hunt-Crossley K", self.K)
        _positive("sphere radius R", self.R)
        _positive("impact velocity", self.impact_velocity)
        if not 0.0 < self.restitution <= 1.0:
            raise InputError(f"contact: coefficient of restitution must be in (0, 1], got {self.restitution!r}")
        if self.form not in ("lankarani-nikravesh", "hunt-crossley"):
            raise InputError(f"contact: Hunt-Crossley form {self.form!r} is not 'lankarani-nikravesh' or 'hunt-crossley'")

    @property
    def D(self) -> float:
        """The damping factor D [s/m]."""
        e, v = self.restitution, self.impact_velocity
        if self.form == "hunt-crossley":
            return 1.5 * (1.0 - e) / v
        return 0.75 * (1.0 - e * e) / v

    def force(self, alpha: float, rate: float = 0.0) -> float:
        if alpha <= 0.0:
            return 0.0
        return max(self.K * alpha**self.exponent * (1.0 + self.D * rate), 0.0)

    def stiffness(self, alpha: float, rate: float = 0.0) -> float:
        g = 1.0 + self.D * rate
        if alpha <= 0.0 or g <= 0.0:
            return 0.0
        return self.exponent * self.K * alpha ** (self.exponent - 1.0) * g

    def damping(self, alpha: float, rate: float = 0.0) -> float:
        if alpha <= 0.0 or 1.0 + self.D * rate <= 0.0:
            return 0.0
        return self.K * alpha**self.exponent * self.D

    def radius(self, alpha: float) -> float:
        return math.sqrt(self.R * alpha) if alpha > 0.0 else 0.0

    def energy(self, alpha: float) -> float:
        """The elastic part K·α^(n+1)/(n+1) [J]."""
        return self.K * alpha ** (self.exponent + 1.0) / (self.exponent + 1.0) if alpha > 0.0 else 0.0


@dataclass(frozen=True)
class SoftProjectileLaw:
    """F = (m·V²/d)·k·(α/d)^p·(1 + c·α̇/V) ≥ 0, a = sqrt(d·α) (module docstring).

    ``mass`` m [kg], ``diameter`` d [m], ``velocity`` V [m/s] of the projectile;
    ``k``, ``p``, ``c`` dimensionless (already scaled to this diameter; see
    :meth:`scaled`).
    """

    radius_power = 0.5  # the contact radius a = sqrt(c·α) ∝ α^½ (the contact iteration's da/dα = ½·a/α)

    mass: float
    diameter: float
    velocity: float
    k: float
    p: float
    c: float = 0.0

    def __post_init__(self):
        for name in ("mass", "diameter", "velocity", "k", "p"):
            _positive(name, getattr(self, name))
        if not (math.isfinite(self.c) and self.c >= 0.0):
            raise InputError(f"contact: rate coefficient c must be non-negative, got {self.c!r}")

    @classmethod
    def scaled(cls, mass, diameter, velocity, k_ref, p, c_ref, d_ref, q_k=0.0, q_c=0.0, q_p=0.0) -> SoftProjectileLaw:
        """k = k_ref·(d/d_ref)^q_k, c = c_ref·(d/d_ref)^q_c, exponent p·(d/d_ref)^q_p."""
        s = diameter / d_ref
        return cls(mass, diameter, velocity, k_ref * s**q_k, p * s**q_p, c_ref * s**q_c)

    @property
    def scale(self) -> float:
        """m·V²/d [N]."""
        return self.mass * self.velocity**2 / self.diameter

    def _elastic(self, alpha: float) -> float:
        return self.scale * self.k * (alpha / self.diameter) ** self.p

    def force_unclipped(self, alpha: float, rate: float = 0.0) -> float:
        """k·(α/d)^p·(1 + c·α̇/V)·mV²/d for α > 0, negative when the rate term wins [N]."""
        return self._elastic(alpha) * (1.0 + self.c * rate / self.velocity)

    def force(self, alpha: float, rate: float = 0.0) -> float:
        if alpha <= 0.0:
            return 0.0
        return max(self.force_unclipped(alpha, rate), 0.0)

    def response(self, alpha: float, rate: float = 0.0) -> tuple[float, float, float]:
        """(:meth:`force` [N], :meth:`stiffness` [N/m], :meth:`damping` [N·s/m]) at once, the same values,
        for one evaluation of the power law (the contact iteration's need)."""
        g = 1.0 + self.c * rate / self.velocity
        if alpha <= 0.0 or g <= 0.0:
            return 0.0, 0.0, 0.0
        elastic = self._elastic(alpha)
        return elastic * g, self.p * elastic / alpha * g, elastic * self.c / self.velocity

    def stiffness(self, alpha: float, rate: float = 0.0) -> float:
        g = 1.0 + self.c * rate / self.velocity
        if alpha <= 0.0 or g <= 0.0:
            return 0.0
        return self.p * self._elastic(alpha) / alpha * g

    def damping(self, alpha: float, rate: float = 0.0) -> float:
        if alpha <= 0.0 or 1.0 + self.c * rate / self.velocity <= 0.0:
            return 0.0
        return self._elastic(alpha) * self.c / self.velocity

    def radius(self, alpha: float) -> float:
        return math.sqrt(self.diameter * alpha) if alpha > 0.0 else 0.0

    def energy(self, alpha: float) -> float:
        return self._elastic(alpha) * alpha / (self.p + 1.0) if alpha > 0.0 else 0.0


@dataclass(frozen=True)
class MaxwellState:
    """Memory of :class:`ViscoelasticSoftLaw` after a converged step: the arm's strain α⁺/d (α⁺ = max(α, 0))
    and its stress σ (arm force over m·V²/d), both dimensionless."""

    strain: float = 0.0
    stress: float = 0.0


@dataclass(frozen=True)
class MaxwellBranch:
    """:class:`ViscoelasticSoftLaw` within one step: σ(α) = σ_start + g·(α⁺/d − ε_k), affine in α⁺.

    ``stress_start`` = σ_k·E, ``gain`` g = κ·θ·(1 − E)/Δτ, E = exp(−Δτ/θ), Δτ = Δt·V/d: the exact
    update of σ̇ = κ·ε̇ − σ/θ for a strain rate constant over the step (module docstring).
    The base law's constants are copied once per branch (plain floats: the contact iteration calls
    :meth:`response` thousands of times per run); every result is the same arithmetic as the base law's.
    """

    radius_power = 0.5  # the contact radius a = sqrt(c·α) ∝ α^½ (the contact iteration's da/dα = ½·a/α)

    law: ViscoelasticSoftLaw
    strain_start: float
    stress_start: float
    gain: float

    def __post_init__(self):
        law = self.law
        base = law.__dict__.get("_branch_const")
        if base is None:
            b = law.base
            scale = b.scale
            # (m·V²/d)·k, d, p, c, V, m·V²/d, ½·(m·V²/d)·d, κ: the factors of force, stiffness, damping, energy
            base = (scale * b.k, b.diameter, b.p, b.c, b.velocity, scale, 0.5 * scale * b.diameter, law.kappa)
            object.__setattr__(law, "_branch_const", base)
        object.__setattr__(self, "_const", (*base, base[5] * self.gain / base[1]))  # last: (m·V²/d)·g/d

    @classmethod
    def _of(cls, law: ViscoelasticSoftLaw, strain_start: float, stress_start: float, gain: float) -> MaxwellBranch:
        """``MaxwellBranch(law, strain_start, stress_start, gain)``, the same object, built without the frozen
        dataclass's ``__init__`` and with the constants of the law's last gain reused (a contact loop builds
        one branch a step: this is its cost)."""
        last = law.__dict__.get("_branch_gain")
        if last is None or last[0] != gain:
            const = cls(law, strain_start, stress_start, gain)._const
            last = (gain, const)
            object.__setattr__(law, "_branch_gain", last)
        branch = object.__new__(cls)
        branch.__dict__.update(law=law, strain_start=strain_start, stress_start=stress_start, gain=gain, _const=last[1])
        return branch

    def stress(self, alpha: float) -> float:
        """σ at the end of the step if the approach there is ``alpha`` [m]."""
        return self.stress_start + self.gain * (max(alpha, 0.0) / self._const[1] - self.strain_start)

    def response(self, alpha: float, rate: float = 0.0) -> tuple[float, float, float]:
        """(:meth:`force` [N], :meth:`stiffness` [N/m], :meth:`damping` [N·s/m]) at once, the same values:
        what one iteration of the contact solve needs, for one evaluation of the power law."""
        if alpha <= 0.0:
            return 0.0, 0.0, 0.0
        sk, d, p, c, v, scale, _, _, kg = self._const
        ad = alpha / d
        elastic = sk * ad**p
        unclipped = elastic * (1.0 + c * rate / v)
        f = unclipped + scale * (self.stress_start + self.gain * (ad - self.strain_start))
        if f <= 0.0:
            return 0.0, 0.0, 0.0
        return f, p * unclipped / alpha + kg, elastic * c / v

    def force(self, alpha: float, rate: float = 0.0) -> float:
        return self.response(alpha, rate)[0]

    def stiffness(self, alpha: float, rate: float = 0.0) -> float:
        return self.response(alpha, rate)[1]

    def damping(self, alpha: float, rate: float = 0.0) -> float:
        return self.response(alpha, rate)[2]

    def radius(self, alpha: float) -> float:
        return math.sqrt(self._const[1] * alpha) if alpha > 0.0 else 0.0

    def energy(self, alpha: float) -> float:
        """Elastic energy of the equilibrium part plus the arm spring's, ½·(mV²/d)·d·σ²/κ [J]."""
        sk, d, p, _, _, _, half_sd, kappa, _ = self._const
        elastic = sk * (alpha / d) ** p * alpha / (p + 1.0) if alpha > 0.0 else 0.0  # SoftProjectileLaw.energy
        stress = self.stress_start + self.gain * (max(alpha, 0.0) / d - self.strain_start)  # self.stress(alpha)
        return elastic + half_sd * stress**2 / kappa


@dataclass(frozen=True)
class ViscoelasticSoftLaw:
    """:class:`SoftProjectileLaw` in parallel with a Maxwell arm in the same scaling (module docstring).

    F = (m·V²/d)·[k·(α/d)^p·(1 + c·α̇/V) + σ] ≥ 0, σ̇ = κ·d(α⁺/d)/dt − σ·V/(θ·d);
    ``kappa`` κ (arm stiffness) and ``theta`` θ (relaxation time in units of d/V) dimensionless.
    A law with memory (:class:`HistoryLaw`) whose memory evolves in time: the solver binds it to
    its step with :meth:`for_time_step` first.
    """

    base: SoftProjectileLaw
    kappa: float
    theta: float
    time_step: float | None = None

    def __post_init__(self):
        _positive("Maxwell arm stiffness kappa", self.kappa)
        _positive("Maxwell relaxation time theta", self.theta)
        if self.time_step is not None:
            _positive("time step", self.time_step)

    def for_time_step(self, dt: float) -> ViscoelasticSoftLaw:
        """The same law bound to the solver's time step dt [s]."""
        return ViscoelasticSoftLaw(self.base, self.kappa, self.theta, dt)

    @property
    def relaxation_time(self) -> float:
        """θ·d/V [s]."""
        return self.theta * self.base.diameter / self.base.velocity

    def _decay(self) -> tuple[float, float]:
        """(E, g) of one step (:class:`MaxwellBranch`), computed once per bound law."""
        decay = self.__dict__.get("_decay_cache")
        if decay is None:
            if self.time_step is None:
                raise ValueError("ViscoelasticSoftLaw: bind the time step first (for_time_step)")
            x = self.time_step / self.relaxation_time
            decay = (math.exp(-x), self.kappa * (-math.expm1(-x)) / x)
            object.__setattr__(self, "_decay_cache", decay)
        return decay

    def initial_state(self) -> MaxwellState:
        return MaxwellState()

    def branch(self, state: MaxwellState) -> MaxwellBranch:
        E, g = self._decay()
        return MaxwellBranch._of(self, state.strain, state.stress * E, g)

    def advance(self, state: MaxwellState, alpha: float, rate: float) -> MaxwellState:
        E, g = self._decay()
        strain = max(alpha, 0.0) / self.base.diameter
        return MaxwellState(strain, state.stress * E + g * (strain - state.strain))  # MaxwellBranch.stress(alpha)

    def settle(self, state: MaxwellState, alpha: float, rate: float) -> tuple[MaxwellState, MaxwellBranch, float]:
        """A converged step's memory at once: ``advance(state, α, α̇)``, the branch of that state, and the
        contact energy at the end of the step [J]: the step's own branch's (``branch(state).energy(α)`` of
        the state before it), whose arm stress at α is the converged σ (one call a step in the contact kernels)."""
        steady = self.__dict__.get("_steady")
        if steady is None:  # (E, g, the branches' constants and those of the energy), once per bound law
            E, g = self._decay()
            const = MaxwellBranch._of(self, 0.0, 0.0, g)._const
            steady = (E, g, const, const[0], const[1], const[2], const[6], const[7])
            object.__setattr__(self, "_steady", steady)
        E, g, const, sk, d, p, half_sd, kappa = steady  # d: the base law's diameter
        strain = (alpha if alpha > 0.0 else 0.0) / d
        stress = state.stress * E + g * (strain - state.strain)
        new = object.__new__(MaxwellState)  # MaxwellState(strain, stress) without the frozen __init__
        new.__dict__.update(strain=strain, stress=stress)
        start = stress * E
        branch = object.__new__(MaxwellBranch)  # MaxwellBranch(self, strain, start, g), as _of builds it
        branch.__dict__.update(law=self, strain_start=strain, stress_start=start, gain=g, _const=const)
        elastic = sk * (alpha / d) ** p * alpha / (p + 1.0) if alpha > 0.0 else 0.0  # the step branch's energy(alpha), inlined
        return new, branch, elastic + half_sd * stress**2 / kappa

    def apart(self, state: MaxwellState, steps: int) -> tuple[MaxwellState, list[float]]:
        """``steps`` steps with the bodies apart (α ≤ 0: the arm's strain α⁺/d is zero, its stress relaxes,
        σ ← σ·E + g·(0 − ε)): the state after them and the contact energy after each [J] (the arm spring's
        ½·(mV²/d)·d·σ²/κ), the values of ``branch(state).energy(α)`` then ``state = advance(state, α, α̇)``
        step by step for any α ≤ 0 (the same arithmetic, without building a state and a branch a step:
        the contact kernels' free flight)."""
        if steps <= 0:
            return state, []
        E, g = self._decay()
        const = self.branch(state)._const
        half_sd, kappa = const[6], const[7]
        # the first step releases the arm's strain; from then on σ ← σ·E + g·(0 − 0) = σ·E: a running product
        factors = np.full(steps, E)
        factors[0] = state.stress * E + g * (0.0 - state.strain)
        stress = np.cumprod(factors).tolist()
        # the energies in Python floats: float ** 2 (C's pow) and numpy's x·x differ in the last bit now and then
        return MaxwellState(0.0, stress[-1]), [0.0 + half_sd * x**2 / kappa for x in stress]


# The contact laws by name (case files' ``contact.law``), each with the class it builds: one table,
# as scipy's ``METHODS``. "identified" is a law.json of ``softimpact identify``: the soft-projectile
# law (or its viscoelastic extension, :class:`ViscoelasticSoftLaw`).
CONTACT_LAWS = {
    "hertz": HertzLaw,
    "hertz-unloading": YangSunLaw,
    "hunt-crossley": HuntCrossleyLaw,
    "identified": SoftProjectileLaw,
}


def resolve_law(law, hertz: Callable[[], HertzLaw]):
    """A contact law given as a name of :data:`CONTACT_LAWS` or as an object, resolved in one place.

    ``"hertz"`` is the pair's own Hertz law, ``hertz()``; the other names need their parameters
    (restitution, a law file…), so they come as objects (a :class:`ContactLaw` or a
    :class:`HistoryLaw`), returned as they are. InputError (argument ``law``) otherwise.
    """
    if isinstance(law, str):
        if law not in CONTACT_LAWS:
            raise InputError(f"unknown contact law {law!r} (known: {', '.join(CONTACT_LAWS)})", "law")
        if law != "hertz":
            raise InputError(f"contact law {law!r} needs its parameters: give the law object ({CONTACT_LAWS[law].__name__})", "law")
        return hertz()
    if not isinstance(law, (ContactLaw, HistoryLaw)):
        raise InputError(f"law must be one of {', '.join(CONTACT_LAWS)} or a contact law object, got {type(law).__name__}", "law")
    return law


def law_name(law) -> str:
    """The name of :data:`CONTACT_LAWS` a law object (or name) goes by; the class name if none."""
    if isinstance(law, str):
        return law
    for name, cls in CONTACT_LAWS.items():
        if type(law) is cls:
            return name
    return "identified" if isinstance(law, ViscoelasticSoftLaw) else type(law).__name__
