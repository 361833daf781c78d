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

Solvers: :func:`solve_static` (load steps, full Newton per step, convergence reported) and
:class:`VonKarmanNewmark` (implicit Newmark with Newton iterations per step, the same β, γ as
:mod:`softimpact.fem.newmark`, energies reported). Both take any geometrically nonlinear structure
model with this interface: ``K`` (the linear stiffness), ``M``, ``n`` (free DOFs), ``internal_force(d)``,
``nonlinear_force(d)`` (= internal_force(d) − K d), ``tangent(d)`` and ``strain_energy(d)``; the plate's
:class:`PlateVK` and the plane beam's :class:`~softimpact.fem.plane_tl.PlaneTL`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse

from ..errors import InputError, SolverFailed
from .newmark import NewmarkParameters, spd_factor
from .plate import EDGES, PHI_X, PHI_Y, Plate, PlateFE, U, V, W, _gauss01, _lagrange
from .scatter import ElementTangents

__all__ = ["DynamicResult", "IN_PLANE", "KINEMATICS", "PlateVK", "StaticResult", "VonKarmanNewmark", "solve_static"]

KINEMATICS = ("linear", "von-karman")
IN_PLANE = ("immovable", "movable")
UNCOUPLED = 1e-12  # membrane–bending entries of K and M below this fraction of the largest diagonal entry are round-off of B = 0


class PlateVK(ElementTangents):
    """The plate's von Kármán model over its free DOFs: ``K`` (linear), ``M``, the internal
    force :meth:`internal_force`, the tangent :meth:`tangent` and the strain energy
    :meth:`strain_energy`; rows :meth:`deflection` and loads :meth:`load_vector` as
    :class:`~softimpact.fem.plate.PlateFE`'s, over this model's free DOFs."""

    def __init__(self, plate: Plate, in_plane: str = "immovable"):
        if in_plane not in IN_PLANE:
            raise InputError(f"plate in_plane: {in_plane!r} is not one of {', '.join(IN_PLANE)}")
        self.plate, self.in_plane = plate, in_plane
        # The linear model over every DOF (no support, membrane kept), reduced here to our own supports.
        self.fe = fe = PlateFE(replace(plate, supports=("free",) * 4, membrane=True))
        self.fixed = self._support_dofs()
        self.free = np.setdiff1d(np.arange(fe.basis.N), self.fixed)
        self.n = self.free.size
        self._index = np.full(fe.basis.N, -1)
        self._index[self.free] = np.arange(self.n)
        self.K = fe.K[self.free][:, self.free].tocsr()
        self.M = fe.M[self.free][:, self.free].tocsr()
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
        fixed = []
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
        nx, ny = fe.xs.size - 1, fe.ys.size - 1
        I, J = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
        I, J = I.ravel(), J.ravel()
        hx, hy = np.diff(fe.xs)[I], np.diff(fe.ys)[J]
        self._Dx = dNs[None] / hx[:, None, None]  # (ne, nq, npe)
        self._Dy = dNt[None] / hy[:, None, None]
        self._wq = wq[None] * (hx * hy)[:, None]  # (ne, nq)
        nodes = fe.grid_node[p * I[:, None] + a, p * J[:, None] + b]  # (ne, npe)
        self.coupled = not np.allclose(sec.B, 0.0, atol=1e-12 * np.abs(sec.A).max() * sec.thickness)
        self._comps = (U, V, W, PHI_X, PHI_Y) if self.coupled else (U, V, W)
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
        if self.coupled:
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
        return self.fe.deflection(x, y)[self.free]

    def load_vector(self, pressure) -> np.ndarray:
        """Consistent nodal loads of a transverse pressure [Pa] (up +), as PlateFE.load_vector."""
        return self.fe.load_vector(pressure)[self.free]

    def dof(self, node: int, component: int) -> int:
        """Index in this model's reduced system of a node's component; −1 if fixed."""
        return int(self._index[self.fe.basis.nodal_dofs[component, node]])


def _factor(A):
    """A factor of the sparse symmetric A with a ``solve``: :func:`~softimpact.fem.newmark.spd_factor`
    (band or minimum-degree Cholesky-like) while A is positive definite, SuperLU with pivoting on
    the minimum-degree ordering of A + Aᵀ otherwise (compressive membrane forces can make the
    static tangent indefinite)."""
    import scipy.sparse.linalg

    csc = scipy.sparse.csc_matrix(A)
    try:
        return spd_factor(csc)
    except np.linalg.LinAlgError:
        return scipy.sparse.linalg.splu(csc, permc_spec="MMD_AT_PLUS_A")


def _factor_solve(A, b):
    """A⁻¹ b (see :func:`_factor`)."""
    return _factor(A).solve(b)


@dataclass(frozen=True)
class StaticResult:
    """Load-stepped Newton solution: displacements ``u`` (steps, n) at the load factors
    ``load_factors`` (steps,), Newton ``iterations`` per step, the final relative residual
    of each step ``residuals``, ``converged`` (all steps) and ``message``."""

    u: np.ndarray
    load_factors: np.ndarray
    iterations: np.ndarray
    residuals: np.ndarray
    converged: bool
    message: str


def solve_static(
    model, load: np.ndarray, *, load_steps: int = 10, load_factors=None, rtol: float = 1e-10, max_iterations: int = 30, kinematics: str = "von-karman"
) -> StaticResult:
    """Static equilibrium f_int(u) = λ·load at λ = k/load_steps, k = 1 … load_steps (or at the
    increasing ``load_factors`` given), by full Newton with the consistent tangent, each step
    starting from the previous step's solution. A step has converged when the residual is below
    ``rtol`` of the load's norm. With ``kinematics="linear"``: one solve with K."""
    if kinematics not in KINEMATICS:
        raise InputError(f"kinematics: {kinematics!r} is not one of {', '.join(KINEMATICS)}")
    if not (isinstance(load_steps, (int, np.integer)) and load_steps >= 1):
        raise InputError(f"load_steps must be a positive integer, got {load_steps!r}")
    load = np.asarray(load, float)
    lams = np.arange(1, load_steps + 1) / load_steps if load_factors is None else np.asarray(load_factors, float)
    if lams.ndim != 1 or lams.size == 0 or np.any(np.diff(lams) <= 0) or lams[0] <= 0:
        raise InputError(f"load_factors must increase from a positive value, got {load_factors!r}")
    load_steps = lams.size
    if kinematics == "linear":
        u1 = _factor_solve(model.K, load)
        return StaticResult(np.outer(lams, u1), lams, np.ones(load_steps, int), np.zeros(load_steps), True, "linear")
    u = np.zeros(model.n)
    us, its, res = [], [], []
    converged, message = True, "converged"
    for lam in lams:
        f = lam * load
        scale = max(np.linalg.norm(f), 1e-300)
        it = 0
        while it < max_iterations:
            it += 1
            r = f - model.internal_force(u)
            u = u + _factor_solve(model.tangent(u), r)
            rel = np.linalg.norm(f - model.internal_force(u)) / scale
            if rel <= rtol:
                break
        else:
            converged, message = False, f"Newton did not converge at load factor {lam:g} ({max_iterations} iterations, residual {rel:.3g})"
        us.append(u.copy())
        its.append(it)
        res.append(rel)
        if not converged:
            break
    return StaticResult(np.array(us), lams[: len(us)], np.array(its), np.array(res), converged, message)


@dataclass(frozen=True)
class DynamicResult:
    """Nonlinear Newmark run: ``t`` (steps + 1,), ``outputs`` (rows, steps + 1), the energies
    ``kinetic``, ``strain``, ``work`` (external, trapezoidal) per time [J], Newton
    ``iterations`` per step, tangent ``factorisations`` in all, final state ``u``, ``v``, ``a``."""

    t: np.ndarray
    outputs: np.ndarray
    kinetic: np.ndarray
    strain: np.ndarray
    work: np.ndarray
    iterations: np.ndarray
    factorisations: int
    u: np.ndarray
    v: np.ndarray
    a: np.ndarray

    def balance_error(self) -> np.ndarray:
        """(kinetic + strain) − (initial energy + work) [J] per time."""
        return self.kinetic + self.strain - (self.kinetic[0] + self.strain[0]) - self.work


class VonKarmanNewmark:
    """Implicit Newmark (β, γ of :class:`~softimpact.fem.newmark.NewmarkParameters`) for
    M a + C v + f_int(u) = f(t) of a nonlinear structure ``model`` (:class:`PlateVK`,
    :class:`~softimpact.fem.plane_tl.PlaneTL`: the interface of the module docstring), with Newton
    iterations per step on u_{n+1}:

        r = f_{n+1} − M a_{n+1} − C v_{n+1} − f_int(u_{n+1}),   J = K_T(u_{n+1}) + a0 M + a1 C,

    a_{n+1} = a0 (u_{n+1} − u_n) − a2 v_n − a3 a_n, v_{n+1} = v_n + dt ((1 − γ) a_n + γ a_{n+1}).
    ``tangent="newton"`` refactors J at every iteration (quadratic convergence);
    ``tangent="modified"`` keeps a factor while each iteration cuts the residual by at least
    ``MODIFIED_RATE`` (so most steps of a small-amplitude run reuse one factor) and refactors
    otherwise. A step has converged when ‖r‖ ≤ ``rtol``·max(‖r_0‖, ‖f_{n+1}‖, ‖M a_n‖), r_0 the
    residual at the predictor, or when a correction after the first is below ``rtol`` of the step's
    increment. The default
    1e-6 leaves the energy balance to the time integrator (the balance error does not move between
    1e-9 and 1e-6 on the tests' impulsive load) and, with ``"modified"``, takes two solves a step
    to w/h > 1 on one factor.

    Loads depending on u: :meth:`step` takes an optional ``extra(u) -> (force, stiffness)``, a
    load (a sparse stiffness or None) that joins the residual and the Jacobian: one monolithic
    Newton over the structure and that load.

    Contact (the coupled stepper contract): ``contact``, an object with ``load(u) -> (F, b)``, the
    contact force F [N] on the structure at u and the nodal shape b (n,) of a unit contact force
    there (F·b the nodal loads), and ``solve(u, z) -> F'``, the contact force when the structure
    is at u + F'·z (its scalar contact equation, bracketed). Each iteration condenses the contact
    onto the structure's own linearisation: with J the structure's Jacobian (no contact term),
    d = J⁻¹(r − F·b) the correction without contact force and z = J⁻¹·b its response to a unit
    one (one more back-substitution), the new iterate is u + d + F'·z with F' = ``solve(u + d, z)``.
    Why not the contact's tangent in J: a crushing or flowing law's force goes through the approach
    RATE α̇ = γ/(β·dt)·α + q, so within one step F(w) rises with slopes of 10¹⁰ N/m over nanometres
    and is clipped to zero where the rate turns negative (the end of a crush); Newton on the
    monolithic residual then jumps between the clipped branch (no force, no tangent) and the
    loaded one and never converges, consistent tangent or not. Condensed, the nonsmooth part is
    the scalar equation the contact Newton brackets (:func:`softimpact.fem.impact.newton_contact`),
    J stays the structure's (so ``"modified"`` keeps its factor across contact), and the step
    converges as the structure's own Newton does.
    """

    MODIFIED_RATE = 0.25  # a kept factor must cut the residual at least 4× per iteration

    def __init__(
        self,
        model,
        dt: float,
        C=None,
        params: NewmarkParameters = NewmarkParameters(),
        *,
        rtol: float = 1e-6,
        max_iterations: int = 30,
        tangent: str = "newton",
    ):
        if not (math.isfinite(dt) and dt > 0):
            raise InputError(f"time_step must be positive, got {dt!r}", "time_step")
        if tangent not in ("newton", "modified"):
            raise InputError(f"tangent: {tangent!r} is not 'newton' or 'modified'")
        b, g = params.beta, params.gamma
        self.model, self.dt, self.params, self.C = model, dt, params, C
        self.a0, self.a1, self.a2, self.a3 = 1.0 / (b * dt * dt), g / (b * dt), 1.0 / (b * dt), 1.0 / (2.0 * b) - 1.0
        self.rtol, self.max_iterations, self.tangent_kind = rtol, max_iterations, tangent
        self._lu = None
        self.factorisations = 0
        # K_eff = K + a0 M + a1 C: the linear part of the residual in one product per iteration
        self._keff = (model.K + self.a0 * model.M + (0.0 if C is None else self.a1 * C)).tocsr()

    def _jacobian(self, u, extra_k):
        J = self.model.tangent(u) + self.a0 * self.model.M
        if self.C is not None:
            J = J + self.a1 * self.C
        if extra_k is not None:
            J = J + extra_k
        self.factorisations += 1
        self._lu = _factor(J)

    def initial_acceleration(self, u, v, f):
        """a_0 from M a = f − C v − f_int(u)."""
        rhs = f - self.model.internal_force(u) - (0.0 if self.C is None else self.C @ v)
        if not np.any(rhs):
            return np.zeros_like(rhs)  # at rest and unloaded (an impact's first contact): no factor of M needed
        return _factor_solve(self.model.M, rhs)

    def _finish(self, u1, u, v, a):
        a1 = self.a0 * (u1 - u) - self.a2 * v - self.a3 * a
        return u1, v + self.dt * ((1 - self.params.gamma) * a + self.params.gamma * a1), a1

    def step(self, u, v, a, f1, extra=None, contact=None):
        """(u1, v1, a1, iterations) of one step to the load f1, with ``extra`` and ``contact`` (class docstring)."""
        g, dt = self.params.gamma, self.dt
        M, C, model = self.model.M, self.C, self.model
        u1 = u + dt * v + dt * dt * (0.5 - self.params.beta) * a  # zero new acceleration: the Newmark predictor
        # M a1 + C v1 + K u1 = K_eff u1 − p with p from the step's start (Newmark's a1, v1 are affine in u1)
        ma = M @ a
        p = M @ (self.a0 * u + self.a2 * v) + self.a3 * ma
        if C is not None:
            p = p - C @ (v + dt * (1 - g) * a - dt * g * (self.a0 * u + self.a2 * v + self.a3 * a))
        rhs = f1 + p
        last = scale = np.inf
        for it in range(1, self.max_iterations + 1):
            r = rhs - self._keff @ u1 - model.nonlinear_force(u1)
            ek = None
            if extra is not None:
                fe, ek = extra(u1)
                r = r + fe
            if contact is not None:
                fc, shape = contact.load(u1)
                r = r + fc * shape
            norm = np.linalg.norm(r)
            if it == 1:
                # the forces in balance: load, inertia (at the step's start), the predictor's out-of-balance force
                scale = max(norm, np.linalg.norm(f1), np.linalg.norm(ma), 1e-300)
            elif norm <= self.rtol * scale:
                return self._finish(u1, u, v, a) + (it - 1,)
            if self._lu is None or self.tangent_kind == "newton" or norm > self.MODIFIED_RATE * last:
                self._jacobian(u1, ek)
            last = norm
            du = self._lu.solve(r)
            if contact is not None:
                # the contact condensed on the linearised structure (class docstring): u + d + F'·z
                z = self._lu.solve(shape)
                free = u1 + du - fc * z
                du = free + contact.solve(free, z) * z - u1
            u1 = u1 + du
            if it > 1 and np.linalg.norm(du) <= self.rtol * np.linalg.norm(u1 - u):
                # a correction at round-off of the step's increment (Bathe's displacement criterion): no further force evaluation
                return self._finish(u1, u, v, a) + (it,)
        raise SolverFailed(
            f"the von Karman Newmark–Newton step did not converge in {self.max_iterations} iterations (residual {norm:.3g} N): try a smaller time step"
        )

    def run(self, load, steps: int, rows: np.ndarray | None = None, u0=None, v0=None, energies: bool = True, extra=None) -> DynamicResult:
        """March ``steps`` steps; ``load(t)`` -> force vector (or None for free vibration);
        ``rows`` (k, n) the outputs recorded (default: none); ``energies=False`` skips the
        strain energy (one more pass over the elements per step) and leaves it zero; ``extra``
        as in :meth:`step` (its work is not in ``work``: a conservative ``extra``'s energy is
        the caller's to add)."""
        n = self.model.n
        u = np.zeros(n) if u0 is None else np.asarray(u0, float).copy()
        v = np.zeros(n) if v0 is None else np.asarray(v0, float).copy()
        zero = np.zeros(n)

        def force(t):
            return zero if load is None else np.asarray(load(t), float)

        f = force(0.0)
        a = self.initial_acceleration(u, v, f)
        rows = np.zeros((0, n)) if rows is None else np.atleast_2d(rows)
        t = np.arange(steps + 1) * self.dt
        out = np.zeros((rows.shape[0], steps + 1))
        kin, strain, work, its = np.zeros(steps + 1), np.zeros(steps + 1), np.zeros(steps + 1), np.zeros(steps, int)
        out[:, 0] = rows @ u
        kin[0], strain[0] = 0.5 * v @ (self.model.M @ v), self.model.strain_energy(u)
        for k in range(steps):
            f1 = force(t[k + 1])
            u1, v1, a1, its[k] = self.step(u, v, a, f1, extra)
            work[k + 1] = work[k] + 0.5 * (u1 - u) @ (f + f1)
            u, v, a, f = u1, v1, a1, f1
            out[:, k + 1] = rows @ u
            kin[k + 1] = 0.5 * v @ (self.model.M @ v)
            strain[k + 1] = self.model.strain_energy(u) if energies else 0.0
        return DynamicResult(t, out, kin, strain, work, its, self.factorisations, u, v, a)
