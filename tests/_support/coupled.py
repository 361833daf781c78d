"""The paper's long beam model, its ContactStructure (fem.contact) and an independent explicit coupled integration."""

import math
from dataclasses import replace

import numpy as np
import scipy.sparse.linalg as spl

from softimpact.fem.newmark import SolverSpec
from softimpact.input.beam_case import load_beam_case
from softimpact.workflows.beam_impact import BeamModel

from .constants import INCH


def beam_structure(model: BeamModel, position: float, reach: float):
    """The beam model's ContactStructure, struck at ``position`` [m] within ``reach`` [m] (``model.contact_structure``)."""
    return model.contact_structure(position, reach)


def long_beam_model(time_step=0.5e-6, duration=600e-6, nx=200, nz=6):
    """BeamModel of the paper's long beam (paper-long-beam case) with the given step and mesh."""
    problem, _ = load_beam_case("paper-long-beam")
    beam = replace(problem.beam, nx=nx, nz=nz)
    solver = SolverSpec(time_step, duration, problem.solver.newmark)
    return BeamModel(replace(problem, beam=beam, solver=solver))


def independent_explicit(model, d, m, V, law_K, duration, dt_fraction=0.4):
    """Same formulation, different code and scheme: explicit central differences on M, K of the
    same mesh (consistent mass factored by SuperLU), contact force from the current approach, own
    cosine patch integrals, own mid-surface and gauge functionals, step 0.4·dt_crit."""
    pm = model.plane
    M, K = pm.M.tocsc(), pm.K.tocsr()
    lu = spl.splu(M)
    op = spl.LinearOperator(K.shape, matvec=lambda q: lu.solve(K @ q))
    w_max = math.sqrt(abs(spl.eigs(op, k=1, which="LM", return_eigenvectors=False)[0]))
    dt = dt_fraction * 2 / w_max
    steps = int(math.ceil(duration / dt))
    xc, R = 3 * INCH, d / 2
    X, Z = pm.node_x, pm.node_z
    h = Z.max()
    top = np.flatnonzero(np.isclose(Z, h))
    top = top[np.abs(X[top] - xc) < R + 0.05 * INCH]
    top = top[np.argsort(X[top])]
    xt = X[top] - xc
    edges = np.concatenate(([xt[0]], 0.5 * (xt[1:] + xt[:-1]), [xt[-1]]))
    zdof = np.array([pm.dof(n, 1) for n in top])
    mid = np.flatnonzero(np.isclose(Z, h / 2) & np.isclose(X, xc))
    assert mid.size == 1
    wdof = pm.dof(int(mid[0]), 1)
    near = int(np.argmin(np.abs(xt)))

    def gauge_dofs(g):
        z = 0.0 if g.surface == "bottom" else h
        face = np.flatnonzero(np.isclose(Z, z))
        out = []
        for xp, sgn in ((g.position + g.length / 2, 1), (g.position - g.length / 2, -1)):
            i = face[np.argsort(X[face])]
            k = np.searchsorted(X[i], xp) - 1
            s = (xp - X[i[k]]) / (X[i[k + 1]] - X[i[k]])
            out += [(pm.dof(i[k], 0), sgn * (1 - s) / g.length), (pm.dof(i[k + 1], 0), sgn * s / g.length)]
        return out

    gauges = [gauge_dofs(g) for g in model.problem.gauges]
    u_prev = np.zeros(pm.n)
    u = np.zeros(pm.n)
    x_prev, x = -V * dt, 0.0
    t = np.arange(steps + 1) * dt
    F = np.zeros(steps + 1)
    eps = np.zeros((len(gauges), steps + 1))
    for k in range(steps + 1):
        a = x + u[wdof]  # impactor moves down (+), mid-surface z is up (+): α = x − (−w_z)
        f = law_K * a**1.5 if a > 0 else 0.0
        F[k] = f
        for j, g in enumerate(gauges):
            eps[j, k] = sum(u[q] * c for q, c in g)
        if k == steps:
            break
        load = np.zeros(pm.n)
        if f > 0:
            r = math.sqrt(R * a)
            if r < 0.5 * np.min(np.diff(xt)):
                load[zdof[near]] = -f
            else:
                lo, hi = np.clip(edges[:-1], -r, r), np.clip(edges[1:], -r, r)
                # ∫ (πF/4r)·cos(πs/2r) ds over [lo, hi] = (F/2)(sin(πhi/2r) − sin(πlo/2r))
                load[zdof] = -0.5 * f * (np.sin(np.pi * hi / (2 * r)) - np.sin(np.pi * lo / (2 * r)))
        u_next = 2 * u - u_prev + dt * dt * lu.solve(load - K @ u)
        x_next = 2 * x - x_prev - dt * dt * f / m
        u_prev, u, x_prev, x = u, u_next, x, x_next
    on = F > 0
    k_end = int(np.flatnonzero(~on[1:])[0]) + 1  # first sample with no force after t = 0
    return t, F, eps, k_end, dt
