"""Contact laws between an impactor and a target, eqs (1)–(3).

A contact law maps the approach α [m] (positive when the bodies overlap) to a
compressive force F(α) [N]. It has ``force(alpha)``, ``stiffness(alpha)`` =
dF/dα and ``energy(alpha)`` = ∫F dα; all are zero for α ≤ 0 (no tension).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from .materials import Material

__all__ = ["Hertz", "effective_modulus", "HERTZ_DURATION"]

# Rigid-wall Hertz impact lasts HERTZ_DURATION·α_max/V: (4/5)·B(2/5, 1/2) = 2·∫₀¹(1 − s^(5/2))^(-1/2) ds.
HERTZ_DURATION = 2.9432752


def effective_modulus(a: Material, b: Material) -> float:
    """E* = k1·k2/(k1 + k2), k = E/(1 − ν²), the modulus factor of eq (2) [Pa]."""
    k1, k2 = a.plane_modulus, b.plane_modulus
    return k1 * k2 / (k1 + k2)


@dataclass(frozen=True)
class Hertz:
    """Hertz law F = K·α^n, eq (1), with n = 3/2.

    ``K`` [N/m^1.5]. Build it from geometry with :meth:`sphere_on_flat`
    (eq 3) or :meth:`sphere_on_sphere` (eq 2).
    """

    K: float
    exponent: float = 1.5

    def __post_init__(self):
        if not (math.isfinite(self.K) and self.K > 0):
            raise InputError(f"contact: Hertz constant K must be positive, got {self.K!r}")
        if not self.exponent >= 1.0:
            raise InputError(f"contact: exponent must be >= 1, got {self.exponent!r}")

    @classmethod
    def sphere_on_sphere(cls, r1: float, r2: float, m1: Material, m2: Material) -> Hertz:
        """Eq (2): K = 4/3·sqrt(R1R2/(R1+R2))·k1k2/(k1+k2); radii in m."""
        if r1 <= 0 or r2 <= 0:
            raise InputError(f"contact: radii must be positive, got {r1!r}, {r2!r}")
        radius = r1 * r2 / (r1 + r2)
        return cls(4.0 / 3.0 * math.sqrt(radius) * effective_modulus(m1, m2))

    @classmethod
    def sphere_on_flat(cls, radius: float, sphere: Material, flat: Material) -> Hertz:
        """Eq (3): the flat target, R2 → ∞: K = 4/3·sqrt(R1)·k1k2/(k1+k2)."""
        if radius <= 0:
            raise InputError(f"contact: sphere radius must be positive, got {radius!r}")
        return cls(4.0 / 3.0 * math.sqrt(radius) * effective_modulus(sphere, flat))

    def force(self, alpha):
        """F(α) = K·max(α, 0)^n [N]."""
        if isinstance(alpha, float):  # fast path for the stepping loop
            return self.K * alpha**self.exponent if alpha > 0.0 else 0.0
        return self.K * np.maximum(alpha, 0.0) ** self.exponent

    def stiffness(self, alpha):
        """dF/dα = n·K·max(α, 0)^(n−1) [N/m]."""
        if isinstance(alpha, float):
            return self.exponent * self.K * alpha ** (self.exponent - 1.0) if alpha > 0.0 else 0.0
        return self.exponent * self.K * np.maximum(alpha, 0.0) ** (self.exponent - 1.0)

    def energy(self, alpha):
        """Stored energy ∫0^α F dα = K·α^(n+1)/(n+1) [J]."""
        return self.K * np.maximum(alpha, 0.0) ** (self.exponent + 1.0) / (self.exponent + 1.0)

    def rigid_impact(self, mass: float, velocity: float) -> tuple[float, float, float]:
        """Closed form for a mass hitting a rigid, immovable flat (Hertz 1882).

        Returns (α_max, F_max, duration): α_max = (5mV²/(4K))^(2/5) and
        duration = (4/5)·B(2/5, 1/2)·α_max/V = 2.9433·α_max/V (n = 3/2 only),
        the same as 3.2181·(m/K)^(2/5)·V^(-1/5).
        """
        if self.exponent != 1.5:
            raise ValueError("closed form exists for n = 3/2 only")
        alpha_max = (5.0 * mass * velocity**2 / (4.0 * self.K)) ** 0.4
        return alpha_max, float(self.force(alpha_max)), HERTZ_DURATION * alpha_max / velocity
