"""Contact structures: a beam or plate model as a :class:`~softimpact.fem.impact.ContactStructure`.

One builder per kind of structure; the structure models (:class:`softimpact.fem.linear.LinearModel`
and its subclasses) call them from ``contact_structure(point, reach)``.

A plane (Q4) beam is struck on its top face: the impactor moves down (−z); the
contact force loads the top-face nodes within reach of the impact point (their z
DOFs, pushed down: ``load_sign = −1``); the approach uses the MID-SURFACE
deflection under the impact point (down +), so the beam's own through-thickness
squeeze is not counted as indentation, which belongs to the contact law. A plate
is struck on its top face too, the force spread over contact discs
(:class:`softimpact.fem.plate_loads.DiscShares`), the approach measured on the
mid-surface deflection. A rod (the bar) is struck axially at its end.
"""

from __future__ import annotations

import numpy as np

from ..errors import NoContactRoom
from .impact import ContactStructure
from .plate_loads import CircularPatch, DiscShares

__all__ = ["mid_surface_row", "plane_contact_structure", "plate_contact_structure", "plate_reach", "rod_contact_structure", "output_groups", "group_outputs"]


def mid_surface_row(plane, x: float) -> np.ndarray:
    """Row r (n,) with r·u the z-displacement (up +) of the mid-surface at ``x`` [m].

    Linear along the element edge; with an odd number of element layers the
    mid-surface lies between two node rows, and the mean of both is taken.
    """
    zs = np.unique(plane.node_z)
    h = zs[-1]
    below, above = zs[zs <= h / 2 + 1e-12 * h].max(), zs[zs >= h / 2 - 1e-12 * h].min()
    rows = []
    for z in {below, above}:
        nodes = np.flatnonzero(np.isclose(plane.node_z, z))
        nodes = nodes[np.argsort(plane.node_x[nodes])]
        xs = plane.node_x[nodes]
        i = int(np.clip(np.searchsorted(xs, x) - 1, 0, len(xs) - 2))
        s = (x - xs[i]) / (xs[i + 1] - xs[i])
        row = np.zeros(plane.n)
        for node, wgt in ((nodes[i], 1 - s), (nodes[i + 1], s)):
            k = plane.dof(node, 1)
            if k >= 0:  # a supported DOF does not move
                row[k] += wgt
        rows.append(row)
    return np.mean(rows, axis=0)


def output_groups(**sizes: int) -> dict[str, tuple[int, ...]]:
    """Named groups of consecutive output rows, in the order given: ``output_groups(gauges=2, damage=4)``
    → {"gauges": (0, 1), "damage": (2, 3, 4, 5)}."""
    out, start = {}, 0
    for name, size in sizes.items():
        out[name] = tuple(range(start, start + size))
        start += size
    return out


def group_outputs(result, groups: dict[str, tuple[int, ...]] | None):
    """A :class:`~softimpact.fem.impact.CoupledResult` whose ``strain`` holds the ``"gauges"`` group of its output
    rows only, the other groups in ``result.groups`` (name → (row names, (n_rows, n))); unchanged when ``groups``
    is None (every row a gauge) or the result is grouped already."""
    from dataclasses import replace

    if groups is None or result.groups is not None:
        return result
    names, rows = result.strain_names, result.strain
    gauges = list(groups.get("gauges", ()))
    other = {g: (tuple(names[i] for i in idx), rows[list(idx)]) for g, idx in groups.items() if g != "gauges"}
    return replace(result, strain=rows[gauges], strain_names=tuple(names[i] for i in gauges), groups=other)


def plane_contact_structure(plane, position: float, reach: float, outputs: np.ndarray, names=(), C=None, groups=None) -> ContactStructure:
    """The plane model struck downward on its top face at ``position`` [m].

    ``reach`` [m]: the widest contact radius the run may need; top-face nodes
    within reach (plus one node spacing) of the impact point are loadable.
    ``outputs`` (n_out, n): rows of the output histories (gauge strains), ``groups`` their named
    groups (:func:`output_groups`; None: all gauges).
    """
    top = plane.top_nodes
    xs = plane.node_x[top]
    dx = float(np.min(np.diff(xs)))
    sel = np.abs(xs - position) <= reach + dx
    dofs = np.array([plane.dof(n, 1) for n in top[sel]])
    free = dofs >= 0  # a supported node takes no load
    xs, dofs = xs[sel][free], dofs[free]
    return ContactStructure(
        M=plane.M,
        K=plane.K,
        surface_x=xs,
        surface_dofs=dofs,
        load_sign=-1.0,
        center=position,
        approach_row=-mid_surface_row(plane, position),
        outputs=np.asarray(outputs, float).reshape(-1, plane.n),
        output_names=tuple(names),
        C=C,
        groups=groups,
    )


def plate_contact_structure(fe, position: tuple[float, float], max_radius: float, outputs: np.ndarray, names=(), C=None, groups=None) -> ContactStructure:
    """A plate (:class:`softimpact.fem.plate.PlateFE`) struck downward (−z) on its top face at
    ``position`` (x, y) [m]: contact discs up to ``max_radius`` [m] spread by the cosine pressure
    of eq (11) over the nodes (exact integrals, :class:`softimpact.fem.plate_loads.DiscShares`);
    the approach is measured on the mid-surface deflection there; ``outputs`` (n_out, n) rows of
    the output histories (gauge strains) and ``groups`` their named groups, ``C`` the damping or None."""
    patch = CircularPatch(fe, position, max_radius, grow=True)
    return ContactStructure(
        M=fe.M,
        K=fe.K,
        surface_x=fe.node_xy()[0, patch.nodes],
        surface_dofs=patch.dofs,
        load_sign=-1.0,  # w is up +, the impact pushes down
        center=float(position[0]),
        approach_row=-fe.deflection(*position),
        outputs=np.asarray(outputs, float).reshape(-1, fe.n),
        output_names=tuple(names),
        C=C,
        patch=DiscShares(patch),
        groups=groups,
    )


def plate_reach(fe, supports: tuple[str, str, str, str], position: tuple[float, float], diameter: float) -> float:
    """The widest contact disc [m] a plate (``fe``, edge ``supports`` x0, x1, y0, y1) loads about the
    impact point: the impactor's diameter (a Hertz radius sqrt(R·α) and a flattened sphere's
    sqrt(d·α) stay within it while α < d), cut so the disc stays on the plate and its elements
    off a supported edge (whose w is fixed); a symmetry edge through the impact point does not cut it."""
    x, y = position
    h = (float(np.max(np.diff(fe.xs))), float(np.max(np.diff(fe.ys))))
    room = diameter
    for (dist, hh), kind in zip(((x - fe.xs[0], h[0]), (fe.xs[-1] - x, h[0]), (y - fe.ys[0], h[1]), (fe.ys[-1] - y, h[1])), supports):
        if kind == "symmetry" and dist <= 1e-9 * hh:
            continue
        room = min(room, dist - (1.01 * hh if kind in ("clamped", "simply-supported") else 0.0))
    if not room > 0:
        raise NoContactRoom("the impact point is within one element of a supported edge: no room for the contact disc")
    return room


def rod_contact_structure(rod, outputs: np.ndarray | None = None, names=()) -> ContactStructure:
    """An assembled rod (:class:`softimpact.fem.bar.RodModel`) struck axially at its end x = 0: the
    force loads the end's axial DOF (pushing into the bar, +x), the approach is the end's
    displacement; ``outputs`` (n_out, n) rows of the output histories (strain probes), none by default."""
    end = np.zeros(rod.n)
    end[rod.end_dof] = 1.0
    return ContactStructure(
        M=rod.M,
        K=rod.K,
        surface_x=np.array([0.0]),
        surface_dofs=np.array([rod.end_dof]),
        load_sign=1.0,
        center=0.0,
        approach_row=end,
        outputs=np.zeros((0, rod.n)) if outputs is None else np.asarray(outputs, float).reshape(-1, rod.n),
        output_names=tuple(names),
    )
