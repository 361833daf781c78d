"""Plate section of a laminate: A, B, D, transverse shear stiffness and inertias.

First-order shear deformation (Mindlin–Reissner) theory of a laminated plate
(Reddy, *Mechanics of Laminated Composite Plates and Shells*, 2nd ed., §3.4):

    (N, M) = [[A, B], [B, D]]·(ε0, κ),   Q = S·γ,

with ε0 = (u,x, v,y, u,y + v,x), κ = (φx,x, φy,y, φx,y + φy,x) and the transverse
shear strains γ = (γxz, γyz) = (w,x + φx, w,y + φy). x is the 0° fibre direction
(axis 1 of :mod:`softimpact.models.laminate`), z up from the mid-plane, plies top
first. A, B, D come from the plane-stress reduced ply stiffnesses
(:func:`softimpact.models.laminate.abd`).

Transverse shear: S = k·Σ_k C_s,k t_k with the rotated ply shear stiffnesses
C_s = [[C55, C45], [C45, C44]] (Voigt 13 and 23) and the uniform shear
correction factor k = 5/6 (the Reissner/Mindlin value for a homogeneous section).
The ply-wise energy approach would give a slightly different k for a
cross-ply; 5/6 is used so that the plate FE and any FSDT closed form share one
definition.

Inertias per unit area: (I0, I1, I2) = Σ_k ρ_k ∫ (1, z, z²) dz [kg/m², kg/m, kg].
All SI: A [N/m], B [N], D [N·m], S [N/m].
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from .laminate import Stack, abd

__all__ = ["PlateSection", "SHEAR_CORRECTION", "plate_section", "isotropic_section"]

SHEAR_CORRECTION = 5.0 / 6.0  # Reissner's value: parabolic shear stress in a homogeneous section


@dataclass(frozen=True, eq=False)
class PlateSection:
    """Stiffness and inertia of a plate section per unit area (module docstring)."""

    A: np.ndarray  # (3, 3) N/m
    B: np.ndarray  # (3, 3) N
    D: np.ndarray  # (3, 3) N·m
    S: np.ndarray  # (2, 2) N/m, order (γxz, γyz)
    I0: float  # kg/m²
    I1: float  # kg/m
    I2: float  # kg
    thickness: float  # m

    def is_symmetric(self, rtol: float = 1e-10) -> bool:
        """True when bending and stretching decouple: B = 0 and I1 = 0 (to ``rtol``)."""
        scale_b = rtol * np.abs(self.A).max() * self.thickness
        scale_i = rtol * self.I0 * self.thickness
        return bool(np.abs(self.B).max() <= scale_b and abs(self.I1) <= scale_i)

    def mirror_coupling(self, rtol: float = 1e-9) -> dict[str, float]:
        """The section terms that a mirror plane x = const or y = const cannot carry, relative to their scale.

        Reflecting the plate about such a plane maps every ply angle θ to −θ, which changes the
        sign of the shear-extension and bending–twisting terms A16, A26, B16, B26, D16, D26 and of
        the transverse-shear coupling S12. A symmetry edge (a half or quarter model) is exact only
        when they vanish (an orthotropic laminate about the mirror: e.g. cross-ply, or ±θ pairs
        in a balanced symmetric stack still leave D16, D26 ≠ 0). Returns {name: |term| / scale}
        for the terms above ``rtol`` of their matrix's diagonal scale (B's: max|A|·thickness)."""
        a, d, s = np.abs(self.A).max(), np.abs(self.D).max(), np.abs(self.S).max()
        terms = {
            "A16": (self.A[0, 2], a),
            "A26": (self.A[1, 2], a),
            "B16": (self.B[0, 2], a * self.thickness),
            "B26": (self.B[1, 2], a * self.thickness),
            "D16": (self.D[0, 2], d),
            "D26": (self.D[1, 2], d),
            "S12": (self.S[0, 1], s),
        }
        return {name: abs(v) / scale for name, (v, scale) in terms.items() if scale > 0 and abs(v) > rtol * scale}

    def stiffness(self) -> np.ndarray:
        """The 6×6 [[A, B], [B, D]]."""
        return np.block([[self.A, self.B], [self.B, self.D]])


def plate_section(stack: Stack, shear_correction: float = SHEAR_CORRECTION) -> PlateSection:
    """A, B, D, S and the inertias of a stack (plies top first)."""
    if not 0 < shear_correction <= 1:
        raise InputError(f"shear_correction must be in (0, 1], got {shear_correction!r}")
    Cs = stack.ply_stiffnesses()
    t = np.full(len(Cs), stack.ply.thickness)
    A, B, D = abd(Cs, t)
    h = t.sum()
    tops = h / 2 - np.concatenate(([0.0], np.cumsum(t)[:-1]))
    bottoms = tops - t
    S = np.zeros((2, 2))
    I0 = I1 = I2 = 0.0
    rho = stack.ply.density
    for C, zt, zb in zip(Cs, tops, bottoms):
        S += C[np.ix_([4, 3], [4, 3])] * (zt - zb)
        I0 += rho * (zt - zb)
        I1 += rho * (zt**2 - zb**2) / 2
        I2 += rho * (zt**3 - zb**3) / 3
    return PlateSection(A, B, D, shear_correction * S, I0, I1, I2, float(h))


def isotropic_section(
    youngs_modulus: float, poisson_ratio: float, density: float, thickness: float, shear_correction: float = SHEAR_CORRECTION
) -> PlateSection:
    """The section of a homogeneous isotropic plate (a metal skin): A = Q·h, B = 0, D = Q·h³/12 with the plane-stress
    Q = E/(1 − ν²)·[[1, ν, 0], [ν, 1, 0], [0, 0, (1 − ν)/2]], S = k·G·h·I (G = E/(2(1 + ν))), I0 = ρh, I1 = 0, I2 = ρh³/12."""
    for name, v in (("youngs_modulus", youngs_modulus), ("density", density), ("thickness", thickness)):
        if not (np.isfinite(v) and v > 0):
            raise InputError(f"{name} must be a positive finite number, got {v!r}", name)
    if not (-1.0 < poisson_ratio < 0.5):
        raise InputError(f"poisson_ratio must lie in (-1, 0.5), got {poisson_ratio!r}", "poisson_ratio")
    if not 0 < shear_correction <= 1:
        raise InputError(f"shear_correction must be in (0, 1], got {shear_correction!r}")
    E, nu, h = youngs_modulus, poisson_ratio, thickness
    Q = E / (1 - nu * nu) * np.array([[1.0, nu, 0.0], [nu, 1.0, 0.0], [0.0, 0.0, 0.5 * (1 - nu)]])
    G = E / (2 * (1 + nu))
    return PlateSection(Q * h, np.zeros((3, 3)), Q * h**3 / 12, shear_correction * G * h * np.eye(2), density * h, 0.0, density * h**3 / 12, float(h))
