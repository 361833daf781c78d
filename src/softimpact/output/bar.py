"""Outputs of ``softimpact bar``: history.csv, summary.json, strain-along-bar.csv, Figs 4–6."""

from __future__ import annotations

import numpy as np

from ..fem.bar import Rod
from ..units import display
from .files import csv_text, figure_bytes, json_text, strain_peaks, with_units
from .impact import impact_columns
from .report import Section

__all__ = ["bar_summary", "bar_validity", "bar_files", "bar_section"]

MICROSECOND = 1e-6  # s: the column names of strain-along-bar.csv give the instant in µs (file contract)


def bar_validity(result):
    """The contact law's envelope on the bar (:func:`softimpact.models.validity.contact_validity`): approach
    against the projectile's diameter, contact radius against the projectile's and the bar's radius, and the
    law's own envelope (:func:`softimpact.models.contact_laws.law_validity`)."""
    from ..models.contact_laws import law_validity
    from ..models.validity import contact_validity

    p = result.problem
    v = contact_validity(p.law_name, float(np.max(result.approach)), float(np.max(result.contact_radius)), p.projectile.diameter, p.bar.diameter / 2)
    return v + law_validity(p.contact_law(), p.projectile.velocity)  # the law's own envelope (ice: strain rate; gelatin: shock)


def bar_summary(result, plain=None) -> dict:
    """The scalars of a bar run, SI with unit-suffixed keys, and the resolved case; with ``plain`` (the same run
    without the end cap) also its first-contact scalars (``without_end_cap``).

    ``energy_balance_relative`` (the key every command's summary.json uses for its energy check): the
    spread (max − min) of the mechanical energy, projectile KE + bar KE + strain energy + the contact's
    stored energy (:attr:`softimpact.fem.energies.Energies.mechanical`), over the run, relative to its
    initial value (the impact KE). The mechanical energy is constant for an elastic contact law (Hertz), so
    there it measures the coupled stepping's energy error; a lossy law adds what it dissipates."""
    p = result.problem
    gauges = {}
    for g, eps in zip(p.gauges, result.strain):
        gauges[g.name] = {"position_m": g.position, **strain_peaks(result.time, eps)}
    e = result.energies.mechanical
    out = {
        "title": p.title,
        "peak_force_N": result.peak_force,
        "time_of_peak_s": result.time_of_peak,
        "contact_duration_s": result.contact_duration,
        "impulse_N_s": result.total_impulse,
        "rebound_velocity_m_s": result.rebound_velocity,
        "rebound_velocity_note": "impactor velocity after separation, positive toward the bar (negative = bounced back)",
        "contact_intervals": len(result.contacts),
        "projectile_mass_kg": p.projectile.mass,
        "end_cap_mass_kg": 0.0 if p.bar.end_cap is None else p.bar.end_cap.mass,
        "hertz_constant_N_per_m1_5": p.hertz().K,
        "bar_wave_speed_m_s": Rod.of(p.bar).wave_speed,
        "energy_balance_relative": float((e.max() - e.min()) / e[0]),
        "newton_iterations": result.newton_iterations,
        "gauges": gauges,
        "validity": bar_validity(result).summary(),
        "case_SI": _case(p),
    }
    if plain is not None:
        out["without_end_cap"] = {
            "peak_force_N": plain.peak_force,
            "time_of_peak_s": plain.time_of_peak,
            "contact_duration_s": plain.contact_duration,
        }
    return out


def _case(p) -> dict:
    """The resolved case as summary.json has always written it: ``contact`` the law's name and ``law``
    the law object (null for the bar's own Hertz law), though the problem holds one ``law``."""
    return {
        "bar": p.bar,
        "projectile": p.projectile,
        "solver": p.solver,
        "gauges": p.gauges,
        "contact": p.law_name,
        "title": p.title,
        "snapshots": p.snapshots,
        "law": None if isinstance(p.law, str) else p.law,
    }


def bar_files(
    result, plain=None, inferred=None, figures: bool = True, prefix: str = "", summary: dict | None = None, *, units: str = "in-lbf-s"
) -> dict[str, bytes | str]:
    """history.csv, summary.json, strain-along-bar.csv and (optionally) Figs 4–6 and the energy plot.

    ``plain``: the same run without the end cap (Fig 5); ``inferred``: (time, force,
    gauge name), the force read from a gauge (Fig 5); ``summary``: the run path's :func:`bar_summary`
    (made here when None); ``units``: the display system of the figures (and summary.json's ``case_SI.units``).
    """
    from . import plots

    p = result.problem
    cols = impact_columns(result, target=False, energies=False)
    cols["energy_total_J"] = result.energies.mechanical
    summary = bar_summary(result, plain) if summary is None else summary
    files = {prefix + "history.csv": csv_text(cols), prefix + "summary.json": json_text(with_units(summary, units))}
    L_over_c = p.bar.length / Rod.of(p.bar).wave_speed
    chosen = [t for t in p.snapshots if t <= result.time[-1]]
    instants = np.array(chosen) if chosen else np.linspace(0.0, min(result.time[-1], 2.0 * L_over_c), 7)[1:]
    dt = result.time[1] - result.time[0]
    along = {"x_m": result.bar_x}
    for t in instants:
        k = int(round(t / dt))
        along[f"strain_t{result.time[k] / MICROSECOND:.1f}us"] = result.bar_strain[:, k]
    files[prefix + "strain-along-bar.csv"] = csv_text(along)
    if figures:
        system = units
        files[prefix + "fig04-gauge-strain.png"] = figure_bytes(plots.bar_gauge_strain(result, system))
        files[prefix + "fig05-contact-force.png"] = figure_bytes(plots.bar_contact_force(result, plain, inferred, system))
        files[prefix + "fig06-strain-along-bar.png"] = figure_bytes(plots.bar_strain_profiles(result, instants, system))
        files[prefix + "energy.png"] = figure_bytes(plots.bar_energy(result, system))
    return files


def bar_section(result, plain, lag, prefix: str, units: str = "in-lbf-s") -> Section:
    """The report section of the calibration test, in display ``units``; ``lag``: the gauge-derived force's
    (peak ratio, time lag [s]) against the contact force, or None without a gauge."""
    p = result.problem
    sysname = units
    fu, tu, su = display(sysname, "force"), display(sysname, "time"), display(sysname, "strain")
    iu, vu = display(sysname, "impulse"), display(sysname, "velocity")
    reading = "The force read from the gauge is F = −EA·ε(t + x/c)."
    if lag is not None:
        ratio, delay = lag
        reading = (
            f"The force read from the gauge, F = −EA·ε(t + x/c), peaks {abs(1 - ratio):.1%} {'below' if ratio < 1 else 'above'} the contact force "
            f"and {delay * tu.factor:.1f} {tu.label} {'later' if delay >= 0 else 'earlier'}"
            + (
                ": the end cap's inertia sits between the contact and the bar, so the bar carries the force less the cap's "
                "m·a, delayed by the cap. A record reduced without the end-cap correction would understate F0 by this much."
                if p.bar.end_cap is not None
                else "."
            )
        )
    rows = [
        ["peak contact force", f"{result.peak_force * fu.factor:.1f} {fu.label}"],
        ["time of peak", f"{result.time_of_peak * tu.factor:.1f} {tu.label}"],
        ["contact duration", f"{result.contact_duration * tu.factor:.1f} {tu.label}"],
        ["impulse", f"{result.total_impulse * iu.factor:.4g} {iu.label}"],
        ["rebound velocity (toward bar +)", f"{result.rebound_velocity * vu.factor:.3g} {vu.label}"],
    ]
    if plain is not None:
        rows.append(["peak force without end cap", f"{plain.peak_force * fu.factor:.1f} {fu.label}"])
        rows.append(["contact duration without end cap", f"{plain.contact_duration * tu.factor:.1f} {tu.label}"])
    for g, eps in zip(p.gauges, result.strain):
        k = int(np.argmin(eps))
        rows.append([f"peak compressive strain at {g.name}", f"{eps[k] * su.factor:.1f} {su.label} at {result.time[k] * tu.factor:.1f} {tu.label}"])
    return Section(
        p.title or "Bar impact",
        [
            "Hermite rod elements (u, du/dx per node), Hertz contact (eq 3) to a lumped impactor mass, "
            "Newmark average acceleration with Newton iterations on the contact. The end cap is lumped mass at the struck end. " + reading
        ],
        [("Calibration test results", ["quantity", "value"], rows)],
        [
            (prefix + "fig04-gauge-strain.png", "Fig 4: strain history at the gauge"),
            (prefix + "fig05-contact-force.png", "Fig 5: contact force with and without end cap, and as read from the gauge"),
            (prefix + "fig06-strain-along-bar.png", "Fig 6: strain along the bar; the compressive pulse returns from the free end as tension"),
            (prefix + "energy.png", "Energy balance (the total stays flat)"),
        ],
    )
