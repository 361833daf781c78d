"""``softimpact predict``: a force history from the empirical or a classical model."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..input.scaling_constants import scaling_law
from ..input.sweep_spec import case_files
from ..models.empirical import PROJECTILES, HertzModel, PulseParameters, WilbeckModel
from ..models.materials import lookup
from ..output.predict import predict_files
from ..units import display, parse
from . import Outcome, Progress, no_progress
from .options import PREDICT, display_system

__all__ = ["MODELS", "predict"]

MODELS = next(o.choices for o in PREDICT if o.name == "model")  # eqs (4)-(7) with (15); elastic impact, eqs (1)-(3); steady flow ρV²A


def predict(
    *,
    projectile: str | None,
    mass: str | None,
    diameter: str | None,
    velocity: str,
    model: str,
    constants: str | None,
    group: str,
    tail: bool,
    material: str,
    target: str,
    bar: str | None,
    beam: str | None,
    units: str | None,
    figures: bool,
    progress: Progress = no_progress,
) -> Outcome:
    """Force history of a projectile at a velocity; quantities are strings with units, as typed. The
    options, their defaults and help: :data:`softimpact.app.options.PREDICT` (every one given here); ``units`` None: the
    display system of the ``bar`` or ``beam`` case driven, else in-lbf-s."""
    if model not in MODELS:
        raise InputError(f"--model: {model!r} is not one of {', '.join(MODELS)}")
    if bar is not None and beam is not None:
        raise InputError("--bar and --beam: drive one structure at a time")
    units = display_system(units, _driven_units(bar, beam))
    proj, m, d = _projectile(projectile, mass, diameter)
    V = parse(velocity, "velocity", "--velocity")
    if not V > 0:
        raise InputError(f"--velocity must be positive, got {velocity!r}")
    sphere = lookup(proj.material if proj else material, "--material")
    density = m / (math.pi / 6 * d**3)
    models = {
        "hertz": HertzModel(sphere, lookup(target, "--target")),
        "wilbeck": WilbeckModel(density),
        **_material_models(sphere, model),
    }
    notes = []
    law = None
    if model == "empirical" or constants is not None or proj is not None:
        law = scaling_law(constants, group, proj)
        models["empirical"] = law
        notes.extend(_range_notes(law, velocity, V, d, units))
    notes.extend(_envelope_notes(model, models, sphere, m, d, V))
    chosen = models[model]
    pulse = chosen.pulse(m, d, V, tail=tail) if model == "empirical" else chosen.pulse(m, d, V)
    params = chosen.parameters(m, d, V)
    inputs, driven, gauge_peak = _driven(bar, beam, pulse)
    curves = _curves(models, model, m, d, V, tail, pulse) if figures else []
    files = predict_files(
        model=model,
        projectile={"name": proj.name if proj else "", "mass_kg": m, "diameter_m": d, "velocity_m_s": V},
        params=params,
        pulse=pulse,
        law=law,
        notes=notes,
        curves=curves,
        driven=driven,
        gauge_peak=gauge_peak,
        system=units,
        figures=figures,
    )
    fu, tu, iu = display(units, "force"), display(units, "time"), display(units, "impulse")
    line = (
        f"{model}: F0 {params.peak_force * fu.factor:.4g} {fu.label} at {params.time_of_peak * tu.factor:.4g} {tu.label}, "
        f"T {params.duration * tu.factor:.4g} {tu.label}, I {params.impulse * iu.factor:.4g} {iu.label}"
    )
    if constants is not None and Path(constants).is_file():  # a scaling.json: read, so never removed
        inputs = [*inputs, Path(constants)]
    return Outcome(files, line, tuple(inputs), tuple(notes))


def _envelope_notes(model: str, models: dict, sphere, m: float, d: float, V: float) -> list[str]:
    """The chosen model's own envelope flags: Hertz's approach and contact radius against the ball
    (:func:`~softimpact.models.validity.contact_validity`), a crushing or hydrodynamic law's (ice: strain rate; gelatin:
    shock release, :func:`~softimpact.models.contact_laws.law_validity`); none for the others."""
    if model == "hertz":
        from ..models.validity import contact_validity

        hertz = models["hertz"].law(d)
        alpha_max = hertz.rigid_impact(m, V)[0]
        return list(contact_validity("hertz", alpha_max, hertz.radius(alpha_max), d).flags)
    if model in ("crushing", "hydrodynamic"):
        from ..models.contact_laws import CONTACT_LAWS, law_validity

        return list(law_validity(CONTACT_LAWS[model].of(sphere, d, m, V), V).flags)
    return []


def _curves(models: dict, model: str, m: float, d: float, V: float, tail: bool, pulse) -> list[tuple]:
    """(label, time [s], force [N]) of every model's pulse for the comparison figure, over 1.5 × the longest."""
    curves = []
    for name, mod in models.items():
        pl = mod.pulse(m, d, V, tail=tail) if name == "empirical" else mod.pulse(m, d, V)
        tt = np.linspace(0, 1.5 * max(pl.duration, pulse.duration), 1501)
        curves.append((f"{name}{' (chosen)' if name == model else ''}", tt, pl(tt)))
    return curves


@dataclass(frozen=True)
class _RigidTarget:
    """The contact law ``name`` of the projectile's material (:data:`~softimpact.models.contact_laws.MATERIAL_LAWS`:
    ice crushing, gelatin flowing) on a rigid target (:func:`softimpact.models.crushing_law.rigid_target_pulse`),
    with the ``parameters``/``pulse`` of the other predict models."""

    name: str
    material: object

    def pulse(self, m: float, d: float, V: float):
        from ..models.contact_laws import CONTACT_LAWS
        from ..models.crushing_law import rigid_target_pulse

        return rigid_target_pulse(CONTACT_LAWS[self.name].of(self.material, d, m, V), m, V)

    def parameters(self, m: float, d: float, V: float) -> PulseParameters:
        p = self.pulse(m, d, V)
        k = int(np.argmax(p.force))
        return PulseParameters(float(p.force[k]), float(p.time[k]), float(p.time[-1]), float(np.trapezoid(p.force, p.time)))


def _material_models(sphere, model: str) -> dict:
    """The crushing and hydrodynamic models the projectile's material has the data for (ice, gelatin); InputError
    naming ``--material`` when the chosen one is not among them."""
    from ..models.contact_laws import CONTACT_LAWS, MATERIAL_LAWS

    out = {}
    for name in MATERIAL_LAWS:
        try:
            CONTACT_LAWS[name].of(sphere, 1.0, 1.0, 1.0)  # the material has the law's data (a unit sphere: only the check)
        except InputError:
            if model == name:
                raise InputError(f"--material: {sphere.name!r} has no data for the {name} model (ice: crushing, gelatin: hydrodynamic)") from None
            continue
        out[name] = _RigidTarget(name, sphere)
    return out


def _projectile(projectile: str | None, mass: str | None, diameter: str | None):
    """(the named projectile or None, mass [kg], diameter [m]): a named projectile or a mass and a diameter."""
    if projectile is not None:
        if projectile not in PROJECTILES:
            raise InputError(f"--projectile: unknown {projectile!r} (known: {', '.join(PROJECTILES)})")
        if mass is not None or diameter is not None:
            raise InputError("--projectile: give either a named projectile or --mass and --diameter, not both")
        proj = PROJECTILES[projectile]
        return proj, proj.mass, proj.diameter
    if mass is None or diameter is None:
        raise InputError("--projectile or both --mass and --diameter are required")
    m, d = parse(mass, "mass", "--mass"), parse(diameter, "length", "--diameter")
    if not (m > 0 and d > 0):
        raise InputError(f"--mass and --diameter must be positive, got {mass!r}, {diameter!r}")
    return None, m, d


def _range_notes(law, velocity: str, V: float, d: float, units: str) -> list[str]:
    """The notes when the velocity V [m/s] or the diameter d [m] lies outside what the scaling constants were
    fitted on (10 % beyond their diameters), or when the constants do not record it; in display ``units``."""
    notes = []
    if not law.in_range(V):
        lo, hi = law.velocity_range
        vu = display(units, "velocity")
        notes.append(f"velocity {velocity} is outside the range of the constants ({lo * vu.factor:.4g}-{hi * vu.factor:.4g} {vu.label}): extrapolated")
    dlo, dhi = law.diameter_range
    if math.isfinite(dhi) and not 0.9 * dlo <= d <= 1.1 * dhi:
        lu = display(units, "length")
        notes.append(
            f"diameter {d * lu.factor:.4g} {lu.label} is outside the diameters the constants were fitted on "
            f"({dlo * lu.factor:.4g}-{dhi * lu.factor:.4g} {lu.label}): extrapolated"
        )
    if not math.isfinite(law.velocity_range[1]):
        notes.append(f"the constants {law.name} do not record the velocities and diameters they were fitted on: the range cannot be checked")
    return notes


def _driven_units(bar: str | None, beam: str | None) -> str | None:
    """The display system of the case ``bar`` or ``beam`` names (its ``units`` key), None when neither is given."""
    if bar is None and beam is None:
        return None
    from ..input.toml import case_units

    return case_units(bar if bar is not None else beam)


def _driven(bar: str | None, beam: str | None, pulse):
    """(the case files read, (time, force, gauges, strain) of the structure driven by ``pulse`` or None, the
    gauges' peak sense): the bar of a bar case or the beam of a beam case under the predicted force."""
    from ..cases.run import execute

    if bar is not None:
        from ..input.bar_case import load_bar_case

        problem, path = load_bar_case(bar)
        res = execute(problem, force=pulse).result
        return list(case_files(path)), (res.time, res.force, problem.gauges, res.strain), "compressive"
    if beam is not None:
        from ..input.beam_case import load_beam_case

        problem, path = load_beam_case(beam)
        res = execute(problem, energy=False, force=pulse).result
        return list(case_files(path)), (res.time, res.force, problem.gauges, res.strain), "absolute"
    return [], None, ""
