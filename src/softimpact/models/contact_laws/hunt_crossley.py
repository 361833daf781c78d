"""Hunt–Crossley: F = K·α^n·(1 + D·α̇) ≥ 0 (Hunt & Crossley 1975; Lankarani & Nikravesh 1990)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from ...errors import InputError
from ..protocols import PowerRadiusLaw
from ._common import _positive

__all__ = ["HuntCrossleyLaw"]


@dataclass(frozen=True)
class HuntCrossleyLaw(PowerRadiusLaw):
    """F = K·α^n·(1 + D·α̇) ≥ 0 with D from the restitution e (module docstring).

    ``form``: ``"lankarani-nikravesh"`` (D = 3(1 − e²)/(4v⁻)) or ``"hunt-crossley"``
    (D = 3(1 − e)/(2v⁻)). ``impact_velocity`` v⁻ > 0 [m/s].
    """

    source = "Hunt & Crossley 1975 (J. Appl. Mech. 42:440-445); Lankarani & Nikravesh 1990 (J. Mech. Des. 112:369-376)"  # where the law comes from (softimpact catalogue); a class attribute, not a field

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
