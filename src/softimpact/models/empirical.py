"""Force-history models of a projectile of mass m [kg], diameter d [m] at velocity V [m/s].

- :class:`ScalingLaw`: the paper's empirical model, eqs (4)–(7) with eq (15) as
  the shape: F0 = α1·mV²/(2d), T = α2·d/V, t_F0 = α3·T, I = α4·2mV.
- :class:`HertzModel`: the classical elastic impact the paper argues against
  (eqs 1–3 against a rigid flat): F0 ∝ V^1.2, duration ∝ V^-0.2.
- :class:`WilbeckModel`: hydrodynamic soft-body impact: steady-flow force
  ρV²·A(t) on the sphere's cross-section at the squash plane, over the squash
  time d/V.

Each has ``parameters(m, d, V)`` → :class:`PulseParameters` and
``pulse(m, d, V)`` → a pulse with ``__call__(t)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..units import INCH
from .contact_laws import HertzLaw
from .materials import Material
from .pulses import SkewedPulse, TabulatedPulse, TailedPulse

__all__ = ["PulseParameters", "ScalingLaw", "HertzModel", "WilbeckModel", "PRESETS", "PROJECTILES", "ProjectilePreset", "REGRESSORS"]


# Regressor x and response y of each law of eqs (4)–(7) (y = α·x), read from a test point with m, d, V and
# F0, t_F0, T, I (duck-typed: softimpact.workflows.scaling.TestPoint): its name, then x and y.
REGRESSORS = {
    "alpha1": ("mV²/(2d)", lambda p: p.mass * p.velocity**2 / (2 * p.diameter), lambda p: p.peak_force),
    "alpha2": ("d/V", lambda p: p.diameter / p.velocity, lambda p: p.duration),
    "alpha3": ("T", lambda p: p.duration, lambda p: p.time_of_peak),
    "alpha4": ("2mV", lambda p: 2 * p.mass * p.velocity, lambda p: p.impulse),
}


@dataclass(frozen=True)
class PulseParameters:
    """F0 [N], t_F0 [s], T [s], I [N·s]."""

    peak_force: float
    time_of_peak: float
    duration: float
    impulse: float


def _check(m, d, V):
    for name, value in (("mass", m), ("diameter", d), ("velocity", V)):
        if not (math.isfinite(value) and value > 0):
            raise InputError(f"{name} must be positive, got {value!r}")


@dataclass(frozen=True)
class ScalingLaw:
    """Eqs (4)–(7): the α's, where they come from, and the velocity [m/s] and diameter [m] ranges
    they were fitted on ((0, inf): not known)."""

    alpha1: float
    alpha2: float
    alpha3: float
    alpha4: float
    name: str = "user"
    source: str = "user input"
    velocity_range: tuple[float, float] = (0.0, math.inf)
    diameter_range: tuple[float, float] = (0.0, math.inf)

    def __post_init__(self):
        for k in ("alpha1", "alpha2", "alpha4"):
            if not getattr(self, k) > 0:
                raise InputError(f"{k} must be positive, got {getattr(self, k)!r}")
        if not 0 < self.alpha3 < 1:
            raise InputError(f"alpha3 = t_F0/T must lie in (0, 1), got {self.alpha3!r}")

    def parameters(self, m: float, d: float, V: float) -> PulseParameters:
        """Eqs (4)–(7)."""
        _check(m, d, V)
        T = self.alpha2 * d / V
        return PulseParameters(self.alpha1 * m * V**2 / (2 * d), self.alpha3 * T, T, self.alpha4 * 2 * m * V)

    def pulse(self, m: float, d: float, V: float, tail: bool = False):
        """Eq (15) with eqs (4)–(6); with ``tail``, the exponential tail that carries
        the rest of eq (7)'s impulse (I − 2F0T/π), starting at 4 % of F0."""
        p = self.parameters(m, d, V)
        main = SkewedPulse(p.peak_force, p.time_of_peak, p.duration)
        if not tail or p.impulse <= main.impulse * (1 + 1e-9):
            return main
        return TailedPulse.with_impulse(main, TAIL_LEVEL, p.impulse)

    def in_range(self, V: float) -> bool:
        lo, hi = self.velocity_range
        return lo <= V <= hi

    def envelope(self, d: float, V: float, what: str = ""):
        """The velocity V [m/s] and diameter d [m] against the ranges the constants were fitted on
        (:func:`softimpact.models.validity.range_flags`; unknown ranges are not checked)."""
        from .validity import range_flags

        checks = [
            (k, x, r, u) for k, x, r, u in (("velocity", V, self.velocity_range, "m/s"), ("diameter", d, self.diameter_range, "m")) if math.isfinite(r[1])
        ]
        return range_flags(what or f"the constants {self.name}", checks)


TAIL_LEVEL = 0.04  # fraction of F0 where the synthetic tail takes over from eq (15)

_TABLE_I = "Table I of the paper (longitudinal bar tests, 1000-5000 in/s)"

PRESETS = {
    "silicone-3/8in": ScalingLaw(4.00, 1.03, 0.25, 0.74, "silicone-3/8in", _TABLE_I, (1000 * INCH, 5000 * INCH), (0.375 * INCH, 0.375 * INCH)),
    # α3 of the 1/2-in ball did not survive in Table I; the 3/8-in value is used, as
    # the paper finds the trends characteristic of the material, not the size.
    "silicone-1/2in": ScalingLaw(
        4.25, 0.93, 0.25, 0.66, "silicone-1/2in", _TABLE_I + "; alpha3 missing, 0.25 (3/8-in value) used", (1000 * INCH, 5000 * INCH), (0.5 * INCH, 0.5 * INCH)
    ),
}


@dataclass(frozen=True)
class ProjectilePreset:
    """A named projectile of the paper: diameter [m], mass [kg], its material and scaling law
    (the sphere that strikes, with its velocity, is :class:`softimpact.models.specimens.Impactor`)."""

    name: str
    diameter: float
    mass: float
    material: str
    law: str
    source: str = "user input"


PROJECTILES = {
    "rubber-1/2in": ProjectilePreset(
        "rubber-1/2in", 0.5 * INCH, 1.1e-3, "silicone rubber", "silicone-1/2in", "the paper's text (1/2-in silicone rubber ball, 1.1 g); its law Table I"
    ),
    # 0.46 g: the same density as the 1.1-g half-inch ball (docs/modelling-notes.md).
    "rubber-3/8in": ProjectilePreset(
        "rubber-3/8in",
        0.375 * INCH,
        1.1e-3 * 0.75**3,
        "silicone rubber",
        "silicone-3/8in",
        "the paper's 3/8-in ball (Table I); mass from the 1/2-in ball's density (docs/modelling-notes.md)",
    ),
}


@dataclass(frozen=True)
class HertzModel:
    """Elastic sphere (material ``sphere``) on a rigid-backed flat of ``target``: eqs (1)–(3).

    The force history is the exact solution of m·α̈ = −K·α^(3/2), sampled finely.
    """

    sphere: Material
    target: Material

    def law(self, d: float) -> HertzLaw:
        return HertzLaw.sphere_on_flat(d / 2, self.sphere, self.target)

    def parameters(self, m, d, V) -> PulseParameters:
        _check(m, d, V)
        alpha_max, F0, T = self.law(d).rigid_impact(m, V)
        return PulseParameters(F0, T / 2, T, 2 * m * V)

    def pulse(self, m, d, V, samples: int = 401) -> TabulatedPulse:
        """F(t) from the energy integral: t(α) = ∫dα/sqrt(V² − (4K/5m)α^(5/2)), mirrored at the peak."""
        from scipy.integrate import solve_ivp

        law = self.law(d)
        _, _, T = law.rigid_impact(m, V)

        def rhs(t, y):
            return [y[1], -law.K * max(y[0], 0.0) ** 1.5 / m]

        t = np.linspace(0, T, samples)
        sol = solve_ivp(rhs, (0, T), [0.0, V], t_eval=t, rtol=1e-10, atol=1e-14)
        return TabulatedPulse(t, law.force(sol.y[0]))


@dataclass(frozen=True)
class WilbeckModel:
    """Hydrodynamic (steady-flow) soft-body impact of a sphere of density ρ [kg/m³].

    A fluid-like projectile squashing on a rigid target at V exerts ρV² on the
    area it is squashing: F(t) = ρV²·A(t), A = π(d·s − s²) the sphere's section
    at the squash depth s = V·t, for the squash time L/V = d/V. Peak ρV²·πd²/4 at
    d/(2V); impulse mV (perfectly plastic: no rebound). The initial shock
    (Hugoniot) spike is not modelled.
    """

    density: float

    def parameters(self, m, d, V) -> PulseParameters:
        _check(m, d, V)
        return PulseParameters(self.density * V**2 * math.pi * d**2 / 4, d / (2 * V), d / V, self.density * V * math.pi * d**3 / 6)

    def pulse(self, m, d, V, samples: int = 401) -> TabulatedPulse:
        t = np.linspace(0, d / V, samples)
        s = V * t
        return TabulatedPulse(t, self.density * V**2 * math.pi * np.maximum(d * s - s * s, 0.0))
