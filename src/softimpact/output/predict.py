"""Outputs of ``softimpact predict``: history.csv (the force, and the structure's gauge strains
under --bar/--beam), summary.json and force-history.png."""

from __future__ import annotations

import numpy as np

from .. import units
from .files import csv_text, figure_bytes, json_text

__all__ = ["predict_files"]


def predict_files(
    *, model: str, projectile: dict, params, pulse, law, notes, curves, driven=None, gauge_peak: str = "", system: str = "in-lbf-s", figures: bool = True
) -> dict:
    """history.csv, summary.json and (with figures) force-history.png of a prediction.

    ``projectile``: name, mass_kg, diameter_m, velocity_m_s; ``params``: the chosen model's
    pulse parameters (SI); ``pulse``: its force history F(t) [N]; ``law``: the scaling law
    (None for a classical model without constants); ``curves``: (label, t [s], F [N]) of
    every model, for the figure. ``driven``: (time [s], force [N], gauges, strains of shape
    (n_gauges, n_steps)) of the structure the force drove, or None; ``gauge_peak``:
    ``"compressive"`` (bar: the most negative strain, ``peak_compressive_strain``) or
    ``"absolute"`` (beam: the largest |strain|, ``peak_strain``).
    """
    t = np.linspace(0.0, 1.5 * pulse.duration, 1501)
    F = pulse(t)
    cols = {"time_s": t, "force_N": F}
    summary = {
        "model": model,
        "projectile": projectile,
        "peak_force_N": params.peak_force,
        "time_of_peak_s": params.time_of_peak,
        "duration_s": params.duration,
        "impulse_N_s": params.impulse,
        "impulse_of_history_N_s": float(np.trapezoid(F, t)),
        "constants": None
        if law is None
        else {"alpha1": law.alpha1, "alpha2": law.alpha2, "alpha3": law.alpha3, "alpha4": law.alpha4, "name": law.name, "source": law.source},
        "notes": notes,
    }
    if driven is not None:
        time, force, gauges, strains = driven
        cols = {"time_s": time, "force_N": force}
        for g, eps in zip(gauges, strains):
            cols[f"strain_{g.name}"] = eps
            if gauge_peak == "compressive":
                k = int(np.argmin(eps))
                summary.setdefault("gauges", {})[g.name] = {"peak_compressive_strain": float(eps[k]), "time_s": float(time[k])}
            else:
                k = int(np.argmax(np.abs(eps)))
                summary.setdefault("gauges", {})[g.name] = {"peak_strain": float(eps[k]), "time_s": float(time[k])}
    files = {"history.csv": csv_text(cols), "summary.json": json_text(summary)}
    if figures:
        from . import plots

        vu = units.display(system, "velocity")
        V = projectile["velocity_m_s"]
        files["force-history.png"] = figure_bytes(plots.predicted_forces(curves, system, f"Predicted force, V = {V * vu.factor:.4g} {vu.label}"))
    return files
