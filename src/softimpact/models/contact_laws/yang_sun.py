"""Yang–Sun: Hertz loading, unloading with permanent indentation (Yang & Sun 1982; Tan & Sun 1985)."""

from __future__ import annotations

from dataclasses import dataclass

from ...errors import InputError
from ..protocols import PowerRadiusLaw
from ._common import _positive
from .hertz import HertzLaw

__all__ = ["YangSunState", "YangSunBranch", "YangSunLaw"]


@dataclass(frozen=True)
class YangSunState:
    """Memory of the Yang–Sun law: the largest approach reached so far, α_m [m]."""

    alpha_max: float = 0.0


@dataclass(frozen=True)
class YangSunBranch(PowerRadiusLaw):
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

    source = "Yang & Sun 1982 (ASTM STP 787:425-449); Tan & Sun 1985 (J. Appl. Mech. 52:6-12)"  # where the law comes from (softimpact catalogue); a class attribute, not a field

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
