"""Bilinear mixed-mode cohesive law of an interface (delamination growth).

A cohesive interface ties two faces through a traction t [Pa] that depends on their
relative displacement δ [m]: the opening δ_n (normal, mode I; positive when the faces
separate) and the sliding δ_s (tangential, mode II/III). Arrays hold the components on
the last axis: ``(..., 1 + n_shear)``, index 0 the opening, then one (2-D) or two (3-D)
sliding components; the damage state is one scalar per point, shape ``(...)``.

The law (Camanho & Dávila 2002, NASA/TM-2002-211737, "Mixed-mode decohesion finite
elements for the simulation of delamination in composite materials"; the same
formulas as MOOSE's ``BiLinearMixedModeTraction``, idaholab/moose
modules/solid_mechanics/src/materials/cohesive_zone_model/BiLinearMixedModeTraction.C, which implements that report):

- penalty stiffness K [N/m³] until onset, t = K·δ;
- the mixed-mode displacement δ_m = sqrt(<δ_n>² + |δ_s|²), <·> the positive part, and
  the mode mixity B = |δ_s|²/δ_m² (= G_II/(G_I + G_II) under proportional loading with
  one penalty for both modes; B = 1 in closure);
- onset by the quadratic stress criterion (<t_n>/N)² + (t_s/S)² = 1 along the loading
  direction: δ_0 = δ_n0·δ_s0 / sqrt((1 − B)·δ_s0² + B·δ_n0²), δ_n0 = N/K, δ_s0 = S/K;
- propagation by Benzeggagh & Kenane (1996, Compos. Sci. Technol. 56:439–449):
  G_c(B) = G_Ic + (G_IIc − G_Ic)·B^η, reached at δ_f = 2·G_c(B)/(K·δ_0);
- linear softening: damage d = δ_f·(δ_m − δ_0) / (δ_m·(δ_f − δ_0)) clipped to [0, 1],
  irreversible (d never decreases: the state is the largest damage reached);
- traction t_n = (1 − d)·K·<δ_n> + K·(δ_n − <δ_n>) (interpenetration is resisted by the
  undamaged penalty whatever d), t_s = (1 − d)·K·δ_s.

Under proportional loading the energy dissipated per unit area to full decohesion is
½·K·δ_0·δ_f = G_c(B) (:meth:`BilinearCohesive.fracture_energy`), exactly B-K's toughness.

Validity: rate-independent, small relative displacements, one penalty for all modes.
The B-K criterion paired with a quadratic onset of unrelated strengths is not
thermodynamically consistent under a changing mode mixity (Turon et al. 2010 proposed
S = N·sqrt(G_IIc/G_Ic) to make it so; not retrieved here, hence not enforced); the
irreversible damage variable keeps the traction from ever healing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError

__all__ = ["BilinearCohesive", "CohesiveResponse", "ZONE_FACTOR", "ZONE_ELEMENTS", "process_zone_length", "turon_strength"]

ZONE_FACTOR = 9 * math.pi / 32  # M of l_cz = M·E·G_c/τ²: Rice's value, the one Turon et al. 2007 (eq. 12) is built on
ZONE_ELEMENTS = 3  # the fewest node spacings a process zone may span (the floor; Turon et al. recommend more)


def process_zone_length(E: float, G: float, strength: float) -> float:
    """l_cz = M·E·G_c/τ⁰² [m] (M = :data:`ZONE_FACTOR`): the length of the cohesive zone ahead of a crack in a body of
    transverse modulus E [Pa] (Turon, Dávila, Camanho & Costa 2007, Eng. Fract. Mech. 74:1665, as quoted in NASA's
    CompDam_DGD and saullocastro/panels — the paper itself not retrieved; the prefactor is Rice's 9π/32 ≈ 0.88)."""
    return ZONE_FACTOR * E * G / strength**2


def turon_strength(E: float, G: float, size: float, elements: int = ZONE_ELEMENTS) -> float:
    """τ̄ = sqrt(9π·E·G_c/(32·N_e·l_e)) [Pa] (Turon et al. 2007, eq. 12, as quoted second-hand): the interface strength
    whose process zone :func:`process_zone_length` spans ``elements`` N_e node spacings of ``size`` l_e [m] — a
    lowered strength that keeps the fracture energy G_c, so that a coarser mesh resolves the zone."""
    return math.sqrt(9 * math.pi * E * G / (32 * elements * size))


@dataclass(frozen=True)
class CohesiveResponse:
    """Traction [Pa] (..., m), the damage after the step (...) and the consistent tangent ∂t/∂δ [N/m³] (..., m, m)."""

    traction: np.ndarray
    damage: np.ndarray
    tangent: np.ndarray


@dataclass(frozen=True)
class BilinearCohesive:
    """Bilinear mixed-mode cohesive law (module docstring): penalty ``K`` [N/m³], strengths ``N`` (normal)
    and ``S`` (shear) [Pa], toughnesses ``GIc``, ``GIIc`` [J/m²] and the B-K exponent ``eta``."""

    K: float
    N: float
    S: float
    GIc: float
    GIIc: float
    eta: float

    def __post_init__(self):
        for k in ("K", "N", "S", "GIc", "GIIc", "eta"):
            v = getattr(self, k)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise InputError(f"{k} must be positive and finite, got {v!r}", k)
        # Softening needs δ_f > δ_0 in both pure modes: ½·K·δ_0² (the elastic energy at onset) below G_c.
        for mode, strength, G in (("I", self.N, self.GIc), ("II", self.S, self.GIIc)):
            if strength**2 / (2 * self.K) >= G:
                raise InputError(
                    f"mode {mode}: the elastic energy at onset, strength²/(2K) = {strength**2 / (2 * self.K):.4g} J/m², must be below the "
                    f"toughness {G:.4g} J/m²: raise K or lower the strength",
                    "K",
                )

    # -- the law's characteristic quantities --------------------------------------------------------------------
    def mode_mixity(self, opening) -> np.ndarray:
        """B = |δ_s|²/δ_m² (1 in closure or pure sliding, 0 in pure opening; 0 at δ = 0)."""
        d = np.asarray(opening, float)
        dn = np.maximum(d[..., 0], 0.0)
        ds2 = np.sum(d[..., 1:] ** 2, axis=-1)
        dm2 = dn * dn + ds2
        return np.divide(ds2, dm2, out=np.zeros_like(dm2), where=dm2 > 0)

    def toughness(self, B) -> np.ndarray:
        """Benzeggagh–Kenane's mixed-mode toughness G_c(B) = G_Ic + (G_IIc − G_Ic)·B^η [J/m²]."""
        return self.GIc + (self.GIIc - self.GIc) * np.asarray(B, float) ** self.eta

    def onset_displacement(self, B) -> np.ndarray:
        """δ_0(B) [m]: the quadratic stress criterion reached along a proportional path of mixity B."""
        B = np.asarray(B, float)
        dn0, ds0 = self.N / self.K, self.S / self.K
        return dn0 * ds0 / np.sqrt((1 - B) * ds0**2 + B * dn0**2)

    def final_displacement(self, B) -> np.ndarray:
        """δ_f(B) = 2·G_c(B)/(K·δ_0(B)) [m]: where the traction vanishes."""
        return 2 * self.toughness(B) / (self.K * self.onset_displacement(B))

    def fracture_energy(self, B) -> np.ndarray:
        """Energy dissipated per unit area to full decohesion along a proportional path of mixity B [J/m²]:
        the triangle ½·K·δ_0·δ_f under the bilinear law."""
        return 0.5 * self.K * self.onset_displacement(B) * self.final_displacement(B)

    def characteristic_length(self, E: float) -> float:
        """E·G_Ic/N² [m]: the length scale of a mode-I process zone in a body of modulus ``E`` [Pa]. The
        published prefactors (Hillerborg's, Rice's, Turon et al. 2007's M) were not retrieved: this is the
        scale only; a simulation reports the damaged length it resolved (:mod:`softimpact.fem.cohesive_beam`)."""
        return float(E * self.GIc / self.N**2)

    def process_zone(self, E: float) -> float:
        """The shorter of the pure-mode process zones, min(l_cz(G_Ic, N), l_cz(G_IIc, S)) [m], in a body of transverse
        modulus ``E`` (:func:`process_zone_length`): what a mesh must resolve."""
        return min(process_zone_length(E, self.GIc, self.N), process_zone_length(E, self.GIIc, self.S))

    def adjusted(self, E: float, size: float, elements: int = ZONE_ELEMENTS) -> BilinearCohesive:
        """This law with Turon et al.'s engineering strengths for node spacing ``size`` [m]: each pure-mode strength
        lowered to :func:`turon_strength` where it is higher (never raised), toughnesses and penalty kept."""
        from dataclasses import replace

        return replace(self, N=min(self.N, turon_strength(E, self.GIc, size, elements)), S=min(self.S, turon_strength(E, self.GIIc, size, elements)))

    # -- the constitutive update --------------------------------------------------------------------------------
    def initial_damage(self, shape) -> np.ndarray:
        """The undamaged state, shape ``shape``."""
        return np.zeros(shape)

    def traction(self, opening, damage) -> CohesiveResponse:
        """Traction, new damage and consistent tangent at ``opening`` (..., m) from the committed ``damage`` (...).

        The damage returned is max(committed, d(δ)); the tangent includes ∂d/∂δ where the damage grows
        (loading on the softening branch), so Newton converges quadratically on a fixed set of loading points.
        """
        d = np.asarray(opening, float)
        d_old = np.asarray(damage, float)
        K = self.K
        dn = d[..., 0]
        s = d[..., 1:]
        dn_pos = np.maximum(dn, 0.0)
        open_ = dn >= 0  # at δ_n = 0 the faces touch without pressure: the open branch's tangent
        ds2 = np.sum(s * s, axis=-1)
        dm2 = dn_pos**2 + ds2
        dm = np.sqrt(dm2)
        safe_dm = np.where(dm > 0, dm, 1.0)
        B = np.where(dm > 0, ds2 / safe_dm**2, 0.0)

        dn0, ds0 = self.N / K, self.S / K
        q = (1 - B) * ds0**2 + B * dn0**2
        d0 = dn0 * ds0 / np.sqrt(q)
        Gc = self.toughness(B)
        df = 2 * Gc / (K * d0)
        trial = np.where(dm > d0, df * (dm - d0) / (safe_dm * (df - d0)), 0.0)
        trial = np.clip(trial, 0.0, 1.0)
        dmg = np.maximum(d_old, trial)
        growing = (trial > d_old) & (trial < 1.0) & (dm > d0)

        m = d.shape[-1]
        t = np.empty_like(d)
        t[..., 0] = (1 - dmg) * K * dn_pos + K * (dn - dn_pos)
        t[..., 1:] = ((1 - dmg) * K)[..., None] * s

        T = np.zeros(d.shape + (m,))
        diag = np.where(open_, 1 - dmg, 1.0)
        T[..., 0, 0] = K * diag
        for i in range(1, m):
            T[..., i, i] = K * (1 - dmg)

        if np.any(growing):
            # ∂d/∂δ through δ_m and through the mixity B (δ_0 and δ_f depend on B).
            a = np.concatenate([dn_pos[..., None], s], axis=-1)  # the active part of δ
            dd_ddm = df * d0 / (safe_dm**2 * (df - d0))
            dd_dd0 = df * (dm - df) / (safe_dm * (df - d0) ** 2)
            dd_ddf = -d0 * (dm - d0) / (safe_dm * (df - d0) ** 2)
            dd0_dB = -0.5 * d0**3 * (dn0**2 - ds0**2) / (dn0**2 * ds0**2)
            Bpow = np.where(B > 0, B, 1.0) ** (self.eta - 1)
            dGc_dB = np.where(B > 0, (self.GIIc - self.GIc) * self.eta * Bpow, 0.0)
            ddf_dB = 2 * dGc_dB / (K * d0) - df / d0 * dd0_dB
            dd_dB = dd_dd0 * dd0_dB + dd_ddf * ddf_dB
            # δ_m and B as functions of the components (B = |s|²/δ_m²).
            ddm = a / safe_dm[..., None]
            dB = np.empty_like(a)
            dB[..., 0] = -2 * ds2 * dn_pos / safe_dm**4
            dB[..., 1:] = 2 * s * (dn_pos**2 / safe_dm**4)[..., None]
            grad = dd_ddm[..., None] * ddm + dd_dB[..., None] * dB
            grad = np.where(growing[..., None], grad, 0.0)
            T -= K * a[..., :, None] * grad[..., None, :]
        return CohesiveResponse(t, dmg, T)

    def stored_energy(self, opening, damage) -> np.ndarray:
        """Recoverable energy per unit area [J/m²] at ``opening`` with ``damage``: ½(1 − d)K(<δ_n>² + |δ_s|²)
        + ½K(δ_n − <δ_n>)². The energy dissipated by a structure is its external work minus this (and its
        strain energy)."""
        d = np.asarray(opening, float)
        dn_pos = np.maximum(d[..., 0], 0.0)
        act = dn_pos**2 + np.sum(d[..., 1:] ** 2, axis=-1)
        return 0.5 * self.K * ((1 - np.asarray(damage, float)) * act + (d[..., 0] - dn_pos) ** 2)
