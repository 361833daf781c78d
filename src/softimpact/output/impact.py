"""Outputs of ``softimpact impact``: history.csv, summary.json and the figures of a coupled impact."""

from __future__ import annotations

import math

import numpy as np

from ..studies.damage import DAMAGE_PREFIX, _bar, _opposite, damage_problem, split_damage
from ..units import display
from .files import csv_text, figure_bytes, json_text, strain_peaks

__all__ = [
    "DAMAGE_PREFIX",
    "damage_problem",
    "damage_keys",
    "split_damage",
    "impact_damage_summary",
    "impact_summary",
    "impact_columns",
    "impact_files",
    "impact_figures",
    "snapshot_steps",
    "SNAPSHOTS",
]

SNAPSHOTS = 6  # instants of a plate's deflected-shape figure


def snapshot_steps(steps: int) -> np.ndarray:
    """Step indices of a plate's deflected-shape figure: SNAPSHOTS instants doubling up to the end
    of the run (…, T/4, T/2, T), so the early, local wave and the later whole-plate response both show."""
    return np.unique(np.maximum(np.round(steps / 2.0 ** np.arange(SNAPSHOTS - 1, -1, -1)).astype(int), 1))


def damage_keys(problem) -> tuple[str, ...]:
    """The dotted damage outputs of an impact problem (sweeps): none unless :func:`damage_problem` adds its gauges."""
    from ..models.failure import CRITERIA

    if _bar(problem) or damage_problem(problem) is problem:
        return ()
    points = ["at_load"] + [f"at_{g.name}" for g in problem.target.gauges]
    keys = [f"damage.{c}" for c in CRITERIA] + [f"damage.{k}" for k in ("delamination", "threshold_force_N", "interlaminar_shear_max_Pa", "interlaminar_index")]
    return tuple(keys + [f"damage.{p}.{c}" for p in points for c in CRITERIA])


def _no_damage(problem) -> dict:
    """``damage_note``: why an impact has no damage outputs, when its target's laminate is the reason
    (no layup, or a ply without strengths); empty otherwise (the run was not asked for them)."""
    from ..workflows.damage import damage_refusal

    why = None if _bar(problem) else damage_refusal(problem)
    return {} if why is None else {"damage_note": why}


def impact_damage_summary(problem, result, pseudo: dict) -> dict:
    """summary.json's ``damage`` of a coupled impact (:func:`softimpact.workflows.damage.impact_damage`):
    indices at the load point and at each gauge, Davies–Zhang against the peak force, interlaminar shear."""
    from ..workflows.damage import impact_damage, section_strains, strain_tensor

    target = problem.target
    stack = target.plate.stack if problem.on_plate else target.beam.stack
    points = {}
    if problem.on_plate:
        for name in ["at_load"] + [f"at_{g.name}" for g in target.gauges]:
            top, bottom = (strain_tensor(*(pseudo[f"{DAMAGE_PREFIX}.{name}.{f}.{d}"] for d in ("x", "y", "45.0"))) for f in ("top", "bottom"))
            points[name] = (0.5 * (top + bottom), (top - bottom) / stack.thickness)
        width = None
    else:
        plane = target.beam.plane
        points["at_load"] = section_strains(stack, plane, pseudo[f"{DAMAGE_PREFIX}.at_load.top"], pseudo[f"{DAMAGE_PREFIX}.at_load.bottom"])
        for j, g in enumerate(target.gauges):
            other = pseudo[f"{DAMAGE_PREFIX}.at_{g.name}.{_opposite(g.surface)}"]
            top, bottom = (result.strain[j], other) if g.surface == "top" else (other, result.strain[j])
            points[f"at_{g.name}"] = section_strains(stack, plane, top, bottom)
        width = target.beam.width
    peak = max(c.peak_force for c in result.contacts)  # every contact's refined peak (parabola through the top samples)
    dmg = impact_damage(stack, stack.ply.strength, points, result.force, result.contact_radius, width, peak)
    return dmg.summary()


def impact_validity(problem, result, damage: dict | None = None):
    """The envelopes of a coupled run (:mod:`softimpact.models.validity`): the contact law's approach and
    contact radius against the impactor's size, the target's deflection against its thickness (linear
    theory), and with ``damage`` (summary.json's) the strains against the ply allowables."""
    from ..models.validity import allowable_flags, contact_validity, deflection_validity

    d = problem.impactor.diameter
    v = contact_validity(problem.law_name, float(np.max(result.approach)), float(np.max(result.contact_radius)), d)
    if problem.on_plate:
        v += deflection_validity("linear plate theory (FSDT)", float(np.max(np.abs(result.deflection))), problem.target.plate.stack.thickness)
    else:
        v += deflection_validity("linear beam theory", float(np.max(np.abs(result.deflection))), problem.target.beam.thickness)
    if damage is not None:
        v += allowable_flags("the target's plies", damage["max_strain"])
    return v


def _contact(c) -> dict:
    return {
        "start_s": c.start,
        "end_s": c.end,
        "duration_s": c.duration,
        "peak_force_N": c.peak_force,
        "time_of_peak_s": c.time_of_peak,
        "impulse_N_s": c.impulse,
    }


def _plate_target(problem, model, result) -> dict:
    """What a plate user reads besides the impact's scalars: the model, and the mid-surface
    deflection under the impact point (along the impact direction, down +)."""
    p = problem.target
    w = result.deflection
    k = int(np.argmax(np.abs(w)))
    return {
        "model": f"fsdt ({p.plate.element.upper()})",
        "dofs": model.fe.n,
        "elements": list(p.plate.elements),
        "supports": dict(zip(("x0", "x1", "y0", "y1"), p.plate.supports)),
        "impact_point_m": list(p.load.position),
        "peak_deflection_at_impact_m": float(w[k]),
        "time_of_peak_deflection_s": float(result.time[k]),
        "deflection_note": "mid-surface deflection under the impact point, positive along the impact direction (into the plate)",
    }


def impact_summary(problem, result, model=None) -> dict:
    """The scalars of a coupled run (first contact), every contact, gauge peaks and the resolved case; SI.
    On a plate (``model`` a PlateModel) also ``target``: the plate model and its deflection under the impact.
    With the damage pseudo-gauges (:func:`damage_problem`) also ``damage`` (:func:`impact_damage_summary`)."""
    problem, result, pseudo = split_damage(problem, result)
    damage = impact_damage_summary(problem, result, pseudo) if pseudo else None
    plate = getattr(problem, "on_plate", False)
    gauges = {}
    for j, (name, eps) in enumerate(zip(result.strain_names, result.strain)):
        gauges[name] = {**strain_peaks(result.time, eps), "peak_abs_strain": float(np.max(np.abs(eps)))}
        if plate:
            g = problem.target.gauges[j]
            gauges[name].update(position_m=list(g.position), surface=g.surface, direction=g.direction, length_m=g.length)
    first = result.contacts[0]
    sel = result.time <= (first.end if math.isfinite(first.end) else result.time[-1])
    E = result.energies
    KE0 = result.impactor.kinetic_energy
    balance = E.total - KE0 - E.surface_mismatch
    # after the first contact: KE0 = rebound KE + structure energy + contact work, short by the mismatch
    k_sep = int(np.searchsorted(result.time, first.end)) if math.isfinite(first.end) else None
    after = float(E.surface_mismatch[k_sep] / KE0) if k_sep is not None and k_sep < result.time.size else None
    return {
        "title": problem.title,
        "contact_law": problem.law_name,
        "peak_force_N": result.peak_force,
        "time_of_peak_s": result.time_of_peak,
        "contact_duration_s": result.contact_duration,
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
        **({"target": _plate_target(problem, model, result)} if plate and model is not None else {}),
        **({"damage": damage} if damage is not None else _no_damage(problem)),
        "validity": impact_validity(problem, result, damage).summary(),
        "case_SI": problem,
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
        cols["target_displacement_m"] = result.deflection
    for name, eps in zip(result.strain_names, result.strain):
        cols[f"strain_{name}"] = eps
    if energies:
        E = result.energies
        cols["impactor_kinetic_energy_J"] = E.impactor_kinetic
        cols["structure_kinetic_energy_J"] = E.kinetic
        cols["structure_strain_energy_J"] = E.strain
        cols["contact_work_J"] = E.contact_work
        cols["contact_stored_energy_J"] = E.contact_energy
        cols["surface_mismatch_J"] = E.surface_mismatch
    return cols


def impact_figures(problem, result, prefix: str = "") -> dict[str, bytes]:
    """force-history.png, approach.png, gauge-strains.png, energy.png."""
    from .plots import _figure

    system = problem.units
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
    ax.plot(t, result.deflection * lu.factor, label="target mid-surface displacement")
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


def plate_impact_figures(problem, model, result, prefix: str = "") -> dict[str, bytes]:
    """plate-mesh.png (the impact point, the widest contact disc reached, the gauges) and
    deflection.png (the mid-surface at the kept instants)."""
    from types import SimpleNamespace

    from . import plate_plots

    p = problem.target
    r_max = float(np.max(result.contact_radius))
    shown = SimpleNamespace(fe=model.fe, problem=p)
    lu = display(problem.units, "length")
    label = f"widest contact disc (r = {r_max * lu.factor:.3g} {lu.label})"
    out = {prefix + "plate-mesh.png": figure_bytes(plate_plots.plate_mesh(shown, problem.units, patch=(r_max, label)))}
    if result.displacement is not None and result.displacement.shape[1]:
        out[prefix + "deflection.png"] = figure_bytes(plate_plots.plate_deflection(model, result, problem.units))
    return out


def impact_files(problem, result, figures: bool = True, prefix: str = "", model=None) -> dict[str, bytes | str]:
    """history.csv, summary.json and (optionally) the figures; on a plate (``model`` its PlateModel)
    also the plate's mesh and deflected shapes. The damage pseudo-gauges (:func:`damage_problem`) feed
    summary.json's ``damage`` only."""
    summary = json_text(impact_summary(problem, result, model))
    problem, result, _ = split_damage(problem, result)
    files = {prefix + "history.csv": csv_text(impact_columns(result)), prefix + "summary.json": summary}
    if figures:
        files.update(impact_figures(problem, result, prefix))
        if getattr(problem, "on_plate", False) and model is not None:
            files.update(plate_impact_figures(problem, model, result, prefix))
    return files
