"""Metals for skins and plates: isotropic elastic constants, yield, hardening and (where sourced) strain rate.

Every value is typical, room temperature, read second-hand from the pages named in each entry's ``source``
(ASM / Aluminum Association typical values as reproduced by MatWeb, SubsTech, the Princeton MAE324 glossary
and ASM's MatWeb; FreeCAD's material cards) — not MMPDS design allowables (A/B basis, lower: 2024-T3 sheet's
minimum yield is 269–276 MPa, Alcoa's data sheet as quoted by Wikipedia, against 345 MPa typical). The research
notes behind them are in docs/metals.md.

Hardening: Brar, Joshi & Harris 2009 (AIP Conf. Proc. 1195:945) give Johnson–Cook constants for 7075-T6
(A = 546 MPa, B = 674 MPa, n = 0.72); for the other metals no published hardening law was retrieved, so the
catalogue uses the *engineering estimate* of a linear hardening through the 0.2 % yield stress and the
ultimate strength reached at the elongation at break, H = (σ_u − σ_y)/(e_f − σ_y/E) — derived here, not
published; it understates the early hardening (σ_u is reached at the uniform elongation, before e_f) and
is marked so in ``hardening_source``.

Strain rate: none of the rate laws sought (Johnson–Cook for 2024-T3 and Ti-6Al-4V, Lesuer 2000 and Kay
2003; Cowper–Symonds for mild steel and aluminium) could be read, and Brar 2009's C for 7075-T6 lacks its
reference rate in the retrieved abstract, so every catalogue metal is rate-independent (``rate`` None);
runs say so. A user's metal may carry a :class:`~softimpact.models.plasticity.CowperSymonds` or
:class:`~softimpact.models.plasticity.JohnsonCookRate` law.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import InputError
from .materials import Material
from .plasticity import CowperSymonds, J2PlaneStress, JohnsonCookRate, LinearHardening, PowerHardening

__all__ = ["Metal", "METALS", "metal", "bilinear_hardening"]


def bilinear_hardening(E: float, yield_stress: float, ultimate: float, elongation: float) -> LinearHardening:
    """The linear hardening through (σ_y at ε̄ᵖ = 0) and (σ_u at ε̄ᵖ = e_f − σ_y/E): H = (σ_u − σ_y)/(e_f − σ_y/E)
    (module docstring: an engineering estimate)."""
    plastic = elongation - yield_stress / E
    if not (ultimate >= yield_stress and plastic > 0):
        raise InputError(f"hardening: ultimate strength {ultimate!r} Pa below yield {yield_stress!r} Pa or elongation {elongation!r} within the elastic strain")
    return LinearHardening(yield_stress, (ultimate - yield_stress) / plastic)


@dataclass(frozen=True)
class Metal(Material):
    """An isotropic elastic–plastic metal (J2, :mod:`softimpact.models.plasticity`): the elastic constants of
    :class:`~softimpact.models.materials.Material`, the ``hardening`` law (its initial yield stress σ_y0), the
    ``ultimate`` strength [Pa] and ``elongation`` at break where known, an optional ``rate`` law, and the
    sources of the hardening and rate (``hardening_source``, ``rate_source``)."""

    hardening: LinearHardening | PowerHardening | None = None
    ultimate: float | None = None
    elongation: float | None = None
    rate: CowperSymonds | JohnsonCookRate | None = None
    hardening_source: str = "user input"
    rate_source: str = "none: rate effects not modelled"

    def __post_init__(self):
        super().__post_init__()
        if self.hardening is None:
            raise InputError(f"{self.name}: a metal needs its yield stress (a hardening law)", "yield_stress")
        if self.hardening.yield_stress >= self.youngs_modulus:
            raise InputError(f"{self.name}: yield stress {self.hardening.yield_stress:.4g} Pa is not below Young's modulus {self.youngs_modulus:.4g} Pa")
        for key in ("ultimate", "elongation"):
            v = getattr(self, key)
            if v is not None and not (math.isfinite(v) and v > 0):
                raise InputError(f"{self.name}: {key} must be a positive finite number, got {v!r}", key)

    @property
    def yield_stress(self) -> float:
        """σ_y0 [Pa]: the initial (0.2 % offset) yield stress."""
        return float(self.hardening.yield_stress)

    def plasticity(self) -> J2PlaneStress:
        """The plane-stress J2 model of this metal."""
        return J2PlaneStress(self.youngs_modulus, self.poisson_ratio, self.hardening)


def _typical(name, E, nu, rho, sy, su, ef, source) -> Metal:
    return Metal(
        name,
        E,
        nu,
        rho,
        source,
        hardening=bilinear_hardening(E, sy, su, ef),
        ultimate=su,
        elongation=ef,
        hardening_source="linear through the typical yield and ultimate strengths at the elongation at break: an engineering estimate, not a published law",
    )


METALS = {
    m.name: m
    for m in (
        _typical(
            "Al 2024-T3",
            73e9,
            0.33,
            2780.0,
            345e6,
            485e6,
            0.18,
            "typical values: sigma_y 345 MPa, sigma_u 485 MPa, elongation 18 % in 50 mm (Princeton MAE324 glossary; ASM Metals "
            "Handbook Desk Edition 1995 p. 6-34); E 73 GPa (SubsTech, makeitfrom); density 2780 kg/m^3 (MatWeb, AA typical); "
            "nu 0.33 is 2024-T4's (makeitfrom): 2024-T3's own was not retrieved",
        ),
        Metal(
            "Al 7075-T6",
            71.7e9,
            0.33,
            2810.0,
            "E 71.7 GPa, nu 0.33, elongation 11 % (Wikipedia 7075 infobox); sigma_u 572 MPa, density 2810 kg/m^3 (SubsTech, MatWeb AA typical)",
            hardening=PowerHardening(546e6, 674e6, 0.72),
            ultimate=572e6,
            elongation=0.11,
            hardening_source="Johnson-Cook strain term A = 546 MPa, B = 674 MPa, n = 0.72: Brar, Joshi & Harris 2009, AIP Conf. Proc. 1195:945 (abstract)",
            rate_source="none: Brar 2009's C = 0.059 lacks its reference rate in the retrieved abstract",
        ),
        _typical(
            "Al 6061-T6",
            69e9,
            0.33,
            2700.0,
            276e6,
            310e6,
            0.12,
            "typical values: sigma_y 276 MPa, sigma_u 310 MPa, elongation 12 %, E 69 GPa, density 2700 kg/m^3 (SubsTech); nu 0.33 (Wikipedia 6061 infobox, FreeCAD card)",
        ),
        _typical(
            "steel S355",
            210e9,
            0.3,
            7800.0,
            355e6,
            510e6,
            0.22,
            "EN 10025 S355J2G3 as in FreeCAD's material card (Steel-S355J2G3.FCMat): E 210 GPa, nu 0.3, density 7800 kg/m^3, "
            "sigma_y 355 MPa, sigma_u 510 MPa, ultimate strain 22 %",
        ),
        _typical(
            "Ti-6Al-4V",
            114e9,
            0.33,
            4430.0,
            830e6,
            900e6,
            0.10,
            "Grade 5, annealed bar (ASM/MatWeb MTP644): E 114 GPa, nu 0.33, density 4430 kg/m^3, sigma_y 830 MPa, sigma_u 900 MPa, elongation 10 %",
        ),
    )
}


def metal(name: str, key: str = "material") -> Metal:
    """The catalogue metal ``name`` (case-insensitive), or an :class:`~softimpact.errors.InputError` naming the catalogue."""
    for known, m in METALS.items():
        if known.lower() == str(name).strip().lower():
            return m
    raise InputError(f"{key}: unknown metal {name!r} (catalogue: {', '.join(METALS)})", key)
