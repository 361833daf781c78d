"""Outputs of ``softimpact impact``: history.csv, summary.json and the figures of a coupled impact."""

from __future__ import annotations

import math

import numpy as np

from ..units import display
from .files import case_record, csv_text, figure_bytes, json_text, strain_peaks, with_units

__all__ = ["damage_keys", "impact_summary", "impact_columns", "impact_files", "impact_figures", "snapshot_steps", "SNAPSHOTS"]

SNAPSHOTS = 6  # instants of a plate's deflected-shape figure


def snapshot_steps(steps: int) -> np.ndarray:
    """Step indices of a plate's deflected-shape figure: SNAPSHOTS instants doubling up to the end
    of the run (…, T/4, T/2, T), so the early, local wave and the later whole-plate response both show."""
    return np.unique(np.maximum(np.round(steps / 2.0 ** np.arange(SNAPSHOTS - 1, -1, -1)).astype(int), 1))


def damage_keys(points) -> tuple[str, ...]:
    """The dotted ``damage`` outputs of summary.json (sweeps) for damage ``points`` ("at_load", "at_<gauge>"):
    the worst of each criterion, the delamination and interlaminar scalars (Davies–Zhang, Olsson's onset, the
    interfaces' largest shear and largest shear averaged around the load, the mass ratio of the regime, the bending
    stiffness left by the failed plies), and each point's criteria."""
    from ..models.failure import CRITERIA

    keys = [f"damage.{c}" for c in CRITERIA] + [f"damage.{k}" for k in ("delamination", "threshold_force_N", "interlaminar_shear_max_Pa", "interlaminar_index")]
    keys += [f"damage.{k}" for k in ("olsson_threshold_force_N", "peak_over_olsson", "interface_shear_max_Pa", "impactor_over_target_mass")]
    keys += [f"damage.{k}" for k in ("interface_shear_mean_max_Pa", "residual_D11_ratio", "residual_D22_ratio")]
    return tuple(keys + [f"damage.{p}.{c}" for p in points for c in CRITERIA])


def _contact(c) -> dict:
    return {
        "start_s": c.start,
        "end_s": c.end,
        "duration_s": c.duration,
        "peak_force_N": c.peak_force,
        "time_of_peak_s": c.time_of_peak,
        "impulse_N_s": c.impulse,
    }


def impact_summary(problem, result, validity, damage: dict | None = None, damage_note: str | None = None, extras: dict | None = None) -> dict:
    """summary.json of a coupled run: the scalars of the first contact, every contact, gauge peaks (with each
    gauge's own entries, :meth:`~softimpact.models.protocols.Target.gauge_summary`), the target's ``extras``
    (:meth:`~softimpact.models.protocols.Target.summary_extras`), ``damage`` (``ImpactDamage.summary()``) or the
    ``damage_note`` saying why there is none, the run's ``validity`` and the resolved case; SI. Computes nothing:
    the run path (:func:`softimpact.cases.run.execute`) gives them."""
    gauges = {}
    for g, (name, eps) in zip(problem.target.gauges, zip(result.strain_names, result.strain)):
        gauges[name] = {**strain_peaks(result.time, eps), "peak_abs_strain": float(np.max(np.abs(eps))), **problem.target.gauge_summary(g)}
    first = result.contacts[0]
    sel = result.time <= (first.end if math.isfinite(first.end) else result.time[-1])
    E = result.energies
    KE0 = result.impactor.kinetic_energy
    balance = E.total - KE0 - E.surface_mismatch
    # after the first contact: KE0 = rebound KE + structure energy + contact work, short by the mismatch
    k_sep = int(np.searchsorted(result.time, first.end)) if math.isfinite(first.end) else None
    after = float(E.surface_mismatch[k_sep] / KE0) if k_sep is not None and k_sep < result.time.size else None
    threat = getattr(problem, "threat", None)
    return {
        "title": problem.title,
        **({"threat": threat.summary()} if threat is not None else {}),
        "contact_law": problem.law_name,
        "peak_force_N": result.peak_force,
        "time_of_peak_s": result.time_of_peak,
        "contact_duration_s": result.contact_duration,
        **(
            {}
            if math.isfinite(result.contact_duration)
            else {
                "contact_duration_note": f"null: the first contact had not ended at the end of the run ({float(result.time[-1]) * 1e6:.4g} us); "
                "its duration and the rebound velocity are unknown and its peak may come later: lengthen solver.duration"
            }
        ),
        "impulse_N_s": result.impulse,
        "rebound_velocity_m_s": result.rebound_velocity,
        "rebound_velocity_note": "impactor velocity after the first contact, positive toward the target (negative = bounced back), as for the bar",
        "max_approach_m": float(np.max(result.approach[sel])),
        "max_contact_radius_m": float(np.max(result.contact_radius[sel])),
        "contacts": [_contact(c) for c in result.contacts],
        "number_of_contacts": len(result.contacts),
        "total_impulse_N_s": result.total_impulse,
        "final_impactor_velocity_m_s": result.final_velocity,
        "impactor_mass_kg": result.impactor.mass,
        "impactor_kinetic_energy_J": KE0,
        "energy_balance_relative": float(np.max(np.abs(balance)) / KE0) if np.all(np.isfinite(balance)) else None,
        "surface_mismatch_relative_max": float(np.max(np.abs(E.surface_mismatch)) / KE0),
        "energy_error_after_first_contact_relative": after,
        "energy_note": "energy_balance_relative: KE0 = impactor KE + structure energy + contact work + surface mismatch, to round-off; "
        "the mismatch (work of the force on the loaded nodes minus on the mid-surface point of the approach) is the formulation's "
        "energy error: its largest value over the run, and its value at the end of the first contact",
        "newton_iterations": result.newton_iterations,
        "gauges": gauges,
        **(extras or {}),
        **({"damage": damage} if damage is not None else {"damage_note": damage_note} if damage_note is not None else {}),
        "validity": validity.summary(),
        "case_SI": case_record(problem),
    }


def impact_columns(result, target: bool = True, energies: bool = True) -> dict[str, np.ndarray]:
    """The columns of history.csv of a coupled run (:class:`softimpact.fem.impact.CoupledResult`): time,
    force, impactor, approach; with ``target`` the approach rate, contact radius and target
    deflection; the strains; with ``energies`` the energy histories. The bar's history.csv is
    this builder without ``target`` and ``energies`` (:func:`softimpact.output.bar.bar_files`)."""
    cols = {
        "time_s": result.time,
        "contact_force_N": result.force,
        "impactor_velocity_m_s": result.impactor_velocity,
        "impactor_displacement_m": result.impactor_displacement,
        "approach_m": result.approach,
    }
    if target:
        cols["approach_rate_m_s"] = result.approach_rate
        cols["contact_radius_m"] = result.contact_radius
        cols["target_displacement_m"] = result.target_displacement
    for name, eps in zip(result.strain_names, result.strain):
        cols[f"strain_{name}"] = eps
    for name, values in zip(*(result.groups or {}).get("columns", ((), ()))):
        cols[name] = values  # the target's own columns, by their names (cohesive interfaces: delaminated areas, energies)
    if energies:
        E = result.energies
        cols["impactor_kinetic_energy_J"] = E.impactor_kinetic
        cols["structure_kinetic_energy_J"] = E.kinetic
        cols["structure_strain_energy_J"] = E.strain
        cols["contact_work_J"] = E.contact_work
        cols["contact_stored_energy_J"] = E.contact_energy
        cols["surface_mismatch_J"] = E.surface_mismatch
    return cols


def impact_figures(problem, result, prefix: str = "", units: str = "in-lbf-s") -> dict[str, bytes]:
    """force-history.png, approach.png, gauge-strains.png, energy.png, in display ``units``."""
    from .plots import _figure

    system = units
    tu, fu, lu, su = (display(system, k) for k in ("time", "force", "length", "strain"))
    t = result.time * tu.factor
    out = {}

    fig, ax = _figure()
    ax.plot(t, result.force * fu.factor, label=f"contact force ({problem.law_name})")
    for i, c in enumerate(result.contacts):
        ax.axvline(c.start * tu.factor, color="0.6", lw=0.8, ls=":")
        ax.annotate(f"contact {i + 1}", (c.start * tu.factor, c.peak_force * fu.factor), fontsize=8)
    ax.set_xlabel(f"time since first contact [{tu.label}]")
    ax.set_ylabel(f"contact force [{fu.label}] (compression +)")
    ax.set_title(f"{problem.title}: contact force", fontsize=10)
    ax.legend()
    out[prefix + "force-history.png"] = figure_bytes(fig)

    fig, ax = _figure()
    ax.plot(t, result.impactor_displacement * lu.factor, label="impactor displacement")
    ax.plot(t, result.target_displacement * lu.factor, label="target mid-surface displacement")
    ax.plot(t, result.approach * lu.factor, label="approach α (contact law's indentation)")
    ax.plot(t, result.contact_radius * lu.factor, "--", label="contact radius")
    ax.set_xlabel(f"time since first contact [{tu.label}]")
    ax.set_ylabel(f"[{lu.label}] (along the impact direction)")
    ax.set_title("Approach: impactor minus target mid-surface", fontsize=10)
    ax.legend(fontsize=8)
    out[prefix + "approach.png"] = figure_bytes(fig)

    fig, ax = _figure()
    for name, eps in zip(result.strain_names, result.strain):
        ax.plot(t, eps * su.factor, label=f"gauge {name}")
    ax.set_xlabel(f"time since first contact [{tu.label}]")
    ax.set_ylabel(f"axial strain [{su.label}] (tension +)")
    ax.set_title("Strain at the gauges, coupled impact", fontsize=10)
    if len(result.strain_names):
        ax.legend()
    out[prefix + "gauge-strains.png"] = figure_bytes(fig)

    fig, ax = _figure()
    E = result.energies
    KE0 = result.impactor.kinetic_energy
    for label, e in (
        ("impactor kinetic", E.impactor_kinetic),
        ("structure kinetic", E.kinetic),
        ("structure strain", E.strain),
        ("stored in the contact", E.contact_energy),
        ("lost in the contact", E.contact_loss),
        ("sum − surface mismatch", E.total - E.surface_mismatch),
    ):
        ax.plot(t, e / KE0, label=label)
    ax.set_xlabel(f"time since first contact [{tu.label}]")
    ax.set_ylabel("energy / impactor's initial kinetic energy")
    ax.set_title("Energy balance", fontsize=10)
    ax.legend(fontsize=8)
    out[prefix + "energy.png"] = figure_bytes(fig)
    return out


def plate_impact_figures(problem, model, result, prefix: str = "", units: str = "in-lbf-s") -> dict[str, bytes]:
    """plate-mesh.png (the impact point, the widest contact disc reached, the gauges) and
    deflection.png (the mid-surface at the kept instants), in display ``units``."""
    from types import SimpleNamespace

    from . import plate_plots

    p = problem.target
    r_max = float(np.max(result.contact_radius))
    shown = SimpleNamespace(fe=model.fe, problem=p)
    lu = display(units, "length")
    label = f"widest contact disc (r = {r_max * lu.factor:.3g} {lu.label})"
    out = {prefix + "plate-mesh.png": figure_bytes(plate_plots.plate_mesh(shown, units, patch=(r_max, label)))}
    if result.displacement is not None and result.displacement.shape[1]:
        out[prefix + "deflection.png"] = figure_bytes(plate_plots.plate_deflection(model, result, units))
    return out


def impact_files(problem, result, figures: bool = True, prefix: str = "", model=None, *, summary: dict, units: str = "in-lbf-s") -> dict[str, bytes | str]:
    """history.csv, summary.json (``summary``: :func:`impact_summary`'s, from the run path) and (optionally) the
    figures in display ``units`` (also summary.json's ``case_SI.units``); for a target that draws its deflected shapes (a plate, ``model`` its PlateModel) also its mesh and
    deflected shapes. ``result``'s gauges only: its other output groups (the damage strains) fed ``summary``."""
    files = {prefix + "history.csv": csv_text(impact_columns(result)), prefix + "summary.json": json_text(with_units(summary, units))}
    if figures:
        files.update(impact_figures(problem, result, prefix, units))
        if problem.target.deflected_shapes and model is not None:
            files.update(plate_impact_figures(problem, model, result, prefix, units))
            if "columns" in (result.groups or {}):  # cohesive interfaces: the delaminated area and the damage map
                from .delamination_plots import delamination_figures

                files.update(delamination_figures(problem, model, result, prefix, units))
    return files
