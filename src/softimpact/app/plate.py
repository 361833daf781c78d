"""``softimpact plate``: transverse impact of a laminated plate (FSDT, MITC4); and the
paper report's beam-as-plate section (the plane-strain assumption measured)."""

from __future__ import annotations

import time

import numpy as np

from ..input.plate_case import load_plate_case
from ..output.plate import plate_files, snapshot_steps
from ..units import display
from ..workflows.plate_impact import PlateModel
from . import Outcome, Progress, no_progress

__all__ = ["plate"]


def plate(case: str, history: int | None = None, figures: bool = True, progress: Progress = no_progress) -> Outcome:
    """Run a plate case (file or built-in name), optionally with row ``history`` of its [[load.table]]."""
    problem, path = load_plate_case(case, history)
    t0 = time.perf_counter()
    model = PlateModel(problem)
    steps = problem.solver.steps
    result = model.direct(progress=lambda k: progress(k, steps, "stepping"), snapshots=snapshot_steps(steps) if figures else ())
    progress(steps, steps, "stepping")
    files = plate_files(model, result, figures)
    su, lu = display(problem.units, "strain"), display(problem.units, "length")
    peaks = "".join(f", {g.name} {eps[np.argmax(np.abs(eps))] * su.factor:.0f} {su.label}" for g, eps in zip(problem.gauges, result.strain))
    w = result.deflection[0]
    line = f"{model.fe.n} DOF, {steps} steps ({time.perf_counter() - t0:.1f} s); peak deflection {w[np.argmax(np.abs(w))] * lu.factor:.3g} {lu.label}{peaks}"
    return Outcome(files, line, (path,))


BEAM_CASES = ("paper-long-beam", "paper-short-beam")
STRIP_ELEMENT = 0.0625 * 0.0254  # m: 16 MITC4 elements across the 1-in width, 96 along the long beam's 6 in


def beam_as_plate(plate_element: float = STRIP_ELEMENT, progress: Progress = no_progress):
    """The paper's beams (plane-strain FE, as in their cases) and the same strips as FSDT plates
    (clamped at x = 0, free elsewhere; the patch a disc on the centre line, the gauges on it),
    under every force history of their [[load.table]]. Returns, per beam, its label, the times,
    and per history (label, {gauge: (beam strain, plate strain)})."""
    from ..input.beam_case import load_beam_case, table_rows
    from ..models.pulses import SkewedPulse
    from ..workflows.beam_impact import BeamModel
    from ..workflows.plate_impact import PlateGauge, PlateLoad, PlateProblem, PlateSpec

    out = []
    for i, name in enumerate(BEAM_CASES):
        progress(i, len(BEAM_CASES), name)
        problem, _ = load_beam_case(name)
        rows = table_rows(name)
        rmax = max(r["contact_radius"] for r in rows)
        spec = problem.beam
        b = spec.width
        elements = (max(2, round(spec.length / plate_element)), max(2, round(b / plate_element)))
        plate = PlateProblem(
            PlateSpec(spec.length, b, elements, spec.stack, ("clamped", "free", "free", "free")),
            PlateLoad((problem.load.position, b / 2), problem.load.contact_radius, problem.load.history),
            problem.solver,
            tuple(PlateGauge(g.name, (g.position, b / 2), g.surface, "x", g.length) for g in problem.gauges),
            title=problem.title,
            units=problem.units,
        )
        beam_model, plate_model = BeamModel(problem, patch_radius=rmax), PlateModel(plate, patch_radius=rmax)
        histories = []
        for k, r in enumerate(rows, 1):
            pulse = SkewedPulse(r["peak_force"], r["time_of_peak"], r["duration"])
            eb = beam_model.respond(pulse, r["contact_radius"]).strain
            ep = plate_model.respond(pulse, r["contact_radius"]).strain
            histories.append((f"history {k}", {g.name: (eb[j], ep[j]) for j, g in enumerate(problem.gauges)}))
        out.append((name, problem, plate_model, problem.solver.times(), histories))
    return out


def plate_structure(model: PlateModel, position: tuple[float, float], max_radius: float):
    """The plate as a :class:`softimpact.fem.impact.ContactStructure` for the coupled solver:
    struck downward (−z) on its top face at ``position`` (x, y) [m], contact discs up to
    ``max_radius`` [m] spread by the cosine pressure of eq (11) over the nodes (exact
    integrals, :class:`softimpact.fem.plate_loads.DiscShares`); the approach is measured
    on the mid-surface deflection there; the outputs are the model's gauges."""
    from ..fem.impact import ContactStructure
    from ..fem.plate_loads import CircularPatch, DiscShares

    fe = model.fe
    patch = CircularPatch(fe, position, max_radius, grow=True)
    gauges = model.problem.gauges
    return ContactStructure(
        M=fe.M,
        K=fe.K,
        surface_x=fe.node_xy()[0, patch.nodes],
        surface_dofs=patch.dofs,
        load_sign=-1.0,  # w is up +, the impact pushes down
        center=float(position[0]),
        approach_row=-fe.deflection(*position),
        outputs=model.O[: len(gauges)],
        output_names=tuple(g.name for g in gauges),
        C=model.stepper.C,
        patch=DiscShares(patch),
    )
