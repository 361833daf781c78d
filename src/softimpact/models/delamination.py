"""Delamination onset under transverse load: closed-form thresholds of a laminated plate, and the LEFM
closed forms of the delamination specimens the cohesive model is verified against.

Plate thresholds (SI: forces in N, bending stiffnesses D in N·m, toughness G_IIc in J/m²):

- Effective bending stiffness of an orthotropic plate (Olsson's D*, as given to the project; Olsson's text
  was not retrieved here, so the form is **unverified against the source**):
  D* = sqrt(D11·D22·(A + 1)/2), A = (D12 + 2·D66)/sqrt(D11·D22). For an isotropic plate A = 1 and D* = D.
  D16 and D26 are ignored (a specially orthotropic plate).
- :func:`olsson_threshold` — Olsson's quasi-static delamination threshold F_d = π·sqrt(32·D*·G_IIc/9), as
  given to the project (source text not retrieved: **unverified**). Validity as stated for threshold loads of
  this family: a thin plate (Kirchhoff), small deflections (no membrane stiffening), the load spread over a
  region small against the plate, mode II growth of a circular delamination, a quasi-static response
  (large-mass impact).
- :func:`suemasu_threshold` — n delaminations of equal radius, equally spaced through the thickness, grown
  together under a central point load (the idealisation of Suemasu & Majima 1998, J. Compos. Mater.
  32(2), whose abstract was retrieved; their formula was not: **unverified**): F_dn = π·sqrt(32·D·G_IIc/(n + 2)).
  The form follows from Davies & Zhang's own assumption: inside the delaminated radius the n + 1
  sublaminates bend separately, with a bending stiffness D_in = D/(n + 1)² in all, under the radial moment
  M = P/(4π) (the part of a point load's moment that does not depend on the radius); the energy released
  per unit area of the n interfaces is G = M²·(1/D_in − 1/D)/(2n) = P²·(n + 2)/(32·π²·D). n = 1 is Davies &
  Zhang's threshold exactly. (The exact two-region axisymmetric plate gives a G that varies with the radius
  through the logarithm of a point load's moment: the closed forms are the constant-moment idealisation.)
- :func:`davies_zhang_threshold` — Davies & Zhang (1995): P_c = π·sqrt(8·E·h³·G_IIc/(9·(1 − ν²))) for an
  isotropic (quasi-isotropic) plate, i.e. π·sqrt(32·D·G_IIc/3) with D = E·h³/(12(1 − ν²)): Suemasu's n = 1.
  Hence Davies–Zhang / Olsson = sqrt(3) for an isotropic plate, exactly.

Missing (not retrieved, hence not implemented — a constant is never guessed): Olsson's dynamic threshold
for small-mass impact and its factor over the quasi-static one; the bounds of Olsson's response-regime
classification on the impactor-to-plate mass ratio ("wave-controlled", "intermediate", "quasi-static").
:func:`response_regime` takes the bounds as arguments until they are retrieved.

Specimen closed forms (linear elastic fracture mechanics of Euler–Bernoulli arms of thickness h, width b,
modulus E, I = b·h³/12; derived by Irwin–Kies, G = P²/(2b)·dC/da, from the beam compliances):

- DCB (mode I), arms on the interface's penalty K as a Winkler foundation of modulus k = 2·K·b (the opening
  is twice an arm's deflection), λ⁴ = k/(4·E·I) — the semi-infinite beam on an elastic foundation
  (Hetényi) under the crack-tip shear P and moment P·a, as in Kanninen's augmented DCB (1973, not
  retrieved; re-derived here): opening δ = P·(2a³/(3EI))·[1 + 3/(λa) + 3/(λa)² + 3/(2(λa)³)],
  G_I = P²·(a + 1/λ)²/(b·E·I). The crack-length correction 1/λ is this model's corrected-beam-theory Δ
  (the measured Δ of ASTM D5528 also holds shear and root rotation, which Euler–Bernoulli arms lack).
  Critical load P_c = sqrt(b·E·I·G_Ic)/(a + 1/λ); the propagation branch P = sqrt(2·(b·E·I·G_Ic)^(3/2)/(3·E·I·δ))
  (simple beam theory) does not depend on a.
- ENF (mode II), span 2L, centre load: C = (3a³ + 2L³)/(8·E·b·h³), G_II = 9·P²·a²/(16·b²·E·h³). Under
  displacement control the growth is stable where dG/da < 0 at fixed δ: a³ > L³/3, a/L > 0.693 (the "a/L ≥
  0.7" of the ENF literature).
- MMB (Reeder & Crews 1990 lever, lever arm c, half-span L): the loads split into P_I = P·(3c − L)/(4L)
  (DCB-like) and P_II = P·(c + L)/L (ENF-like), G_I = P_I²·(a + 1/λ)²/(b·E·I), G_II = 9·P_II²·a²/(16·b²·E·h³).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError

__all__ = [
    "effective_bending_stiffness",
    "olsson_threshold",
    "suemasu_threshold",
    "davies_zhang_threshold",
    "isotropic_bending_stiffness",
    "response_regime",
    "REGIMES",
    "REGIME_BOUNDS",
    "REGIME_BOUNDS_NOTE",
    "CRITERIA",
    "criterion_validity",
    "OnsetThresholds",
    "onset_thresholds",
    "DCB",
    "ENF",
    "MMB",
]


def _positive(name: str, v) -> float:
    if not (isinstance(v, (int, float, np.floating)) and math.isfinite(v) and v > 0):
        raise InputError(f"{name} must be positive and finite, got {v!r}", name)
    return float(v)


def isotropic_bending_stiffness(E: float, nu: float, thickness: float) -> float:
    """D = E·h³/(12·(1 − ν²)) [N·m]."""
    return _positive("E", E) * _positive("thickness", thickness) ** 3 / (12 * (1 - nu**2))


def effective_bending_stiffness(D) -> float:
    """Olsson's D* = sqrt(D11·D22·(A + 1)/2), A = (D12 + 2·D66)/sqrt(D11·D22) [N·m] of a (3, 3) bending
    stiffness matrix D (order x, y, xy, as :class:`softimpact.models.plate_laminate.PlateSection` ``.D``)."""
    D = np.asarray(D, float)
    if D.shape != (3, 3):
        raise InputError(f"D must be a (3, 3) bending stiffness matrix, got shape {D.shape}", "D")
    D11, D22, D12, D66 = D[0, 0], D[1, 1], D[0, 1], D[2, 2]
    if D11 <= 0 or D22 <= 0:
        raise InputError(f"D11 and D22 must be positive, got {D11!r} and {D22!r}", "D")
    A = (D12 + 2 * D66) / math.sqrt(D11 * D22)
    return float(math.sqrt(D11 * D22 * (A + 1) / 2))


def olsson_threshold(D_star: float, GIIc: float) -> float:
    """Olsson's quasi-static delamination threshold F_d = π·sqrt(32·D*·G_IIc/9) [N] (module docstring: unverified)."""
    return math.pi * math.sqrt(32 * _positive("D_star", D_star) * _positive("GIIc", GIIc) / 9)


def suemasu_threshold(D: float, GIIc: float, n: int = 1) -> float:
    """Threshold of ``n`` equal, equally spaced delaminations grown together: π·sqrt(32·D·G_IIc/(n + 2)) [N]."""
    if not (isinstance(n, (int, np.integer)) and n >= 1):
        raise InputError(f"n must be a positive integer, got {n!r}", "n")
    return math.pi * math.sqrt(32 * _positive("D", D) * _positive("GIIc", GIIc) / (n + 2))


def davies_zhang_threshold(E: float, nu: float, thickness: float, GIIc: float) -> float:
    """Davies & Zhang (1995): π·sqrt(8·E·h³·G_IIc/(9·(1 − ν²))) [N]."""
    return math.pi * math.sqrt(8 * _positive("E", E) * _positive("thickness", thickness) ** 3 * _positive("GIIc", GIIc) / (9 * (1 - nu**2)))


@dataclass(frozen=True)
class OnsetThresholds:
    """The onset thresholds of a laminate: Olsson's D* [N·m] and F_d [N], and Suemasu's F_dn [N] for
    n = 1, 2, … (``suemasu[0]`` is n = 1, with D* for D: Davies–Zhang's form for an orthotropic plate)."""

    D_star: float
    olsson: float
    suemasu: tuple[float, ...]


def onset_thresholds(stack, GIIc: float, *, n_max: int = 3) -> OnsetThresholds:
    """Thresholds of a :class:`softimpact.models.laminate.Stack` from its bending stiffnesses (the D of
    :func:`softimpact.models.plate_laminate.plate_section`) and the mode-II toughness ``GIIc`` [J/m²]."""
    from .plate_laminate import plate_section

    D_star = effective_bending_stiffness(plate_section(stack).D)
    return OnsetThresholds(D_star, olsson_threshold(D_star, GIIc), tuple(suemasu_threshold(D_star, GIIc, n) for n in range(1, n_max + 1)))


REGIMES = ("wave-controlled", "intermediate", "quasi-static")

# Olsson's bounds on M_i/M_p were not retrieved (module docstring): these stand-ins are this project's choice,
# NOT Olsson's. 1/4 is the mass ratio at which the impactor weighs as much as a simply supported plate's
# fundamental mode at its centre (modal mass ρh·∫∫sin²(πx/a)·sin²(πy/b) dx dy = M_p/4, derived here): a lighter
# impactor is stopped before the plate's global mode takes up the load (wave-controlled); above ten times that
# ratio the mode's inertia is under a tenth of the impactor's and the plate responds as a spring (quasi-static).
REGIME_BOUNDS = (0.25, 2.5)
REGIME_BOUNDS_NOTE = (
    "Olsson's mass-ratio bounds not retrieved; stand-in bounds M_i/M_p < 0.25 wave-controlled, > 2.5 quasi-static "
    "(0.25: impactor mass equal to a simply supported plate's fundamental modal mass M_p/4; 2.5: ten times it), "
    "this project's choice, not Olsson's"
)


def response_regime(impactor_mass: float, plate_mass: float, *, wave_below: float, quasi_static_above: float) -> str:
    """Olsson's classification of an impact response by the impactor-to-plate mass ratio M_i/M_p: below
    ``wave_below`` "wave-controlled", above ``quasi_static_above`` "quasi-static", else "intermediate".

    Olsson's bounds (and his definition of the plate mass) were not retrieved: they are arguments, to be
    given from the source (module docstring); the damage outputs of an impact use :data:`REGIME_BOUNDS`,
    this project's stand-ins (:data:`REGIME_BOUNDS_NOTE`)."""
    lo, hi = _positive("wave_below", wave_below), _positive("quasi_static_above", quasi_static_above)
    if not lo < hi:
        raise InputError(f"wave_below must be below quasi_static_above, got {lo!r} and {hi!r}", "wave_below")
    r = _positive("impactor_mass", impactor_mass) / _positive("plate_mass", plate_mass)
    return REGIMES[0] if r < lo else REGIMES[2] if r > hi else REGIMES[1]


# Which delamination criterion applies where (docs/delamination.md, "Which criterion where"): by the name the maps and
# damage outputs give it, (what it is, the response regimes its derivation holds in, why).
CRITERIA = {
    "olsson": (
        "Olsson's F_d",
        ("quasi-static",),
        "a quasi-static threshold: derived for a plate bending under a slowly applied point load (large-mass impact)",
    ),
    "delamination": (
        "Davies-Zhang's P_c",
        ("quasi-static",),
        "a quasi-static threshold: derived for a static point load on a plate, the moment P/(4 pi) at the delamination front",
    ),
    "interlaminar_index": (
        "the interlaminar index",
        REGIMES,
        "the run's own interlaminar shear against the ply's shear strengths, at every instant: no response regime assumed",
    ),
}


def criterion_validity(regime: str, criteria):
    """A ``criterion_outside_regime`` flag when one of ``criteria`` (keys of :data:`CRITERIA`) was derived for a response
    regime other than the impact's ``regime`` (:func:`response_regime`): Olsson's and Davies–Zhang's thresholds are
    quasi-static, so on a wave-controlled or intermediate impact their ratio is reported but not a verdict (the
    interlaminar index, computed from the run's own stresses, applies in every regime). Nothing for an unknown regime."""
    from .validity import Validity

    outside = [c for c in criteria if c in CRITERIA and regime in REGIMES and regime not in CRITERIA[c][1]]
    if not outside:
        return Validity({})
    names = " and ".join(CRITERIA[c][0] for c in outside)
    return Validity(
        {},
        (
            f"{names}: {'a quasi-static threshold' if len(outside) == 1 else 'quasi-static thresholds'} applied to {'an' if regime[:1] in 'aeiou' else 'a'} {regime} impact, outside the regime "
            f"{'it was' if len(outside) == 1 else 'they were'} derived for (the regime by M_i/M_p, stand-in bounds): "
            "a ratio to read, not a verdict; the interlaminar index and the run's own stresses apply in every regime",
        ),
        ("criterion_outside_regime",),
    )


@dataclass(frozen=True)
class DCB:
    """LEFM of the double cantilever beam (module docstring): arms of modulus ``E``, thickness ``h`` (each) and
    width ``b``; ``K`` the interface penalty [N/m³] of the Winkler correction (``inf``: simple beam theory)."""

    E: float
    h: float
    b: float
    K: float = math.inf

    @property
    def EI(self) -> float:
        """An arm's bending stiffness E·b·h³/12 [N·m²]."""
        return self.E * self.b * self.h**3 / 12

    @property
    def correction(self) -> float:
        """1/λ [m], λ⁴ = 2·K·b/(4·E·I); 0 for a rigid interface."""
        return 0.0 if math.isinf(self.K) else (4 * self.EI / (2 * self.K * self.b)) ** 0.25

    def compliance(self, a):
        """Opening per unit pull [m/N] at crack length a [m]."""
        a = np.asarray(a, float)
        if math.isinf(self.K):
            return 2 * a**3 / (3 * self.EI)
        la = a / self.correction
        return 2 * a**3 / (3 * self.EI) * (1 + 3 / la + 3 / la**2 + 1.5 / la**3)

    def energy_release_rate(self, P, a):
        """G_I = P²·(a + 1/λ)²/(b·E·I) [J/m²]."""
        return np.asarray(P, float) ** 2 * (np.asarray(a, float) + self.correction) ** 2 / (self.b * self.EI)

    def critical_load(self, a, GIc: float):
        """P_c = sqrt(b·E·I·G_Ic)/(a + 1/λ) [N]."""
        return math.sqrt(self.b * self.EI * GIc) / (np.asarray(a, float) + self.correction)

    def propagation_load(self, opening, GIc: float):
        """The propagation branch of simple beam theory, P(δ) = sqrt(2·(b·E·I·G_Ic)^(3/2)/(3·E·I·δ)) [N]."""
        return np.sqrt(2 * (self.b * self.EI * GIc) ** 1.5 / (3 * self.EI * np.asarray(opening, float)))


@dataclass(frozen=True)
class ENF:
    """LEFM of the end-notched flexure (module docstring): arms ``E``, ``h`` (each), width ``b``, half-span ``L``."""

    E: float
    h: float
    b: float
    L: float

    def compliance(self, a):
        """Load-point compliance [m/N], C = (3a³ + 2L³)/(8·E·b·h³)."""
        a = np.asarray(a, float)
        return (3 * a**3 + 2 * self.L**3) / (8 * self.E * self.b * self.h**3)

    def energy_release_rate(self, P, a):
        """G_II = 9·P²·a²/(16·b²·E·h³) [J/m²]."""
        return 9 * np.asarray(P, float) ** 2 * np.asarray(a, float) ** 2 / (16 * self.b**2 * self.E * self.h**3)

    def critical_load(self, a, GIIc: float):
        """P_c = (4·b·h/(3a))·sqrt(E·h·G_IIc) [N]."""
        return 4 * self.b * self.h / (3 * np.asarray(a, float)) * math.sqrt(self.E * self.h * GIIc)

    def stable(self, a) -> bool:
        """Stable growth under displacement control: a³ > L³/3."""
        return bool(np.all(np.asarray(a, float) ** 3 > self.L**3 / 3))


@dataclass(frozen=True)
class MMB:
    """LEFM of Reeder & Crews' mixed-mode bending (module docstring): lever arm ``c``; the mode-I part carries the
    DCB's Winkler correction of penalty ``K``."""

    E: float
    h: float
    b: float
    L: float
    c: float
    K: float = math.inf

    @property
    def parts(self) -> tuple[float, float]:
        """(P_I/P, P_II/P) = ((3c − L)/(4L), (c + L)/L)."""
        return (3 * self.c - self.L) / (4 * self.L), (self.c + self.L) / self.L

    def energy_release_rates(self, P, a):
        """(G_I, G_II) [J/m²]."""
        pI, pII = self.parts
        P = np.asarray(P, float)
        dcb = DCB(self.E, self.h, self.b, self.K)
        enf = ENF(self.E, self.h, self.b, self.L)
        return dcb.energy_release_rate(pI * P, a), enf.energy_release_rate(pII * P, a)

    def mode_mixity(self, a=None) -> float:
        """G_II/(G_I + G_II) (at crack length ``a``; independent of it for a rigid interface)."""
        a = 1.0 if a is None else a
        GI, GII = self.energy_release_rates(1.0, a)
        return float(GII / (GI + GII))

    def compliance(self, a):
        """Lever load-point compliance [m/N]: (P_I/P)²·C_DCB + (P_II/P)²·C_ENF."""
        pI, pII = self.parts
        return pI**2 * DCB(self.E, self.h, self.b, self.K).compliance(a) + pII**2 * ENF(self.E, self.h, self.b, self.L).compliance(a)

    def critical_load(self, a, Gc: float):
        """The lever load at which G_I + G_II = ``Gc`` [N]."""
        GI, GII = self.energy_release_rates(1.0, a)
        return np.sqrt(Gc / (GI + GII))
