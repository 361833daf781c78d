"""Plate cases (``softimpact plate``): a force history on a laminated plate (FSDT, MITC9/MITC4)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from ._common import LOAD_KEYS, expand_ply, gauge_keys, gauge_outputs, magnitude_and_history, without

__all__ = ["PlateKind", "mirrored_loads", "geometry_validity"]


def _wants_damage(outputs) -> bool:
    return not outputs or any(o.startswith("damage.") for o in outputs)


def mirrored_loads(problem) -> tuple[str, ...]:
    """A warning per symmetry edge that misses the load point (:meth:`PlateProblem.mirrored_edges`)."""
    return tuple(
        f'plate.support.{edge} = "symmetry" does not pass through the load point: the model carries the load mirrored about it too'
        for edge in problem.mirrored_edges()
    )


def geometry_validity(problem):
    """A plate theory's envelope in the plate's geometry (:func:`softimpact.models.validity.plate_thickness_validity`):
    the laminate's thickness over the shorter span (:func:`~softimpact.models.validity.plate_span`), on every plate run
    (dynamic, static, a coupled impact's target, a map's row)."""
    from ..models.validity import plate_span, plate_thickness_validity

    spec = problem.plate
    return plate_thickness_validity(spec.total_thickness, plate_span(spec.length_x, spec.length_y, spec.supports))


class PlateKind:
    """Plate cases. Sweep runs differing only in the force history share one PlateModel and its
    impulse responses (reciprocity: one adjoint run per output, then one FFT product a run).

    For the damage indices the model carries its ``"damage"`` output group: point strains (length 0) in x, y
    and 45° on both faces under the impact point and at each gauge's centre
    (:meth:`~softimpact.workflows.plate.PlateProblem.damage_gauges`), six engine outputs per point; the indices are those of
    :func:`softimpact.workflows.damage.plate_damage` at each point, and their maximum over the points.
    """

    name = "plate"
    table = "plate"

    def detect(self, data):
        return "plate" in data

    def load(self, case, history=None):
        from ..input.plate_case import load_plate_case
        from ..input.sweep_spec import case_files

        problem, path = load_plate_case(case, history)
        return problem, case_files(path)  # the case and every file it names

    def problem(self, data, base):
        from ..input.plate_case import plate_problem

        return plate_problem(data, base)

    def problem_class(self):
        from ..workflows.plate import PlateProblem

        return PlateProblem

    def check(self, problem):
        problem.check()

    def refine(self, problem, factor):
        self._linear_dynamic_only(problem, "converge")
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
        """The plate stepped directly (:func:`softimpact.cases.run.execute`), its displacement kept at the
        deflected-shape figure's instants (``figures``: ``shown``) and the fields' frames (``fields``: ``kept``);
        its warnings: the symmetry edges that miss the load, then the envelopes. A coupled run's options do not apply;
        ``force``: a force history F(t) in place of the problem's (its load's ``history``); ``summary``: False leaves the Run's summary empty."""
        from dataclasses import replace

        from ..models.validity import Validity
        from ..output.fields import FRAMES, sampled_steps
        from ..output.plate import plate_summary, plate_validity, snapshot_steps
        from .run import Run

        if force is not None:
            problem = replace(problem, load=replace(problem.load, history=force))
        if problem.analysis == "static":
            return self._static(problem, model)
        model = model or problem.model()
        steps = problem.solver.steps
        shown = snapshot_steps(steps) if figures else ()
        kept = sampled_steps(steps, FRAMES if frames is None else frames) if fields else ()
        snaps = np.union1d(shown, kept).astype(int) if fields else shown
        result = model.direct(force, progress=progress, energy=energy, snapshots=snaps)  # force None: the model's problem's history
        validity = Validity({}, mirrored_loads(problem)) + plate_validity(result) + geometry_validity(problem)
        return Run(result, model, plate_summary(model, result, validity) if summary else {}, validity, problem, shown, kept)

    def _static(self, problem, model=None):
        """A static plate run (:func:`softimpact.workflows.plate.solve_plate_static`): its summary and envelope;
        a Newton that did not converge is a warning of the run (summary.json says where)."""
        from ..models.validity import Validity
        from ..output.plate import plate_static_summary, plate_static_validity
        from ..workflows.plate import solve_plate_static
        from .run import Run

        model, result = solve_plate_static(problem, model)
        validity = plate_static_validity(result, model) + geometry_validity(problem)
        if not result.converged:
            validity += Validity({}, (f"static plate: {result.message}",), ("",))
        return Run(result, model, plate_static_summary(model, result, validity), validity, problem)

    def damage_refusal(self, problem):
        from ..workflows.damage import damage_refusal

        return damage_refusal(problem)

    def refusal(self, problem, study):
        """Why ``study`` ("a sweep", "converge") cannot run ``problem``: only linear dynamic plates are wired into them
        (a static plate has no steps to refine nor impulse responses to share), None for those."""
        if problem.analysis == "static":
            return (
                f"{study} of a plate case runs linear dynamic plates only for now: this one is static (solver.analysis = 'static'); "
                "run each load with `softimpact plate`"
            )
        if problem.kinematics != "linear":
            return f"{study} of a plate case runs linear dynamic plates only for now (plate.kinematics = 'linear'); an impact case on it sweeps and converges"
        return None

    def _linear_dynamic_only(self, problem, what: str) -> None:
        """Refuse a static or von Kármán plate case where only linear dynamic runs are wired (``what``: the study)."""
        from ..errors import InputError

        why = self.refusal(problem, what)
        if why is not None:
            raise InputError(why)

    def study(self, problem, stride, progress=None):
        """Peak deflection under the load, gauge peaks and histories; the model's size."""
        from ..output.plate import plate_scalars
        from .run import execute

        self._linear_dynamic_only(problem, "converge")
        run = execute(problem, energy=False, progress=progress, summary=False)
        model, r = run.model, run.result

        out = {"peak_deflection_at_load_m": plate_scalars(r)["peak_deflection_at_load_m"], "deflection_at_load_history_m": r.deflection[0][::stride]}
        magnitude_and_history(out, [g.name for g in problem.gauges], r.strain, stride)
        return out, {"elements": problem.elements, "time_step_s": problem.solver.time_step, "dofs": int(model.size)}

    def structure_key(self, data):
        return without(data, LOAD_KEYS)

    def prepare(self, data, base, runs, outputs=(), cases=()):
        from ..workflows.plate import PlateModel

        problem = self.problem(data, base)
        self._linear_dynamic_only(problem, "a sweep")
        model = PlateModel(problem, damage=_wants_damage(outputs) and problem.has_damage_outputs)
        # Several runs: only the kernels, the patch's tables and the problem travel to the workers (the
        # light copy: no mesh, matrices or factor, which does not pickle; 15 MB → under 1 MB).
        return model.for_workers() if runs > 1 else model

    def run(self, prepared, data, base, outputs=()):
        from ..input.beam_case import read_history
        from ..input.toml import Table, naming

        model = prepared
        if model.stepper is not None:  # a group of one run: stepping beats building the kernels
            from .run import execute

            problem = model.problem
            result = execute(problem, model=model, energy=False, summary=False).result
        else:
            # Only the force history differs within a group: parse it alone, on the group's problem.
            pulse = read_history(Table(data["load"], "load"), "history", Path(base))
            with naming({"time_step": "solver.time_step", "history": "load.history"}):
                problem = dataclasses.replace(model.problem, load=dataclasses.replace(model.problem.load, history=pulse))
            result = model.respond(pulse)
        out = self.summary(problem, result)
        if _wants_damage(outputs) and result.damage is not None:
            out["damage"] = self._damage(problem, dict(zip((g.name for g in model.damage), result.damage)), result.force)
        return out

    def summary(self, problem, result, model=None):
        """Peak force, impulse, deflection under the load and its time (:func:`softimpact.output.plate.plate_scalars`,
        as ``softimpact plate``'s summary.json) and gauge peaks; ``validity_flags``: the names of the run's validity
        flags (:func:`softimpact.output.plate.plate_validity`, as the command's)."""
        from ..output.plate import plate_scalars, plate_validity

        scalars = {**plate_scalars(result), **gauge_outputs(result.time, [g.name for g in problem.gauges], result.strain)}
        v = plate_validity(result) + geometry_validity(problem)
        return {**scalars, "validity": {"deflection_over_thickness": v.values["deflection_over_thickness"]}, "validity_flags": v.names}

    def _damage(self, problem, strains: dict, force: np.ndarray) -> dict:
        from ..workflows.damage import plate_damage, strain_tensor
        from ..workflows.plate import DAMAGE_DIRECTIONS

        stack = problem.plate.stack
        points = [p for p in problem.damage_points() if f"{p}.top.x" in strains]
        faces = {face: np.array([strain_tensor(*(strains[f"{p}.{face}.{d}"] for d in DAMAGE_DIRECTIONS)) for p in points]) for face in ("top", "bottom")}
        dmg = plate_damage(stack, stack.ply.strength, faces["top"], faces["bottom"], force)
        out = {**dmg.peaks(), "threshold_force_N": dmg.threshold_force}
        for i, p in enumerate(points):
            out[p] = {c: float(v[i].max()) for c, v in dmg.ply.items()}
        return out

    def output_keys(self, problem):
        from ..models.failure import CRITERIA

        keys = ["peak_force_N", "impulse_N_s", "peak_deflection_at_load_m", "time_of_peak_deflection_s", "validity.deflection_over_thickness"]
        keys += gauge_keys([g.name for g in problem.gauges])
        if problem.has_damage_outputs:
            keys += [f"damage.{c}" for c in CRITERIA] + ["damage.delamination", "damage.threshold_force_N"]
            keys += [f"damage.{p}.{c}" for p in problem.damage_points() for c in CRITERIA]
        return tuple(keys)

    def expand(self, data, key):
        expand_ply(data, key, "plate.laminate.ply")
