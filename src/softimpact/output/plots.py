"""Figures (matplotlib, imported on use). Each function returns a Figure.

Quantities arrive in SI and are shown in the case's display units.
"""

from __future__ import annotations

import numpy as np

from ..units import display

__all__ = ["LINESTYLES", "curve_colors", "bar_gauge_strain", "bar_contact_force", "bar_strain_profiles", "bar_energy"]


LINESTYLES = ("-", "--", ":", "-.")  # after the colours of the cycle (ten by default): 40 distinct curves


def _figure(width=6.4, height=4.0):
    """A figure and its axes; curves not given a style cycle colour × line style (the ten colours solid,
    then dashed, dotted, dash-dotted), so up to 40 curves stay distinct."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from cycler import cycler

    fig, ax = plt.subplots(figsize=(width, height), layout="constrained")
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]  # C0…C9 as values (a cycle cannot hold "C0")
    ax.set_prop_cycle(cycler(linestyle=LINESTYLES) * cycler(color=colors))
    ax.grid(True, alpha=0.3)
    return fig, ax


def curve_colors(n: int) -> list:
    """n distinct colours for curves whose line style already carries a meaning (measured solid, model
    dashed): the ten of the cycle up to 10, tab20 up to 20, evenly spaced on viridis beyond."""
    import matplotlib

    if n <= 10:
        return [f"C{i}" for i in range(n)]
    cmap = matplotlib.colormaps["tab20" if n <= 20 else "viridis"]
    return [cmap(i if n <= 20 else i / (n - 1)) for i in range(n)]


def bar_gauge_strain(result, system: str):
    """Fig 4: strain history at each gauge."""
    tu, su = display(system, "time"), display(system, "strain")
    fig, ax = _figure()
    for gauge, eps in zip(result.problem.gauges, result.strain):
        ax.plot(result.time * tu.factor, eps * su.factor, label=f"gauge {gauge.name} (FE)")
    ax.set_xlabel(f"time since first contact [{tu.label}]")
    ax.set_ylabel(f"axial strain [{su.label}] (tension +)")
    ax.set_title("Strain history at the gauges (paper Fig 4)")
    ax.legend()
    return fig


def bar_contact_force(result, plain=None, inferred=None, system: str = "SI"):
    """Fig 5: contact force, with end cap, without it, and inferred from the gauge (F = EA·ε)."""
    tu, fu = display(system, "time"), display(system, "force")
    fig, ax = _figure()
    cap = result.problem.bar.end_cap is not None
    ax.plot(result.time * tu.factor, result.force * fu.factor, label="FE, with end cap" if cap else "FE")
    if plain is not None:
        ax.plot(plain.time * tu.factor, plain.force * fu.factor, "--", label="FE, without end cap")
    if inferred is not None:
        t, f, name = inferred
        ax.plot(t * tu.factor, f * fu.factor, ":", lw=2, label=f"EA·ε at gauge {name}, shifted by x/c")
    end = result.contact_duration if np.isfinite(result.contact_duration) else result.time[-1]
    ax.set_xlim(0, 1.6 * end * tu.factor)
    top = max(result.peak_force, 0.0 if plain is None else plain.peak_force) * fu.factor
    ax.set_ylim(-0.05 * top, 1.15 * top)  # the reflected tension in the late gauge signal is off this window
    ax.set_xlabel(f"time since first contact [{tu.label}]")
    ax.set_ylabel(f"contact force [{fu.label}] (compression +)")
    ax.set_title("Contact force history (paper Fig 5)")
    ax.legend()
    return fig


def bar_strain_profiles(result, instants, system: str):
    """Fig 6: strain along the bar at several instants."""
    tu, lu, su = display(system, "time"), display(system, "length"), display(system, "strain")
    fig, ax = _figure(8.0, 4.2)
    for t in instants:
        k = int(round(t / (result.time[1] - result.time[0])))
        ax.plot(result.bar_x * lu.factor, result.bar_strain[:, k] * su.factor, label=f"t = {result.time[k] * tu.factor:.0f} {tu.label}")
    for g in result.problem.gauges:
        ax.axvline(g.position * lu.factor, color="k", lw=0.6, ls=":")
    ax.set_xlabel(f"distance from the struck end [{lu.label}]")
    ax.set_ylabel(f"axial strain [{su.label}] (tension +)")
    ax.set_title("Propagation and free-end reflection of the strain pulse (paper Fig 6)")
    _legend_outside(ax, fontsize="small")
    return fig


def _legend_outside(ax, **kwargs):
    """A legend to the right of the axes, where it cannot cover the data."""
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, **kwargs)


def bar_energy(result, system: str = "SI"):
    """Energy terms and their sum (the sum should stay flat)."""
    tu, eu = display(system, "time"), display(system, "energy")
    fig, ax = _figure(7.4, 4.0)
    e = result.energies
    for label, y in (
        ("impactor kinetic", e.impactor_kinetic),
        ("bar kinetic", e.kinetic),
        ("bar strain", e.strain),
        ("contact", e.contact_energy),
        ("total", e.mechanical),
    ):
        ax.plot(result.time * tu.factor, y * eu.factor, label=label, lw=2 if label == "total" else 1)
    ax.set_xlabel(f"time since first contact [{tu.label}]")
    ax.set_ylabel(f"energy [{eu.label}]")
    ax.set_title("Energy balance of the bar impact")
    _legend_outside(ax)
    return fig


def force_history(reduction, system: str, title: str = ""):
    """Fig 7: a reduced force history with F0, t_F0 and T marked, and the eq-15 fit."""
    tu, fu = display(system, "time"), display(system, "force")
    fig, ax = _figure()
    r = reduction
    t = r.time * tu.factor
    ax.plot(t, r.force * fu.factor, lw=0.8, color="0.35", label="force from the gauge record")
    ax.plot(t, r.fit(r.time) * fu.factor, "--", color="C3", label="eq (15) fit")
    ax.axvspan(r.direct_until * tu.factor, t[-1], color="C1", alpha=0.08, label="reflection-corrected")
    F0, tp, T = r.peak_force * fu.factor, r.time_of_peak * tu.factor, r.duration * tu.factor
    ax.plot([tp], [F0], "o", color="C3")
    ax.annotate(f"F0 = {F0:.3g} {fu.label}", (tp, F0), xytext=(8, 4), textcoords="offset points")
    ax.annotate("", xy=(tp, 0.45 * F0), xytext=(0, 0.45 * F0), arrowprops=dict(arrowstyle="<->"))
    ax.text(tp * 1.05, 0.45 * F0, f" tF0 = {tp:.3g} {tu.label}", ha="left", va="center")
    ax.annotate("", xy=(T, 0.2 * F0), xytext=(0, 0.2 * F0), arrowprops=dict(arrowstyle="<->"))
    ax.text(T / 2, 0.23 * F0, f"T = {T:.3g} {tu.label}", ha="center")
    ax.set_xlim(-0.05 * T, min(t[-1], 3.0 * T))
    ax.set_xlabel(f"time since first contact [{tu.label}]")
    ax.set_ylabel(f"contact force [{fu.label}]")
    ax.set_title(title or "Force history at the struck end (paper Fig 7)")
    ax.legend(fontsize="small")
    return fig


def dispersion_comparison(corrected, uncorrected, system: str):
    """Force history with and without the Pochhammer–Chree correction, on the corrected one's clock."""
    tu, fu = display(system, "time"), display(system, "force")
    fig, ax = _figure()
    shift = uncorrected.first_contact_record_time - corrected.first_contact_record_time
    ax.plot(
        (uncorrected.time + shift) * tu.factor,
        uncorrected.force * fu.factor,
        lw=0.8,
        color="0.55",
        label=f"uncorrected: non-dispersive bar (F0 = {uncorrected.peak_force * fu.factor:.4g})",
    )
    ax.plot(
        corrected.time * tu.factor,
        corrected.force * fu.factor,
        lw=0.9,
        color="C0",
        label=f"Pochhammer–Chree corrected (F0 = {corrected.peak_force * fu.factor:.4g})",
    )
    T = corrected.duration * tu.factor
    ax.set_xlim(-0.1 * T, min(corrected.time[-1] * tu.factor, 2.0 * T))
    ax.set_xlabel(f"time since first contact [{tu.label}]")
    ax.set_ylabel(f"contact force [{fu.label}]")
    ax.set_title("Dispersion correction of the force history")
    ax.legend(fontsize="small")
    return fig


def _groups(fits):
    return [(label, f) for label, f in fits.items() if label != "pooled"] or list(fits.items())


def _through_origin(ax, fits, name: str, factor: float) -> float:
    """Points and fitted line y = α·x of one law of :data:`REGRESSORS`, per group; returns the largest x shown."""
    from ..models.empirical import REGRESSORS

    _, fx, fy = REGRESSORS[name]
    top = 0.0
    for i, (label, f) in enumerate(_groups(fits)):
        x = np.array([fx(p) for p in f.points]) * factor
        y = np.array([fy(p) for p in f.points]) * factor
        a = f.origin[name]
        top = max(top, x.max())
        ax.plot(x, y, "o", color=f"C{i}", label=f"d = {label}")
        xx = np.linspace(0, x.max() * 1.05, 2)
        ax.plot(xx, a.slope * xx, "-", color=f"C{i}", label=f"α{name[-1]} = {a.slope:.3g} [{a.slope_ci[0]:.3g}, {a.slope_ci[1]:.3g}]")
    return top


def scaling_peak_force(fits, system: str):
    """Figs 8 and 12: F0 against mV²/(2d), with the fitted α1 lines."""
    fu = display(system, "force")
    fig, ax = _figure()
    _through_origin(ax, fits, "alpha1", fu.factor)
    ax.set_xlabel(f"mV²/(2d) [{fu.label}]")
    ax.set_ylabel(f"peak force F0 [{fu.label}]")
    ax.set_title("Peak force against mV²/(2d), eq (4) (paper Figs 8, 12)")
    ax.legend(fontsize="small")
    return fig


def scaling_duration(fits, system: str):
    """Figs 9 and 13: 1/T against V, with the fitted α2 (1/T = V/(α2·d))."""
    vu, tu = display(system, "velocity"), display(system, "time")
    fig, ax = _figure()
    for i, (label, f) in enumerate(_groups(fits)):
        V = np.array([p.velocity for p in f.points])
        inv = np.array([1 / (p.duration * tu.factor) for p in f.points])
        a = f.origin["alpha2"]
        d = f.points[0].diameter
        ax.plot(V * vu.factor, inv, "o", color=f"C{i}", label=f"d = {label}")
        vv = np.linspace(0, V.max() * 1.05, 2)
        ax.plot(vv * vu.factor, vv / (a.slope * d * tu.factor), color=f"C{i}", label=f"α2 = {a.slope:.3g} [{a.slope_ci[0]:.3g}, {a.slope_ci[1]:.3g}]")
    ax.set_xlabel(f"impact velocity V [{vu.label}]")
    ax.set_ylabel(f"1/T [1/{tu.label}]")
    ax.set_title("Inverse contact time against velocity, eq (5) (paper Figs 9, 13)")
    ax.legend(fontsize="small")
    return fig


def scaling_skewness(fits, system: str):
    """Figs 10 and 14: t_F0/T against V, with the fitted α3."""
    vu = display(system, "velocity")
    fig, ax = _figure()
    for i, (label, f) in enumerate(_groups(fits)):
        V = np.array([p.velocity for p in f.points]) * vu.factor
        ratio = np.array([p.time_of_peak / p.duration for p in f.points])
        a = f.origin["alpha3"]
        ax.plot(V, ratio, "o", color=f"C{i}", label=f"d = {label}")
        ax.axhline(a.slope, color=f"C{i}", label=f"α3 = {a.slope:.3g} [{a.slope_ci[0]:.3g}, {a.slope_ci[1]:.3g}]")
    ax.set_ylim(0, 0.6)
    ax.axhline(0.5, color="k", ls=":", lw=0.8)
    ax.text(ax.get_xlim()[0], 0.51, " symmetric (Hertzian) pulse", fontsize="small")
    ax.set_xlabel(f"impact velocity V [{vu.label}]")
    ax.set_ylabel("tF0 / T")
    ax.set_title("Skewness of the force history, eq (6) (paper Figs 10, 14)")
    ax.legend(fontsize="small", loc="lower right")
    return fig


def scaling_impulse(fits, system: str):
    """Figs 11 and 15: I against 2mV, with the fitted α4 and the line I = 2mV."""
    iu = display(system, "impulse")
    fig, ax = _figure()
    top = _through_origin(ax, fits, "alpha4", iu.factor)
    xx = np.linspace(0, top * 1.05, 2)
    ax.plot(xx, xx, "k:", label="I = 2mV (elastic rebound from a rigid wall)")
    ax.set_xlabel(f"incident momentum × 2, 2mV [{iu.label}]")
    ax.set_ylabel(f"impulse I [{iu.label}]")
    ax.set_title("Impulse against incident momentum, eq (7) (paper Figs 11, 15)")
    ax.legend(fontsize="small")
    return fig


def predicted_forces(histories, system: str, title: str):
    """Force histories of several models, one curve each: histories = [(label, t, F)]."""
    tu, fu = display(system, "time"), display(system, "force")
    fig, ax = _figure()
    for label, t, F in histories:
        ax.plot(t * tu.factor, F * fu.factor, label=label)
    ax.set_xlabel(f"time since first contact [{tu.label}]")
    ax.set_ylabel(f"contact force [{fu.label}]")
    ax.set_title(title)
    ax.legend(fontsize="small")
    return fig


def beam_gauge_strains(result, system: str, measured=None, title: str = ""):
    """Figs 21–22: strain at each gauge (and, if given, the measured strains as dashed lines)."""
    import matplotlib.pyplot as plt

    tu, su, lu = display(system, "time"), display(system, "strain"), display(system, "length")
    gauges = result.problem.gauges
    fig, axes = plt.subplots(len(gauges), 1, figsize=(6.6, 2.6 * len(gauges) + 0.6), sharex=True, layout="constrained", squeeze=False)
    for ax, g, eps in zip(axes[:, 0], gauges, result.strain):
        ax.grid(True, alpha=0.3)
        ax.plot(result.time * tu.factor, eps * su.factor, label="computed")
        if measured is not None and g.name in measured:
            t, y = measured[g.name]
            ax.plot(t * tu.factor, y * su.factor, "--", color="k", lw=0.8, label="measured")
        ax.axhline(0, color="k", lw=0.5)
        ax.set_ylabel(f"strain [{su.label}]")
        ax.set_title(f"gauge {g.name}: x = {g.position * lu.factor:.3g} {lu.label} from the support, {g.surface} face", fontsize="medium")
        ax.legend(fontsize="small")
    axes[-1, 0].set_xlabel(f"time since first contact [{tu.label}]")
    fig.suptitle(title or "Strain histories at the gauges (paper Figs 21, 22)")
    return fig


def beam_load_distribution(model, result, system: str, instants):
    """Fig 20: nodal forces of the contact patch at a few instants."""
    lu, fu, tu = display(system, "length"), display(system, "force"), display(system, "time")
    fig, ax = _figure(9.0, 4.0)
    loads = model.nodal_loads(result.force)
    x = (model.patch.x - model.patch.center) * lu.factor
    dt = result.time[1] - result.time[0]
    last = len(result.time) - 1
    kept = [t for t in instants if round(t / dt) <= last] or [result.time[-1]]  # a run shorter than the pulse: its instants only
    for t in kept:
        k = min(int(round(t / dt)), last)
        r = model.patch.half_width(result.force, model.problem.load.contact_radius)[k]
        ax.plot(
            x,
            loads[:, k] * fu.factor,
            "o-",
            ms=3,
            label=f"t = {result.time[k] * tu.factor:.0f} {tu.label}: F = {result.force[k] * fu.factor:.3g} {fu.label}, r = {r * lu.factor:.3g} {lu.label}",
        )
    ax.set_xlabel(f"distance from the impact point [{lu.label}]")
    ax.set_ylabel(f"nodal force [{fu.label}]")
    ax.set_title("Nodal force distribution of the contact patch (paper Fig 20)")
    _legend_outside(ax, fontsize="x-small")
    return fig


def beam_mesh(model, system: str, span: float):
    """Fig 18: a segment of the mesh around the impact point, with gauges and the patch."""
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection

    lu = display(system, "length")
    pm = model.plane
    p, t = pm.basis.mesh.p * lu.factor, pm.basis.mesh.t
    xc = model.problem.load.position * lu.factor
    fig, ax = plt.subplots(figsize=(8, 3.0), layout="constrained")
    segs = [p[:, [t[i, e], t[(i + 1) % 4, e]]].T for e in range(t.shape[1]) for i in range(4)]
    ax.add_collection(LineCollection(segs, colors="0.4", linewidths=0.4))
    r0 = model.problem.load.contact_radius * lu.factor
    top = pm.beam.thickness * lu.factor
    ax.plot([xc - r0, xc + r0], [top * 1.04] * 2, color="C3", lw=3, label="contact patch (r0)")
    lo, hi = xc - span * lu.factor, xc + span * lu.factor
    margin = 0.1 * span * lu.factor  # gauges near the window's edge are drawn whole, inside it
    for g in model.problem.gauges:
        x = g.position * lu.factor
        if lo - 2 * margin <= x <= hi + 2 * margin:
            lo, hi = min(lo, x - margin), max(hi, x + margin)
    for g in model.problem.gauges:
        x = g.position * lu.factor
        if not lo <= x <= hi:
            continue
        z = 0 if g.surface == "bottom" else top
        dz = -0.12 * top if z == 0 else 0.12 * top
        ax.plot([x], [z + dz], "^" if z == 0 else "v", color="C2", ms=7, label="gauge" if g is model.problem.gauges[0] else None)
        ax.annotate(g.name, (x, z + dz), xytext=(8, 0), textcoords="offset points", va="center", fontsize="small", color="C2")
    ax.plot([xc], [top * 1.25], "v", color="C3", ms=8, label="impact point")
    ax.set_xlim(lo, hi)
    ax.set_ylim(-0.45 * top, 1.5 * top)
    ax.set_aspect("equal")
    ax.set_xlabel(f"x [{lu.label}]")
    ax.set_ylabel(f"z [{lu.label}]")
    ax.set_title(f"Mesh near the impact point ({pm.beam.nx} × {pm.beam.nz} elements, {pm.n} DOF) (paper Fig 18)")
    ax.legend(fontsize="small", loc="upper center", bbox_to_anchor=(0.5, -0.45), ncol=3, frameon=False)
    return fig


def beam_deformed(model, result, system: str, instants):
    """The beam's mid-plane deflection at a few instants."""
    lu, tu = display(system, "length"), display(system, "time")
    fig, ax = _figure(7.0, 3.6)
    pm = model.plane
    nodes = pm.top_nodes
    x = pm.node_x[nodes]
    full = pm.expand(result.displacement)
    dofs = pm.basis.nodal_dofs[1, nodes]
    dt = result.time[1] - result.time[0]
    last = len(result.time) - 1
    kept = [t for t in instants if round(t / dt) <= last] or [result.time[-1]]  # a run shorter than the pulse: its instants only
    for t in kept:
        k = min(int(round(t / dt)), last)
        ax.plot(x * lu.factor, full[dofs, k] * lu.factor, label=f"t = {result.time[k] * tu.factor:.0f} {tu.label}")
    ax.axvline(model.problem.load.position * lu.factor, color="k", lw=0.6, ls=":")
    ax.set_xlabel(f"x, from the clamp [{lu.label}]")
    ax.set_ylabel(f"deflection of the top face [{lu.label}] (up +)")
    ax.set_title("Flexural waves spreading from the impact")
    ax.legend(fontsize="small")
    return fig


def calibration_strains(cal, model, system: str, title: str):
    """Measured against computed strain at each gauge."""
    import matplotlib.pyplot as plt

    tu, su = display(system, "time"), display(system, "strain")
    gauges = model.problem.gauges
    fig, axes = plt.subplots(len(gauges), 1, figsize=(6.6, 2.5 * len(gauges) + 0.6), sharex=True, layout="constrained", squeeze=False)
    tm = cal.time if cal.time is not None else model.problem.solver.times()
    p = cal.prepared
    for ax, g, y, c in zip(axes[:, 0], gauges, p.strains, cal.computed):
        ax.grid(True, alpha=0.3)
        ax.plot(p.time * tu.factor, y * su.factor, color="0.55", lw=0.6, label="measured (offset removed)")
        ax.plot(tm * tu.factor, c * su.factor, color="C0", label=f"computed ({cal.method})")
        ax.set_xlim(min(p.time[0], 0) * tu.factor, tm[-1] * tu.factor)
        ax.set_ylabel(f"strain [{su.label}]")
        ax.set_title(f"gauge {g.name}", fontsize="medium")
        ax.legend(fontsize="small")
    axes[-1, 0].set_xlabel(f"time since first contact [{tu.label}]")
    fig.suptitle(title)
    return fig


def calibration_forces(cal, deconvolved, system: str, title: str, truth=None):
    """The calibrated eq-15 force, the deconvolved force, the bar-model start (and the truth, when known)."""
    tu, fu = display(system, "time"), display(system, "force")
    fig, ax = _figure()
    T = cal.duration if np.isfinite(cal.duration) else cal.start.duration
    t = np.linspace(0, 1.6 * max(T, cal.start.duration), 800)
    ax.plot(t * tu.factor, cal.start(t) * fu.factor, ":", color="0.5", label="start: bar model (eqs 4-6, 15)")
    if deconvolved is not None:
        ax.plot(deconvolved.pulse.time * tu.factor, deconvolved.pulse.force * fu.factor, color="C2", lw=1, label="deconvolved")
    ax.plot(t * tu.factor, cal.pulse(t) * fu.factor, color="C0", lw=2, label=f"calibrated ({cal.method})")
    if truth is not None:
        ax.plot(t * tu.factor, truth(t) * fu.factor, "--", color="k", lw=1, label="history used to make the synthetic data")
    ax.set_xlim(0, t[-1] * tu.factor)
    ax.set_xlabel(f"time since first contact [{tu.label}]")
    ax.set_ylabel(f"contact force [{fu.label}]")
    ax.set_title(title)
    ax.legend(fontsize="small")
    return fig


REPORT_FONT_PT = 10  # text of the report's multi-panel figures: shown at >= 8 pt when a 10-in figure is shrunk to the report's ~970 px


def _superscript(n: int) -> str:
    return str(n).translate(str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹"))


def _decade(values) -> int:
    """The power of ten (a multiple of 3) that brings the largest of ``values`` below 1000: the axis is
    labelled in scaled units (``10⁶ (in/s)²``), never with matplotlib's offset or multiplier."""
    top = float(np.max(np.abs(values))) if np.size(values) else 0.0
    return 3 * int(np.floor(np.log10(top) / 3)) if top >= 1000 else 0


def _plain_axes(ax):
    """No offset or scientific multiplier on either axis (the tick labels carry the values)."""
    ax.ticklabel_format(axis="both", style="plain", useOffset=False)


def beam_force_scaling(groups, system: str):
    """Figs 23–25: F0 against V², 1/T against V, t_F0/T against V, for each beam (groups: label → rows
    of (V, F0, tF0, T) in SI; labels ending in '(paper)' are drawn as open markers, as in the paper, large
    and above ours, which are small filled markers, so that neither hides the other), each with its line
    through the origin (eqs 4-6; the paper's dotted). Two by two, the fourth panel the legend; V² in scaled
    units and 1/T in 1/ms (no offset notation); text at :data:`REPORT_FONT_PT`."""
    import matplotlib.pyplot as plt

    vu, fu = display(system, "velocity"), display(system, "force")
    prepared = []
    for label, rows in groups.items():
        rows = np.asarray(rows, float)
        if rows.size:
            prepared.append((label, rows.reshape(-1, 4)))
    v2 = np.concatenate([(r[:, 0] * vu.factor) ** 2 for _, r in prepared]) if prepared else np.zeros(0)
    k = _decade(v2)
    with plt.rc_context({"font.size": REPORT_FONT_PT}):
        fig, grid = plt.subplots(2, 2, figsize=(10, 7.2), layout="constrained")
        axes, key = grid.ravel()[:3], grid.ravel()[3]
        for i, (label, rows) in enumerate(prepared):
            V, F0, tp, T = rows.T
            paper = label.endswith("(paper)")
            color = f"C{i // 2}" if len(groups) > 2 else f"C{i}"
            if paper:
                style = dict(marker="o", ms=10, mew=1.5, mfc="none", ls="", color=color, zorder=3, label=label)
            else:
                style = dict(marker="o", ms=5, ls="", color=color, zorder=2, label=label)
            line = dict(color=color, ls=":" if paper else "-", lw=1.3 if paper else 1.0, zorder=1)
            x, v = (V * vu.factor) ** 2 / 10.0**k, V * vu.factor
            inv_T = 1e-3 / T  # 1/ms
            axes[0].plot(x, F0 * fu.factor, **style)
            axes[1].plot(v, inv_T, **style)
            axes[2].plot(v, tp / T, **style)
            # Eqs (4)-(6) through the origin: F0 ∝ V², 1/T ∝ V, tF0/T constant.
            xs, vs = np.linspace(0, x.max() * 1.05, 50), np.linspace(0, v.max() * 1.05, 50)
            axes[0].plot(xs, xs * (x @ (F0 * fu.factor)) / (x @ x), **line)
            axes[1].plot(vs, vs * (v @ inv_T) / (v @ v), **line)
            axes[2].plot(vs, np.full_like(vs, np.mean(tp / T)), **line)
        scale = f"10{_superscript(k)} " if k else ""
        axes[0].set_xlabel(f"V² [{scale}({vu.label})²]")
        axes[0].set_ylabel(f"F0 [{fu.label}]")
        axes[0].set_title("Fig 23: force amplitude against V²")
        axes[1].set_xlabel(f"V [{vu.label}]")
        axes[1].set_ylabel("1/T [1/ms]")
        axes[1].set_title("Fig 24: inverse contact time against V")
        axes[2].set_xlabel(f"V [{vu.label}]")
        axes[2].set_ylabel("tF0 / T")
        axes[2].set_ylim(0, 0.3)
        axes[2].set_title("Fig 25: skewness against V")
        for ax in axes:
            ax.grid(True, alpha=0.3)
            _plain_axes(ax)
        key.axis("off")
        handles, labels = axes[0].get_legend_handles_labels()
        if handles:
            key.legend(handles, labels, loc="center", frameon=False, title="filled: ours; open: the paper's; lines: fits through the origin")
    return fig
