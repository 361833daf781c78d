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


def nodal_areas(fe) -> np.ndarray:
    """Tributary area [m²] of every node of a PlateFE's mesh (numbered ``fe.grid_node``): the tensor product of
    the 1-D Newton–Cotes weights of the element's nodes (trapezoid for order 1, Simpson for order 2); they sum
    to the plate's area."""
    rules = {1: np.array([0.5, 0.5]), 2: np.array([1.0, 4.0, 1.0]) / 6.0}
    rule, p = rules[fe.order], fe.order

    def weights(lines):
        w = np.zeros(p * (lines.size - 1) + 1)
        for e, h in enumerate(np.diff(lines)):
            w[p * e : p * e + p + 1] += h * rule
        return w

    wx, wy = weights(fe.xs), weights(fe.ys)
    area = np.zeros(fe.grid_node.size)
    area[fe.grid_node.ravel()] = np.outer(wx, wy).ravel()
    return area


class CohesivePlate(NonlinearModel):
    """The plate of ``plate`` (its mesh, supports, element; its section is replaced) with the laminate ``stack``
    split below the plies ``splits`` (1 = the top ply: 3 splits between plies 3 and 4) into sublaminates tied by
    ``law`` (module docstring). Sublaminates top first, each over its
    free DOFs with ``in_plane`` edges (:class:`~softimpact.fem.plate_vk.PlateVK`: ``"movable"`` is the whole
    laminate's simple support: the tangential in-plane displacement and rotation zero on every sublaminate);
    the stacked DOFs numbered node by node (:meth:`layer_dofs`: a sublaminate's positions).

    ``K``, ``M``: block-diagonal, the sublaminates' own (no interface); ``damage`` (interfaces, nodes): the
    committed damage; ``area`` (nodes,): the nodes' tributary areas."""

    def __init__(self, plate: Plate, stack: Stack, splits, law: BilinearCohesive, in_plane: str = "movable"):
        n_ply = len(stack.angles)
        splits = tuple(int(k) for k in splits)
        if not splits or list(splits) != sorted(set(splits)) or splits[0] < 1 or splits[-1] >= n_ply:
            raise InputError(f"cohesive interfaces: plies {splits!r} must increase strictly from 1 to {n_ply - 1} (an interface lies below each)")
        if not isinstance(law, BilinearCohesive):
            raise InputError(f"cohesive interfaces: the law must be a BilinearCohesive, got {type(law).__name__}")
        self.plate, self.stack, self.splits, self.law = plate, stack, splits, law
        bounds = (0, *splits, n_ply)
        self.stacks = tuple(Stack(stack.ply, tuple(stack.angles[a:b])) for a, b in zip(bounds[:-1], bounds[1:]))
        self.layers = tuple(PlateVK(replace(plate, section=plate_section(s), membrane=True), in_plane) for s in self.stacks)
        self.thicknesses = tuple(s.thickness for s in self.stacks)
        sizes = [layer.n for layer in self.layers]
        self.offsets = tuple(int(o) for o in np.concatenate(([0], np.cumsum(sizes)[:-1])))  # of the layer-major numbering
        self.n = int(sum(sizes))
        # The stacked DOFs node by node (a node's DOFs of every sublaminate together): the interfaces couple a
        # node's sublaminates, so the layer-major order would make the band a whole sublaminate wide
        node = np.concatenate([lay.free // 5 for lay in self.layers])
        layer = np.repeat(np.arange(len(sizes)), sizes)
        self.order = np.lexsort((np.arange(self.n), layer, node))  # position → layer-major index
        self.position = np.empty(self.n, int)
        self.position[self.order] = np.arange(self.n)  # layer-major index → position
        o = self.order
        self.K = scipy.sparse.block_diag([lay.K for lay in self.layers], format="csr")[o][:, o].tocsr()
        self.M = scipy.sparse.block_diag([lay.M for lay in self.layers], format="csr")[o][:, o].tocsr()
        fe = self.layers[0].fe
        self.nodes = fe.grid_node.size
        self.area = nodal_areas(fe)
        self.G = self._interface_operator()[:, o].tocsr()
        self.top = self.position[: sizes[0]]  # the top sublaminate's free DOFs, in its own order
        self.interfaces = len(splits)
        self._a = np.tile(self.area, self.interfaces)  # per interface point (interface-major)
        self.history_names = HISTORY_ROWS + tuple(f"{q}_{j}" for q in HISTORY_ROWS[:2] for j in range(self.interfaces))
        self.reset()

    # ---- the interfaces' kinematics -------------------------------------------------------
    def _global(self, layer: int, component: int) -> np.ndarray:
        """The stacked DOF of ``component`` at every node of sublaminate ``layer`` (−1 where fixed)."""
        lay = self.layers[layer]
        local = lay._index[lay.fe.basis.nodal_dofs[component]]
        return np.where(local >= 0, local + self.offsets[layer], -1)

    def _interface_operator(self) -> scipy.sparse.csr_matrix:
        """G (3·nodes·interfaces, n): rows (opening, sliding x, sliding y) per node, interface-major (module docstring)."""
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
        shape = (3 * nn * len(self.splits), self.n)
        return scipy.sparse.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=shape)

    def opening(self, u: np.ndarray) -> np.ndarray:
        """δ (interfaces·nodes, 3) [m]: opening, sliding x, sliding y at every node of every interface."""
        return (self.G @ u).reshape(-1, 3)

    # ---- force, tangent, energies (the model VonKarmanNewmark steps) ----------------------------------
    def _response(self, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(traction (points, 3) [Pa], its tangent (points, 3, 3) [N/m³]) at ``u`` with the committed damage held
        fixed (the law's traction at that damage: (1 − d)·K on the active part, K in closure)."""
        delta = self.opening(u)
        d = self.damage.ravel()
        K = self.law.K
        dn = delta[:, 0]
        pos = np.maximum(dn, 0.0)
        t = np.empty_like(delta)
        t[:, 0] = (1 - d) * K * pos + K * (dn - pos)
        t[:, 1:] = ((1 - d) * K)[:, None] * delta[:, 1:]
        T = np.zeros(delta.shape + (3,))
        T[:, 0, 0] = np.where(dn >= 0, (1 - d) * K, K)
        T[:, 1, 1] = T[:, 2, 2] = (1 - d) * K
        return t, T

    def nonlinear_force(self, u: np.ndarray) -> np.ndarray:
        """f_c(u) = Gᵀ(a ⊙ t(δ)) [N] at the committed damage."""
        t = self._response(u)[0]
        return self.G.T @ (self._a[:, None] * t).ravel()

    def internal_force(self, u: np.ndarray) -> np.ndarray:
        """K u + f_c(u) [N]."""
        return self.K @ u + self.nonlinear_force(u)

    def tangent(self, u: np.ndarray) -> scipy.sparse.csr_matrix:
        """K + Gᵀ diag(a ∂t/∂δ) G at the committed damage (positive semi-definite interfaces: no softening within a step)."""
        T = self._response(u)[1] * self._a[:, None, None]
        m = T.shape[0]
        idx = 3 * np.arange(m)[:, None] + np.arange(3)[None, :]
        rows = np.broadcast_to(idx[:, :, None], T.shape).ravel()
        cols = np.broadcast_to(idx[:, None, :], T.shape).ravel()
        B = scipy.sparse.csr_matrix((T.ravel(), (rows, cols)), shape=(3 * m, 3 * m))
        return (self.K + self.G.T @ B @ self.G).tocsr()

    def stored_energy(self, u: np.ndarray) -> float:
        """The interfaces' recoverable energy Σ a_p φ(δ_p, d_p) [J] at the committed damage."""
        return float(self._a @ self.law.stored_energy(self.opening(u), self.damage.ravel()))

    def strain_energy(self, u: np.ndarray) -> float:
        """½uᵀKu + the interfaces' stored energy [J] (the recoverable part: what the dissipated energy is not)."""
        return 0.5 * float(u @ (self.K @ u)) + self.stored_energy(u)

    LAGGED_STATE = True  # the damage is held within a step and raised after it (module docstring)

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
    def layer_dofs(self, layer: int) -> np.ndarray:
        """The stacked positions of sublaminate ``layer``'s free DOFs (in its own order)."""
        o = self.offsets[layer]
        return self.position[o : o + self.layers[layer].n]

    def layer_row(self, layer: int, row: np.ndarray) -> np.ndarray:
        """A row over sublaminate ``layer``'s free DOFs as a row over the stacked DOFs."""
        out = np.zeros(self.n)
        out[self.layer_dofs(layer)] = row
        return out

    def deflection(self, x: float, y: float) -> np.ndarray:
        """Row r with r·d = w(x, y) [m] of the top sublaminate (the struck one)."""
        return self.layer_row(0, self.layers[0].deflection(x, y))
