"""Beams stacked through the thickness and tied by cohesive interfaces: quasi-static delamination.

A stack of ``n`` Euler–Bernoulli arms (sublaminates), top first, shares one mesh of nodes along x
[m]. Every arm has three DOFs per node, (u, w, θ): the axial displacement of its mid-plane, the
deflection (up positive) and the slope θ = w'; u is linear and w cubic (Hermite) in an element.
DOF index: ``(arm·n_nodes + node)·3 + component``. Arm k's stiffness is the textbook one,
∫EA u'v' + ∫EI w''v'' (EA, EI per arm, of width b).

Interface k ties arm k (above) to arm k + 1 (below). At x its opening and sliding are

    δ_n = w_k − w_{k+1},   δ_s = u_k + (h_k/2)·w_k' − u_{k+1} + (h_{k+1}/2)·w_{k+1}'

(the axial displacements of the lower face of arm k and the upper face of arm k + 1 under
Euler–Bernoulli kinematics u(z) = u − z·w'). Its virtual work is b∫t·δ(v) dx with the traction t
of a :class:`softimpact.models.cohesive.BilinearCohesive` law, integrated by Gauss–Lobatto points
(``points`` per element, the nodes included: nodal integration damps the traction oscillations of
stiff interfaces, Schellekens & de Borst 1993 — not retrieved; a choice tested here by the
specimen tests). A pre-crack is an interface whose points start fully damaged (d = 1): it carries
only contact (a penalty in closure), no tension or friction.

The interface assembly (:class:`CohesiveInterfaces`) is separate from the specimens: a stacked
impact model can reuse it for its sublaminates (the lead's later step).

Quasi-static solution (:func:`solve_quasistatic`): the load is a force λ along a fixed direction g
(a DOF vector: f_ext = λ·g), and a control c (a DOF vector) whose value cᵀu is raised step by
step: Newton with the consistent tangent on the bordered system

    [K_T   −g] [Δu]   [λ·g − f_int(u)]
    [cᵀ     0] [Δλ] = [c̄ − cᵀu      ],

with cᵀu = c̄ imposed exactly. With c = g this is load-point displacement control; controlling a
crack-tip sliding or opening instead (a local control, which grows monotonically) passes the
snap-backs of unstable specimens. Steps that do not converge are halved.

The specimens (DCB, ENF, MMB) are built in :mod:`softimpact.fem.cohesive_specimens`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse
import scipy.sparse.linalg

from ..errors import InputError, SolverFailed
from ..models.cohesive import BilinearCohesive

__all__ = [
    "Arm",
    "BeamStack",
    "CohesiveInterfaces",
    "Specimen",
    "Curve",
    "dof",
    "beam_stiffness",
    "solve_quasistatic",
]

U, W, T = 0, 1, 2  # components of a node's DOFs


@dataclass(frozen=True)
class Arm:
    """One sublaminate: axial modulus ``E`` [Pa] (the arm's bending modulus, E·I = E·b·h³/12) and ``thickness`` h [m]."""

    E: float
    thickness: float


@dataclass(frozen=True, eq=False)
class BeamStack:
    """Arms (top first) of width ``width`` [m] on nodes ``x`` [m] (increasing), tied by ``law``.

    ``cracked`` (n_arms − 1, n_elements) bool: the elements of each interface that start fully
    damaged (a pre-crack, contact only). ``points`` Gauss–Lobatto points per element on the interface.
    ``closure`` "contact" (the law's: separated faces carry only a compressive penalty) or "tied" (the normal
    penalty holds in tension too and the law sees only the sliding and the closure: faces that never separate,
    frictionless — a mode-II specimen, where the near-zero contact pressure along a closed crack would
    otherwise make Newton chatter between open and closed) or "none" (fully separated faces carry nothing, not
    even contact: a specimen whose crack is held open, where the caller checks that no opening is negative)."""

    x: np.ndarray
    arms: tuple[Arm, ...]
    width: float
    law: BilinearCohesive
    cracked: np.ndarray
    points: int = 3
    closure: str = "contact"

    def __post_init__(self):
        x = np.asarray(self.x, float)
        if x.ndim != 1 or x.size < 2 or np.any(np.diff(x) <= 0):
            raise InputError("x must be increasing node positions, at least two", "x")
        if len(self.arms) < 2:
            raise InputError(f"a stack needs at least two arms, got {len(self.arms)}", "arms")
        if np.shape(self.cracked) != (len(self.arms) - 1, x.size - 1):
            raise InputError(f"cracked must have shape {(len(self.arms) - 1, x.size - 1)}, got {np.shape(self.cracked)}", "cracked")
        if self.closure not in ("contact", "tied", "none"):
            raise InputError(f"closure must be 'contact', 'tied' or 'none', got {self.closure!r}", "closure")
        if self.points not in _LOBATTO:
            raise InputError(f"points must be one of {sorted(_LOBATTO)}, got {self.points!r}", "points")

    @property
    def n_nodes(self) -> int:
        """Nodes along x."""
        return len(self.x)

    @property
    def size(self) -> int:
        """DOFs: 3 per node and arm."""
        return 3 * len(self.arms) * len(self.x)


def dof(stack: BeamStack, arm: int, node: int, component: int) -> int:
    """Global index of ``component`` (0 u, 1 w, 2 θ) of ``node`` of ``arm``."""
    return (arm * stack.n_nodes + node) * 3 + component


def beam_stiffness(stack: BeamStack) -> scipy.sparse.csr_matrix:
    """The arms' linear stiffness (Euler–Bernoulli, axial and bending uncoupled in each arm's mid-plane)."""
    x = np.asarray(stack.x, float)
    Le = np.diff(x)
    n_el = Le.size
    rows, cols, vals = [], [], []
    for a, arm in enumerate(stack.arms):
        b, h = stack.width, arm.thickness
        EA, EI = arm.E * b * h, arm.E * b * h**3 / 12
        ka = EA / Le
        L, L2, L3 = Le, Le**2, Le**3
        kb = EI / L3
        kbend = np.stack(
            [
                np.stack([12 * kb, 6 * L * kb, -12 * kb, 6 * L * kb], -1),
                np.stack([6 * L * kb, 4 * L2 * kb, -6 * L * kb, 2 * L2 * kb], -1),
                np.stack([-12 * kb, -6 * L * kb, 12 * kb, -6 * L * kb], -1),
                np.stack([6 * L * kb, 2 * L2 * kb, -6 * L * kb, 4 * L2 * kb], -1),
            ],
            1,
        )  # (n_el, 4, 4) on (w_i, θ_i, w_j, θ_j)
        base = (a * stack.n_nodes + np.arange(n_el)) * 3
        bdofs = np.stack([base + W, base + T, base + 3 + W, base + 3 + T], -1)
        adofs = np.stack([base + U, base + 3 + U], -1)
        kax = ka[:, None, None] * np.array([[1.0, -1.0], [-1.0, 1.0]])
        for d, k in ((bdofs, kbend), (adofs, kax)):
            rows.append(np.repeat(d, d.shape[1], axis=1).ravel())
            cols.append(np.tile(d, (1, d.shape[1])).ravel())
            vals.append(k.ravel())
    n = stack.size
    return scipy.sparse.coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n)).tocsr()


# Gauss–Lobatto points on [0, 1] and their weights.
_LOBATTO = {
    2: (np.array([0.0, 1.0]), np.array([0.5, 0.5])),
    3: (np.array([0.0, 0.5, 1.0]), np.array([1.0, 4.0, 1.0]) / 6),
    4: (np.array([0.0, 0.5 - np.sqrt(5) / 10, 0.5 + np.sqrt(5) / 10, 1.0]), np.array([1.0, 5.0, 5.0, 1.0]) / 12),
}


@dataclass(frozen=True, eq=False)
class CohesiveInterfaces:
    """The interface part of a stack: the operator from DOFs to (δ_n, δ_s) at every integration point and
    the assembly of its forces and consistent tangent. Built once by :meth:`of`.

    ``B`` (n_int, n_el, n_pts, 2, 12) maps an element's DOFs ``dofs`` (n_int, n_el, 12) — arm above node i,
    node j (u, w, θ each), then arm below likewise — to the opening and sliding; ``weights`` (n_el, n_pts)
    the integration weights times b·L_e [m²]; ``xq`` (n_el, n_pts) the points' positions [m]."""

    stack: BeamStack
    B: np.ndarray
    dofs: np.ndarray
    weights: np.ndarray
    xq: np.ndarray
    _pattern: tuple = field(repr=False, default=())

    @classmethod
    def of(cls, stack: BeamStack) -> CohesiveInterfaces:
        """The interfaces of ``stack``: the operator B at every integration point, the DOF map and the weights."""
        x = np.asarray(stack.x, float)
        Le = np.diff(x)
        n_el = Le.size
        xi, wq = _LOBATTO[stack.points]
        # Hermite shape functions of w (on w_i, θ_i, w_j, θ_j) and their x-derivatives; linear ones of u.
        H = np.stack([1 - 3 * xi**2 + 2 * xi**3, xi - 2 * xi**2 + xi**3, 3 * xi**2 - 2 * xi**3, -(xi**2) + xi**3], -1)  # times (1, L, 1, L)
        dH = np.stack([-6 * xi + 6 * xi**2, 1 - 4 * xi + 3 * xi**2, 6 * xi - 6 * xi**2, -2 * xi + 3 * xi**2], -1)  # times (1/L, 1, 1/L, 1)
        Nu = np.stack([1 - xi, xi], -1)
        L = Le[:, None]
        Hw = np.empty((n_el, xi.size, 4))
        Hw[..., 0], Hw[..., 1], Hw[..., 2], Hw[..., 3] = H[:, 0], H[:, 1] * L, H[:, 2], H[:, 3] * L
        dHw = np.empty((n_el, xi.size, 4))
        dHw[..., 0], dHw[..., 1], dHw[..., 2], dHw[..., 3] = dH[:, 0] / L, dH[:, 1], dH[:, 2] / L, dH[:, 3]
        n_int = len(stack.arms) - 1
        B = np.zeros((n_int, n_el, xi.size, 2, 12))
        dofs = np.empty((n_int, n_el, 12), dtype=np.int64)
        for k in range(n_int):
            hu, hl = stack.arms[k].thickness, stack.arms[k + 1].thickness
            for side, (arm, sign) in enumerate(((k, 1.0), (k + 1, -1.0))):
                o = 6 * side  # (u_i, w_i, θ_i, u_j, w_j, θ_j) of this arm
                wcols = [o + 1, o + 2, o + 4, o + 5]
                B[k, :, :, 0, wcols] = np.moveaxis(sign * Hw, -1, 0)
                half = hu / 2 if side == 0 else hl / 2
                B[k, :, :, 1, [o, o + 3]] = np.moveaxis(sign * np.broadcast_to(Nu, (n_el, xi.size, 2)), -1, 0)
                B[k, :, :, 1, wcols] += np.moveaxis(half * dHw, -1, 0)
                base = (arm * stack.n_nodes + np.arange(n_el)) * 3
                dofs[k, :, 6 * side : 6 * side + 6] = np.stack([base, base + 1, base + 2, base + 3, base + 4, base + 5], -1)
        weights = stack.width * Le[:, None] * wq[None, :]
        xq = x[:-1, None] + Le[:, None] * xi[None, :]
        rows = np.repeat(dofs, 12, axis=-1).ravel()
        cols = np.tile(dofs, (1, 1, 12)).ravel()
        return cls(stack, B, dofs, weights, xq, (rows, cols))

    def initial_damage(self) -> np.ndarray:
        """Damage (n_int, n_el, n_pts): 1 on the pre-cracked elements, 0 elsewhere."""
        d = np.zeros(self.B.shape[:3])
        d[np.asarray(self.stack.cracked, bool)] = 1.0
        return d

    def openings(self, u: np.ndarray) -> np.ndarray:
        """(δ_n, δ_s) [m] at every point, shape (n_int, n_el, n_pts, 2)."""
        return (self.B @ u[self.dofs][:, :, None, :, None])[..., 0]

    def assemble(self, u: np.ndarray, damage: np.ndarray):
        """(f_int, K_T, new damage) of the interfaces at ``u`` from the committed ``damage``."""
        f, ke, d = self.element_arrays(u, damage)
        rows, cols = self._pattern
        n = self.stack.size
        return f, scipy.sparse.coo_matrix((ke.ravel(), (rows, cols)), shape=(n, n)).tocsr(), d

    def element_arrays(self, u: np.ndarray, damage: np.ndarray):
        """(f_int (n_dofs,), element tangents (n_int, n_el, 12, 12) in the order of :attr:`pattern`, new damage)."""
        delta = self.openings(u)
        law = self.stack.law
        if self.stack.closure == "tied":
            opening = delta[..., 0].copy()
            delta[..., 0] = np.minimum(opening, 0.0)
            r = law.traction(delta, damage)
            t, T = r.traction.copy(), r.tangent.copy()
            t[..., 0] += law.K * np.maximum(opening, 0.0)
            T[..., 0, 0] = law.K
            r = type(r)(t, r.damage, T)
        else:
            r = law.traction(delta, damage)
            if self.stack.closure == "none":  # fully separated faces pass through each other
                gone = (r.damage >= 1.0) & (delta[..., 0] < 0)
                if np.any(gone):
                    t, T = r.traction.copy(), r.tangent.copy()
                    t[..., 0] = np.where(gone, 0.0, t[..., 0])
                    T[..., 0, 0] = np.where(gone, 0.0, T[..., 0, 0])
                    r = type(r)(t, r.damage, T)
        w = self.weights[None, :, :, None, None]
        ni, ne, npt = self.B.shape[:3]
        Bf = self.B.reshape(ni, ne, 2 * npt, 12)  # the points' rows stacked: Σ_p B_pᵀ X_p = Bfᵀ Xf
        fe = (np.swapaxes(Bf, -1, -2) @ (w[..., 0] * r.traction).reshape(ni, ne, 2 * npt, 1))[..., 0]
        ke = np.swapaxes(Bf, -1, -2) @ (w * (r.tangent @ self.B)).reshape(ni, ne, 2 * npt, 12)
        f = np.bincount(self.dofs.ravel(), weights=fe.ravel(), minlength=self.stack.size)
        return f, ke, r.damage

    @property
    def pattern(self) -> tuple[np.ndarray, np.ndarray]:
        """(rows, cols) of the raveled element tangents in the global numbering."""
        return self._pattern

    def stored_energy(self, u: np.ndarray, damage: np.ndarray) -> float:
        """Recoverable energy in the interfaces [J]."""
        delta = self.openings(u)
        e = self.stack.law.stored_energy(delta, damage)
        if self.stack.closure == "tied":  # the tie's tension is elastic whatever the damage
            e = e + 0.5 * self.stack.law.K * np.asarray(damage) * np.maximum(delta[..., 0], 0.0) ** 2
        return float(np.sum(e * self.weights[None]))


@dataclass(frozen=True, eq=False)
class Specimen:
    """A stack with its supports and loading: ``fixed`` DOFs held at zero; the load f_ext = λ·``load``;
    ``control`` the DOF vector whose value is raised (default: ``load``, the load-point displacement);
    ``name`` for messages."""

    stack: BeamStack
    fixed: np.ndarray
    load: np.ndarray
    control: np.ndarray
    name: str = "specimen"


@dataclass(frozen=True)
class Curve:
    """A quasi-static path: the load-point displacement ``displacement`` = gᵀu [m] (work-conjugate to the force),
    the ``force`` λ [N], the ``control`` value [m], the ``external_work`` [J], the interfaces' ``stored``
    (recoverable) energy and the arms' ``strain_energy`` [J], the ``crack_tip`` x [m] (the first interface's
    last fully damaged point), the ``process_zone`` length [m] (its points with 0 < d < 1) and
    ``elements_in_zone`` (that length over the element size), each (n_steps,); ``newton`` the iterations of
    each step; ``damage`` the final damage (n_int, n_el, n_pts); ``u`` the final DOFs; ``min_separated_opening`` the smallest
    opening [m] of a fully separated point over the path (negative: the faces interpenetrated)."""

    displacement: np.ndarray
    force: np.ndarray
    control: np.ndarray
    external_work: np.ndarray
    stored: np.ndarray
    strain_energy: np.ndarray
    crack_tip: np.ndarray
    process_zone: np.ndarray
    elements_in_zone: np.ndarray
    newton: np.ndarray
    damage: np.ndarray
    u: np.ndarray
    min_separated_opening: float = 0.0

    @property
    def dissipated(self) -> np.ndarray:
        """External work minus the recoverable energy [J] (the energy the interfaces dissipated)."""
        return self.external_work - self.stored - self.strain_energy


NEWTON_MAX = 30  # iterations before a step is halved
NEWTON_TOL = 1e-7  # residual norm relative to the largest of the load and the internal force
STEP_TOL = 1e-10  # a full Newton correction below this fraction of |u|: converged (the round-off floor)
LINE_SEARCH_AFTER = 8  # plain Newton iterations before the backtracking starts
LINE_SEARCH_MIN = 1.0 / 16  # smallest fraction of a Newton step the backtracking tries
ROUNDOFF = 1e-12  # the beams' force's round-off floor relative to |K0|·|u| (about 10⁴ ε: sums of ~10 terms, an n_dof-long norm)
MIN_STEP_FRACTION = 1.0 / 1024  # of the requested control increment: below it the solver gives up


class _Bordered:
    """The bordered Newton system of a specimen (module docstring) in the free numbering: the beams' stiffness and
    the bordering entries are fixed, the interfaces' tangent changes every iteration. ``c`` is oriented so that
    raising the control loads the specimen (λ > 0 on the initial tangent): a local control (a crack-tip sliding)
    has no obvious sign."""

    def __init__(self, spec: Specimen):
        stack = spec.stack
        self.spec = spec
        self.K0 = beam_stiffness(stack)
        self.ifc = ifc = CohesiveInterfaces.of(stack)
        self.n = n = stack.size
        free = np.ones(n, bool)
        free[np.asarray(spec.fixed, int)] = False
        self.idx = idx = np.flatnonzero(free)
        self.g = g = np.asarray(spec.load, float)[idx]
        c = np.asarray(spec.control, float)[idx]
        self.K0f = K0f = self.K0[idx][:, idx]
        self.K0f_abs = abs(K0f)  # |K0|: the round-off floor of the beams' force |K0|·|u|·ε (residual)
        self.nf = nf = idx.size
        # The bordered matrix [[K0 + K_i, −g], [cᵀ, 0]] as coo triplets.
        red = np.full(n, -1)
        red[idx] = np.arange(nf)
        K0c = K0f.tocoo()
        ri, ci = (red[p] for p in ifc.pattern)
        self.keep = keep = (ri >= 0) & (ci >= 0)
        gi, ck = np.flatnonzero(g), np.flatnonzero(c)
        self.rows = np.concatenate([K0c.row, ri[keep], gi, np.full(ck.size, nf)])
        self.cols = np.concatenate([K0c.col, ci[keep], np.full(gi.size, nf), ck])
        _, ke0, _ = ifc.element_arrays(np.zeros(n), ifc.initial_damage())
        K_init = (K0f + scipy.sparse.coo_matrix((ke0.ravel()[keep], (ri[keep], ci[keep])), shape=(nf, nf))).tocsc()
        if c @ scipy.sparse.linalg.spsolve(K_init, g) < 0:
            c = -c
        self.c = c
        self.fixed_vals = (K0c.data, -g[gi], c[ck])

    def full(self, uf: np.ndarray) -> np.ndarray:
        """The DOF vector (n,) of the free values ``uf``, zero on the fixed DOFs."""
        u = np.zeros(self.n)
        u[self.idx] = uf
        return u

    def residual(self, uf, lam, dmg_old):
        """(residual of the free equations, the interfaces' tangent values, the new damage, the residual's scale)."""
        fi, ke, d_new = self.ifc.element_arrays(self.full(uf), dmg_old)
        fb = self.K0f @ uf
        r = lam * self.g - (fb + fi[self.idx])
        # The residual's round-off floor: the beams' and the interfaces' forces cancel to the load, and each entry of
        # the beams' force K0·u is a sum of terms |K0|·|u| far larger than it on fine elements (EI/L_e³ grows as
        # L_e⁻³): their round-off, ε·|K0|·|u|, sits above NEWTON_TOL·|K0·u| once L_e is a few hundredths of h.
        floor = ROUNDOFF / NEWTON_TOL * np.linalg.norm(self.K0f_abs @ np.abs(uf))
        scale = max(abs(lam) * np.linalg.norm(self.g), np.linalg.norm(fb), np.linalg.norm(fi), floor, 1e-30)
        return r, ke.ravel()[self.keep], d_new, scale

    def newton(self, uf, lam, trial, dmg):
        """Newton from (``uf``, ``lam``) to the control value ``trial`` with the committed damage ``dmg``:
        (converged, uf, λ, damage at uf, iterations, residual norm)."""
        c, nf = self.c, self.nf
        r, Ki, d_new, scale = self.residual(uf, lam, dmg)
        iters = 0
        for it in range(NEWTON_MAX):
            rc = trial - c @ uf
            if np.linalg.norm(r) <= NEWTON_TOL * scale and abs(rc) <= NEWTON_TOL * max(abs(trial), 1e-30):
                return True, uf, lam, d_new, iters, np.linalg.norm(r)
            vals = np.concatenate([self.fixed_vals[0], Ki, self.fixed_vals[1], self.fixed_vals[2]])
            A = scipy.sparse.csc_matrix((vals, (self.rows, self.cols)), shape=(nf + 1, nf + 1))
            sol = scipy.sparse.linalg.spsolve(A, np.concatenate([r, [rc]]))
            # Backtracking on the residual norm after LINE_SEARCH_AFTER plain iterations: the damage front switches
            # points between loading and elastic unloading, and full Newton steps can cycle between the two (seen
            # at a coarse DCB's onset); plain Newton is faster when it converges. A partial step leaves part of
            # the (linear) control constraint to the next iteration.
            r0 = np.linalg.norm(r)
            alpha = 1.0
            while True:
                u_try, lam_try = uf + alpha * sol[:-1], lam + alpha * sol[-1]
                r_try, Ki_try, d_try, scale_try = self.residual(u_try, lam_try, dmg)
                if it < LINE_SEARCH_AFTER or np.linalg.norm(r_try) < r0 or alpha <= LINE_SEARCH_MIN:
                    break
                alpha /= 2
            uf, lam, r, Ki, d_new, scale = u_try, lam_try, r_try, Ki_try, d_try, scale_try
            iters += 1
            # The penalty makes the residual's round-off floor K_penalty·|u|·ε, far above ε·|f| at small loads:
            # a full Newton step that no longer moves u is converged too.
            if alpha == 1.0 and np.linalg.norm(sol[:-1]) <= STEP_TOL * np.linalg.norm(uf):
                return True, uf, lam, d_new, iters, np.linalg.norm(r)
        return False, uf, lam, d_new, iters, np.linalg.norm(r)


@dataclass
class _Path:
    """The committed state of a quasi-static path: DOFs ``u``, force ``lam``, damage ``dmg``, control value ``cbar``,
    the external work so far and the load-point displacement at the last commit."""

    u: np.ndarray
    dmg: np.ndarray
    lam: float = 0.0
    cbar: float = 0.0
    work: float = 0.0
    disp: float = 0.0


def _advance(system: _Bordered, path: _Path, target: float) -> int:
    """Raise ``path``'s control to ``target``, halving a step that fails (down to MIN_STEP_FRACTION of the
    increment, then :class:`SolverFailed`) and doubling after a success; returns the Newton iterations spent."""
    remaining = target - path.cbar
    step = remaining
    iters = 0
    load = np.asarray(system.spec.load, float)
    while abs(target - path.cbar) > 1e-15 * max(1.0, abs(target)):
        trial = path.cbar + step if abs(step) < abs(target - path.cbar) else target
        ok, uf, lam, d_new, it, rnorm = system.newton(path.u[system.idx].copy(), path.lam, trial, path.dmg)
        iters += it
        if not ok:
            step = (trial - path.cbar) / 2
            if abs(step) < MIN_STEP_FRACTION * abs(remaining):
                raise SolverFailed(f"{system.spec.name}: Newton did not converge at control {trial:.6g} m (residual {rnorm:.3g} N)")
            continue
        path.u = system.full(uf)
        path.dmg = d_new  # the damage at the converged u: committed
        disp = float(load @ path.u)
        path.work += 0.5 * (lam + path.lam) * (disp - path.disp)
        path.lam, path.disp, path.cbar = lam, disp, trial
        step = min(abs(step) * 2, abs(remaining)) * np.sign(remaining)
    return iters


def _crack_measures(stack: BeamStack, ifc: CohesiveInterfaces, dmg: np.ndarray) -> tuple[float, float, float]:
    """(crack tip x [m], process-zone length [m], that length in elements) of the first interface."""
    Le = np.diff(np.asarray(stack.x, float))
    d0 = dmg[0].ravel()
    xq = ifc.xq.ravel()
    full = xq[d0 >= 1.0]
    tip = float(full.max()) if full.size else float(stack.x[0])
    zone_pts = xq[(d0 > 0) & (d0 < 1.0)]
    zone = float(zone_pts.max() - zone_pts.min()) if zone_pts.size > 1 else 0.0
    el = np.searchsorted(stack.x, zone_pts.mean()) - 1 if zone_pts.size else 0
    return tip, zone, zone / Le[min(max(el, 0), Le.size - 1)]


def solve_quasistatic(spec: Specimen, targets) -> Curve:
    """Raise the control to each of ``targets`` [m] in turn (Newton on the bordered system, module docstring);
    returns the :class:`Curve` at the targets. A step that fails to converge is split in halves, down to
    1/1024 of it, then :class:`SolverFailed`."""
    system = _Bordered(spec)
    ifc = system.ifc
    path = _Path(u=np.zeros(system.n), dmg=ifc.initial_damage())
    out = {k: [] for k in ("disp", "force", "ctrl", "work", "stored", "strain", "tip", "zone", "nz", "newton")}
    min_sep = np.inf
    for target in np.asarray(targets, float):
        iters = _advance(system, path, target)
        u, dmg = path.u, path.dmg
        tip, zone, nz = _crack_measures(spec.stack, ifc, dmg)
        out["disp"].append(float(np.asarray(spec.load, float) @ u))
        out["force"].append(path.lam)
        out["ctrl"].append(path.cbar)
        out["work"].append(path.work)
        out["stored"].append(ifc.stored_energy(u, dmg))
        out["strain"].append(0.5 * float(u @ (system.K0 @ u)))
        out["tip"].append(tip)
        out["zone"].append(zone)
        out["nz"].append(nz)
        out["newton"].append(iters)
        sep = ifc.openings(u)[..., 0][dmg >= 1.0]
        min_sep = min(min_sep, float(sep.min())) if sep.size else min_sep
    a = {k: np.asarray(v) for k, v in out.items()}
    min_sep = min_sep if np.isfinite(min_sep) else float("nan")  # nothing separated
    return Curve(a["disp"], a["force"], a["ctrl"], a["work"], a["stored"], a["strain"], a["tip"], a["zone"], a["nz"], a["newton"], path.dmg, path.u, min_sep)
