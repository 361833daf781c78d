"""An elastic–plastic section in the plate of :mod:`softimpact.fem.plate_vk`: J2 plasticity integrated through the thickness.

The same plate (MITC4/MITC9 FSDT elements, five DOFs per node, the same supports and in-plane restraint), with
linear or von Kármán kinematics, whose membrane forces and moments come from a plane-stress J2 material
(:mod:`softimpact.models.plasticity`) at layer points through the thickness instead of N = A ε0, M = D κ:

    ε(z) = ε0 + z κ,   σ(z) = the return mapping of ε(z) from the committed plastic strains,
    N = Σ_l w_l σ_l,   M = Σ_l w_l z_l σ_l,   ∂(N, M)/∂(ε0, κ) = Σ_l w_l [[D_l, z_l D_l], [z_l D_l, z_l² D_l]],

D_l the consistent tangent of layer point l. The thickness is cut into ``layers`` equal layers of two Gauss points
each (:data:`LAYERS` = 8: 16 points), and two points of weight zero at the faces, where a bent plate yields
first (they count in the plastic zone and the yield onset, not in the resultants). That rule integrates z² exactly, so an elastic section is the linear plate's
to round-off; for the elastic–plastic moment of a rectangular section it is within 0.33 % of the closed form
M/M_p = 1 − (κ_y/κ)²/3 over κ/κ_y ∈ [0.2, 20] (a single 9-point Gauss rule: 1.75 %; 8 layers of Simpson's rule:
1.1 %), exact at full plasticity M_p = σ_y h²/4 (z = 0 is a layer boundary). The transverse shear stays elastic
(Q = k G h γ, the linear model's): the model is one of thin plates whose yielding is governed by bending and
stretching, as the rigid-plastic plate theories it is checked against assume.

With K the linear plate's stiffness (the elastic section's membrane, bending and shear terms, assembled once), the
internal force and tangent are those of the layered section less the linear elastic membrane–bending part that K
already holds:

    f_int = K d + ∫ B_mᵀ (N − A ε_L) + B_bᵀ (M − D κ) + B_wᵀ Gᵀ N dA,
    K_T   = K + ∫ B(d)ᵀ C_T B(d) − B_Lᵀ C_e B_L + B_wᵀ N̂ B_w dA,

B(d) = B_L + [G B_w; 0] the generalized strains' derivative (the von Kármán term in the membrane rows), C_e the
elastic section (A, D), N̂ the membrane forces (geometric stiffness) — :class:`~softimpact.fem.plate_vk.PlateVK`'s
expressions with the section's resultants in place of A ε0, D κ. The state (plastic strains and equivalent plastic
strain at every layer point of every quadrature point) is committed after each converged step
(:meth:`PlasticPlate.commit`), where the plastic work Σ w σ_{n+1}·Δεᵖ (backward Euler: the return mapping's own
rule) is counted, so that the energy balance kinetic + elastic + plastic work = work in is a check. A rate law
multiplies the yield stress by R(ε̇) of the equivalent strain rate of the previous step at each point (lagged).

Valid for: small strains (von Kármán: moderate rotations), isotropic metals (J2, isotropic hardening: no
Bauschinger effect, so reversed yielding on rebound is overestimated), thin plates (elastic transverse shear).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from ..errors import InputError
from ..models.plasticity import J2PlaneStress, von_mises
from .plate import Plate
from .plate_vk import PlateVK

__all__ = ["LAYERS", "PlasticPlate", "layer_points"]


class _Section(NamedTuple):
    """The section of one displacement at the quadrature points: the fields (each (ne, nq, ·)), the resultants N, M
    (ne, nq, 3), the active points' flat indices (a,), their layer strains (a, L, 3) and return mapping (or None)."""

    eL: np.ndarray
    e0: np.ndarray
    kappa: np.ndarray
    wx: np.ndarray
    wy: np.ndarray
    N: np.ndarray
    M: np.ndarray
    active: np.ndarray
    strain: np.ndarray | None
    rm: object


LAYERS = 8  # equal layers through the thickness, two Gauss points each (module docstring)


def layer_points(thickness: float, layers: int = LAYERS) -> tuple[np.ndarray, np.ndarray]:
    """Heights z (2·layers + 2,) [m] from the mid-plane and weights w [m] (Σ w = thickness) of the composite rule,
    the two faces last with weight zero: they carry no part of the resultants, but yield there first (the outermost
    Gauss point, at 0.474 h from the mid-plane, would see the first yield of a bent plate 5.6 % late)."""
    if isinstance(layers, bool) or not (isinstance(layers, (int, np.integer)) and layers >= 1):
        raise InputError(f"layers must be a positive integer, got {layers!r}", "layers")
    g = np.array([-1.0, 1.0]) / math.sqrt(3.0)
    edges = np.linspace(-thickness / 2, thickness / 2, layers + 1)
    mid, half = 0.5 * (edges[:-1] + edges[1:]), 0.5 * np.diff(edges)
    z = (mid[:, None] + half[:, None] * g[None, :]).ravel()
    w = np.repeat(half, 2)
    return np.concatenate((z, [-thickness / 2, thickness / 2])), np.concatenate((w, [0.0, 0.0]))


class PlasticPlate(PlateVK):
    """The plate of ``plate`` (its mesh, supports, element; an isotropic section of ``material``'s elastic constants
    and ``plate.section.thickness``) with the elastic–plastic ``material`` (:class:`~softimpact.models.plasticity.J2PlaneStress`)
    integrated through the thickness, ``kinematics`` ``"von-karman"`` or ``"linear"``, ``in_plane`` as
    :class:`~softimpact.fem.plate_vk.PlateVK`'s; ``rate`` an optional rate law R(ε̇) (module docstring).
    State: ``plastic_strain`` (ne, nq, L, 3) and ``eps_p`` (ne, nq, L), committed; ``plastic_work`` [J]."""

    history_names = ("plastic_work_J", "plastic_zone_area_m2", "max_equivalent_plastic_strain")

    def __init__(self, plate: Plate, material: J2PlaneStress, *, kinematics: str = "von-karman", in_plane: str = "immovable", layers: int = LAYERS, rate=None):
        if kinematics not in ("linear", "von-karman"):
            raise InputError(f"kinematics: {kinematics!r} is not 'linear' or 'von-karman'", "kinematics")
        if not isinstance(material, J2PlaneStress):
            raise InputError(f"material must be a J2PlaneStress, got {type(material).__name__}", "material")
        super().__init__(plate, in_plane, curvatures=True)
        self.material, self.kinematics, self.rate = material, kinematics, rate
        h = plate.section.thickness
        self.z, self.wz = layer_points(h, layers)
        Ce = material.elastic
        self._Ce6 = np.block([[Ce * h, np.zeros((3, 3))], [np.zeros((3, 3)), Ce * h**3 / 12]])  # the elastic section, as K holds it
        if not np.allclose(plate.section.A, Ce * h, rtol=1e-9, atol=1e-9 * np.abs(Ce).max() * h):
            raise InputError("the plastic plate's section must be the isotropic one of its material (A = Cₑ·h)", "section")
        ne, nq, _ = self._Dx.shape
        self._shape = (ne, nq, self.z.size)
        self.reset()

    # ---- state ----------------------------------------------------------------------------------
    def reset(self) -> None:
        ne, nq, nl = self._shape
        Q = ne * nq
        self.plastic_strain = np.zeros((Q, nl, 3))  # per quadrature point (element-major) and layer point
        self.eps_p = np.zeros((Q, nl))
        self.loading = np.zeros((Q, nl), bool)  # layer points that flowed in their last committed increment
        self.rate_factor = np.ones((Q, nl))
        self.plastic_work = 0.0
        self._strain = np.zeros((Q, nl, 3))  # the committed total strains (for the rate)
        self.displacement = np.zeros(self.n)  # the last committed state
        self._cache = None

    def dissipated_energy(self) -> float:
        """The plastic work Σ w σ·Δεᵖ so far [J] (module docstring)."""
        return self.plastic_work

    # ---- the section at the quadrature points ----------------------------------------------------
    def _generalized(self, d: np.ndarray):
        """(ε_L, ε0, κ, w,x, w,y) at the quadrature points, each (ne, nq, ·)."""
        eL, eN, kappa, wx, wy = self._fields(d)
        e0 = eL + eN if self.kinematics == "von-karman" else eL
        return eL, e0, kappa, wx, wy

    def _section(self, d: np.ndarray) -> _Section:
        """The section at every quadrature point for ``d`` (cached for the last d). Points that never yielded and
        whose elastic trial stays below yield on both faces (the strain is linear through the thickness, the von
        Mises stress of a linear stress field largest at a face) take the elastic section's closed form N = Aε0,
        M = Dκ; the others ("active") integrate the return mapping through the thickness."""
        if self._cache is not None and np.array_equal(self._cache[0], d):
            return self._cache[1]
        eL, e0, kappa, wx, wy = self._generalized(d)
        ne, nq, nl = self._shape
        e0f, kf = e0.reshape(-1, 3), kappa.reshape(-1, 3)
        h = self.plate.section.thickness
        Ce = self.material.elastic
        N, M = e0f @ (Ce * h).T, kf @ (Ce * h**3 / 12).T
        sy0 = self.material.hardening.yield_stress * self.rate_factor.min(axis=1)
        top, bottom = von_mises((e0f + 0.5 * h * kf) @ Ce.T), von_mises((e0f - 0.5 * h * kf) @ Ce.T)
        active = np.flatnonzero(np.any(self.eps_p > 0.0, axis=1) | (top > sy0) | (bottom > sy0))
        rm = strain = None
        if active.size:
            strain = e0f[active, None, :] + self.z[None, :, None] * kf[active, None, :]  # (a, L, 3)
            rm = self.material.return_map(
                strain.reshape(-1, 3),
                self.plastic_strain[active].reshape(-1, 3),
                self.eps_p[active].ravel(),
                self.rate_factor[active].ravel(),
                self.loading[active].ravel(),
            )
            stress = rm.stress.reshape(active.size, nl, 3)
            N[active] = np.tensordot(stress, self.wz, axes=([1], [0]))
            M[active] = np.tensordot(stress, self.wz * self.z, axes=([1], [0]))
        out = _Section(eL, e0, kappa, wx, wy, N.reshape(ne, nq, 3), M.reshape(ne, nq, 3), active, strain, rm)
        self._cache = (np.array(d, copy=True), out)
        return out

    def resultants(self, d: np.ndarray):
        """(N, M) at the quadrature points, each (ne, nq, 3) [N/m, N]: the layer stresses integrated (module docstring)."""
        sec = self._section(d)
        return sec.N, sec.M

    def membrane_forces(self, d: np.ndarray) -> np.ndarray:
        """N at the quadrature points, shape (ne, nq, 3) [N/m]."""
        return self._section(d).N

    def membrane_strain(self, d: np.ndarray) -> np.ndarray:
        """The mid-surface strains ε0 at the quadrature points, (ne, nq, 3)."""
        return self._generalized(d)[1]

    def nonlinear_force(self, d: np.ndarray) -> np.ndarray:
        """f_int(d) − K d [N] (module docstring)."""
        sec = self._section(d)
        eL, kappa, wx, wy, N, M = sec.eL, sec.kappa, sec.wx, sec.wy, sec.N, sec.M
        h, Ce = self.plate.section.thickness, self.material.elastic
        dN = (N - eL @ (Ce * h).T) * self._wq[..., None]
        dM = (M - kappa @ (Ce * h**3 / 12).T) * self._wq[..., None]
        S = [(dN[..., 0], dN[..., 2]), (dN[..., 2], dN[..., 1])]
        if self.kinematics == "von-karman":
            Nw = N * self._wq[..., None]
            S.append((wx * Nw[..., 0] + wy * Nw[..., 2], wy * Nw[..., 1] + wx * Nw[..., 2]))
        else:
            S.append((np.zeros_like(wx), np.zeros_like(wx)))
        S += [(dM[..., 0], dM[..., 2]), (dM[..., 2], dM[..., 1])]
        return self._GT @ np.stack([np.stack(pair) for pair in S]).ravel()

    def _section_tangent(self, sec: _Section) -> np.ndarray:
        """∂(N, M)/∂(ε0, κ) at the quadrature points, (ne, nq, 6, 6): the elastic section's, the layers' tangents
        integrated at the active points."""
        ne, nq, nl = self._shape
        C = np.broadcast_to(self._Ce6, (ne * nq, 6, 6)).copy()
        if sec.active.size:
            D = sec.rm.tangent.reshape(sec.active.size, nl, 9)
            wz, z = self.wz, self.z
            C[sec.active, :3, :3] = np.tensordot(D, wz, axes=([1], [0])).reshape(-1, 3, 3)
            C[sec.active, :3, 3:] = C[sec.active, 3:, :3] = np.tensordot(D, wz * z, axes=([1], [0])).reshape(-1, 3, 3)
            C[sec.active, 3:, 3:] = np.tensordot(D, wz * z * z, axes=([1], [0])).reshape(-1, 3, 3)
        return C.reshape(ne, nq, 6, 6)

    def _element_tangents(self, d: np.ndarray) -> np.ndarray:
        """∫ B(d)ᵀ C_T B(d) − B_Lᵀ C_e B_L + B_wᵀ N̂ B_w per element, (ne, 5·npe, 5·npe), component-major."""
        sec = self._section(d)
        wx, wy = sec.wx, sec.wy
        Dx, Dy = self._Dx, self._Dy
        ne, nq, npe = Dx.shape
        C = self._section_tangent(sec)
        # B_L: rows ε_L (0–2) and κ (3–5) over (component, local node)
        BL = np.zeros((ne, nq, 6, 5, npe))
        BL[:, :, 0, 0], BL[:, :, 1, 1], BL[:, :, 2, 0], BL[:, :, 2, 1] = Dx, Dy, Dy, Dx
        BL[:, :, 3, 3], BL[:, :, 4, 4], BL[:, :, 5, 3], BL[:, :, 5, 4] = Dx, Dy, Dy, Dx
        B = BL.copy()
        vk = self.kinematics == "von-karman"
        if vk:  # δε_N = G δ∇w in the membrane rows
            B[:, :, 0, 2] = wx[..., None] * Dx
            B[:, :, 1, 2] = wy[..., None] * Dy
            B[:, :, 2, 2] = wy[..., None] * Dx + wx[..., None] * Dy
        B = B.reshape(ne, nq, 6, 5 * npe)
        BL = BL.reshape(ne, nq, 6, 5 * npe)
        wq = self._wq[..., None, None]
        # Σ_q w_q (Bᵀ C B − B_Lᵀ C_e B_L), as batched matrix products (BLAS) over the points
        Ke = (np.swapaxes(B, -1, -2) @ (C @ B) * wq).sum(axis=1) - (np.swapaxes(BL, -1, -2) @ (self._Ce6 @ BL) * wq).sum(axis=1)
        if vk:
            Nq = sec.N * self._wq[..., None]
            Kww = np.einsum("eq,eqp,eqr->epr", Nq[..., 0], Dx, Dx) + np.einsum("eq,eqp,eqr->epr", Nq[..., 1], Dy, Dy)
            Kww += np.einsum("eq,eqp,eqr->epr", Nq[..., 2], Dx, Dy) + np.einsum("eq,eqp,eqr->epr", Nq[..., 2], Dy, Dx)
            Ke = Ke.reshape(ne, 5, npe, 5, npe)
            Ke[:, 2, :, 2, :] += Kww
            Ke = Ke.reshape(ne, 5 * npe, 5 * npe)
        return Ke

    # ---- energies and the committed state ----------------------------------------------------------
    def strain_energy(self, d: np.ndarray) -> float:
        """The elastic energy at d [J]: the transverse shear's (K's less its membrane–bending part) and the section's,
        ½(ε − εᵖ)ᵀCₑ(ε − εᵖ) through the thickness at the trial plastic strains (the closed form ½ε0ᵀAε0 + ½κᵀDκ where
        no layer yielded)."""
        sec = self._section(d)
        h, Ce = self.plate.section.thickness, self.material.elastic
        lin = np.einsum("eqi,ij,eqj->eq", sec.eL, Ce * h, sec.eL) + np.einsum("eqi,ij,eqj->eq", sec.kappa, Ce * h**3 / 12, sec.kappa)
        shear = 0.5 * float(d @ (self.K @ d)) - 0.5 * float(np.sum(lin * self._wq))
        e0, kf = sec.e0.reshape(-1, 3), sec.kappa.reshape(-1, 3)
        dens = 0.5 * (np.einsum("qi,ij,qj->q", e0, Ce * h, e0) + np.einsum("qi,ij,qj->q", kf, Ce * h**3 / 12, kf))
        if sec.active.size:
            layers = self.material.stress_energy(sec.strain.reshape(-1, 3), sec.rm.plastic_strain).reshape(sec.active.size, -1)
            dens[sec.active] = layers @ self.wz
        return shear + float(dens @ self._wq.ravel())

    def commit(self, d: np.ndarray, dt: float | None = None) -> None:
        """Store the return mapping's state at the converged ``d``; count its plastic work; the rate factor for the
        next step from this step's equivalent strain rate (when a rate law is given and ``dt``)."""
        sec = self._section(d)
        a = sec.active
        if self.rate is not None and dt:
            strain = sec.e0.reshape(-1, 1, 3) + self.z[None, :, None] * sec.kappa.reshape(-1, 1, 3)
            de = strain - self._strain
            # the equivalent (von Mises) strain increment of an incompressible plane-stress flow: ε_z = −(ε_x + ε_y)
            eq = np.sqrt(2.0 / 3.0 * (de[..., 0] ** 2 + de[..., 1] ** 2 + (de[..., 0] + de[..., 1]) ** 2 + 0.5 * de[..., 2] ** 2))
            self.rate_factor = self.rate(eq / dt)
            self._strain = strain
        if a.size:
            nl = self.z.size
            ep = sec.rm.plastic_strain.reshape(a.size, nl, 3)
            s = sec.rm.stress.reshape(a.size, nl, 3)
            work = np.einsum("ali,ali->al", s, ep - self.plastic_strain[a]) @ self.wz
            self.plastic_work += float(work @ self._wq.ravel()[a])
            alpha = sec.rm.equivalent_plastic_strain.reshape(a.size, nl)
            self.loading[:] = False
            self.loading[a] = alpha > self.eps_p[a]
            self.plastic_strain[a], self.eps_p[a] = ep, alpha
        else:
            self.loading[:] = False
        self.displacement = np.array(d, copy=True)
        self._cache = None

    def yielded(self) -> np.ndarray:
        """(ne, nq) bool: quadrature points with plastic strain at any layer."""
        return np.any(self.eps_p > 0.0, axis=-1).reshape(self._shape[:2])

    def history(self, d: np.ndarray) -> np.ndarray:
        """The plastic work [J], the plastic zone's area [m²] (the quadrature weights of the points that yielded at any
        layer) and the largest equivalent plastic strain."""
        return np.array([self.plastic_work, float(np.sum(self._wq[self.yielded()])), float(self.eps_p.max())])

    def von_mises(self, d: np.ndarray) -> np.ndarray:
        """The largest von Mises stress through the thickness at every quadrature point (ne, nq) [Pa]."""
        sec = self._section(d)
        h, Ce = self.plate.section.thickness, self.material.elastic
        e0, kf = sec.e0.reshape(-1, 3), sec.kappa.reshape(-1, 3)
        out = np.maximum(von_mises((e0 + 0.5 * h * kf) @ Ce.T), von_mises((e0 - 0.5 * h * kf) @ Ce.T))
        if sec.active.size:
            out[sec.active] = von_mises(sec.rm.stress).reshape(sec.active.size, -1).max(axis=1)
        return out.reshape(self._shape[:2])
