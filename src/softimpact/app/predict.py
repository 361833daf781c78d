"""``softimpact predict``: a force history from the empirical or a classical model."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .. import units
from ..errors import InputError
from ..models.empirical import PRESETS, PROJECTILES, HertzModel, ScalingLaw, WilbeckModel
from ..models.materials import lookup
from ..output.files import csv_text, figure_bytes, json_text
from ..output.scaling_json import read_scaling_law
from . import Outcome

__all__ = ["MODELS", "predict", "scaling_law"]

MODELS = ("empirical", "hertz", "wilbeck")  # eqs (4)-(7) with (15); elastic impact, eqs (1)-(3); steady flow ρV²A


def scaling_law(constants: str | None, group: str, projectile) -> ScalingLaw:
    """The α's: a preset name, a scaling.json from `softimpact fit`, or the projectile's preset."""
    if constants is None:
        if projectile is None:
            raise InputError("--constants: needed with --mass/--diameter (a preset or a scaling.json)")
        return PRESETS[projectile.law]
    if constants in PRESETS:
        return PRESETS[constants]
    path = Path(constants)
    if not path.is_file():
        raise InputError(f"--constants: {constants!r} is neither a preset ({', '.join(PRESETS)}) nor a file")
    return read_scaling_law(path, group)


def predict(
    projectile: str | None,
    mass: str | None,
    diameter: str | None,
    velocity: str,
    model: str = "empirical",
    constants: str | None = None,
    group: str = "pooled",
    tail: bool = False,
    material: str = "silicone rubber",
    target: str = "Al 6061-T6",
    bar_case: str | None = None,
    system: str = "in-lbf-s",
    figures: bool = True,
    beam_case: str | None = None,
) -> Outcome:
    """Force history of a projectile at a velocity; quantities are strings with units, as typed."""
    if model not in MODELS:
        raise InputError(f"--model: {model!r} is not one of {', '.join(MODELS)}")
    if bar_case is not None and beam_case is not None:
        raise InputError("--bar and --beam: drive one structure at a time")
    proj = None
    if projectile is not None:
        if projectile not in PROJECTILES:
            raise InputError(f"--projectile: unknown {projectile!r} (known: {', '.join(PROJECTILES)})")
        if mass is not None or diameter is not None:
            raise InputError("--projectile: give either a named projectile or --mass and --diameter, not both")
        proj = PROJECTILES[projectile]
        m, d = proj.mass, proj.diameter
    else:
        if mass is None or diameter is None:
            raise InputError("--projectile or both --mass and --diameter are required")
        m, d = units.parse(mass, "mass", "--mass"), units.parse(diameter, "length", "--diameter")
        if not (m > 0 and d > 0):
            raise InputError(f"--mass and --diameter must be positive, got {mass!r}, {diameter!r}")
    V = units.parse(velocity, "velocity", "--velocity")
    if not V > 0:
        raise InputError(f"--velocity must be positive, got {velocity!r}")
    sphere = lookup(proj.material if proj else material, "--material")
    density = m / (math.pi / 6 * d**3)
    models = {
        "hertz": HertzModel(sphere, lookup(target, "--target")),
        "wilbeck": WilbeckModel(density),
    }
    notes = []
    law = None
    if model == "empirical" or constants is not None or proj is not None:
        law = scaling_law(constants, group, proj)
        models["empirical"] = law
        if not law.in_range(V):
            lo, hi = law.velocity_range
            vu = units.display(system, "velocity")
            notes.append(f"velocity {velocity} is outside the range of the constants ({lo * vu.factor:.4g}-{hi * vu.factor:.4g} {vu.label}): extrapolated")
    chosen = models[model]
    pulse = chosen.pulse(m, d, V, tail=tail) if model == "empirical" else chosen.pulse(m, d, V)
    params = chosen.parameters(m, d, V)
    end = 1.5 * pulse.duration
    t = np.linspace(0.0, end, 1501)
    F = pulse(t)
    cols = {"time_s": t, "force_N": F}
    summary = {
        "model": model,
        "projectile": {"name": proj.name if proj else "", "mass_kg": m, "diameter_m": d, "velocity_m_s": V},
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
    files = {}
    inputs = []
    if bar_case is not None:
        from ..input.bar_case import load_bar_case
        from ..workflows.bar_impact import simulate_force

        problem, path = load_bar_case(bar_case)
        inputs.append(path)
        res = simulate_force(problem.bar, problem.solver, problem.gauges, pulse)
        cols = {"time_s": res.time, "force_N": res.force}
        for g, eps in zip(problem.gauges, res.strain):
            cols[f"strain_{g.name}"] = eps
            k = int(np.argmin(eps))
            summary.setdefault("gauges", {})[g.name] = {"peak_compressive_strain": float(eps[k]), "time_s": float(res.time[k])}
    if beam_case is not None:
        from dataclasses import replace

        from ..input.beam_case import load_beam_case
        from ..workflows.beam_impact import BeamLoad, BeamModel

        problem, path = load_beam_case(beam_case)
        inputs.append(path)
        problem = replace(problem, load=BeamLoad(problem.load.position, problem.load.contact_radius, pulse))
        res = BeamModel(problem).direct(energy=False)
        cols = {"time_s": res.time, "force_N": res.force}
        for g, eps in zip(problem.gauges, res.strain):
            cols[f"strain_{g.name}"] = eps
            k = int(np.argmax(np.abs(eps)))
            summary.setdefault("gauges", {})[g.name] = {"peak_strain": float(eps[k]), "time_s": float(res.time[k])}
    files["history.csv"] = csv_text(cols)
    files["summary.json"] = json_text(summary)
    if figures:
        from ..output import plots

        curves = []
        for name, mod in models.items():
            pl = mod.pulse(m, d, V, tail=tail) if name == "empirical" else mod.pulse(m, d, V)
            tt = np.linspace(0, 1.5 * max(pl.duration, pulse.duration), 1501)
            curves.append((f"{name}{' (chosen)' if name == model else ''}", tt, pl(tt)))
        vu = units.display(system, "velocity")
        files["force-history.png"] = figure_bytes(plots.predicted_forces(curves, system, f"Predicted force, V = {V * vu.factor:.4g} {vu.label}"))
    fu, tu, iu = units.display(system, "force"), units.display(system, "time"), units.display(system, "impulse")
    line = (
        f"{model}: F0 {params.peak_force * fu.factor:.4g} {fu.label} at {params.time_of_peak * tu.factor:.4g} {tu.label}, "
        f"T {params.duration * tu.factor:.4g} {tu.label}, I {params.impulse * iu.factor:.4g} {iu.label}"
    )
    return Outcome(files, line, tuple(inputs), tuple(notes))
