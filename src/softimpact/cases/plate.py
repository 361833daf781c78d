"""Plate cases (``softimpact plate``): a force history on a laminated plate (FSDT, MITC9/MITC4)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from ._common import LOAD_KEYS, expand_ply, gauge_keys, gauge_outputs, magnitude_and_history, without

__all__ = ["PlateKind", "DAMAGE_PREFIX", "DAMAGE_DIRECTIONS"]

DAMAGE_PREFIX = "_damage"  # names of the pseudo-gauges the plate kind adds for the damage indices
DAMAGE_DIRECTIONS = ("x", "y", 45.0)  # three normal strains give the in-plane strain tensor


def _damage_points(problem) -> dict[str, tuple[float, float]]:
    """Where a plate's damage indices are read: under the impact point and at each gauge's centre."""
    points = {"at_load": tuple(problem.load.position)}
    points.update({f"at_{g.name}": tuple(g.position) for g in problem.gauges})
    return points


def _wants_damage(outputs) -> bool:
    return not outputs or any(o.startswith("damage.") for o in outputs)


def _screenable(stack) -> bool:
    return stack is not None and hasattr(stack, "angles") and stack.ply.strength is not None


class PlateKind:
    """Plate cases. Sweep runs differing only in the force history share one PlateModel and its
    impulse responses (reciprocity: one adjoint run per output, then one FFT product a run).

    For the damage indices the model carries pseudo-gauges: point strains (length 0) in x, y and
    45° on both faces under the impact point and at each gauge's centre (:func:`_damage_points`),
    six engine outputs per point; the indices are those of
    :func:`softimpact.workflows.damage.plate_damage` at each point, and their maximum over the points.
    """

    name = "plate"
    table = "plate"

    def detect(self, data):
        return "plate" in data

    def load(self, case, history=None):
        from ..input.plate_case import load_plate_case

        problem, path = load_plate_case(case, history)
        return problem, (path,)

    def problem(self, data, base):
        from ..input.plate_case import plate_problem

        return plate_problem(data, base)

    def check(self, problem):
        from ..workflows.plate_impact import check_problem

        check_problem(problem)

    def refine(self, problem, factor):
        from ..workflows.refinement import refine_plate

        return refine_plate(problem, factor)

    def study(self, problem, stride, progress=None):
        """Peak deflection under the load, gauge peaks and histories; the model's size."""
        from ..workflows.plate_impact import PlateModel

        model = PlateModel(problem)
        r = model.direct(progress=progress, energy=False, snapshots=[])
        from ..output.plate import plate_scalars

        out = {"peak_deflection_at_load_m": plate_scalars(r)["peak_deflection_at_load_m"], "deflection_at_load_history_m": r.deflection[0][::stride]}
        magnitude_and_history(out, [g.name for g in problem.gauges], r.strain, stride)
        return out, {"elements": list(problem.plate.elements), "time_step_s": problem.solver.time_step, "dofs": int(model.size)}

    def structure_key(self, data):
        return without(data, LOAD_KEYS)

    def prepare(self, data, base, runs, outputs=()):
        from ..workflows.plate_impact import PlateGauge, PlateModel

        problem = self.problem(data, base)
        if _wants_damage(outputs) and _screenable(problem.plate.stack):
            extra = tuple(
                PlateGauge(f"{DAMAGE_PREFIX}.{name}.{face}.{d}", xy, face, d, 0.0)
                for name, xy in _damage_points(problem).items()
                for face in ("top", "bottom")
                for d in DAMAGE_DIRECTIONS
            )
            problem = dataclasses.replace(problem, gauges=problem.gauges + extra)
        model = PlateModel(problem)
        # Several runs: only the kernels, the patch's tables and the problem travel to the workers (the
        # light copy: no mesh, matrices or factor, which does not pickle; 15 MB → under 1 MB).
        return model.for_workers() if runs > 1 else model

    def run(self, prepared, data, base, outputs=()):
        from ..input.beam_case import read_history
        from ..input.toml import Table, naming

        model = prepared
        if model.stepper is not None:  # a group of one run: stepping beats building the kernels
            problem = model.problem
            result = model.direct(energy=False, snapshots=())
        else:
            # Only the force history differs within a group: parse it alone, on the group's problem.
            pulse = read_history(Table(data["load"], "load"), "history", Path(base))
            with naming({"time_step": "solver.time_step", "history": "load.history"}):
                problem = dataclasses.replace(model.problem, load=dataclasses.replace(model.problem.load, history=pulse))
            result = model.respond(pulse)
        out = self.summary(problem, result)
        strains = dict(zip((g.name for g in problem.gauges), result.strain))
        if _wants_damage(outputs) and _screenable(problem.plate.stack) and any(n.startswith(DAMAGE_PREFIX + ".") for n in strains):
            out["damage"] = self._damage(problem, strains, result.force)
        return out

    def summary(self, problem, result, model=None):
        """Peak force, impulse, deflection under the load and its time (:func:`softimpact.output.plate.plate_scalars`,
        as ``softimpact plate``'s summary.json) and gauge peaks (the damage pseudo-gauges left out); ``validity_flags``:
        the names of the run's validity flags (:func:`softimpact.output.plate.plate_validity`, as the command's)."""
        from ..output.plate import plate_scalars, plate_validity

        keep = [j for j, g in enumerate(problem.gauges) if not g.name.startswith(DAMAGE_PREFIX + ".")]
        real = [(problem.gauges[j].name, result.strain[j]) for j in keep]
        scalars = {**plate_scalars(result), **gauge_outputs(result.time, [n for n, _ in real], [e for _, e in real])}
        # the envelopes of the plate command's own run: its gauges, not the damage pseudo-gauges
        own = dataclasses.replace(result, problem=dataclasses.replace(problem, gauges=tuple(problem.gauges[j] for j in keep)), strain=result.strain[keep])
        v = plate_validity(own)
        return {**scalars, "validity": {"deflection_over_thickness": v.values["deflection_over_thickness"]}, "validity_flags": v.names}

    def _damage(self, problem, strains: dict, force: np.ndarray) -> dict:
        from ..workflows.damage import plate_damage, strain_tensor

        stack = problem.plate.stack
        points = [p for p in _damage_points(problem) if f"{DAMAGE_PREFIX}.{p}.top.x" in strains]
        faces = {
            face: np.array([strain_tensor(*(strains[f"{DAMAGE_PREFIX}.{p}.{face}.{d}"] for d in DAMAGE_DIRECTIONS)) for p in points])
            for face in ("top", "bottom")
        }
        dmg = plate_damage(stack, stack.ply.strength, faces["top"], faces["bottom"], force)
        out = {**dmg.peaks(), "threshold_force_N": dmg.threshold_force}
        for i, p in enumerate(points):
            out[p] = {c: float(v[i].max()) for c, v in dmg.ply.items()}
        return out

    def output_keys(self, problem):
        from ..models.failure import CRITERIA

        keys = ["peak_force_N", "impulse_N_s", "peak_deflection_at_load_m", "time_of_peak_deflection_s", "validity.deflection_over_thickness"]
        keys += gauge_keys([g.name for g in problem.gauges])
        if _screenable(problem.plate.stack):
            keys += [f"damage.{c}" for c in CRITERIA] + ["damage.delamination", "damage.threshold_force_N"]
            keys += [f"damage.{p}.{c}" for p in _damage_points(problem) for c in CRITERIA]
        return tuple(keys)

    def expand(self, data, key):
        expand_ply(data, key, "plate.laminate.ply")
