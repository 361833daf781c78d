"""Figures (matplotlib, imported on use). Each function returns a Figure.

Quantities arrive in SI and are shown in the case's display units.
"""

from __future__ import annotations

import numpy as np

from .units import display

__all__ = ["bar_gauge_strain", "bar_contact_force", "bar_strain_profiles", "bar_energy"]


def _figure(width=6.4, height=4.0):
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(width, height), layout="constrained")
    ax.grid(True, alpha=0.3)
    return fig, ax


def bar_gauge_strain(result, system: str):
    """Fig 4: strain history at each gauge."""
    tu, su = display(system, "time"), display(system, "strain")
    fig, ax = _figure()
    for gauge, eps in zip(result.problem.gauges, result.gauge_strain):
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
    ax.plot(result.time * tu.factor, result.contact_force * fu.factor, label="FE, with end cap" if cap else "FE")
    if plain is not None:
        ax.plot(plain.time * tu.factor, plain.contact_force * fu.factor, "--", label="FE, without end cap")
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
    fig, ax = _figure(7.0, 4.2)
    for t in instants:
        k = int(round(t / (result.time[1] - result.time[0])))
        ax.plot(result.bar_x * lu.factor, result.bar_strain[:, k] * su.factor, label=f"t = {result.time[k] * tu.factor:.0f} {tu.label}")
    for g in result.problem.gauges:
        ax.axvline(g.position * lu.factor, color="k", lw=0.6, ls=":")
    ax.set_xlabel(f"distance from the struck end [{lu.label}]")
    ax.set_ylabel(f"axial strain [{su.label}] (tension +)")
    ax.set_title("Propagation and free-end reflection of the strain pulse (paper Fig 6)")
    ax.legend(fontsize="small", ncol=2)
    return fig


def bar_energy(result):
    """Energy terms and their sum (the sum should stay flat)."""
    fig, ax = _figure()
    e = result.energies
    us = 1e6
    for label, y in (
        ("impactor kinetic", e.impactor_kinetic),
        ("bar kinetic", e.bar_kinetic),
        ("bar strain", e.bar_strain),
        ("contact", e.contact),
        ("total", e.total),
    ):
        ax.plot(result.time * us, y * 1e3, label=label, lw=2 if label == "total" else 1)
    ax.set_xlabel("time since first contact [µs]")
    ax.set_ylabel("energy [mJ]")
    ax.set_title("Energy balance of the bar impact")
    ax.legend()
    return fig
