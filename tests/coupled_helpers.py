"""Test-side adapter: a ContactStructure from the package's plane beam model (the app layer will own this)."""

from dataclasses import replace

import numpy as np

from softimpact.fem.impact import ContactStructure
from softimpact.fem.newmark import SolverSpec
from softimpact.input.beam_case import load_beam_case
from softimpact.workflows.beam_impact import BeamModel

INCH = 0.0254


def long_beam_model(time_step=0.5e-6, duration=600e-6, nx=200, nz=6):
    """BeamModel of the paper's long beam (paper-long-beam case) with the given step and mesh."""
    problem, _ = load_beam_case("paper-long-beam")
    beam = replace(problem.beam, nx=nx, nz=nz)
    solver = SolverSpec(time_step, duration, problem.solver.newmark)
    return BeamModel(replace(problem, beam=beam, solver=solver))


def mid_surface_row(plane, x):
    """Row giving the z-displacement of the mid-surface at x (mid node row, or the mean of the two nearest rows)."""
    zs = np.unique(plane.node_z)
    h = zs[-1]
    below, above = zs[zs <= h / 2 + 1e-12].max(), zs[zs >= h / 2 - 1e-12].min()
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
            if k >= 0:
                row[k] += wgt
        rows.append(row)
    return np.mean(rows, axis=0)


def beam_structure(model, position, max_radius):
    """ContactStructure of a BeamModel struck downward on its top face at ``position`` [m]."""
    pm = model.plane
    top = pm.top_nodes
    xs = pm.node_x[top]
    dx = float(np.min(np.diff(xs)))
    sel = np.abs(xs - position) <= max_radius + dx
    dofs = np.array([pm.dof(n, 1) for n in top[sel]])
    gauges = model.problem.gauges
    outputs = np.array([pm.surface_strain(g.position, g.surface, g.length) for g in gauges])
    return ContactStructure(
        M=pm.M,
        K=pm.K,
        surface_x=xs[sel],
        surface_dofs=dofs,
        load_sign=-1.0,
        center=position,
        approach_row=-mid_surface_row(pm, position),
        outputs=outputs,
        output_names=tuple(g.name for g in gauges),
    )
