"""Contact structures: a beam or plate model as a :class:`~softimpact.fem.impact.ContactStructure`.

A plane (Q4) beam is struck on its top face: the impactor moves down (−z); the
contact force loads the top-face nodes within reach of the impact point (their z
DOFs, pushed down: ``load_sign = −1``); the approach uses the MID-SURFACE
deflection under the impact point (down +), so the beam's own through-thickness
squeeze is not counted as indentation, which belongs to the contact law. A plate
is struck on its top face too, the force spread over contact discs
(:class:`softimpact.fem.plate_loads.DiscShares`), the approach measured on the
mid-surface deflection.
"""

from __future__ import annotations

import numpy as np

from .impact import ContactStructure
from .plate_loads import CircularPatch, DiscShares

__all__ = ["mid_surface_row", "plane_contact_structure", "beam_contact_structure", "plate_structure"]


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


def plane_contact_structure(plane, position: float, reach: float, outputs: np.ndarray, names=(), C=None) -> ContactStructure:
    """The plane model struck downward on its top face at ``position`` [m].

    ``reach`` [m]: the widest contact radius the run may need; top-face nodes
    within reach (plus one node spacing) of the impact point are loadable.
    ``outputs`` (n_out, n): rows of the output histories (gauge strains).
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
    )


def beam_contact_structure(model, position: float, reach: float):
    """The ContactStructure of a BeamModel struck downward on its top face at ``position`` [m],
    with the gauge strains (each on its own face) as outputs and the model's damping."""
    pm = model.plane
    gauges = model.problem.gauges
    outputs = np.array([pm.surface_strain(g.position, g.surface, g.length) for g in gauges]).reshape(len(gauges), pm.n)
    a, b = model.problem.beam.damping
    C = None if a == 0 and b == 0 else a * pm.M + b * pm.K
    return plane_contact_structure(pm, position, reach, outputs, tuple(g.name for g in gauges), C)


def plate_structure(model, position: tuple[float, float], max_radius: float):
    """The plate as a :class:`softimpact.fem.impact.ContactStructure` for the coupled solver:
    struck downward (−z) on its top face at ``position`` (x, y) [m], contact discs up to
    ``max_radius`` [m] spread by the cosine pressure of eq (11) over the nodes (exact
    integrals, :class:`softimpact.fem.plate_loads.DiscShares`); the approach is measured
    on the mid-surface deflection there; the outputs are the model's gauges."""
    fe = model.fe
    patch = CircularPatch(fe, position, max_radius, grow=True)
    gauges = model.problem.gauges
    return ContactStructure(
        M=fe.M,
        K=fe.K,
        surface_x=fe.node_xy()[0, patch.nodes],
        surface_dofs=patch.dofs,
        load_sign=-1.0,  # w is up +, the impact pushes down
        center=float(position[0]),
        approach_row=-fe.deflection(*position),
        outputs=model.O[: len(gauges)],
        output_names=tuple(g.name for g in gauges),
        C=model.stepper.C,
        patch=DiscShares(patch),
    )
