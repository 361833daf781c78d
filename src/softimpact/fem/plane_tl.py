"""Large deflection of the plane beam of :mod:`softimpact.fem.plane`: its Q4 model in a total Lagrangian form.

Same mesh, supports, layered material matrices D, mass and DOF numbering as
:class:`~softimpact.fem.plane.PlaneModel` (two translations per node, x along the axis, z up); the
small strain ε = sym ∇u becomes the Green–Lagrange strain of the displacement gradient H = ∇u
(F = I + H, 2 × 2, rows the components (x, z), columns the derivatives (∂x, ∂z)),

    E = ½ (H + Hᵀ + HᵀH),   Voigt (Exx, Ezz, 2Exz) = ε_L + ε_N,
    ε_L = (ux,x, uz,z, ux,z + uz,x),
    ε_N = (½(ux,x² + uz,x²), ½(ux,z² + uz,z²), ux,x ux,z + uz,x uz,z),

with the second Piola–Kirchhoff stress S = D E of each element layer (St Venant–Kirchhoff): exact for
rotations of any size at small strain, the regime of a slender laminate beam bent far past its
thickness. The strain energy, with K the *linear* model's stiffness as assembled (so that at small
load the model is the linear one to round-off: the extra terms are of order |d|³ and |d|⁴),

    U(d) = ½ dᵀ K d + b ∫ ε_Nᵀ D ε_L + ½ ε_Nᵀ D ε_N dA,

has the gradient, the internal force, and the Hessian, the consistent tangent,

    f_int = K d + b ∫ B_Lᵀ D ε_N + B_Nᵀ S dA,
    K_T   = K + b ∫ B_Lᵀ D B_N + B_Nᵀ D B_L + B_Nᵀ D B_N + K_σ(S) dA,

where δE = (B_L + B_N(d)) δd: for the DOF of component c at local node p, the three rows are
(F_c0 N_p,x, F_c1 N_p,z, F_c0 N_p,z + F_c1 N_p,x) with F = I + H, B_L their value at H = 0, and
K_σ = δ_cc' (Sxx N_p,x N_q,x + Szz N_p,z N_q,z + Sxz (N_p,x N_q,z + N_p,z N_q,x)) the geometric
(initial stress) stiffness. b is the width: forces in N for the whole beam. The terms are integrated
by 2 × 2 Gauss (the linear model's full integration: its K to round-off), all elements at once (numpy
einsum over elements and quadrature points), and the tangent is scattered into a sparsity pattern
computed once. Force and tangent are the exact gradient and Hessian of one discrete energy, so Newton
converges quadratically and the energy balance of the dynamics is the time integrator's alone.

Why total Lagrangian, not von Kármán: von Kármán's strain keeps of HᵀH the square of the transverse
rotation alone (ε_N ≈ (½ uz,x², 0, 0)), an approximation made for a *structural* model whose
rotations are a few tenths of a radian and whose through-thickness fibre is a kinematic assumption.
The plane model is a 2-D continuum: it has no separate rotation DOF to approximate, and dropping
terms of HᵀH selectively would make the strain frame-dependent (a rigid rotation would strain it).
The full Green–Lagrange strain costs the same vectorised pass, is objective, and contains von
Kármán's beam as its moderate-rotation limit (H_zx = w' ≫ the other gradients): the test oracle of
tests/test_beam_tl.py is that von Kármán Euler–Bernoulli beam.

Solvers: those of :mod:`softimpact.fem.plate_vk`, which take any model with this interface
(``K``, ``M``, ``n``, :meth:`internal_force`, :meth:`nonlinear_force`, :meth:`tangent`,
:meth:`strain_energy`): :func:`~softimpact.fem.nonlinear.solve_static` (load steps, Newton) and
:class:`~softimpact.fem.nonlinear.NonlinearNewmark` (implicit Newmark–Newton with the contact hook).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse

from .nonlinear import NonlinearModel
from .plane import PlaneModel
from .scatter import ElementTangents

__all__ = ["PlaneTL"]

GAUSS_2 = 0.5 + np.array([-0.5, 0.5]) / np.sqrt(3.0)  # 2-point Gauss on [0, 1] (weights ½): Q4's full integration


class PlaneTL(ElementTangents, NonlinearModel):
    """The plane beam's total Lagrangian model over the free DOFs of ``plane`` (a
    :class:`~softimpact.fem.plane.PlaneModel`, its supports): ``K`` (linear), ``M``, ``n``, the internal force
    :meth:`internal_force`, the tangent :meth:`tangent` and the strain energy :meth:`strain_energy` (module
    docstring)."""

    def __init__(self, plane: PlaneModel):
        self.plane = plane
        self.K, self.M, self.n, self.free = plane.K, plane.M, plane.n, plane.free
        self._index = plane._index
        self._elements()
        self._BL = None

    def _elements(self) -> None:
        pm, beam = self.plane, self.plane.beam
        mesh = pm.basis.mesh
        t, p = mesh.t, mesh.p  # (4, ne) nodes per element, (2, nodes) coordinates
        x0, z0 = p[0, t].min(axis=0), p[1, t].min(axis=0)
        hx, hz = p[0, t].max(axis=0) - x0, p[1, t].max(axis=0) - z0
        sx = np.rint((p[0, t] - x0) / hx).T  # (ne, 4): each local node's corner on the unit square
        sz = np.rint((p[1, t] - z0) / hz).T
        gs, gt = np.meshgrid(GAUSS_2, GAUSS_2, indexing="ij")
        gs, gt = gs.ravel(), gt.ravel()  # (nq,)
        # N_p(s, t) = (sx s + (1 − sx)(1 − s)) (sz t + (1 − sz)(1 − t)): its derivatives at the points
        fs = sx[:, None, :] * gs[None, :, None] + (1 - sx[:, None, :]) * (1 - gs[None, :, None])
        ft = sz[:, None, :] * gt[None, :, None] + (1 - sz[:, None, :]) * (1 - gt[None, :, None])
        self._Dx = (2 * sx[:, None, :] - 1) * ft / hx[:, None, None]  # (ne, nq, 4)
        self._Dz = fs * (2 * sz[:, None, :] - 1) / hz[:, None, None]
        self._wq = np.full(gs.size, 0.25)[None] * (hx * hz * beam.width)[:, None]  # (ne, nq): b dA
        self._gdofs = pm.basis.nodal_dofs[:, t].transpose(2, 0, 1)  # (ne, 2, 4): component-major
        if len(beam.layers) == 1:
            self._D = np.broadcast_to(np.asarray(beam.layers[0], float), (t.shape[1], 3, 3))
        else:
            centres = p[1, t].mean(axis=0)  # the layers as PlaneModel assigns them
            layer = np.clip(np.floor(centres / beam.thickness * beam.nz).astype(int), 0, beam.nz - 1)
            self._D = np.array([np.asarray(D, float) for D in beam.layers])[layer]
        # The gradient operator over the reduced DOFs, one sparse matrix: rows (c, j, e, q) give H_cj at the
        # point q of element e (a product per evaluation instead of small batched ones), and its transpose
        # assembles the force. D per point: (3, 3, ne·nq), for the elementwise stress.
        ne, nq = self._wq.shape
        rows, cols, vals = [], [], []
        for c in range(2):
            for j, Dj in enumerate((self._Dx, self._Dz)):
                r = (2 * c + j) * ne * nq + np.arange(ne * nq).reshape(ne, nq)
                dof = self._index[self._gdofs[:, c, :]]  # (ne, 4), −1 where fixed
                rr = np.broadcast_to(r[:, :, None], (ne, nq, 4))
                cc = np.broadcast_to(dof[:, None, :], (ne, nq, 4))
                keep = cc >= 0
                rows.append(rr[keep])
                cols.append(cc[keep])
                vals.append(Dj[keep])
        self._A = scipy.sparse.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(4 * ne * nq, self.n))
        self._AT = self._A.T.tocsr()
        self._Dp = np.repeat(self._D, nq, axis=0).transpose(1, 2, 0).copy()  # (3, 3, ne·nq)

    # ---- kinematics -------------------------------------------------------------------
    def expand(self, d: np.ndarray) -> np.ndarray:
        """Full DOF vector (fixed DOFs zero) from a reduced one."""
        full = np.zeros(self.plane.basis.N)
        full[self.free] = d
        return full

    def _gradient(self, d: np.ndarray) -> np.ndarray:
        """H = ∇u at the quadrature points, (ne, nq, 2, 2): [component, derivative]."""
        ne, nq = self._wq.shape
        return (self._A @ d).reshape(2, 2, ne, nq).transpose(2, 3, 0, 1)

    @staticmethod
    def _strains(H: np.ndarray):
        """ε_L, ε_N (Voigt, (ne, nq, 3)) of the gradient H."""
        eL = np.stack([H[..., 0, 0], H[..., 1, 1], H[..., 0, 1] + H[..., 1, 0]], -1)
        eN = np.stack(
            [
                0.5 * (H[..., 0, 0] ** 2 + H[..., 1, 0] ** 2),
                0.5 * (H[..., 0, 1] ** 2 + H[..., 1, 1] ** 2),
                H[..., 0, 0] * H[..., 0, 1] + H[..., 1, 0] * H[..., 1, 1],
            ],
            -1,
        )
        return eL, eN

    def _operators(self, G: np.ndarray) -> np.ndarray:
        """The strain rows δE per DOF for a 2 × 2 field G (I: B_L + B_N; H: B_N), (ne, nq, 3, 2, 4)."""
        Dx, Dz = self._Dx[:, :, None, :], self._Dz[:, :, None, :]  # (ne, nq, 1, 4)
        g0, g1 = G[..., 0][..., None], G[..., 1][..., None]  # (ne, nq, 2, 1): F_c0, F_c1 per component c
        return np.stack([g0 * Dx, g1 * Dz, g0 * Dz + g1 * Dx], 2)

    def _linear_operator(self) -> np.ndarray:
        """B_L, (ne, nq, 3, 2, 4): built once."""
        if self._BL is None:
            ne, nq = self._wq.shape
            self._BL = self._operators(np.broadcast_to(np.eye(2), (ne, nq, 2, 2)))
        return self._BL

    # ---- energy, force, tangent -------------------------------------------------------
    def strain_energy(self, d: np.ndarray) -> float:
        """U(d) [J] (module docstring)."""
        eL, eN = self._strains(self._gradient(d))
        dens = np.sum(eN * self._stress(eL + 0.5 * eN), -1)
        return 0.5 * float(d @ (self.K @ d)) + float(np.sum(dens * self._wq))

    def stresses(self, d: np.ndarray) -> np.ndarray:
        """S = D E, the second Piola–Kirchhoff stress (Sxx, Szz, Sxz) at the quadrature points, (ne, nq, 3) [Pa]."""
        eL, eN = self._strains(self._gradient(d))
        return np.einsum("eij,eqj->eqi", self._D, eL + eN)

    def internal_force(self, d: np.ndarray) -> np.ndarray:
        """f_int(d) = ∂U/∂d [N] (module docstring)."""
        return self.K @ d + self.nonlinear_force(d)

    def _stress(self, e: np.ndarray) -> np.ndarray:
        """D e per element, (ne, nq, 3), of Voigt strains e (ne, nq, 3)."""
        return e @ self._D.transpose(0, 2, 1)

    def nonlinear_force(self, d: np.ndarray) -> np.ndarray:
        """f_int(d) − K d: b ∫ B_Lᵀ D ε_N + B_Nᵀ S dA, zero to second order at d = 0 [N]."""
        h00, h01, h10, h11 = (self._A @ d).reshape(4, -1)  # H_cj at every point
        eL = (h00, h11, h01 + h10)
        eN = (0.5 * (h00 * h00 + h10 * h10), 0.5 * (h01 * h01 + h11 * h11), h00 * h01 + h10 * h11)
        D, w = self._Dp, self._wq.ravel()
        DeN = [w * (D[i, 0] * eN[0] + D[i, 1] * eN[1] + D[i, 2] * eN[2]) for i in range(3)]
        Sxx, Szz, Sxz = (DeN[i] + w * (D[i, 0] * eL[0] + D[i, 1] * eL[1] + D[i, 2] * eL[2]) for i in range(3))
        # (B_Lᵀ D ε_N + B_Nᵀ S) of component c = Σ_q P_cx N,x + P_cz N,z (the rows of the module docstring)
        P = np.concatenate(
            [
                DeN[0] + Sxx * h00 + Sxz * h01,
                DeN[2] + Szz * h01 + Sxz * h00,
                DeN[2] + Sxx * h10 + Sxz * h11,
                DeN[1] + Szz * h11 + Sxz * h10,
            ]
        )
        return self._AT @ P

    def _element_tangents(self, d: np.ndarray) -> np.ndarray:
        """K_T − K per element, (ne, 8, 8), component-major DOFs."""
        H = self._gradient(d)
        eL, eN = self._strains(H)
        D, wq = self._D, self._wq
        ne, nq = wq.shape
        BL = self._linear_operator().reshape(ne, nq, 3, 8)
        BN = self._operators(H).reshape(ne, nq, 3, 8)
        wDBN = (np.einsum("eij,eqjr->eqir", D, BN) * wq[..., None, None]).reshape(ne, 3 * nq, 8)  # b dA · D B_N
        BLt, BNt = BL.reshape(ne, 3 * nq, 8).transpose(0, 2, 1), BN.reshape(ne, 3 * nq, 8).transpose(0, 2, 1)
        Ke = BLt @ wDBN
        Ke += Ke.transpose(0, 2, 1)
        Ke += BNt @ wDBN
        S = np.einsum("eij,eqj->eqi", D, eL + eN) * wq[..., None]
        Dx, Dz = self._Dx, self._Dz
        SxDz = S[..., 2:3] * Dz
        Ks = (S[..., 0:1] * Dx).transpose(0, 2, 1) @ Dx + (S[..., 1:2] * Dz).transpose(0, 2, 1) @ Dz + (S[..., 2:3] * Dx).transpose(0, 2, 1) @ Dz
        Ks += SxDz.transpose(0, 2, 1) @ Dx
        Ke[:, :4, :4] += Ks
        Ke[:, 4:, 4:] += Ks
        return Ke

    # ---- gauges -----------------------------------------------------------------------
    def transverse_rows(self, O: np.ndarray) -> np.ndarray:
        """Rows (k, n) reading the z displacements where the rows ``O`` (k, n) read the x displacements of the same
        nodes (zero where a node's z DOF is fixed): with O a gauge's Δu_x/l (:meth:`PlaneModel.surface_strain`), Δu_z/l."""
        O = np.atleast_2d(np.asarray(O, float))
        nd = self.plane.basis.nodal_dofs
        ix, iz = self._index[nd[0]], self._index[nd[1]]
        both = (ix >= 0) & (iz >= 0)
        Oz = np.zeros_like(O)
        Oz[:, iz[both]] = O[:, ix[both]]
        return Oz

    @staticmethod
    def gauge_strains(O: np.ndarray, Oz: np.ndarray, d: np.ndarray) -> np.ndarray:
        """The strain a gauge reads, the stretch of its chord: |(l + Δu_x, Δu_z)|/l − 1 = √((1 + O·d)² + (Oz·d)²) − 1
        (objective: zero under a rigid rotation, which the linear reading O·d = Δu_x/l turns into a false −θ²/2),
        for the rows O (k, n) of :meth:`PlaneModel.surface_strain` and their :meth:`transverse_rows` Oz."""
        return np.hypot(1.0 + O @ d, Oz @ d) - 1.0

    def linear_stiffness(self) -> scipy.sparse.csr_matrix:
        """b ∫ B_Lᵀ D B_L dA by this module's quadrature (equal to ``K`` to round-off: a check of the element data)."""
        ne, nq = self._wq.shape
        BL = self._linear_operator().reshape(ne, nq, 3, 8)
        return self._scatter_tangents().assemble(np.einsum("eq,eqip,eij,eqjr->epr", self._wq, BL, self._D, BL))
