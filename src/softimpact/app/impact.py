"""``softimpact impact``: a rigid impactor on a laminated beam through a contact law (coupled)."""

from __future__ import annotations

import time

import numpy as np

from ..fem.plane_contact import plane_contact_structure
from ..input.impact_case import ImpactProblem, load_impact_case
from ..output.impact import impact_files
from ..units import display
from ..workflows.beam_impact import BeamModel
from ..workflows.coupled import CoupledResult, simulate_coupled
from . import Outcome, Progress, no_progress

__all__ = ["impact", "run_impact", "beam_contact_structure"]


def beam_contact_structure(model: BeamModel, position: float, reach: float):
    """The ContactStructure of a BeamModel struck downward on its top face at ``position`` [m],
    with the gauge strains (each on its own face) as outputs and the model's damping."""
    pm = model.plane
    gauges = model.problem.gauges
    outputs = np.array([pm.surface_strain(g.position, g.surface, g.length) for g in gauges]).reshape(len(gauges), pm.n)
    a, b = model.problem.beam.damping
    C = None if a == 0 and b == 0 else a * pm.M + b * pm.K
    return plane_contact_structure(pm, position, reach, outputs, tuple(g.name for g in gauges), C)


def run_impact(problem: ImpactProblem, model: BeamModel | None = None) -> tuple[BeamModel, CoupledResult]:
    """The coupled run of an impact problem; ``model``: a BeamModel of the same beam and step to reuse.

    Loadable nodes reach one impactor diameter from the impact point: a Hertz radius
    sqrt(R·α) and a flattened sphere's sqrt(d·α) stay within it while α < d.
    """
    model = model or BeamModel(problem.target)
    structure = beam_contact_structure(model, problem.position, problem.impactor.diameter)
    result = simulate_coupled(structure, problem.law, problem.impactor, problem.solver, stepper=model.stepper)
    return model, result


def impact(case: str, figures: bool = True, progress: Progress = no_progress) -> Outcome:
    """Run an impact case (file or built-in name)."""
    problem, inputs = load_impact_case(case)
    t0 = time.perf_counter()
    steps = problem.solver.steps
    progress(0, steps, "stepping")
    model, result = run_impact(problem)
    progress(steps, steps, "stepping")
    files = impact_files(problem, result, figures)
    fu, tu, su = (display(problem.units, k) for k in ("force", "time", "strain"))
    peaks = ", ".join(f"{n} {eps[np.argmax(np.abs(eps))] * su.factor:.0f} {su.label}" for n, eps in zip(result.gauge_names, result.gauge_strain))
    T = "not separated" if not np.isfinite(result.contact_duration) else f"T {result.contact_duration * tu.factor:.1f} {tu.label}"
    line = (
        f"{problem.law_name}: F0 {result.peak_force * fu.factor:.1f} {fu.label} at {result.time_of_peak * tu.factor:.1f} {tu.label}, {T}, "
        f"{len(result.contacts)} contact(s); peak strains {peaks} ({model.plane.n} DOF, {steps} steps, {time.perf_counter() - t0:.1f} s)"
    )
    return Outcome(files, line, inputs)
