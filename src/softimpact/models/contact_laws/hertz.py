"""Hertz's law F = K·α^n and the moduli of its constant (paper eqs 1–3; Sun's form on a laminate)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...errors import InputError
from ..materials import Material
from ..protocols import PowerRadiusLaw
from ._common import _positive

__all__ = ["HERTZ_DURATION", "HertzLaw", "effective_modulus", "laminate_modulus"]

# Rigid-wall Hertz impact lasts HERTZ_DURATION·α_max/V: (4/5)·B(2/5, 1/2) = 2·∫₀¹(1 − s^(5/2))^(-1/2) ds.
HERTZ_DURATION = 2.9432752


def effective_modulus(a: Material, b: Material) -> float:
    """E* = k1·k2/(k1 + k2), k = E/(1 − ν²), the modulus factor of eq (2) [Pa]."""
    k1, k2 = a.plane_modulus, b.plane_modulus
    return k1 * k2 / (k1 + k2)


def laminate_modulus(sphere: Material, transverse_modulus: float) -> float:
    """E* of a sphere on a laminate, 1/E* = (1 − ν_s²)/E_s + 1/E_2 [Pa] (Sun's form)."""
    _positive("transverse modulus E2", transverse_modulus)
    return 1.0 / ((1.0 - sphere.poisson_ratio**2) / sphere.youngs_modulus + 1.0 / transverse_modulus)


@dataclass(frozen=True)
class HertzLaw(PowerRadiusLaw):
    """F = K·α^n, eq (1), n = 3/2; a = sqrt(R·α); K [N/m^n], R the sphere radius [m].

    Build it from geometry with :meth:`sphere_on_flat` (eq 3), :meth:`sphere_on_sphere`
    (eq 2) or :meth:`sphere_on_laminate` (Sun's form). ``force``, ``stiffness`` and
    ``energy`` take a scalar (the stepping loop's fast path) or an array of α.
    """

    source = "Hertz 1882 (paper eqs 1-3); on a laminate Sun 1977 (NASA CR-1977) and Tan & Sun 1985 (J. Appl. Mech. 52:6-12)"  # where the law comes from (softimpact catalogue); a class attribute, not a field

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
