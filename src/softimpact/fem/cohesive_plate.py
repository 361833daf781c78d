"""Sublaminates tied by cohesive interfaces: delamination that grows in a plate struck by an impactor.

The laminate (plies top first) is split below chosen plies into sublaminates, each an FSDT plate of
:mod:`softimpact.fem.plate` on the same mesh with its in-plane DOFs kept (u, v, w, φx, φy per node) and its
own section about its own mid-plane (:func:`softimpact.models.plate_laminate.plate_section` of its plies: a
sublaminate of a symmetric laminate is in general unsymmetric, B ≠ 0). The sublaminates are *linear*
(small deflection): the only nonlinearity is the interfaces'. Interface j ties the lower face of sublaminate
j (upper) to the upper face of sublaminate j + 1 (lower), t_j and t_{j+1} their thicknesses, through the
relative displacement at every node p (in-plane displacement at height z is u + z·φ, :mod:`~softimpact.fem.plate`):

    δ_n  = w_j − w_{j+1}                                       (opening, + when the faces separate),
    δ_sx = (u_j − t_j/2·φx_j) − (u_{j+1} + t_{j+1}/2·φx_{j+1}),  δ_sy likewise with v, φy,

a linear map δ = G·d of the stacked DOFs d. The traction is the bilinear mixed-mode law of
:mod:`softimpact.models.cohesive` (penalty K, quadratic onset, Benzeggagh–Kenane propagation, damage
irreversible), integrated at the nodes with their tributary areas a_p (the Newton–Cotes rule of the element's
nodes: trapezoid for MITC4, Simpson for MITC9, tensor products over the rectangles; the nodal, "lumped"
integration that avoids the traction oscillations of Gauss-integrated stiff interfaces — the usual choice,
its published comparison not retrieved here). The interface energy is Σ_p a_p·φ(δ_p, d_p), its force and
tangent

    f_c = Gᵀ (a ⊙ t(δ)),    K_c = Gᵀ diag(a_p ∂t/∂δ|_p) G.

The stack is one :class:`~softimpact.fem.nonlinear.NonlinearModel` for the one nonlinear engine
(:class:`softimpact.fem.nonlinear.NonlinearNewmark`: here K the sublaminates' block-diagonal stiffness (DOFs numbered
node by node) and the "nonlinear" force the interfaces'), with the damage held at its committed value within a
step and updated after it (:meth:`CohesivePlate.commit`: the law's max(committed, d(δ)), so damage never heals). The damage thus
lags one step (an error of order dt in when a point softens); in exchange a step is piecewise linear (the
interfaces' stiffness changes only where a damaged face closes) and its Newton iterations converge, where the
implicit update (the law's damage inside the iterations, with its softening tangent) made the iterations of
a coarse mesh cycle between loading and unloading points and fail.

Closure within a step: a damaged face in compression carries the undamaged penalty K, open it carries (1 − d)·K, a
kink at δ_n = 0 between which Newton cycled once much of an interface softened (Turon's strengths: the residual stalled
at 1e-4 of the step's forces). The one engine therefore freezes each point's closure for a step's Newton iterations
(:meth:`CohesivePlate.freeze`: the interface is then linear at the held damage), and re-solves the step from its
answer with the sets updated while any damaged point's converged opening contradicts its set (:meth:`release`): the
accepted step satisfies the law as it is.

Energies, each from the state: the interfaces store φ(δ, d) (:meth:`CohesivePlate.stored_energy`); within a step
(damage fixed) their force is the gradient of that potential, and the commit that raises the damage from d_n to
d_{n+1} at the converged opening δ releases φ(δ, d_n) − φ(δ, d_{n+1}) = ½K(<δ_n>² + |δ_s|²)(d_{n+1} − d_n) per
unit area: the fracture energy dissipated (:meth:`CohesivePlate.dissipated_energy`), summed over the commits. With
average acceleration (β = ¼, γ = ½) kinetic + ½uᵀKu + stored + dissipated then equals the external work up to
the trapezoidal rule's error on the interfaces' kinks (a check that can fail: tests/test_cohesive_plate.py).
The coupled stepper (:class:`~softimpact.fem.vk_stepping.VonKarmanStepper`, as for every nonlinear plate) records
the delaminated (d = 1) and process-zone (0 < d < 1) areas and the interface energies (:meth:`CohesivePlate.history`)
as extra output rows.

Validity: linear sublaminates (small deflection, no contact between delaminated faces other than the
penalty in closure, which the law keeps undamaged), rate-independent interfaces; the process zone must span
a few nodes for the growth to be mesh-independent (the damage map shows the zone's width).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import scipy.sparse

from ..errors import InputError
from ..models.cohesive import BilinearCohesive
from ..models.laminate import Stack
from ..models.plate_laminate import plate_section
from .nonlinear import NonlinearModel
from .plate import PHI_X, PHI_Y, Plate, U, V, W
from .plate_vk import PlateVK

__all__ = ["CohesivePlate", "nodal_areas", "HISTORY_ROWS"]

HISTORY_ROWS = ("delaminated_area_m2", "process_zone_area_m2", "cohesive_stored_energy_J", "fracture_energy_dissipated_J")
"""The scalars a :class:`CohesivePlate` records every step (:meth:`CohesivePlate.history`), summed over the interfaces (then the areas per interface)."""


def nodal_areas(fe, elements: np.ndarray | None = None) -> np.ndarray:
    """Tributary area [m²] of every node of a PlateFE's mesh (numbered ``fe.grid_node``): the tensor product of
    the 1-D Newton–Cotes weights of the element's nodes (trapezoid for order 1, Simpson for order 2), summed over
    the elements (all, or those of the (nx, ny) bool mask ``elements``); they sum to the elements' area."""
    rules = {1: np.array([0.5, 0.5]), 2: np.array([1.0, 4.0, 1.0]) / 6.0}
    rule, p = rules[fe.order], fe.order
    mask = np.ones((fe.xs.size - 1, fe.ys.size - 1), bool) if elements is None else np.asarray(elements, bool)
    hx, hy = np.diff(fe.xs), np.diff(fe.ys)
    area = np.zeros(fe.grid_node.size)
    local = np.outer(rule, rule)  # (p + 1, p + 1) weights on the unit square
    for i, j in zip(*np.nonzero(mask)):
        nodes = fe.grid_node[p * i : p * i + p + 1, p * j : p * j + p + 1]
        area[nodes.ravel()] += (local * hx[i] * hy[j]).ravel()
    return area


class CohesivePlate(NonlinearModel):
    """The plate of ``plate`` (its mesh, supports, element; its section is replaced) with the laminate ``stack``
    split below the plies ``splits`` (1 = the top ply: 3 splits between plies 3 and 4) into sublaminates tied by
    ``law`` (module docstring), sublaminates top first, each with ``in_plane`` edges
    (:class:`~softimpact.fem.plate_vk.PlateVK`: ``"movable"`` is the whole laminate's simple support).

    ``near`` (an (nx, ny) bool mask of the mesh's elements, or None for all) confines the stack to a near field: the
    far field is one plate of the whole laminate (its linear FSDT section: the interfaces there stay intact and the
    skin linear), tied to the stack along the near field's rim, where every sublaminate moves with the laminate's
    normal, u_k = u + z_k·φx, v_k = v + z_k·φy, w_k = w, φ_k = φ (z_k the sublaminate's mid-plane above the
    laminate's): a master–slave elimination, so the stacked DOFs (5 per sublaminate) exist only where damage can
    run and the far field costs 5 DOFs a node. The near field may reach a symmetry edge (each sublaminate mirrored as
    the laminate is), no other supported edge.

    The DOFs are numbered node by node (a node's far-field and sublaminate DOFs together: the interfaces couple a
    node's sublaminates; the layer-major order would make the band a whole sublaminate wide). ``T[k]`` maps them to
    sublaminate k's own free DOFs (:meth:`layer_vector`), ``K``, ``M`` the sublaminates' and the far field's
    assembled through them (no interface); ``damage`` (interfaces, nodes): the committed damage; ``area`` (nodes,):
    the nodes' tributary areas within the near field."""

    def __init__(self, plate: Plate, stack: Stack, splits, law: BilinearCohesive, in_plane: str = "movable", near: np.ndarray | None = None):
        n_ply = len(stack.angles)
        splits = tuple(int(k) for k in splits)
        if not splits or list(splits) != sorted(set(splits)) or splits[0] < 1 or splits[-1] >= n_ply:
            raise InputError(f"cohesive interfaces: plies {splits!r} must increase strictly from 1 to {n_ply - 1} (an interface lies below each)")
        if not isinstance(law, BilinearCohesive):
            raise InputError(f"cohesive interfaces: the law must be a BilinearCohesive, got {type(law).__name__}")
        self.plate, self.stack, self.splits, self.law = plate, stack, splits, law
        bounds = (0, *splits, n_ply)
        self.stacks = tuple(Stack(stack.ply, tuple(stack.angles[a:b])) for a, b in zip(bounds[:-1], bounds[1:]))
        self.thicknesses = tuple(s.thickness for s in self.stacks)
        tops = stack.thickness / 2 - np.concatenate(([0.0], np.cumsum(self.thicknesses)[:-1]))
        self.z = tuple(float(t - h / 2) for t, h in zip(tops, self.thicknesses))  # sublaminates' mid-planes above the laminate's
        shape = (len(plate.grid()[0]) - 1, len(plate.grid()[1]) - 1)
        self.near = np.ones(shape, bool) if near is None else np.asarray(near, bool)
        if self.near.shape != shape or not self.near.any():
            raise InputError(f"cohesive near field: expected a non-empty ({shape[0]}, {shape[1]}) element mask, got shape {self.near.shape}")
        zoned = not self.near.all()
        # a zoned stack keeps the plate's mirror planes (each sublaminate is mirrored as the laminate is); any other
        # support is the far field's (a near field reaching one is refused: _check_interior)
        own = tuple(k if (k == "symmetry" or not zoned) else "free" for k in plate.supports)
        self.layers = tuple(PlateVK(replace(plate, section=plate_section(s), membrane=True, supports=own), in_plane, elements=self.near) for s in self.stacks)
        self.far = PlateVK(replace(plate, membrane=True), in_plane, elements=~self.near) if zoned else None
        fe = self.layers[0].fe
        self.nodes = fe.grid_node.size
        near_nodes = fe.touched_nodes()
        far_nodes = self.far.fe.touched_nodes() if zoned else np.zeros(self.nodes, bool)
        self.rim = near_nodes & far_nodes  # nodes where the stack is slaved to the far field
        if zoned:
            self._check_interior(near_nodes)
        self._number(near_nodes)
        self.area = nodal_areas(fe, self.near)
        self.G = (self._interface_operator() @ self._T).tocsr()
        self.interfaces = len(splits)
        self._a = np.tile(self.area, self.interfaces)  # per interface point (interface-major)
        self.history_names = HISTORY_ROWS + tuple(f"{q}_{j}" for q in HISTORY_ROWS[:2] for j in range(self.interfaces))
        self.reset()

    def _check_interior(self, near_nodes: np.ndarray) -> None:
        """A near field touching a supported edge would need the edge's conditions on every sublaminate: refused."""
        fe = self.layers[0].fe
        for edge, kind in zip(("x0", "x1", "y0", "y1"), self.plate.supports):
            if kind not in ("free", "symmetry") and np.any(near_nodes[fe.edge_nodes(edge)]):
                raise InputError(f"cohesive near field: it reaches the {kind} edge {edge}; keep it inside the plate (a smaller near field or a larger plate)")

    def _number(self, near_nodes: np.ndarray) -> None:
        """The global DOFs (node by node), ``T`` per sublaminate, the stacked operator ``_T`` and K, M."""
        lays, far = self.layers, self.far
        # candidate DOFs: the far field's free DOFs, then each sublaminate's free DOFs off the rim
        keys = []  # (node, layer (−1: far), component) per global DOF
        if far is not None:
            keys.append(np.stack([far.free // 5, np.full(far.n, -1), far.free % 5], 1))
        owned = []
        for k, lay in enumerate(lays):
            own = ~self.rim[lay.free // 5]
            owned.append(own)
            keys.append(np.stack([lay.free[own] // 5, np.full(own.sum(), k), lay.free[own] % 5], 1))
        keys = np.concatenate(keys)
        order = np.lexsort((keys[:, 2], keys[:, 1], keys[:, 0]))  # node, then layer (far first), then component
        self.n = n = keys.shape[0]
        position = np.empty(n, int)
        position[order] = np.arange(n)  # candidate index → global DOF
        offset = 0
        if far is not None:
            self._far_dofs = position[: far.n]
            offset = far.n
            far_index = np.full(far.fe.basis.N, -1)
            far_index[far.free] = self._far_dofs
        T = []
        for k, (lay, own) in enumerate(zip(lays, owned)):
            rows, cols, vals = [], [], []
            mine = np.flatnonzero(own)
            rows.append(mine)
            cols.append(position[offset : offset + mine.size])
            vals.append(np.ones(mine.size))
            offset += mine.size
            slaved = np.flatnonzero(~own)
            if slaved.size:  # rim DOFs: the laminate's normal (class docstring)
                node, comp = lay.free[slaved] // 5, lay.free[slaved] % 5
                nd = far.fe.basis.nodal_dofs
                for c, terms in (
                    (U, ((U, 1.0), (PHI_X, self.z[k]))),
                    (V, ((V, 1.0), (PHI_Y, self.z[k]))),
                    (W, ((W, 1.0),)),
                    (PHI_X, ((PHI_X, 1.0),)),
                    (PHI_Y, ((PHI_Y, 1.0),)),
                ):
                    sel = comp == c
                    for master, weight in terms:
                        g = far_index[nd[master, node[sel]]]
                        keep = g >= 0  # a master fixed by a support carries nothing (refused for the near field's rim anyway)
                        rows.append(slaved[sel][keep])
                        cols.append(g[keep])
                        vals.append(np.full(keep.sum(), weight))
            T.append(scipy.sparse.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(lay.n, n)))
        self.T = tuple(T)
        self._T = scipy.sparse.vstack(T).tocsr()  # the layer-major stacked DOFs from the global ones
        self.offsets = tuple(int(o) for o in np.concatenate(([0], np.cumsum([lay.n for lay in lays])[:-1])))
        self._stacked_n = sum(lay.n for lay in lays)
        K = sum((t.T @ lay.K @ t for t, lay in zip(T, lays)), scipy.sparse.csr_matrix((n, n)))
        M = sum((t.T @ lay.M @ t for t, lay in zip(T, lays)), scipy.sparse.csr_matrix((n, n)))
        if far is not None:
            E = scipy.sparse.csr_matrix((np.ones(far.n), (np.arange(far.n), self._far_dofs)), shape=(far.n, n))
            self._E = E
            K, M = K + E.T @ far.K @ E, M + E.T @ far.M @ E
        self.K, self.M = K.tocsr(), M.tocsr()

    # ---- the interfaces' kinematics -------------------------------------------------------
    def _global(self, layer: int, component: int) -> np.ndarray:
        """The layer-major stacked DOF of ``component`` at every node of sublaminate ``layer`` (−1 where fixed)."""
        lay = self.layers[layer]
        local = lay._index[lay.fe.basis.nodal_dofs[component]]
        return np.where(local >= 0, local + self.offsets[layer], -1)

    def _interface_operator(self) -> scipy.sparse.csr_matrix:
        """G (3·nodes·interfaces, stacked DOFs): rows (opening, sliding x, sliding y) per node, interface-major, over the
        sublaminates' own DOFs, layer-major (module docstring); :attr:`G` is it composed with the global-to-stacked map."""
        rows, cols, vals = [], [], []
        nn = self.nodes
        p = np.arange(nn)
        for j in range(len(self.splits)):
            up, lo = j, j + 1
            base = 3 * (j * nn + p)
            half_up, half_lo = self.thicknesses[up] / 2, self.thicknesses[lo] / 2
            terms = [
                (0, up, W, 1.0),
                (0, lo, W, -1.0),
                (1, up, U, 1.0),
                (1, up, PHI_X, -half_up),
                (1, lo, U, -1.0),
                (1, lo, PHI_X, -half_lo),
                (2, up, V, 1.0),
                (2, up, PHI_Y, -half_up),
                (2, lo, V, -1.0),
                (2, lo, PHI_Y, -half_lo),
            ]
            for row, layer, comp, value in terms:
                dof = self._global(layer, comp)
                keep = dof >= 0
                rows.append(base[keep] + row)
                cols.append(dof[keep])
                vals.append(np.full(keep.sum(), value))
        shape = (3 * nn * len(self.splits), self._stacked_n)
        return scipy.sparse.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=shape)

    def opening(self, u: np.ndarray) -> np.ndarray:
        """δ (interfaces·nodes, 3) [m]: opening, sliding x, sliding y at every node of every interface."""
        return (self.G @ u).reshape(-1, 3)

    # ---- force, tangent, energies (the model VonKarmanNewmark steps) ----------------------------------
    def _response(self, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(traction (points, 3) [Pa], its tangent (points, 3, 3) [N/m³]) at ``u`` with the committed damage held
        fixed (the law's traction at that damage: (1 − d)·K on the active part, K in closure); while a step's closure
        sets are frozen (:meth:`freeze`), each point closed or open as its set says instead of by its opening's sign."""
        delta = self.opening(u)
        d = self.damage.ravel()
        K = self.law.K
        dn = delta[:, 0]
        closed = dn < 0.0 if self._closed is None else self._closed
        t = np.empty_like(delta)
        t[:, 0] = np.where(closed, K, (1 - d) * K) * dn
        t[:, 1:] = ((1 - d) * K)[:, None] * delta[:, 1:]
        T = np.zeros(delta.shape + (3,))
        T[:, 0, 0] = np.where(closed, K, (1 - d) * K)
        T[:, 1, 1] = T[:, 2, 2] = (1 - d) * K
        return t, T

    # ---- the closure sets of a step (the one engine's freeze/release: module docstring) ----------------------
    def freeze(self, u: np.ndarray) -> None:
        """Fix each interface point's closure (closed where δ_n < 0 at ``u``) for the step's Newton iterations."""
        self._closed = self.opening(u)[:, 0] < 0.0

    def release(self, u: np.ndarray) -> int:
        """The damaged points whose closure at the converged ``u`` differs from the frozen one (their sets updated to
        ``u``'s): 0 when the step's solution satisfies the law as it stands."""
        now = self.opening(u)[:, 0] < 0.0
        flips = int(np.count_nonzero((now != self._closed) & (self.damage.ravel() > 0.0)))
        self._closed = now
        return flips

    def thaw(self) -> None:
        """Back to closure by the opening's sign (outside a step)."""
        self._closed = None

    def nonlinear_force(self, u: np.ndarray) -> np.ndarray:
        """f_c(u) = Gᵀ(a ⊙ t(δ)) [N] at the committed damage."""
        t = self._response(u)[0]
        return self.G.T @ (self._a[:, None] * t).ravel()

    def internal_force(self, u: np.ndarray) -> np.ndarray:
        """K u + f_c(u) [N]."""
        return self.K @ u + self.nonlinear_force(u)

    def row_stiffness(self, u: np.ndarray) -> np.ndarray:
        """a_p ∂t/∂δ per row of :attr:`G` [N/m] at the committed damage: the law's tangent is diagonal in (opening,
        sliding x, sliding y) with the damage held, so the interfaces' tangent is Gᵀ diag(this) G."""
        T = self._response(u)[1]
        return (np.einsum("pii->pi", T) * self._a[:, None]).ravel()

    @property
    def row_operator(self) -> scipy.sparse.csr_matrix:
        """:attr:`G`: the rows of :meth:`row_stiffness` (the one engine updates a kept factor where they changed)."""
        return self.G

    def tangent(self, u: np.ndarray) -> scipy.sparse.csr_matrix:
        """K + Gᵀ diag(a ∂t/∂δ) G at the committed damage (positive semi-definite interfaces: no softening within a step)."""
        return (self.K + self.G.T @ scipy.sparse.diags(self.row_stiffness(u)) @ self.G).tocsr()

    def stored_energy(self, u: np.ndarray) -> float:
        """The interfaces' recoverable energy Σ a_p φ(δ_p, d_p) [J] at the committed damage."""
        return float(self._a @ self.law.stored_energy(self.opening(u), self.damage.ravel()))

    def strain_energy(self, u: np.ndarray) -> float:
        """½uᵀKu + the interfaces' stored energy [J] (the recoverable part: what the dissipated energy is not)."""
        return 0.5 * float(u @ (self.K @ u)) + self.stored_energy(u)

    LAGGED_STATE = True  # the damage is held within a step and raised after it (module docstring)
    LINEAR_WITHIN_STEP = True  # damage held and closure frozen: the interfaces (and the linear sublaminates) are linear in a step

    def commit(self, u: np.ndarray, dt: float | None = None) -> None:
        """Store the damage of the converged state ``u`` (irreversible: it never decreases) and count the fracture
        energy its rise releases at that opening (module docstring)."""
        delta = self.opening(u)
        before = self.damage.ravel()
        after = self.law.traction(delta, before).damage
        released = self.law.stored_energy(delta, before) - self.law.stored_energy(delta, after)
        self._dissipated += float(self._a @ released)
        self.damage = after.reshape(self.interfaces, self.nodes)

    def reset(self) -> None:
        """Undamaged interfaces (a new run on the same model)."""
        self.damage = self.law.initial_damage((self.interfaces, self.nodes))
        self._closed = None
        self._dissipated = 0.0

    def dissipated_energy(self) -> float:
        """The fracture energy the interfaces dissipated so far [J] (module docstring)."""
        return self._dissipated

    def history(self, u: np.ndarray) -> np.ndarray:
        """:attr:`history_names` at ``u``: the delaminated and process-zone areas [m²], the interfaces' stored and
        dissipated energies [J], then the two areas per interface."""
        cracked, zone = self.areas()
        return np.concatenate(([cracked.sum(), zone.sum(), self.stored_energy(u), self._dissipated], cracked, zone))

    def areas(self) -> tuple[np.ndarray, np.ndarray]:
        """(delaminated d = 1, process zone 0 < d < 1) area [m²] per interface, of this (possibly partial) model."""
        d = self.damage
        return (d >= 1.0) @ self.area, ((d > 0.0) & (d < 1.0)) @ self.area

    # ---- rows ----------------------------------------------------------------------------------
    def layer_vector(self, layer: int, u: np.ndarray) -> np.ndarray:
        """Sublaminate ``layer``'s own free DOFs of the global vector(s) ``u`` (time on the last axis)."""
        return self.T[layer] @ u

    def layer_dofs(self, layer: int) -> np.ndarray:
        """The global DOF of each of sublaminate ``layer``'s free DOFs (in its own order), −1 where slaved at the rim."""
        t = self.T[layer].tocsr()
        lay = self.layers[layer]
        own = ~self.rim[lay.free // 5]  # off the rim every row holds the one global DOF it is
        out = np.full(t.shape[0], -1)
        out[own] = t.indices[t.indptr[:-1][own]]
        return out

    def layer_row(self, layer: int, row: np.ndarray) -> np.ndarray:
        """A row over sublaminate ``layer``'s free DOFs as a row over the global DOFs."""
        return np.asarray(self.T[layer].T @ row).ravel()

    def in_near_field(self, x: float, y: float) -> bool:
        """(x, y) lies in an element of the near field."""
        fe = self.layers[0].fe
        return any(self.near[i, j] for i, j, _, _ in fe._locate(x, y))

    def far_row(self, row: np.ndarray) -> np.ndarray:
        """A row over the far field's free DOFs as a row over the global DOFs."""
        return np.asarray(self._E.T @ row).ravel()

    def deflection(self, x: float, y: float) -> np.ndarray:
        """Row r with r·d = w(x, y) [m] of the top sublaminate (the struck one) in the near field, of the laminate
        in the far field."""
        if self.far is not None and not self.in_near_field(x, y):
            return self.far_row(self.far.deflection(x, y))
        return self.layer_row(0, self.layers[0].deflection(x, y))

    def surface_strain(self, x: float, y: float, surface: str = "bottom", direction="x", length: float = 0.0) -> np.ndarray:
        """Row r with r·d = the face strain of :meth:`~softimpact.fem.plate.PlateFE.surface_strain` at (x, y): the top
        sublaminate's top face or the bottom one's bottom face in the near field, the laminate's face in the far field."""
        if self.far is not None and not self.in_near_field(x, y):
            far = self.far
            return self.far_row(far.surface_strain(x, y, surface, direction, length))
        k = 0 if surface == "top" else len(self.layers) - 1
        lay = self.layers[k]
        return self.layer_row(k, lay.surface_strain(x, y, surface, direction, length))

    def surface_vector(self, u: np.ndarray) -> np.ndarray:
        """The full DOF vector(s) (5 per node of the mesh, fixed ones zero) of what the fields show: the top
        sublaminate in the near field, the laminate in the far field; time on the last axis."""
        top = self.layers[0]
        full = np.zeros((top.fe.basis.N,) + np.shape(u)[1:])
        if self.far is not None:
            full[self.far.free] = self._E @ u
        full[top.free] = self.T[0] @ u
        return full
