"""The soft projectile's laws: the hydrodynamic power law and its Maxwell-arm extension (module docstring
of :mod:`softimpact.models.contact_laws`)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...errors import InputError
from ..protocols import PowerRadiusLaw, RespondingLaw, SettlingLaw, StepBoundLaw
from ._common import _positive

__all__ = ["SoftProjectileLaw", "MaxwellState", "MaxwellBranch", "ViscoelasticSoftLaw"]


@dataclass(frozen=True)
class SoftProjectileLaw(PowerRadiusLaw, RespondingLaw):
    """F = (m·V²/d)·k·(α/d)^p·(1 + c·α̇/V) ≥ 0, a = sqrt(d·α) (module docstring).

    ``mass`` m [kg], ``diameter`` d [m], ``velocity`` V [m/s] of the projectile;
    ``k``, ``p``, ``c`` dimensionless (already scaled to this diameter; see
    :meth:`scaled`).
    """

    source = "identified from bar tests (workflows/identification.py); its form from Table I's scaling laws and Wilbeck 1978 (AFML-TR-77-134)"  # where the law comes from (softimpact catalogue); a class attribute, not a field

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
class MaxwellBranch(PowerRadiusLaw, RespondingLaw):
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
class ViscoelasticSoftLaw(StepBoundLaw, SettlingLaw):
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
