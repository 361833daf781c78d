"""Figures of a plate run (matplotlib, imported on use): mesh with load and gauges,
deflected shape at instants, gauge histories; and the beam-as-plate comparison.

Quantities arrive in SI and are shown in the case's display units.
"""

from __future__ import annotations

import math

import numpy as np

from ..units import display

__all__ = ["plate_mesh", "plate_deflection", "plate_histories", "beam_as_plate"]

_SUPPORT_STYLE = {"clamped": ("C0", 4.0), "simply-supported": ("C1", 2.5), "free": ("0.6", 0.8), "symmetry": ("C4", 1.5)}


def _plt():
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    return plt


def _gauge_angle(direction) -> float:
    return 0.0 if direction == "x" else 90.0 if direction == "y" else float(direction)


def plate_mesh(model, system: str, patch: tuple[float, str] | None = None):
    """The plate's mesh (every line up to 64 per direction, else every k-th), its supports, the
    contact patch and the gauges (a bar along each gauge's direction, drawn at least 3 % of the plate).
    ``patch``: (radius [m], label) of the disc drawn at the load point (default: the load's r0)."""
    from matplotlib.collections import LineCollection
    from matplotlib.patches import Circle

    plt = _plt()
    lu = display(system, "length")
    fe, p = model.fe, model.problem
    xs, ys = fe.xs * lu.factor, fe.ys * lu.factor
    Lx, Ly = xs[-1], ys[-1]
    fig, ax = plt.subplots(figsize=(6.4, 6.4 * max(min(Ly / Lx, 1.6), 0.35) + 0.8), layout="constrained")
    sx = max(1, math.ceil((xs.size - 1) / 64))
    sy = max(1, math.ceil((ys.size - 1) / 64))
    segs = [[(x, 0), (x, Ly)] for x in xs[::sx]] + [[(0, y), (Lx, y)] for y in ys[::sy]]
    ax.add_collection(LineCollection(segs, colors="0.75", linewidths=0.4))
    edges = {"x0": [(0, 0), (0, Ly)], "x1": [(Lx, 0), (Lx, Ly)], "y0": [(0, 0), (Lx, 0)], "y1": [(0, Ly), (Lx, Ly)]}
    shown = set()
    for (edge, line), kind in zip(edges.items(), p.plate.supports):
        color, lw = _SUPPORT_STYLE[kind]
        (x0, y0), (x1, y1) = line
        ax.plot([x0, x1], [y0, y1], color=color, lw=lw, label=kind if kind not in shown else None, solid_capstyle="butt")
        shown.add(kind)
        ax.annotate(edge, ((x0 + x1) / 2, (y0 + y1) / 2), fontsize="x-small", color="0.3", ha="center", va="center", xytext=(0, 0), textcoords="offset points")
    cx, cy = (c * lu.factor for c in p.load.position)
    radius, label = patch or (p.load.contact_radius, "contact patch (r0)")
    ax.add_patch(Circle((cx, cy), radius * lu.factor, color="C3", alpha=0.5, label=label))
    ax.plot([cx], [cy], "+", color="C3", ms=8)
    draw = 0.03 * max(Lx, Ly)
    for i, g in enumerate(p.gauges):
        th = math.radians(_gauge_angle(g.direction))
        gx, gy = (c * lu.factor for c in g.position)
        half = max(g.length * lu.factor, draw) / 2
        ax.plot(
            [gx - half * math.cos(th), gx + half * math.cos(th)],
            [gy - half * math.sin(th), gy + half * math.sin(th)],
            color="C2",
            lw=3,
            label="gauge" if i == 0 else None,
        )
        ax.annotate(f"{g.name} ({g.surface})", (gx, gy), xytext=(6, 6), textcoords="offset points", fontsize="small", color="C2")
    ax.set_xlim(-0.04 * Lx, 1.04 * Lx)
    ax.set_ylim(-0.04 * Ly, 1.04 * Ly)
    ax.set_aspect("equal")
    ax.set_xlabel(f"x (0° fibres) [{lu.label}]")
    ax.set_ylabel(f"y [{lu.label}]")
    ax.set_title(f"Plate mesh: {fe.xs.size - 1} × {fe.ys.size - 1} {fe.plate.element.upper()} elements, {fe.n} DOF", fontsize="medium")
    ax.legend(fontsize="small", loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=3, frameon=False)
    return fig


def plate_deflection(model, result, system: str):
    """Mid-surface deflection w(x, y) at the kept instants (``result.kept``), one map each,
    on a common colour scale."""
    from ..fem.plate import W

    plt = _plt()
    lu, tu = display(system, "length"), display(system, "time")
    fe = model.fe
    full = fe.expand(result.displacement)
    w = full[fe.basis.nodal_dofs[W]]  # (n_nodes, n_kept), node (i, j) at (node_xs[i], node_ys[j]) is grid_node[i, j]
    shape = fe.grid_node.shape
    n = w.shape[1]
    cols = min(n, 3)
    rows = math.ceil(n / cols)
    X, Y = np.meshgrid(fe.node_xs * lu.factor, fe.node_ys * lu.factor, indexing="ij")
    vmax = np.max(np.abs(w)) * lu.factor or 1.0
    fig, axes = plt.subplots(rows, cols, figsize=(3.3 * cols + 0.8, 3.1 * rows + 0.6), layout="constrained", squeeze=False)
    for k in range(rows * cols):
        ax = axes.flat[k]
        if k >= n:
            ax.axis("off")
            continue
        im = ax.pcolormesh(X, Y, w[:, k].reshape(shape) * lu.factor, cmap="RdBu_r", vmin=-vmax, vmax=vmax, shading="gouraud")
        ax.set_aspect("equal")
        ax.set_title(f"t = {result.time[result.kept[k]] * tu.factor:.0f} {tu.label}", fontsize="medium")
        ax.tick_params(labelsize="x-small")
        if k % cols == 0:
            ax.set_ylabel(f"y [{lu.label}]", fontsize="small")
        if k >= n - cols:
            ax.set_xlabel(f"x (0° fibres) [{lu.label}]", fontsize="small")
    fig.colorbar(im, ax=axes, shrink=0.8, label=f"deflection w [{lu.label}] (up +)")
    fig.suptitle("Deflected shape: flexural waves spreading from the impact")
    return fig


def plate_histories(result, system: str):
    """Force, deflection under the load and the strain at each gauge against time."""
    plt = _plt()
    tu, su, fu, lu = (display(system, k) for k in ("time", "strain", "force", "length"))
    t = result.time * tu.factor
    fig, axes = plt.subplots(3, 1, figsize=(6.8, 7.6), sharex=True, layout="constrained")
    axes[0].plot(t, result.force * fu.factor, color="C3")
    axes[0].set_ylabel(f"force [{fu.label}]")
    axes[1].plot(t, result.deflection[0] * lu.factor, color="C0")
    axes[1].set_ylabel(f"deflection at the\nload point [{lu.label}]")
    for g, eps in zip(result.problem.gauges, result.strain):
        axes[2].plot(t, eps * su.factor, label=f"{g.name}: {g.surface}, {g.direction if isinstance(g.direction, str) else f'{g.direction:g}°'}")
    axes[2].set_ylabel(f"gauge strain [{su.label}]\n(tension +)")
    axes[2].set_xlabel(f"time since first contact [{tu.label}]")
    if result.problem.gauges:
        axes[2].legend(fontsize="small")
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.axhline(0, color="k", lw=0.5)
    fig.suptitle(result.problem.title or "Plate impact")
    return fig


def beam_as_plate(rows, system: str):
    """Gauge strains of the paper's beams as plane-strain beams (smeared, layered) and as
    1-inch-wide plates. ``rows``: (label, time [s], {gauge: (smeared, layered, plate)}) per case."""
    plt = _plt()
    tu, su = display(system, "time"), display(system, "strain")
    gauges = list(rows[0][2])
    fig, axes = plt.subplots(len(rows), len(gauges), figsize=(4.4 * len(gauges), 2.7 * len(rows) + 0.9), layout="constrained", squeeze=False, sharex=True)
    for i, (label, time, strains) in enumerate(rows):
        for j, g in enumerate(gauges):
            ax = axes[i, j]
            smeared, layered, plate = strains[g]
            ax.plot(time * tu.factor, smeared * su.factor, lw=1.0, label="plane-strain beam, smeared")
            ax.plot(time * tu.factor, layered * su.factor, lw=1.0, label="plane-strain beam, layered")
            ax.plot(time * tu.factor, plate * su.factor, "k--", lw=1.0, label="FSDT plate, 1 in wide")
            ax.grid(True, alpha=0.3)
            ax.set_title(f"{label}, gauge {g}", fontsize="small")
            if j == 0:
                ax.set_ylabel(f"strain [{su.label}]")
    for ax in axes[-1]:
        ax.set_xlabel(f"time [{tu.label}]")
    axes[0, 0].legend(fontsize="x-small")
    fig.suptitle("The plane-strain assumption: beams against 1-inch-wide plates")
    return fig
