"""Damage screening of laminates: ply stresses by classical lamination theory,
first-ply failure indices and the Davies–Zhang delamination threshold.

Axes as in :mod:`softimpact.models.laminate`: x along the beam, y across the
width, z up from the mid-plane; ply material axes 1 (fibre), 2, 3. In-plane
order (x, y, xy) / (1, 2, 12), engineering shear strains. Stresses in Pa.

Every index is scaled so that 1 is failure by its criterion, and (except
Hashin's quadratic modes, for which the square root is taken) it grows in
proportion to the load: the threshold velocity is where it first reaches 1.

- maximum strain: max over ε1, ε2, γ12 of the strain over its allowable
  (allowables X/E1, Y/E2, S/G12);
- Tsai–Wu (1971): 1/R with R the strength ratio solving
  a·R² + b·R = 1, a = F11σ1² + F22σ2² + F66τ² + 2F12σ1σ2, b = F1σ1 + F2σ2,
  F12 = −½·sqrt(F11·F22);
- Hashin (1980, plane stress): the largest of the fibre and matrix modes,
  square-rooted;
- Davies–Zhang (1995): delamination starts at the force
  P_c = π·sqrt(8·E·h³·G_IIc / (9·(1 − ν²))) [N] for a quasi-isotropic plate of
  thickness h; the index is F/P_c.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from .laminate import PLIES, STRENGTH_KEYS, PlyStrength, ply_stiffness, reduced_stiffness

__all__ = [
    "CRITERIA",
    "PlyStrength",
    "STRENGTHS",
    "strength_of",
    "ply_stresses",
    "failure_indices",
    "HASHIN_MODES",
    "hashin_modes",
    "PLY_DISCOUNT_RETAINED",
    "discounted_abd",
    "davies_zhang_force",
    "InterlaminarShear",
    "interlaminar_shear",
]

CRITERIA = ("max_strain", "tsai_wu", "hashin")


# Catalogue strengths by ply name (the catalogue plies carry them: ``PLIES[name].strength``).
STRENGTHS = {name: p.strength for name, p in PLIES.items() if p.strength is not None}


def strength_of(ply, where: str = "ply") -> PlyStrength:
    """The strengths a damage output needs from ``ply``; an InputError naming the missing keys
    (``where``: the ply's key in the case) when the ply has none (an inline ply without them)."""
    if ply.strength is None:
        raise InputError(
            f"{where}: damage outputs need the ply's strengths; ply {ply.name!r} has none: give {', '.join(STRENGTH_KEYS)} "
            f"(stresses with units, G_IIc in J/m^2) in its table, or use a catalogue ply ({', '.join(STRENGTHS)})"
        )
    return ply.strength


def ply_stresses(ply, angles, midplane_strain, curvature, z) -> tuple[np.ndarray, np.ndarray]:
    """Material-axis strains and stresses at heights ``z`` [m] of a laminate.

    ``midplane_strain`` (ε_x0, ε_y0, γ_xy0) and ``curvature`` (κ_x, κ_y, κ_xy),
    each shape (3,) or (3, n) for n instants; ``angles[k]`` is the fibre angle [°]
    of the ply holding height ``z[k]``. CLT kinematics ε(z) = ε0 + z·κ and plane
    stress in each ply: σ_12 = Q·ε_12 with Q the ply's reduced stiffness.
    Returns (strain, stress), each shape (len(z), 3) or (len(z), 3, n).
    """
    e0, k = np.asarray(midplane_strain, float), np.asarray(curvature, float)
    z = np.atleast_1d(np.asarray(z, float))
    angles = np.asarray(angles, float)
    Q = reduced_stiffness(ply_stiffness(ply))
    zs = z.reshape((-1,) + (1,) * e0.ndim)
    eps = e0[None] + zs * k[None]  # (nz, 3[, n]) laminate strains
    strain = np.empty_like(eps)
    for a in np.unique(angles):
        t = math.radians(a)
        c, s = math.cos(t), math.sin(t)
        # Engineering strain transformation, laminate (x, y, xy) → ply (1, 2, 12).
        Te = np.array([[c * c, s * s, c * s], [s * s, c * c, -c * s], [-2 * c * s, 2 * c * s, c * c - s * s]])
        m = angles == a
        strain[m] = np.einsum("ij,kj...->ki...", Te, eps[m])
    stress = np.einsum("ij,kj...->ki...", Q, strain)
    return strain, stress


def failure_indices(ply, strength: PlyStrength, strain: np.ndarray, stress: np.ndarray) -> dict[str, np.ndarray]:
    """Indices of :data:`CRITERIA` from ply strains and stresses of shape (..., 3, ...) with
    (1, 2, 12) on axis ``-2`` if 3-D or axis 0 otherwise (as :func:`ply_stresses` returns them)."""
    ax = 1 if stress.ndim >= 2 else 0
    s1, s2, s6 = np.take(stress, 0, ax), np.take(stress, 1, ax), np.take(stress, 2, ax)
    e1, e2, e6 = np.take(strain, 0, ax), np.take(strain, 1, ax), np.take(strain, 2, ax)
    X = strength
    Q = reduced_stiffness(ply_stiffness(ply))
    # Allowable strains of the unidirectional ply loaded along one axis: X/E1, Y/E2, S/G12.
    E1, E2 = 1 / np.linalg.inv(Q)[0, 0], 1 / np.linalg.inv(Q)[1, 1]
    max_strain = np.maximum.reduce(
        [
            np.where(e1 >= 0, e1 / (X.Xt / E1), -e1 / (X.Xc / E1)),
            np.where(e2 >= 0, e2 / (X.Yt / E2), -e2 / (X.Yc / E2)),
            np.abs(e6) / (X.S12 / Q[2, 2]),
        ]
    )
    F1, F2 = 1 / X.Xt - 1 / X.Xc, 1 / X.Yt - 1 / X.Yc
    F11, F22, F66 = 1 / (X.Xt * X.Xc), 1 / (X.Yt * X.Yc), 1 / X.S12**2
    F12 = -0.5 * math.sqrt(F11 * F22)
    a = F11 * s1**2 + F22 * s2**2 + F66 * s6**2 + 2 * F12 * s1 * s2
    b = F1 * s1 + F2 * s2
    # 1/R where a·R² + b·R − 1 = 0, R > 0: 1/R = (b + sqrt(b² + 4a))/2 (no division by a = 0).
    tsai_wu = 0.5 * (b + np.sqrt(b * b + 4 * a))
    fibre = np.where(s1 >= 0, (s1 / X.Xt) ** 2 + (s6 / X.S12) ** 2, (s1 / X.Xc) ** 2)
    matrix = np.where(
        s2 >= 0,
        (s2 / X.Yt) ** 2 + (s6 / X.S12) ** 2,
        (s2 / (2 * X.S23)) ** 2 + ((X.Yc / (2 * X.S23)) ** 2 - 1) * s2 / X.Yc + (s6 / X.S12) ** 2,
    )
    hashin = np.sqrt(np.maximum(np.maximum(fibre, matrix), 0.0))
    return {"max_strain": max_strain, "tsai_wu": tsai_wu, "hashin": hashin}


HASHIN_MODES = ("fibre_tension", "fibre_compression", "matrix_tension", "matrix_compression")


def hashin_modes(strength: PlyStrength, stress: np.ndarray) -> dict[str, np.ndarray]:
    """Hashin's (1980, plane stress) four modes separately, square-rooted as :func:`failure_indices`' ``hashin`` (their
    largest): a mode is 0 where its sign condition does not hold (fibre: σ1 ≥ 0 tension, σ1 < 0 compression; matrix:
    σ2 ≥ 0 tension, σ2 < 0 compression). ``stress`` as :func:`failure_indices` takes it."""
    ax = 1 if stress.ndim >= 2 else 0
    s1, s2, s6 = np.take(stress, 0, ax), np.take(stress, 1, ax), np.take(stress, 2, ax)
    X = strength

    def root(v):
        return np.sqrt(np.maximum(v, 0.0))

    matrix_c = (s2 / (2 * X.S23)) ** 2 + ((X.Yc / (2 * X.S23)) ** 2 - 1) * s2 / X.Yc + (s6 / X.S12) ** 2
    return {
        "fibre_tension": np.where(s1 >= 0, root((s1 / X.Xt) ** 2 + (s6 / X.S12) ** 2), 0.0),
        "fibre_compression": np.where(s1 < 0, np.abs(s1) / X.Xc, 0.0),
        "matrix_tension": np.where(s2 >= 0, root((s2 / X.Yt) ** 2 + (s6 / X.S12) ** 2), 0.0),
        "matrix_compression": np.where(s2 < 0, root(matrix_c), 0.0),
    }


PLY_DISCOUNT_RETAINED = 1e-6  # the fraction of a discounted modulus kept (0 would leave a singular stiffness)


def _discounted_q(ply, mode: str | None, retained: float) -> np.ndarray:
    """Plane-stress Q (1, 2, 12) of a ply after the discount of ``mode``: none intact; a matrix mode keeps the
    fibre (E2, G12 × ``retained``, ν21 = ν12·E2/E1 following); a fibre mode discounts the whole ply (E1, E2, G12)."""
    E1, E2, G12, nu12 = ply.E1, ply.E2, ply.G12, ply.nu12
    if mode in ("matrix_tension", "matrix_compression"):
        E2, G12 = retained * E2, retained * G12
    elif mode in ("fibre_tension", "fibre_compression"):
        E1, E2, G12 = retained * E1, retained * E2, retained * G12
    elif mode is not None:
        raise InputError(f"unknown Hashin mode {mode!r}: one of {', '.join(HASHIN_MODES)}", "mode")
    nu21 = nu12 * E2 / E1 if E1 > 0 else 0.0  # retained 0: a removed ply
    d = 1 - nu12 * nu21
    return np.array([[E1 / d, nu12 * E2 / d, 0.0], [nu12 * E2 / d, E2 / d, 0.0], [0.0, 0.0, G12]])


def discounted_abd(stack, failed: dict, retained: float = PLY_DISCOUNT_RETAINED) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A, B, D (per unit width, plies top first, z up) of ``stack`` with the plies of ``failed`` (ply number, 1 = top →
    its Hashin mode, :data:`HASHIN_MODES`) discounted by mode: a ply-discount model chosen here (no source retrieved):
    a matrix failure keeps only the fibre's stiffness (E2 and G12 × ``retained``), a fibre failure removes the ply
    (E1, E2 and G12 × ``retained``). Each ply's Q is the plane-stress one of its engineering constants, turned to the
    laminate's axes by Q̄ = Tᵀ·Q·T with T the engineering strain transformation of :func:`ply_stresses`."""
    t, n = stack.ply.thickness, len(stack.angles)
    h = n * t
    A, B, D = np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((3, 3))
    for k, angle in enumerate(stack.angles):
        c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
        T = np.array([[c * c, s * s, c * s], [s * s, c * c, -c * s], [-2 * c * s, 2 * c * s, c * c - s * s]])
        Qbar = T.T @ _discounted_q(stack.ply, failed.get(k + 1), retained) @ T
        zt = h / 2 - k * t
        zb = zt - t
        A += Qbar * (zt - zb)
        B += Qbar * (zt**2 - zb**2) / 2
        D += Qbar * (zt**3 - zb**3) / 3
    return A, B, D


def davies_zhang_force(E: float, nu: float, thickness: float, GIIc: float) -> float:
    """Delamination threshold force [N], Davies & Zhang (1995): π·sqrt(8·E·h³·G_IIc/(9(1 − ν²)))."""
    return math.pi * math.sqrt(8 * E * thickness**3 * GIIc / (9 * (1 - nu**2)))


@dataclass(frozen=True)
class InterlaminarShear:
    """Interlaminar shear stresses at the ply interfaces per unit transverse shear resultant.

    ``z`` (n_interfaces,) heights [m] of the interior interfaces (top first); ``tau_xz``,
    ``tau_yz`` (n_interfaces,) [Pa per N/m] in the axes of the resultant (x along it); ``index``
    (n_interfaces,) [per N/m] the quadratic delamination-onset index of each interface
    sqrt((τ13/S13)² + (τ23/S23)²), the worse of the two plies that meet there, with S13 = S12
    (transversely isotropic ply). Everything is linear in the resultant q [N/m]: multiply by |q|.
    """

    z: np.ndarray
    tau_xz: np.ndarray
    tau_yz: np.ndarray
    index: np.ndarray


def interlaminar_shear(ply, angles, strength: PlyStrength, direction: float = 0.0) -> InterlaminarShear:
    """Interlaminar shear recovered from the equilibrium equations through the thickness.

    A transverse shear resultant Q_x = dM_x/dx (x at ``direction`` [°] from the laminate's x,
    ``angles`` top ply first) with the in-plane forces constant: by CLT
    d(ε0, κ)/dx = (ABD)⁻¹·(0, 0, 0, Q_x, 0, 0), so in ply k dσ/dx = Q̄_k·(dε0/dx + z·dκ/dx), and
    integrating ∂σ_x/∂x + ∂τ_xz/∂z = 0 and ∂τ_xy/∂x + ∂τ_yz/∂z = 0 up from the free bottom face
    (τ = 0 at z = −h/2):

        τ_xz(z) = −∫_{−h/2}^{z} dσ_x/dx dζ,   τ_yz(z) = −∫_{−h/2}^{z} dτ_xy/dx dζ.

    For one orthotropic ply angle this is Jourawski's 3Q/(2h) at the mid-plane. Exact per ply (the
    integrand is linear in ζ within a ply).
    """
    from .laminate import abd, rotate

    rel = np.asarray(angles, float) - direction
    n, t = rel.size, ply.thickness
    C = ply_stiffness(ply)
    Qbar = [reduced_stiffness(rotate(C, a)) for a in rel]
    A, B, D = abd([rotate(C, a) for a in rel], [t] * n)
    d = np.linalg.solve(np.block([[A, B], [B, D]]), np.array([0, 0, 0, 1.0, 0, 0]))
    de0, dk = d[:3], d[3:]
    h = n * t
    tops = h / 2 - t * np.arange(n)  # ply k spans [tops[k] − t, tops[k]]
    tau = np.zeros((n + 1, 2))  # at the faces from the bottom up: tau[j] at z = −h/2 + j·t
    for j, k in enumerate(range(n - 1, -1, -1)):
        lo, hi = tops[k] - t, tops[k]
        # ∫ Q̄(dε0 + ζ dκ) dζ over the ply
        integral = Qbar[k] @ (de0 * (hi - lo) + dk * 0.5 * (hi * hi - lo * lo))
        tau[j + 1] = tau[j] - integral[[0, 2]]
    interior = tau[1:-1][::-1]  # top first: the interface below ply k is tops[k] − t, k = 0..n−2
    z = tops[:-1] - t
    index = np.zeros(n - 1)
    for i in range(n - 1):
        for k in (i, i + 1):  # the plies above and below the interface
            c, s = math.cos(math.radians(rel[k])), math.sin(math.radians(rel[k]))
            t13 = c * interior[i, 0] + s * interior[i, 1]
            t23 = -s * interior[i, 0] + c * interior[i, 1]
            index[i] = max(index[i], math.hypot(t13 / strength.S12, t23 / strength.S23))
    return InterlaminarShear(z, interior[:, 0], interior[:, 1], index)
