"""Outputs of ``softimpact plate``: history.csv, summary.json and the figures."""

from __future__ import annotations

import math

import numpy as np

from .files import csv_text, energy_balance, figure_bytes, json_text, strain_peaks, with_units

__all__ = [
    "plate_validity",
    "plate_summary",
    "plate_scalars",
    "plate_files",
    "plate_static_summary",
    "plate_static_validity",
    "plate_static_files",
    "SNAPSHOTS",
]

SNAPSHOTS = 6  # instants of the deflected-shape figure, spread over the run


def snapshot_steps(steps: int) -> np.ndarray:
    """Step indices of the deflected-shape figure: SNAPSHOTS instants after t = 0, the last at the end."""
    return np.unique(np.round(np.linspace(0, steps, SNAPSHOTS + 1)[1:]).astype(int))


def plate_validity(result):
    """The envelopes of a plate run (:mod:`softimpact.models.validity`): peak deflection under the load against
    the thickness (linear FSDT), and with ply strengths each gauge's peak strain against the most a face strain
    reaches before the ply fails (:func:`softimpact.models.validity.surface_strain_bound`)."""
    from ..models.validity import gauge_allowable_flags

    p = result.problem
    stack = p.plate.stack
    v = p.validity(float(np.max(np.abs(result.deflection[0]))))  # the kinematics' envelope (von Kármán: the ratio alone)
    if stack.ply.strength is not None and len(p.gauges):
        k = int(np.argmax([np.max(np.abs(e)) for e in result.strain]))
        v += gauge_allowable_flags(f"gauge {p.gauges[k].name}", stack.ply, float(np.max(np.abs(result.strain[k]))))
    return v


def plate_summary(model, result, validity=None) -> dict:
    """The scalars of a plate run, SI with unit-suffixed keys, and the resolved case.

    A gauge's peak is the extreme within the run's window; when it sits on the
    window's last sample the strain may still be growing, and the summary says so.
    """
    p = result.problem
    gauges = {}
    for g, eps in zip(p.gauges, result.strain):
        gauges[g.name] = {
            "position_m": list(g.position),
            "surface": g.surface,
            "direction": g.direction,
            "length_m": g.length,
            **strain_peaks(result.time, eps, window_end=True),
        }
    out = {
        "title": p.title,
        "model": f"fsdt ({p.plate.element.upper()})",
        "element": p.plate.element,
        "kinematics": p.kinematics,
        "dofs": int(model.size),
        "elements": list(p.plate.elements),
        "supports": dict(zip(("x0", "x1", "y0", "y1"), p.plate.supports)),
        "natural_frequencies_Hz": [float(f) for f in model.frequencies(min(5, model.size - 2))],
        **plate_scalars(result),
        "gauges": gauges,
        "validity": (plate_validity(result) if validity is None else validity).summary(),  # the run's (cases.plate), with its geometry's
        "case_SI": p,
    }
    if result.energies:
        out["energy_balance_relative"] = energy_balance(result.energies)
    return out


def plate_scalars(result) -> dict:
    """The scalars of a plate run that every plate output names alike (summary.json, sweep outputs,
    converge): peak force [N], impulse [N·s], the signed peak deflection under the load [m] and its time [s]."""
    w = result.deflection[0]
    k = int(np.argmax(np.abs(w)))
    return {
        "peak_force_N": float(result.force.max()),
        "impulse_N_s": float(np.trapezoid(result.force, result.time)),
        "peak_deflection_at_load_m": float(w[k]),
        "time_of_peak_deflection_s": float(result.time[k]),
    }


def plate_files(model, result, figures: bool = True, summary: dict | None = None, *, units: str = "in-lbf-s") -> dict[str, bytes | str]:
    """history.csv, summary.json (``summary``: the run path's :func:`plate_summary`, made here when None) and,
    with figures, plate-mesh.png, deflection.png, histories.png, in display ``units`` (also summary.json's ``case_SI.units``)."""
    p = result.problem
    cols = {"time_s": result.time, "force_N": result.force, "deflection_m": result.deflection[0]}
    for g, eps in zip(p.gauges, result.strain):
        cols[f"strain_{g.name}"] = eps
    files = {"history.csv": csv_text(cols), "summary.json": json_text(with_units(plate_summary(model, result) if summary is None else summary, units))}
    if figures:
        from . import plate_plots

        files["plate-mesh.png"] = figure_bytes(plate_plots.plate_mesh(model, units))
        files["histories.png"] = figure_bytes(plate_plots.plate_histories(result, units))
        if result.displacement is not None and result.displacement.shape[1]:
            files["deflection.png"] = figure_bytes(plate_plots.plate_deflection(model, result, units))
    return files


def plate_static_validity(result, model=None):
    """The envelope of a static plate run: with linear kinematics, the largest deflection against the
    thickness (:func:`softimpact.models.validity.deflection_validity`); von Kármán kinematics is the model
    past it (its ratio is reported, not flagged), within its own small strains: with its ``model``, the largest principal
    mid-surface strain (:func:`~softimpact.models.validity.small_strain_validity`: a plate at 17 thicknesses stretched
    3 % is flagged). With von Kármán kinematics and ply strengths, the mid-surface strains
    against the ply allowables (``membrane_strain_index``, a lower bound of the faces' index: flagged past 1)."""
    from ..models.validity import Validity, allowable_flags, deflection_validity, small_strain_validity

    h = result.problem.plate.total_thickness
    w = float(result.max_deflection[-1])
    if result.kinematics == "linear":
        v = deflection_validity("linear plate theory (FSDT)", w, h)
    else:
        v = Validity({"deflection_over_thickness": w / h}, ())
        if model is not None:
            e = np.asarray(model.membrane_strain(result.u), float).reshape(-1, 3)  # (εx, εy, γxy) at the plate's points
            mean, radius = 0.5 * (e[:, 0] + e[:, 1]), np.hypot(0.5 * (e[:, 0] - e[:, 1]), 0.5 * e[:, 2])
            v += small_strain_validity("von Karman plate", float(np.max(np.abs(mean) + radius)))  # the largest principal strain's magnitude
    if math.isfinite(result.membrane_strain_index):
        v += allowable_flags(
            "the plate's plies, from the mid-surface strains alone (a lower bound of the faces')", result.membrane_strain_index, "membrane_strain_index"
        )
    return v


def plate_static_summary(model, result, validity=None) -> dict:
    """summary.json of a static plate run (uniform pressure): the largest mid-surface deflection
    ``max_deflection_m`` (its magnitude, along the pressure) and ``kinematics``, Newton's convergence
    (``newton``: iterations and final relative residual per load step, ``converged``, ``message``), the
    load steps' pressures and deflections, and the resolved case."""
    p = result.problem
    return {
        "title": p.title,
        "analysis": "static",
        "model": f"fsdt ({p.plate.element.upper()})",
        "element": p.plate.element,
        "kinematics": result.kinematics,
        "in_plane": p.in_plane if result.kinematics == "von-karman" else None,
        "dofs": int(model.n),
        "elements": list(p.plate.elements),
        "supports": dict(zip(("x0", "x1", "y0", "y1"), p.plate.supports)),
        "pressure_Pa": float(p.pressure),
        "max_deflection_m": float(result.max_deflection[-1]),
        "max_deflection_over_thickness": float(result.max_deflection[-1] / p.plate.total_thickness),
        "deflection_note": "largest transverse deflection of the mid-surface over the plate, positive along the pressure",
        "load_steps": {"pressure_Pa": [float(q) for q in result.pressure], "max_deflection_m": [float(w) for w in result.max_deflection]},
        "newton": {
            "iterations": [int(i) for i in result.iterations],
            "residual_relative": [float(r) for r in result.residuals],
            "converged": bool(result.converged),
            "message": result.message,
        },
        "validity": (plate_static_validity(result, model) if validity is None else validity).summary(),
        "case_SI": p,
    }


def plate_static_files(summary: dict, units: str = "in-lbf-s") -> dict[str, str]:
    """summary.json of a static plate run (:func:`plate_static_summary`; ``units``: its ``case_SI.units``): no history, no figures."""
    return {"summary.json": json_text(with_units(summary, units))}
