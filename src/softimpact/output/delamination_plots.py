"""Figures of delamination growth in a coupled impact on sublaminates tied by cohesive interfaces
(:mod:`softimpact.fem.cohesive_plate`): the delaminated and process-zone areas against time, and each interface's
damage at the end of the run over the model's mesh."""

from __future__ import annotations

import numpy as np

from ..units import display
from .files import figure_bytes

__all__ = ["delamination_figures"]


def delamination_figures(problem, model, result, prefix: str = "", units: str = "in-lbf-s") -> dict[str, bytes]:
    """delamination-area.png (``result``'s ``"columns"`` group: delaminated, d = 1, and process-zone, 0 < d < 1, areas
    summed and per interface, of the whole plate) and delamination-map.png (``model.damage_map()``: the damage of
    each interface at the end, nodes of ``model.fe``; a half or quarter model shows its part), in display ``units``.
    Empty without the group."""
    from .plots import _figure

    groups = result.groups or {}
    if "columns" not in groups or "delaminated_area_m2" not in groups["columns"][0]:
        return {}
    cols = dict(zip(*groups["columns"]))
    tu, lu = display(units, "time"), display(units, "length")
    a2 = lu.factor**2
    t = result.time * tu.factor
    fig, ax = _figure()
    ax.plot(t, cols["delaminated_area_m2"] * a2, color="k", lw=2, label="delaminated (d = 1), all interfaces")
    ax.plot(t, cols["process_zone_area_m2"] * a2, color="k", ls="--", label="process zone (0 < d < 1), all interfaces")
    for name, values in cols.items():
        if name.startswith("delaminated_area_m2_"):
            ax.plot(t, values * a2, label=f"delaminated, {name.removeprefix('delaminated_area_m2_').replace('_', ' ', 1).replace('_', '/')}")
    ax.set_xlabel(f"time since first contact [{tu.label}]")
    ax.set_ylabel(f"area [{lu.label}²] (whole plate)")
    ax.set_title("Delamination growth at the cohesive interfaces", fontsize=10)
    ax.legend(fontsize=8)
    out = {prefix + "delamination-area.png": figure_bytes(fig)}

    damage = np.asarray(model.damage_map())
    fe = model.fe
    labels = [n.removeprefix("delaminated_area_m2_") for n in cols if n.startswith("delaminated_area_m2_")]
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(damage), figsize=(4.2 * len(damage), 3.8), layout="constrained", squeeze=False)
    x, y = fe.node_xs * lu.factor, fe.node_ys * lu.factor
    for ax, d, label in zip(axes[0], damage, labels):
        grid = d[fe.grid_node]  # (node x, node y)
        mesh = ax.pcolormesh(x, y, grid.T, vmin=0.0, vmax=1.0, cmap="magma_r", shading="nearest")
        ax.set_aspect("equal")
        ax.set_title(f"interface {label.replace('_', ' ', 1).replace('_', '/')}", fontsize=9)
        ax.set_xlabel(f"x [{lu.label}]")
        ax.set_ylabel(f"y [{lu.label}]")
    fig.colorbar(mesh, ax=axes[0].tolist(), label="damage d at the end of the run (1: delaminated)")
    out[prefix + "delamination-map.png"] = figure_bytes(fig)
    return out
