"""J2 (von Mises) plasticity in plane stress: hardening laws, rate laws and the return mapping.

A plate's layer point carries the in-plane stress σ = (σ_xx, σ_yy, τ_xy) [Pa] and strain
ε = (ε_xx, ε_yy, γ_xy) (engineering shear), σ_zz = 0. With the projector

    P = ⅓ [[2, −1, 0], [−1, 2, 0], [0, 0, 6]],   ½ σᵀPσ = J2 = (σ_xx² + σ_yy² − σ_xx σ_yy)/3 + τ_xy²,

the von Mises stress is σ_vm = sqrt(3 J2) and the yield function Φ = ½ σᵀPσ − ⅓ σ_y(ε̄ᵖ)² ≤ 0, with the
equivalent plastic strain ε̄ᵖ and the hardening curve σ_y(ε̄ᵖ) (:class:`LinearHardening`,
:class:`PowerHardening`). Associative flow ε̇ᵖ = γ̇ P σ, ε̄̇ᵖ = γ̇ sqrt(⅔ σᵀPσ).

The return mapping is the plane-stress-projected closest-point algorithm (Simo & Taylor 1986; as written in
de Souza Neto, Perić & Owen 2008, *Computational Methods for Plasticity*, §9.4.3, Boxes 9.4–9.6, transcribed
from their program HYPLAS, routines SUVMPS and CTVMPS): the elastic trial σ* = Cᵉ(ε − εᵖ_n), its invariants
a1 = (σ*_xx + σ*_yy)², a2 = (σ*_yy − σ*_xx)², a3 = τ*_xy², and the scalar equation in Δγ

    ξ(Δγ) = (a1/6)/(1 + E Δγ/(3(1 − ν)))² + (a2/2 + 2 a3)/(1 + 2 G Δγ)²,
    Φ(Δγ) = ½ ξ(Δγ) − ⅓ σ_y(ε̄ᵖ_n + Δγ sqrt(⅔ ξ(Δγ)))² = 0,

solved by Newton (vectorised over points); then σ = [Cᵉ⁻¹ + Δγ P]⁻¹ Cᵉ⁻¹ σ*, εᵖ = εᵖ_n + Δγ P σ and the
consistent tangent (Box 9.6) D = Ê − α n nᵀ, Ê = [Cᵉ⁻¹ + Δγ P]⁻¹, n = Ê P σ,
α = 1/(σᵀ P n + 2 ξ H/(3 − 2 H Δγ)), H = dσ_y/dε̄ᵖ. The tests check it independently: the elastic limit, the
uniaxial, equibiaxial and pure-shear yield stresses, the consistency Φ = 0 and D against finite differences.

Rate dependence (:class:`CowperSymonds`, :class:`JohnsonCookRate`) multiplies σ_y by a factor R(ε̇) ≥ 1 of the
equivalent strain rate; the plate evaluates it from the previous step's rate (explicitly, so that a step's
return mapping stays rate-independent: an error of order dt in when the rate acts).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError

__all__ = [
    "P",
    "LinearHardening",
    "PowerHardening",
    "CowperSymonds",
    "JohnsonCookRate",
    "J2PlaneStress",
    "ReturnMap",
    "von_mises",
]

P = np.array([[2.0, -1.0, 0.0], [-1.0, 2.0, 0.0], [0.0, 0.0, 6.0]]) / 3.0
NEWTON_RTOL = 1e-12  # the return mapping's scalar equation, relative to ⅓σ_y²
NEWTON_ITERATIONS = 50
SURFACE_RTOL = 1e-8  # a trial this close to the yield surface (relative, in ⅓σ_y² units) lies on it


def _finite_positive(name: str, value) -> None:
    if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
        raise InputError(f"{name} must be a positive finite number, got {value!r}", name)


def _finite_non_negative(name: str, value) -> None:
    if not (isinstance(value, (int, float)) and math.isfinite(value) and value >= 0):
        raise InputError(f"{name} must be a non-negative finite number, got {value!r}", name)


def von_mises(stress: np.ndarray) -> np.ndarray:
    """σ_vm = sqrt(σ_xx² + σ_yy² − σ_xx σ_yy + 3 τ_xy²) [Pa] of plane stresses (..., 3)."""
    s = np.asarray(stress, float)
    return np.sqrt(np.maximum(s[..., 0] ** 2 + s[..., 1] ** 2 - s[..., 0] * s[..., 1] + 3.0 * s[..., 2] ** 2, 0.0))


@dataclass(frozen=True)
class LinearHardening:
    """σ_y(ε̄ᵖ) = σ_y0 + H·ε̄ᵖ [Pa]: initial yield stress ``yield_stress`` σ_y0 and hardening modulus
    ``modulus`` H ≥ 0 (0: perfectly plastic)."""

    yield_stress: float
    modulus: float = 0.0

    def __post_init__(self):
        _finite_positive("yield_stress", self.yield_stress)
        _finite_non_negative("hardening modulus", self.modulus)

    def __call__(self, eps_p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(σ_y, dσ_y/dε̄ᵖ) at ε̄ᵖ (any shape)."""
        e = np.asarray(eps_p, float)
        return self.yield_stress + self.modulus * e, np.full(e.shape, float(self.modulus))

    def describe(self) -> str:
        return f"linear hardening, sigma_y = {self.yield_stress / 1e6:.4g} MPa + {self.modulus / 1e6:.4g} MPa x plastic strain"


@dataclass(frozen=True)
class PowerHardening:
    """σ_y(ε̄ᵖ) = A + B·(ε̄ᵖ)ⁿ [Pa] (the strain term of Johnson & Cook's law); the slope nB(ε̄ᵖ)ⁿ⁻¹ is infinite at
    ε̄ᵖ = 0 for n < 1, so it is evaluated at max(ε̄ᵖ, ``SLOPE_FLOOR``)."""

    A: float
    B: float
    n: float

    SLOPE_FLOOR = 1e-6  # the plastic strain below which the power law's slope is held (n < 1 makes it infinite at 0)

    def __post_init__(self):
        _finite_positive("A", self.A)
        _finite_non_negative("B", self.B)
        if not (math.isfinite(self.n) and 0 < self.n <= 1):
            raise InputError(f"hardening exponent n must lie in (0, 1], got {self.n!r}", "n")

    @property
    def yield_stress(self) -> float:
        return self.A

    def __call__(self, eps_p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        e = np.maximum(np.asarray(eps_p, float), 0.0)
        return self.A + self.B * e**self.n, self.n * self.B * np.maximum(e, self.SLOPE_FLOOR) ** (self.n - 1)

    def describe(self) -> str:
        return f"power hardening, sigma_y = {self.A / 1e6:.4g} + {self.B / 1e6:.4g} x eps_p^{self.n:g} MPa"


@dataclass(frozen=True)
class CowperSymonds:
    """R(ε̇) = 1 + (ε̇/D)^(1/q): the dynamic over the static yield stress (Cowper & Symonds 1957)."""

    D: float
    q: float

    def __post_init__(self):
        _finite_positive("Cowper-Symonds D", self.D)
        _finite_positive("Cowper-Symonds q", self.q)

    def __call__(self, rate: np.ndarray) -> np.ndarray:
        return 1.0 + (np.maximum(np.asarray(rate, float), 0.0) / self.D) ** (1.0 / self.q)


@dataclass(frozen=True)
class JohnsonCookRate:
    """R(ε̇) = 1 + C·ln(ε̇/ε̇0) for ε̇ > ε̇0, else 1 (Johnson & Cook 1983's rate term)."""

    C: float
    reference_rate: float

    def __post_init__(self):
        _finite_non_negative("Johnson-Cook C", self.C)
        _finite_positive("Johnson-Cook reference_rate", self.reference_rate)

    def __call__(self, rate: np.ndarray) -> np.ndarray:
        r = np.maximum(np.asarray(rate, float), self.reference_rate)
        return 1.0 + self.C * np.log(r / self.reference_rate)


@dataclass(frozen=True)
class ReturnMap:
    """The return mapping's result at N points: stress (N, 3) [Pa], plastic strain (N, 3), equivalent plastic
    strain (N,), the consistent tangent (N, 3, 3) [Pa], the plastic multiplier Δγ (N,) (0 where elastic)."""

    stress: np.ndarray
    plastic_strain: np.ndarray
    equivalent_plastic_strain: np.ndarray
    tangent: np.ndarray
    multiplier: np.ndarray


@dataclass(frozen=True)
class J2PlaneStress:
    """Isotropic elastic–plastic plane-stress material: Young's modulus ``E`` [Pa], Poisson's ratio ``nu`` and a
    hardening law (module docstring)."""

    E: float
    nu: float
    hardening: LinearHardening | PowerHardening

    def __post_init__(self):
        _finite_positive("E", self.E)
        if not (-1.0 < self.nu < 0.5):
            raise InputError(f"poisson_ratio must lie in (-1, 0.5), got {self.nu!r}", "poisson_ratio")

    @property
    def elastic(self) -> np.ndarray:
        """Cᵉ (3, 3) [Pa], plane stress, engineering shear."""
        E, nu = self.E, self.nu
        return E / (1 - nu * nu) * np.array([[1.0, nu, 0.0], [nu, 1.0, 0.0], [0.0, 0.0, 0.5 * (1 - nu)]])

    def stress_energy(self, strain: np.ndarray, plastic_strain: np.ndarray) -> np.ndarray:
        """½ (ε − εᵖ)ᵀ Cᵉ (ε − εᵖ) [J/m³] per point."""
        ee = np.asarray(strain, float) - np.asarray(plastic_strain, float)
        return 0.5 * np.einsum("...i,ij,...j->...", ee, self.elastic, ee)

    def return_map(self, strain, plastic_strain, eps_p, rate_factor=1.0, loading=None) -> ReturnMap:
        """The stress of the total strains ``strain`` (N, 3) from the committed ``plastic_strain`` (N, 3) and
        equivalent plastic strain ``eps_p`` (N,), the yield stress scaled by ``rate_factor`` (scalar or (N,)).
        ``loading`` (N,) bool: points that flowed plastically in their last committed increment; where such a point's
        trial lies on the yield surface (a new increment's first iterate, the strain not yet moved) its tangent is
        the continuum elastic–plastic one (Δγ → 0) instead of the elastic: the first Newton iterate of a load or time
        step then follows the flow instead of overshooting it (with perfect plasticity, by far)."""
        E, nu = self.E, self.nu
        G = E / (2 * (1 + nu))
        Ce = self.elastic
        strain = np.asarray(strain, float)
        ep_n = np.asarray(plastic_strain, float)
        a_n = np.asarray(eps_p, float)
        rf = np.broadcast_to(np.asarray(rate_factor, float), a_n.shape)
        trial = (strain - ep_n) @ Ce.T
        a1 = (trial[:, 0] + trial[:, 1]) ** 2
        a2 = (trial[:, 1] - trial[:, 0]) ** 2
        a3 = trial[:, 2] ** 2
        xi_trial = a1 / 6 + a2 / 2 + 2 * a3
        sy_n, _ = self.hardening(a_n)
        sy_n = sy_n * rf
        plastic = 0.5 * xi_trial - sy_n**2 / 3 > NEWTON_RTOL * sy_n**2
        stress = trial.copy()
        ep = ep_n.copy()
        alpha = a_n.copy()
        tangent = np.broadcast_to(Ce, (strain.shape[0], 3, 3)).copy()
        dgamma = np.zeros(a_n.shape)
        if np.any(plastic):
            idx = np.flatnonzero(plastic)
            s, p_strain, alpha_p, D, dg = self._plastic(trial[idx], a1[idx], a2[idx], a3[idx], a_n[idx], rf[idx], ep_n[idx], G)
            stress[idx], ep[idx], alpha[idx], tangent[idx], dgamma[idx] = s, p_strain, alpha_p, D, dg
        if loading is not None:
            on = np.flatnonzero(~plastic & np.asarray(loading, bool) & (0.5 * xi_trial - sy_n**2 / 3 >= -SURFACE_RTOL * sy_n**2))
            if on.size:
                _, H = self.hardening(a_n[on])
                tangent[on] = self._continuum(trial[on], H * rf[on])
        return ReturnMap(stress, ep, alpha, tangent, dgamma)

    def _continuum(self, stress, H):
        """The continuum elastic–plastic tangent Cₑ − (CₑPσ)(CₑPσ)ᵀ/(σᵀPCₑPσ + ⅔ξH) (Box 9.6 at Δγ = 0) at stresses (N, 3) on the
        yield surface, H (N,) the hardening slope."""
        Ce = self.elastic
        n = stress @ (Ce @ P).T
        xi = np.einsum("pi,ij,pj->p", stress, P, stress)
        denom = np.einsum("pi,ij,pj->p", stress, P, n) + 2 * xi * H / 3
        return Ce[None] - (1 / denom)[:, None, None] * n[:, :, None] * n[:, None, :]

    def _plastic(self, trial, a1, a2, a3, a_n, rf, ep_n, G):
        """The closest-point return of the plastic points (module docstring). The scalar equation is solved as
        ψ(Δγ) = sqrt(ξ/2) − σ_y/√3 = 0 (the same root as Φ's; sqrt(ξ) falls as 1/(1 + cΔγ), so Newton on ψ converges in a few
        iterations from far trials, where Φ's quadratic form takes tens), from the deviatoric estimate
        sqrt(ξ*)/(1 + 2GΔγ) = sqrt(⅔)σ_y(ε̄ᵖ_n), clipped to Δγ ≥ 0."""
        E, nu = self.E, self.nu
        c1 = E / (3 * (1 - nu))
        sy0 = self.hardening(a_n)[0] * rf
        xi0 = a1 / 6 + a2 / 2 + 2 * a3
        dg = np.maximum((np.sqrt(xi0) / (math.sqrt(2 / 3) * sy0) - 1) / (2 * G), 0.0)
        for _ in range(NEWTON_ITERATIONS):
            b1, b2 = 1 + c1 * dg, 1 + 2 * G * dg
            xi = a1 / 6 / b1**2 + (a2 / 2 + 2 * a3) / b2**2
            sq = np.sqrt(np.maximum(xi, 1e-300))
            alpha = a_n + dg * math.sqrt(2 / 3) * sq
            sy, H = self.hardening(alpha)
            sy, H = sy * rf, H * rf
            psi = sq / math.sqrt(2) - sy / math.sqrt(3)
            if np.all(np.abs(psi) <= NEWTON_RTOL * sy0):
                break
            dxi = -a1 * c1 / (3 * b1**3) - 2 * G * (a2 + 4 * a3) / b2**3
            dalpha = math.sqrt(2 / 3) * (sq + dg * dxi / (2 * sq))
            dpsi = dxi / (2 * math.sqrt(2) * sq) - H * dalpha / math.sqrt(3)
            dg = np.maximum(dg - psi / dpsi, 0.0)
        else:
            raise RuntimeError(f"J2 plane-stress return mapping did not converge in {NEWTON_ITERATIONS} iterations")
        # σ = A(Δγ) σ*: A*1 on the spherical part, A*2 on the deviatoric part (module docstring)
        A1, A2 = 1 / (1 + c1 * dg), 1 / (1 + 2 * G * dg)
        s = np.empty_like(trial)
        s[:, 0] = 0.5 * (A1 + A2) * trial[:, 0] + 0.5 * (A1 - A2) * trial[:, 1]
        s[:, 1] = 0.5 * (A1 - A2) * trial[:, 0] + 0.5 * (A1 + A2) * trial[:, 1]
        s[:, 2] = A2 * trial[:, 2]
        p_strain = ep_n + dg[:, None] * (s @ P.T)
        # the consistent tangent (Box 9.6)
        E1 = 3 * E / (3 * (1 - nu) + E * dg)
        E2 = 2 * G / (1 + 2 * G * dg)
        Ehat = np.zeros((dg.size, 3, 3))
        Ehat[:, 0, 0] = Ehat[:, 1, 1] = 0.5 * (E1 + E2)
        Ehat[:, 0, 1] = Ehat[:, 1, 0] = 0.5 * (E1 - E2)
        Ehat[:, 2, 2] = 0.5 * E2
        n = np.einsum("pij,jk,pk->pi", Ehat, P, s)
        xi = np.einsum("pi,ij,pj->p", s, P, s)
        denom = np.einsum("pi,ij,pj->p", s, P, n) + 2 * xi * H / (3 - 2 * H * dg)
        D = Ehat - (1 / denom)[:, None, None] * n[:, :, None] * n[:, None, :]
        return s, p_strain, alpha, D, dg
