"""Outputs of ``softimpact beam``: history.csv, summary.json, Figs 18 and 20–22, the deformed beam."""

from __future__ import annotations

import numpy as np

from ..models.features import first_zero_crossing
from ..units import display
from .files import csv_text, energy_balance, figure_bytes, json_text, strain_peaks, with_units
from .report import Section

__all__ = ["beam_summary", "beam_scalars", "beam_files", "beam_section"]


def beam_summary(model, result, validity) -> dict:
    """The scalars of a beam run, SI with unit-suffixed keys, its ``validity`` (a
    :class:`~softimpact.models.validity.Validity`, :func:`softimpact.cases.beam.beam_validity`) and the resolved case.

    A gauge's peak is the extreme within the run's window; when it sits on the
    window's last sample the strain may still be growing, and the summary says so
    (``peak_at_window_end``).
    """
    p = result.problem
    gauges = {}
    for g, eps, bend in zip(p.gauges, result.strain, result.bending):
        gauges[g.name] = {
            "position_m": g.position,
            "surface": g.surface,
            **strain_peaks(result.time, eps, window_end=True),
            "first_zero_crossing_of_bending_strain_s": first_zero_crossing(result.time, bend),
        }
    out = {
        "title": p.title,
        "dofs": model.plane.n,
        "elements": [p.beam.nx, p.beam.nz],
        "kinematics": p.kinematics,
        "effective_moduli_Pa": model.moduli(),
        **beam_scalars(result),
        "gauges": gauges,
        "validity": validity.summary(),
        "case_SI": p,
    }
    if result.energies:
        out["energy_balance_relative"] = energy_balance(result.energies)
    return out


def beam_scalars(result) -> dict:
    """The scalars of a beam run that every beam output names alike (summary.json, sweep outputs,
    converge): peak force [N], impulse [N·s] and the signed peak deflection under the load [m]."""
    return {
        "peak_force_N": float(result.force.max()),
        "impulse_N_s": float(np.trapezoid(result.force, result.time)),
        "peak_deflection_under_load_m": float(result.deflection[np.argmax(np.abs(result.deflection))]),
    }


def beam_files(model, result, figures: bool = True, prefix: str = "", *, summary: dict, units: str = "in-lbf-s") -> dict[str, bytes | str]:
    """history.csv, summary.json (``summary``: :func:`beam_summary`'s, from the run path) and Figs 18, 20–22 and the deformed beam,
    in display ``units`` (also summary.json's ``case_SI.units``)."""
    p = result.problem
    cols = {"time_s": result.time, "force_N": result.force}
    for g, eps in zip(p.gauges, result.strain):
        cols[f"strain_{g.name}"] = eps
    for g, bend in zip(p.gauges, result.bending):
        cols[f"bending_strain_{g.name}"] = bend
    cols["deflection_under_load_m"] = result.deflection
    files = {prefix + "history.csv": csv_text(cols), prefix + "summary.json": json_text(with_units(summary, units))}
    if figures:
        from . import plots

        system = units
        files[prefix + "fig21-22-gauge-strains.png"] = figure_bytes(plots.beam_gauge_strains(result, system))
        tp, T = p.load.history.time_of_peak, p.load.history.duration
        files[prefix + "fig20-load-distribution.png"] = figure_bytes(plots.beam_load_distribution(model, result, system, [tp / 3, tp, (tp + T) / 2, 0.9 * T]))
        files[prefix + "fig18-mesh.png"] = figure_bytes(plots.beam_mesh(model, system, 4 * p.load.contact_radius))
        if result.displacement is not None:
            files[prefix + "deformed.png"] = figure_bytes(plots.beam_deformed(model, result, system, np.linspace(0, result.time[-1], 6)[1:]))
    return files


def beam_section(model, result, prefix: str, summary: dict, units: str = "in-lbf-s") -> Section:
    """The report section of a beam run (``summary``: :func:`beam_summary`'s) in display ``units``: moduli, gauge strains, Figs 18, 20–22."""
    p = result.problem
    su, tu = display(units, "strain"), display(units, "time")
    lu, fu, pu = display(units, "length"), display(units, "force"), display(units, "stress")
    bs = summary["effective_moduli_Pa"].get("bending_stiffness_per_width_N_m", {})
    moduli = summary["effective_moduli_Pa"]
    rows = [
        [k, f"{moduli[k] * pu.factor:.4g} {pu.label}" if k[0] in "EG" else f"{moduli[k]:.3f}"]
        for k in ("E1", "E2", "E3", "G12", "G13", "G23", "nu12", "nu13", "nu23")
        if k in moduli
    ]
    if bs:
        mu = display(units, "moment")
        rows.append(["bending stiffness per width, smeared (E·h³/12)", f"{bs['smeared_EI_per_width'] * mu.factor:.4g} {mu.label}"])
        if "clt_D11" in bs:
            rows.append(["bending stiffness per width, real stacking (CLT D11)", f"{bs['clt_D11'] * mu.factor:.4g} {mu.label}"])
    grows = []
    for g, d in summary["gauges"].items():
        z = d["first_zero_crossing_of_bending_strain_s"]
        # the note goes with the peak that sits on the window's last sample (tensile, compressive or both)
        edge = {k: " (at the window's end: still growing?)" if k in d["peak_at_window_end"] else "" for k in ("tensile", "compressive")}
        grows.append(
            [
                g,
                f"{d['position_m'] * lu.factor:.3g} {lu.label} from the support, {d['surface']} face",
                f"{d['peak_tensile_strain'] * su.factor:.0f}{edge['tensile']}",
                f"{d['peak_compressive_strain'] * su.factor:.0f}{edge['compressive']}",
                "—" if z is None or z != z else f"{z * tu.factor:.0f}",
            ]
        )
    return Section(
        p.title,
        [
            f"Plane-strain four-node elements, {p.beam.nx} × {p.beam.nz} ({model.plane.n} DOF), {p.beam.model} laminate, "
            f"{p.beam.support}; force history F0 = {result.force.max() * fu.factor:.0f} {fu.label}, "
            f"T = {p.load.history.duration * tu.factor:.0f} {tu.label}, r0 = {p.load.contact_radius * lu.factor:.3g} {lu.label}. "
            f"Energy balance (work − kinetic − strain): {summary.get('energy_balance_relative', float('nan')):.1e} relative.",
        ],
        [
            ("Effective (smeared) moduli of the laminate", ["quantity", "value"], rows),
            (
                f"Gauge strains ({su.label}, {tu.label}): extremes within the run's window",
                ["gauge", "where", "peak tension", "peak compression", "first zero crossing of bending strain"],
                grows,
            ),
        ],
        [
            (prefix + "fig21-22-gauge-strains.png", "Figs 21-22: strain at the gauges"),
            (prefix + "fig20-load-distribution.png", "Fig 20: nodal forces of the contact patch at several instants"),
            (prefix + "fig18-mesh.png", "Fig 18: the mesh near the impact point"),
            (prefix + "deformed.png", "The beam's deflection at several instants"),
        ],
    )
