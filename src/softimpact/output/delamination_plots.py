"""Figures of delamination growth in a coupled impact on sublaminates tied by cohesive interfaces
(:mod:`softimpact.fem.cohesive_plate`): the delaminated and process-zone areas against time, and each interface's
damage at the end of the run over the model's mesh."""

from __future__ import annotations

import numpy as np

from ..units import display
from .files import figure_bytes

__all__ = ["delamination_figures", "cscan_figure", "draw_cscan"]


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
    out[prefix + "delamination-cscan.png"] = cscan_figure(model.cscan(), lu)
    return out


def cscan_figure(scan, lu) -> bytes:
    """delamination-cscan.png (:func:`draw_cscan` of the whole plate), ``lu`` the display length unit."""
    return figure_bytes(draw_cscan(scan, lu))


def draw_cscan(scan, lu, *, window: tuple[float, float, float, float] | None = None):
    """The whole plate of ``scan`` (:class:`~softimpact.workflows.plate.cscan.CScan`) seen from the struck face as a
    C-scan shows it, each interface's delaminated region (d = 1) in its colour (deeper interfaces darker, the
    shallower drawn over the deeper), the projected envelope outlined in black and each region's major axis (the
    equal-moment ellipse's) dashed through its centroid; ``lu`` the display length unit
    (:func:`softimpact.units.display`), ``window`` (x0, x1, y0, y1) [m] the part of the plate drawn (default the
    whole). Returns the open matplotlib Figure (a notebook shows it; :func:`cscan_figure` renders and closes it)."""
    import matplotlib.pyplot as plt
    from matplotlib import patheffects
    from matplotlib.patches import Patch

    n = len(scan.interfaces)
    colours = plt.get_cmap("viridis_r")(np.linspace(0.1, 0.95, max(n, 1)))
    x, y = scan.xs * lu.factor, scan.ys * lu.factor
    fig, ax = plt.subplots(figsize=(8.0, 5.0), layout="constrained")
    handles = []
    for k in reversed(range(n)):  # the deepest first: a shallower delamination hides what lies below it
        i, d = scan.interfaces[k], scan.damage[k]
        if i.area <= 0.0:
            continue
        ax.contourf(x, y, d.T, levels=[1.0 - 1e-9, 2.0], colors=[colours[k]], alpha=0.9)
        if np.isfinite(i.orientation_deg):
            t = np.radians(i.orientation_deg)
            h = 0.5 * i.major_axis * lu.factor
            cx, cy = (c * lu.factor for c in i.centroid)
            ax.plot(
                [cx - h * np.cos(t), cx + h * np.cos(t)],
                [cy - h * np.sin(t), cy + h * np.sin(t)],
                color=colours[k],
                lw=1.5,
                ls="--",
                path_effects=[patheffects.Stroke(linewidth=3.0, foreground="k"), patheffects.Normal()],  # seen over its own fill
            )
        axis = "round" if not np.isfinite(i.orientation_deg) else f"axis {i.major_axis * lu.factor:.3g} {lu.label} at {i.orientation_deg:.0f}°"
        handles.insert(0, Patch(color=colours[k], label=f"{i.words} (lower ply {i.lower_ply_deg:g}°):\n{i.area * lu.factor**2:.3g} {lu.label}², {axis}"))
    cracked = (scan.damage >= 1.0).any(axis=0).astype(float)
    if cracked.any():
        ax.contour(x, y, cracked.T, levels=[0.5], colors="k", linewidths=1.5)
        handles.insert(0, Patch(facecolor="none", edgecolor="k", label=f"projected envelope: {scan.projected_area * lu.factor**2:.3g} {lu.label}²"))
    else:
        ax.text(0.5, 0.5, "no delamination (no interface reached d = 1)", transform=ax.transAxes, ha="center", va="center")
    x0, x1, y0, y1 = (x[0], x[-1], y[0], y[-1]) if window is None else (c * lu.factor for c in window)
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.set_xlabel(f"x [{lu.label}]", fontsize=10)
    ax.set_ylabel(f"y [{lu.label}]", fontsize=10)
    ax.tick_params(labelsize=9)
    fig.suptitle("C-scan: the delaminations seen from the struck face", fontsize=11)
    if handles:
        fig.legend(handles=handles, fontsize=9, loc="outside right center")  # outside the axes, in the constrained layout's room
    return fig
