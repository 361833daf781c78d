"""Von Kármán (moderately large deflection) kinematics for the FSDT plate of :mod:`softimpact.fem.plate`.

Same elements (MITC4, MITC9), same five DOFs per node (u, v, w, φx, φy) and node numbering
as :class:`~softimpact.fem.plate.PlateFE`; the membrane strain gains the von Kármán term

    ε0 = ε_L + ε_N,   ε_L = (u,x, v,y, u,y + v,x),   ε_N = (½ w,x², ½ w,y², w,x w,y),

with curvatures κ and transverse shears γ unchanged (linear). With the section of
:mod:`softimpact.models.plate_laminate` (N = A ε0 + B κ, M = B ε0 + D κ) the strain energy is

    U(d) = ½ dᵀ K d + ∫ ε_Nᵀ (A ε_L + B κ) + ½ ε_Nᵀ A ε_N dA,

where K is the *linear* model's stiffness (reused as assembled, so that at small load the
model is the linear one to round-off: the extra terms are of order |d|³ and |d|⁴). Its
gradient, the internal force, and its Hessian, the consistent tangent, are

    f_int = K d + ∫ B_mᵀ A ε_N + B_bᵀ B ε_N + B_wᵀ Gᵀ N dA,
    K_T   = K + ∫ B_mᵀ (A G B_w) + B_bᵀ (B G B_w) + (sym.) + (G B_w)ᵀ A (G B_w) + B_wᵀ N̂ B_w dA,

with B_m, B_b, B_w the operators d ↦ ε_L, κ, ∇w; G = [[w,x, 0], [0, w,y], [w,y, w,x]] (so
that δε_N = G δ∇w) and N̂ = [[Nx, Nxy], [Nxy, Ny]] the membrane forces (geometric stiffness).
The extra terms are integrated by the membrane rule of the linear element (2 × 2 Gauss for
MITC4, 3 × 3 for MITC9), element by element at once (numpy einsum over elements and
quadrature points), and the tangent is scattered into a sparsity pattern computed once.
Force and tangent are the exact gradient and Hessian of the same discrete energy, so
Newton converges quadratically and the energy balance of the dynamics is that of the
time integrator alone.

In-plane restraint of the supported edges (``in_plane``), on top of the plate's supports:

- ``immovable``: u = v = 0 along every clamped or simply-supported edge (the edges cannot
  move in their plane: membrane tension builds up, the stiffening of a panel fastened to a
  stiff frame);
- ``movable``: the normal in-plane displacement is free along every such edge (u on an
  x-edge, v on a y-edge) and the tangential one as the support says (zero for both kinds):
  the edges draw in and membrane forces arise only from the non-developable deflected shape.

``free`` and ``symmetry`` edges keep their own conditions (a mirror plane has zero normal
in-plane displacement), so a quarter of a symmetric plate can be modelled.

Cost (the 8 × 8 in plate, 48 × 48 MITC9, 45 505 DOF with the membrane DOFs that the linear
symmetric model drops, 27 455): with a section without B coupling, K and M are kept free of their
round-off membrane–bending entries (:meth:`PlateVK._uncoupled`), so the Jacobian at rest factors as a
bending and a membrane block, 7.0 M stored entries against 13.3 M as one pattern (the linear factor:
4.9 M); gradients at the quadrature points are one sparse product. In the coupled impact
(plate-ss-8in-impact, 500 steps of 0.5 µs) ``"modified"`` Newmark–Newton keeps the factor of the first
step (three solves a step: the contact's stiffness is not in it) and the run costs 3.4× the linear
direct run's stepping wall-clock, 3.7–4.1× its CPU time (benchmarks/bench_vk_ratio.py, BENCHMARKS.md).

Solvers: the one nonlinear engine of :mod:`softimpact.fem.nonlinear` (:func:`solve_static`, :class:`VonKarmanNewmark`,
re-exported here), which steps this plate as any :class:`~softimpact.fem.nonlinear.NonlinearModel`; an elastic–plastic
section plugs into the same plate as :class:`~softimpact.fem.plate_plastic.PlasticPlate`.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import scipy.sparse

from ..errors import InputError
from .nonlinear import KINEMATICS, DynamicResult, NonlinearModel, StaticResult, VonKarmanNewmark, _factor, _factor_solve, solve_static
from .plate import EDGES, PHI_X, PHI_Y, Plate, PlateFE, U, V, W, _gauss01, _lagrange
from .scatter import ElementTangents

__all__ = ["DynamicResult", "IN_PLANE", "KINEMATICS", "PlateVK", "StaticResult", "VonKarmanNewmark", "solve_static", "_factor", "_factor_solve"]

IN_PLANE = ("immovable", "movable")
UNCOUPLED = 1e-12  # membrane–bending entries of K and M below this fraction of the largest diagonal entry are round-off of B = 0


class PlateVK(ElementTangents, NonlinearModel):
    """The plate's von Kármán model over its free DOFs: ``K`` (linear), ``M``, the internal
    force :meth:`internal_force`, the tangent :meth:`tangent` and the strain energy
    :meth:`strain_energy`; rows :meth:`deflection` and loads :meth:`load_vector` as
    :class:`~softimpact.fem.plate.PlateFE`'s, over this model's free DOFs; ``curvatures``: the quadrature fields carry the
    curvatures also when the section has no membrane–bending coupling (:meth:`curvatures`)."""

    def __init__(self, plate: Plate, in_plane: str = "immovable", *, curvatures: bool = False, elements: np.ndarray | None = None):
        self._curvatures = curvatures  # the quadrature fields carry κ (φ's gradients) even when B = 0: a nonlinear section, a stress check
        if in_plane not in IN_PLANE:
            raise InputError(f"plate in_plane: {in_plane!r} is not one of {', '.join(IN_PLANE)}")
        self.plate, self.in_plane = plate, in_plane
        # The linear model over every DOF (no support, membrane kept), reduced here to our own supports; ``elements``:
        # the part of the plate assembled (PlateFE's mask), the nodes outside it removed
        self.fe = fe = PlateFE(replace(plate, supports=("free",) * 4, membrane=True), elements)
        self.fixed = self._support_dofs()
        self.free = np.setdiff1d(np.arange(fe.basis.N), self.fixed)
        self.n = self.free.size
        self._index = np.full(fe.basis.N, -1)
        self._index[self.free] = np.arange(self.n)
        self._loc = loc = fe._index[self.free]  # our free DOFs among the FE's (all of its own but the untouched nodes')
        self.K = fe.K[loc][:, loc].tocsr()
        self.M = fe.M[loc][:, loc].tocsr()
        self._elements()
        if not self.coupled:
            self.K, self.M = self._uncoupled(self.K), self._uncoupled(self.M)

    def _uncoupled(self, A: scipy.sparse.csr_matrix) -> scipy.sparse.csr_matrix:
        """``A`` without its membrane–bending entries when they are round-off (all below ``UNCOUPLED`` of its largest
        diagonal entry: a section with B = 0 assembles them as ~1e-20 relative noise, 1.5 M of them on the 48 × 48
        MITC9 plate), so that the linear K and M, and the Jacobian at rest, split into a bending block and a membrane
        block that factor apart (13.3 M stored entries of one factor fall to the blocks' few; a solve costs less in
        proportion); ``A`` unchanged otherwise."""
        coo = A.tocoo()
        comp = self.free % 5  # the plate numbers DOFs 5·node + component
        bending = np.isin(comp, (W, PHI_X, PHI_Y))
        cross = bending[coo.row] != bending[coo.col]
        if not np.any(cross) or np.abs(coo.data[cross]).max() > UNCOUPLED * np.abs(A.diagonal()).max():
            return A
        keep = ~cross
        return scipy.sparse.csr_matrix((coo.data[keep], (coo.row[keep], coo.col[keep])), shape=A.shape)

    # ---- supports -------------------------------------------------------------------
    def _support_dofs(self) -> np.ndarray:
        nd = self.fe.basis.nodal_dofs
        fixed = [nd[:, ~self.fe.touched_nodes()].ravel()]
        for edge, kind in zip(EDGES, self.plate.supports):
            nodes = self.fe.edge_nodes(edge)
            normal, tangential = (U, V) if edge[0] == "x" else (V, U)
            rotation_t = PHI_Y if edge[0] == "x" else PHI_X
            if kind == "clamped":
                comps = [W, PHI_X, PHI_Y, tangential]
            elif kind == "simply-supported":
                comps = [W, rotation_t, tangential]
            elif kind == "symmetry":
                comps = [normal, PHI_X if edge[0] == "x" else PHI_Y]
            else:
                comps = []
            if kind in ("clamped", "simply-supported") and self.in_plane == "immovable":
                comps.append(normal)
            fixed += [nd[c, nodes] for c in comps]
        return np.unique(np.concatenate(fixed)) if fixed else np.zeros(0, int)

    # ---- element data ---------------------------------------------------------------
    def _elements(self) -> None:
        fe, sec = self.fe, self.plate.section
        p = fe.order
        nq1 = p + 1  # the linear element's membrane rule: exact for its membrane and bending terms
        s, ws = _gauss01(nq1)
        N1, dN1 = _lagrange(p, s)
        a = np.array([a for a, _ in fe._local])
        b = np.array([b for _, b in fe._local])
        dNs = (dN1[:, None, a] * N1[None, :, b]).reshape(-1, a.size)  # (nq, npe)
        dNt = (N1[:, None, a] * dN1[None, :, b]).reshape(-1, a.size)
        wq = np.outer(ws, ws).ravel()
        I, J = np.nonzero(fe.elements)  # the assembled elements, row-major
        hx, hy = np.diff(fe.xs)[I], np.diff(fe.ys)[J]
        self._Dx = dNs[None] / hx[:, None, None]  # (ne, nq, npe)
        self._Dy = dNt[None] / hy[:, None, None]
        self._wq = wq[None] * (hx * hy)[:, None]  # (ne, nq)
        nodes = fe.grid_node[p * I[:, None] + a, p * J[:, None] + b]  # (ne, npe)
        self.coupled = not np.allclose(sec.B, 0.0, atol=1e-12 * np.abs(sec.A).max() * sec.thickness)
        self._comps = (U, V, W, PHI_X, PHI_Y) if (self.coupled or self._curvatures) else (U, V, W)
        # global DOFs per element, component-major: dofs[e, c, k] of component comps[c] at local node k
        self._gdofs = 5 * nodes[:, None, :] + np.array(self._comps)[None, :, None]
        self._A, self._B = sec.A, sec.B
        # One sparse operator from the free DOFs to every gradient at every quadrature point, rows (component, ∂x|∂y,
        # element, point): a gradient pass is one product and the element forces' assembly its transpose's (instead of
        # an einsum and a scatter per component)
        ne, nq, npe = self._Dx.shape
        nc = len(self._comps)
        cols = self._index[self._gdofs]  # (ne, nc, npe), −1 on fixed DOFs (zero there: dropped)
        data = np.stack([self._Dx, self._Dy])  # (2, ne, nq, npe)
        rows = np.arange(nc * 2 * ne * nq).reshape(nc, 2, ne, nq)
        R = np.broadcast_to(rows[..., None], (nc, 2, ne, nq, npe))
        Cc = np.broadcast_to(cols.transpose(1, 0, 2)[:, None, :, None, :], (nc, 2, ne, nq, npe))
        Dd = np.broadcast_to(data[None], (nc, 2, ne, nq, npe))
        keep = Cc >= 0
        self._G = scipy.sparse.csr_matrix((Dd[keep], (R[keep], Cc[keep])), shape=(nc * 2 * ne * nq, self.n))
        self._GT = self._G.T.tocsr()

    def _fields(self, d: np.ndarray):
        """ε_L, ε_N, κ (or None), ∇w at the quadrature points, each (ne, nq, ·), of the reduced vector ``d``."""
        ne, nq, _ = self._Dx.shape
        g = (self._G @ d).reshape(len(self._comps), 2, ne, nq)

        def grad(c):
            return g[c, 0], g[c, 1]

        ux, uy = grad(0)
        vx, vy = grad(1)
        wx, wy = grad(2)
        eL = np.stack([ux, vy, uy + vx], -1)
        eN = np.stack([0.5 * wx * wx, 0.5 * wy * wy, wx * wy], -1)
        kappa = None
        if len(self._comps) == 5:
            px, py_ = grad(3)
            qx, qy = grad(4)
            kappa = np.stack([px, qy, py_ + qx], -1)
        return eL, eN, kappa, wx, wy

    def expand(self, d: np.ndarray) -> np.ndarray:
        """Full DOF vector (fixed DOFs zero) from a reduced one."""
        full = np.zeros(self.fe.basis.N)
        full[self.free] = d
        return full

    # ---- energy, force, tangent -------------------------------------------------------
    def strain_energy(self, d: np.ndarray) -> float:
        """U(d) [J] (module docstring)."""
        eL, eN, kappa, _, _ = self._fields(d)
        m = eL @ self._A.T if kappa is None else eL @ self._A.T + kappa @ self._B.T
        dens = np.einsum("eqi,eqi->eq", eN, m + 0.5 * eN @ self._A.T)
        return 0.5 * float(d @ (self.K @ d)) + float(np.sum(dens * self._wq))

    def membrane_strain(self, d: np.ndarray) -> np.ndarray:
        """The mid-surface strains (ε_x0, ε_y0, γ_xy0) at the quadrature points, shape (ne, nq, 3): ε_L + ε_N, the
        von Kármán strain (module docstring)."""
        eL, eN, _, _, _ = self._fields(d)
        return eL + eN

    def curvatures(self, d: np.ndarray) -> np.ndarray:
        """κ = (φx,x, φy,y, φx,y + φy,x) at the quadrature points, shape (ne, nq, 3) [1/m] (a model built with
        ``curvatures`` or a coupled section)."""
        kappa = self._fields(d)[2]
        if kappa is None:
            raise InputError("this plate model does not carry the curvatures: build it with curvatures=True")
        return kappa

    def membrane_forces(self, d: np.ndarray) -> np.ndarray:
        """N = A ε0 + B κ at the quadrature points, shape (ne, nq, 3) [N/m]."""
        eL, eN, kappa, _, _ = self._fields(d)
        N = (eL + eN) @ self._A.T
        return N if kappa is None else N + kappa @ self._B.T

    def internal_force(self, d: np.ndarray) -> np.ndarray:
        """f_int(d) = ∂U/∂d [N] (module docstring)."""
        return self.K @ d + self.nonlinear_force(d)

    def nonlinear_force(self, d: np.ndarray) -> np.ndarray:
        """f_int(d) − K d: the von Kármán part of the internal force [N]."""
        eL, eN, kappa, wx, wy = self._fields(d)
        A, B = self._A, self._B
        N = (eL + eN) @ A.T if kappa is None else (eL + eN) @ A.T + kappa @ B.T
        nN = (eN @ A.T) * self._wq[..., None]  # A ε_N: the extra membrane force of the linear strains' work
        Nw = N * self._wq[..., None]
        # the weighted stresses each gradient row meets: (component, ∂x|∂y) of the gradient operator's rows
        S = [(nN[..., 0], nN[..., 2]), (nN[..., 2], nN[..., 1]), (wx * Nw[..., 0] + wy * Nw[..., 2], wy * Nw[..., 1] + wx * Nw[..., 2])]
        if self.coupled:
            mN = (eN @ B.T) * self._wq[..., None]  # B ε_N: the extra moment
            S += [(mN[..., 0], mN[..., 2]), (mN[..., 2], mN[..., 1])]
        elif len(self._comps) == 5:  # curvatures carried (``curvatures``) with B = 0: no extra moment
            S += [(np.zeros_like(wx), np.zeros_like(wx))] * 2
        return self._GT @ np.stack([np.stack(pair) for pair in S]).ravel()

    def _element_tangents(self, d: np.ndarray) -> np.ndarray:
        """The nonlinear part of the element tangents, shape (ne, nc·npe, nc·npe), component-major."""
        eL, eN, kappa, wx, wy = self._fields(d)
        A, B = self._A, self._B
        N = (eL + eN) @ A.T if kappa is None else (eL + eN) @ A.T + kappa @ B.T
        Dx, Dy = self._Dx, self._Dy
        ne, nq, npe = Dx.shape
        nc = len(self._comps)
        # G B_w: δε_N per DOF, (ne, nq, 3, npe) over the w DOFs only
        GBw = np.stack([wx[..., None] * Dx, wy[..., None] * Dy, wy[..., None] * Dx + wx[..., None] * Dy], 2)
        # the linear strain operators over all components: ε_L rows 0-2 and κ rows 0-2
        Bm = np.zeros((ne, nq, 3, nc, npe))
        Bm[:, :, 0, 0], Bm[:, :, 1, 1], Bm[:, :, 2, 0], Bm[:, :, 2, 1] = Dx, Dy, Dy, Dx
        lin = np.einsum("ij,eqjcp->eqicp", A, Bm)  # A B_m
        if self.coupled:
            Bb = np.zeros((ne, nq, 3, nc, npe))
            Bb[:, :, 0, 3], Bb[:, :, 1, 4], Bb[:, :, 2, 3], Bb[:, :, 2, 4] = Dx, Dy, Dy, Dx
            lin = lin + np.einsum("ij,eqjcp->eqicp", B, Bb)  # (A B_m + B B_b): B symmetric
        wq = self._wq
        Ke = np.zeros((ne, nc, npe, nc, npe))
        # coupling: (A B_m + B B_b)ᵀ G B_w and its transpose
        cross = np.einsum("eq,eqicp,eqir->ecpr", wq, lin, GBw)  # (ne, nc, npe, npe_w)
        Ke[:, :, :, 2, :] += cross
        Ke[:, 2, :, :, :] += cross.transpose(0, 3, 1, 2)
        # (G B_w)ᵀ A (G B_w) + B_wᵀ N̂ B_w
        AG = np.einsum("ij,eqjr->eqir", A, GBw)
        Kww = np.einsum("eq,eqip,eqir->epr", wq, GBw, AG)
        Nq = N * wq[..., None]
        Kww += np.einsum("eq,eqp,eqr->epr", Nq[..., 0], Dx, Dx) + np.einsum("eq,eqp,eqr->epr", Nq[..., 1], Dy, Dy)
        Kww += np.einsum("eq,eqp,eqr->epr", Nq[..., 2], Dx, Dy) + np.einsum("eq,eqp,eqr->epr", Nq[..., 2], Dy, Dx)
        Ke[:, 2, :, 2, :] += Kww
        return Ke.reshape(ne, nc * npe, nc * npe)

    # ---- rows and loads -------------------------------------------------------------
    def deflection(self, x: float, y: float) -> np.ndarray:
        """Row r with r·d = w(x, y) [m]."""
        return self.fe.deflection(x, y)[self._loc]

    def surface_strain(self, x: float, y: float, surface: str = "bottom", direction="x", length: float = 0.0) -> np.ndarray:
        """Row r with r·d = the face strain of :meth:`~softimpact.fem.plate.PlateFE.surface_strain`, over this model's free DOFs."""
        return self.fe.surface_strain(x, y, surface, direction, length)[self._loc]

    def load_vector(self, pressure) -> np.ndarray:
        """Consistent nodal loads of a transverse pressure [Pa] (up +), as PlateFE.load_vector."""
        return self.fe.load_vector(pressure)[self._loc]

    def dof(self, node: int, component: int) -> int:
        """Index in this model's reduced system of a node's component; −1 if fixed."""
        return int(self._index[self.fe.basis.nodal_dofs[component, node]])
