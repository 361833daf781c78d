"""Beam cases (``softimpact beam``): a force history on a laminated beam (plane model)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from ..errors import InputError
from ._common import LOAD_KEYS, expand_ply, gauge_keys, gauge_outputs, without

__all__ = ["BeamKind", "beam_validity"]


def beam_validity(result):
    """The envelopes of a beam run (:mod:`softimpact.models.validity`): peak deflection under the load
    against the thickness (linear theory), and on a layup with strengths the gauge sections' maximum-strain
    index (:func:`softimpact.workflows.damage.beam_damage`) against 1."""
    from ..models.validity import allowable_flags

    p = result.problem
    v = p.validity(float(np.max(np.abs(result.deflection))))
    if p.has_damage_outputs and p.gauges and np.all(np.isfinite(result.bending)):
        from ..workflows.damage import beam_damage

        stack = p.beam.stack
        other = result.strain - 2 * result.bending
        dmg = beam_damage(stack, stack.ply.strength, p.beam.plane, result.strain, other, [g.surface for g in p.gauges], result.force)
        v += allowable_flags("the beam's plies at the gauge sections", float(dmg.ply["max_strain"].max()))
    return v


class BeamKind:
    """Beam cases. Sweep runs differing only in the force history share one BeamModel and its
    impulse responses (the response engine: one convolution a run)."""

    name = "beam"
    table = "beam"

    def detect(self, data):
        return "beam" in data

    def load(self, case, history=None):
        from ..input.beam_case import load_beam_case
        from ..input.sweep_spec import case_files

        problem, path = load_beam_case(case, history)
        return problem, case_files(path)  # the case and every file it names

    def problem(self, data, base):
        from ..input.beam_case import beam_problem

        return beam_problem(data, base)

    def problem_class(self):
        from ..workflows.beam_impact import BeamProblem

        return BeamProblem

    def check(self, problem):
        problem.check()

    def refine(self, problem, factor):
        return problem.refine(factor)

    def execute(
        self,
        problem,
        *,
        figures=False,
        fields=False,
        frames=None,
        damage=True,
        method="direct",
        kernels=None,
        model=None,
        energy=True,
        stop_after=None,
        progress=None,
        force=None,
        summary=True,
    ):
        """The beam stepped directly (:func:`softimpact.cases.run.execute`), the whole displacement kept with
        ``figures`` or ``fields`` (the frames of the fields: ``kept``); a coupled run's options do not apply.
        ``model``: a model of the same beam, mesh and step to reuse (its patch reaching the problem's contact
        radius), stepped under ``problem``'s force history and contact radius; ``force``: a force history F(t)
        in place of the problem's (its load's ``history``); ``summary``: False leaves the Run's summary empty."""
        from dataclasses import replace

        from ..output.beam import beam_summary
        from ..output.fields import FRAMES, sampled_steps
        from .run import Run

        if force is not None:
            problem = replace(problem, load=replace(problem.load, history=force))
        if model is None:
            model = problem.model()  # a BeamModel, or with beam.kinematics = "von-karman" its total Lagrangian form
            result = model.direct(progress=progress, energy=energy, displacement=figures or fields)
        else:
            load = problem.load
            result = model.direct(load.history, progress, energy, figures or fields, radius=load.contact_radius)
            result = replace(result, problem=problem)
        kept = sampled_steps(problem.solver.steps, FRAMES if frames is None else frames) if fields else ()
        validity = beam_validity(result)
        return Run(result, model, beam_summary(model, result, validity) if summary else {}, validity, problem, kept=kept)

    def refusal(self, problem, study):
        """Every beam case sweeps and converges."""
        return None

    def damage_refusal(self, problem):
        from ..workflows.damage import damage_refusal

        return damage_refusal(problem)

    def study(self, problem, stride, progress=None):
        """Deflection under the load, gauge peaks, first-lobe peaks, first zero crossings and histories; the model's size."""
        from ..models.features import first_lobe_peak, first_zero_crossing
        from ..output.beam import beam_scalars
        from .run import execute

        run = execute(problem, energy=False, progress=progress, summary=False)
        model, r = run.model, run.result

        out = {"peak_deflection_under_load_m": beam_scalars(r)["peak_deflection_under_load_m"]}
        for g, eps in zip(problem.gauges, r.strain):
            out[f"strain_{g.name}_peak_magnitude"] = float(np.max(np.abs(eps)))  # unsigned: see magnitude_and_history
            out[f"strain_{g.name}_first_lobe_peak"] = first_lobe_peak(r.time, eps)
            out[f"strain_{g.name}_first_zero_crossing_s"] = first_zero_crossing(r.time, eps)
            out[f"strain_{g.name}_history"] = eps[::stride]
        return out, {"elements": problem.elements, "time_step_s": problem.solver.time_step, "dofs": int(model.size)}

    def structure_key(self, data):
        return without(data, LOAD_KEYS)

    def prepare(self, data, base, runs, outputs=(), cases=()):
        from ..workflows.beam_impact import BeamModel

        problem = self.problem(data, base)
        if problem.kinematics != "linear":
            return None  # no response engine on a nonlinear beam: each run builds and steps its own model
        model = BeamModel(problem)
        # Several runs: only the kernels, the patch and the problem travel to the workers (the light
        # copy: no mesh, matrices or factor; 8 MB → under 1 MB); one run steps directly.
        return model.for_workers() if runs > 1 else model

    def run(self, prepared, data, base, outputs=()):
        from ..input.beam_case import read_history
        from ..input.toml import Table, naming
        from ..workflows.beam_impact import BeamResult
        from .run import execute

        model = prepared
        if model is None:  # a nonlinear beam (prepare): the run's own problem, stepped directly
            problem = self.problem(data, base)
            result = execute(problem, energy=False, summary=False).result
        elif model.stepper is not None:  # a group of one run: stepping beats building the kernels
            problem = model.problem
            result = execute(problem, model=model, energy=False, summary=False).result
        else:
            # Only the force history differs within a group: parse it alone, on the group's problem.
            pulse = read_history(Table(data["load"], "load"), "history", Path(base))
            with naming({"time_step": "solver.time_step", "history": "load.history"}):
                problem = dataclasses.replace(model.problem, load=dataclasses.replace(model.problem.load, history=pulse))
            F = model.force_samples(pulse)
            if F[0] != 0.0:
                raise InputError("the force must be zero at first contact (t = 0)", "history")
            y = model.engine().convolve(model.nodal_loads(F))
            ng = len(problem.gauges)
            result = BeamResult(problem, problem.solver.times(), F, y[0 : 2 * ng : 2], 0.5 * (y[0 : 2 * ng : 2] - y[1 : 2 * ng : 2]), y[2 * ng])
        out = self.summary(problem, result)
        wanted = not outputs or any(o.startswith("damage.") for o in outputs)
        if wanted and problem.has_damage_outputs:
            out["damage"] = self.damage(problem, result)
        return out

    def summary(self, problem, result, model=None):
        """Peak force, impulse, deflection under the load (:func:`softimpact.output.beam.beam_scalars`, as
        ``softimpact beam``'s summary.json) and gauge peaks; ``validity_flags``: the names of the run's
        validity flags (:func:`beam_validity`, as the command's)."""
        from ..output.beam import beam_scalars

        scalars = {**beam_scalars(result), **gauge_outputs(result.time, [g.name for g in problem.gauges], result.strain)}
        v = beam_validity(result)
        return {**scalars, "validity": {"deflection_over_thickness": v.values["deflection_over_thickness"]}, "validity_flags": v.names}

    def damage(self, problem, result) -> dict:
        """Peak damage indices at the gauge sections and the delamination threshold force."""
        from ..workflows.damage import beam_damage

        stack = problem.beam.stack
        other = result.strain - 2 * result.bending
        dmg = beam_damage(stack, stack.ply.strength, problem.beam.plane, result.strain, other, [g.surface for g in problem.gauges], result.force)
        return {**dmg.peaks(), "threshold_force_N": dmg.threshold_force}

    def output_keys(self, problem):
        from ..models.failure import CRITERIA

        keys = ["peak_force_N", "impulse_N_s", "peak_deflection_under_load_m", "validity.deflection_over_thickness"]
        keys += gauge_keys([g.name for g in problem.gauges])
        if problem.has_damage_outputs:
            keys += [f"damage.{c}" for c in CRITERIA] + ["damage.delamination", "damage.threshold_force_N"]
        return tuple(keys)

    def expand(self, data, key):
        expand_ply(data, key, "beam.laminate.ply")
