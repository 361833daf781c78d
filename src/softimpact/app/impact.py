"""``softimpact impact``: a rigid impactor on a laminated beam or plate through a contact law (coupled)."""

from __future__ import annotations

import time
from dataclasses import replace

import numpy as np

from ..errors import InputError
from ..fem.plane_contact import plane_contact_structure
from ..input.impact_case import ImpactProblem, load_impact_case
from ..output.impact import impact_files, snapshot_steps
from ..units import display
from ..workflows.beam_impact import BeamModel
from ..workflows.coupled import CoupledResult, simulate_coupled
from ..workflows.plate_impact import PlateModel
from . import Outcome, Progress, no_progress
from .plate import plate_structure

__all__ = ["impact", "run_impact", "beam_contact_structure", "plate_reach", "impact_model"]


def beam_contact_structure(model: BeamModel, position: float, reach: float):
    """The ContactStructure of a BeamModel struck downward on its top face at ``position`` [m],
    with the gauge strains (each on its own face) as outputs and the model's damping."""
    pm = model.plane
    gauges = model.problem.gauges
    outputs = np.array([pm.surface_strain(g.position, g.surface, g.length) for g in gauges]).reshape(len(gauges), pm.n)
    a, b = model.problem.beam.damping
    C = None if a == 0 and b == 0 else a * pm.M + b * pm.K
    return plane_contact_structure(pm, position, reach, outputs, tuple(g.name for g in gauges), C)


def plate_reach(model: PlateModel, position: tuple[float, float], diameter: float) -> float:
    """The widest contact disc [m] the plate model loads about the impact point: the impactor's
    diameter (a Hertz radius sqrt(R·α) and a flattened sphere's sqrt(d·α) stay within it while
    α < d), cut so the disc stays on the plate and its elements off a supported edge (whose w
    is fixed); a symmetry edge through the impact point does not cut it."""
    fe = model.fe
    x, y = position
    h = (float(np.max(np.diff(fe.xs))), float(np.max(np.diff(fe.ys))))
    room = diameter
    for (dist, hh), kind in zip(((x - fe.xs[0], h[0]), (fe.xs[-1] - x, h[0]), (y - fe.ys[0], h[1]), (fe.ys[-1] - y, h[1])), model.problem.plate.supports):
        if kind == "symmetry" and dist <= 1e-9 * hh:
            continue
        room = min(room, dist - (1.01 * hh if kind in ("clamped", "simply-supported") else 0.0))
    if not room > 0:
        raise InputError("the impact point is within one element of a supported edge: no room for the contact disc")
    return room


def impact_model(problem: ImpactProblem) -> BeamModel | PlateModel:
    """The target's model for the impact run (a plate's checked for room about the impact point
    first: errors name the target case's load.position)."""
    if not problem.on_plate:
        return BeamModel(problem.target)
    try:
        model = PlateModel(problem.target, patch_radius=min(problem.target.load.contact_radius, problem.impactor.diameter))
        plate_reach(model, problem.position, problem.impactor.diameter)
    except InputError as exc:
        if "patch" not in str(exc) and "contact disc" not in str(exc):
            raise
        raise InputError(f"target.case ({problem.target_case}): load.position {tuple(problem.position)!r} m: {exc}") from None
    return model


def _whole_plate(result: CoupledResult, share: float) -> CoupledResult:
    """A half or quarter plate model (symmetry edges through the impact point) carries ``share`` of
    the force: its energies are ``share`` of the whole plate's, and are scaled back so the balance
    against the impactor closes (the mismatch: the whole plate's work minus F·Δw)."""
    if share == 1.0:
        return result
    E = result.energies
    work = E.structure_work / share
    along_w = E.structure_work - E.surface_mismatch  # Σ F·Δw, the same for part and whole
    energies = replace(
        E, structure_kinetic=E.structure_kinetic / share, structure_strain=E.structure_strain / share, structure_work=work, surface_mismatch=work - along_w
    )
    return replace(result, energies=energies)


def run_impact(
    problem: ImpactProblem, model: BeamModel | PlateModel | None = None, energy: bool = True, stop_after: float | None = None, snapshots=()
) -> tuple[BeamModel | PlateModel, CoupledResult]:
    """The coupled run of an impact problem on a beam or plate; ``model``: a BeamModel or PlateModel
    of the same structure and step to reuse; ``energy``: keep the energy histories; ``stop_after``:
    end the run this long [s] after the impactor has left for good; ``snapshots``: step indices at
    which to keep the structure's displacement.

    Loadable nodes reach one impactor diameter from the impact point: a Hertz radius
    sqrt(R·α) and a flattened sphere's sqrt(d·α) stay within it while α < d (on a plate,
    :func:`plate_reach`).
    """
    model = model or impact_model(problem)
    if problem.on_plate:
        structure = plate_structure(model, problem.position, plate_reach(model, problem.position, problem.impactor.diameter))
    else:
        structure = beam_contact_structure(model, problem.position, problem.impactor.diameter)
    try:
        result = simulate_coupled(structure, problem.law, problem.impactor, problem.solver, energy, model.stepper, stop_after, snapshots)
    except InputError as exc:
        if "runs past" not in str(exc):
            raise
        raise InputError(f"{exc}: the contact outgrew the room about the impact point (target.case: load.position)") from None
    if problem.on_plate:
        result = _whole_plate(result, structure.patch.patch.share)
    return model, result


def impact(case: str, figures: bool = True, progress: Progress = no_progress) -> Outcome:
    """Run an impact case (file or built-in name) on a beam or plate target."""
    problem, inputs = load_impact_case(case)
    t0 = time.perf_counter()
    steps = problem.solver.steps
    model = impact_model(problem)
    progress(0, steps, "stepping")
    snaps = snapshot_steps(steps) if figures and problem.on_plate else ()
    model, result = run_impact(problem, model, snapshots=snaps)
    progress(steps, steps, "stepping")
    files = impact_files(problem, result, figures, model=model)
    fu, tu, su = (display(problem.units, k) for k in ("force", "time", "strain"))
    peaks = ", ".join(f"{n} {eps[np.argmax(np.abs(eps))] * su.factor:.0f} {su.label}" for n, eps in zip(result.gauge_names, result.gauge_strain))
    T = "not separated" if not np.isfinite(result.contact_duration) else f"T {result.contact_duration * tu.factor:.1f} {tu.label}"
    unfinished = (
        ()
        if np.isfinite(result.contact_duration)
        else (
            f"the first contact has not ended by the end of the run ({problem.solver.duration * tu.factor:.4g} {tu.label}): "
            "its duration and the rebound velocity are unknown (null in summary.json) and its peak may be later; lengthen solver.duration",
        )
    )
    dofs = model.fe.n if problem.on_plate else model.plane.n
    line = (
        f"{problem.law_name}: F0 {result.peak_force * fu.factor:.1f} {fu.label} at {result.time_of_peak * tu.factor:.1f} {tu.label}, {T}, "
        f"{len(result.contacts)} contact(s); peak strains {peaks} ({dofs} DOF, {steps} steps, {time.perf_counter() - t0:.1f} s)"
    )
    return Outcome(files, line, inputs, unfinished)
