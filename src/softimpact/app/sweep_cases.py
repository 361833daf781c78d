"""Case types a sweep can run: one small adapter per type, registered in :data:`ADAPTERS`.

An adapter (see :class:`CaseAdapter`) tells the sweep

- ``detect(data)``: whether a parsed case file is of its type;
- ``problem(data, base)``: the case parsed and checked (raises InputError);
- ``structure(data)``: a text equal for two cases exactly when they share the
  expensive part (mesh, factorisation, impulse responses): runs are grouped by it;
- ``prepare(data, base, runs, outputs)``: that expensive part, built once per
  group and sent to the workers (so it must pickle); ``outputs`` (the spec's)
  may let it leave out what no output needs;
- ``run(prepared, data, base, outputs)``: one run → a nested dict of outputs
  (the ``summary.json`` keys of the case's command, plus sweep extras), which
  may skip work none of the dotted ``outputs`` asked for;
- ``output_keys(problem)``: the dotted output names a spec may ask for;
- ``expand(data, key)``: make ``key`` settable (e.g. a catalogue name turned
  into its inline table before one of its properties is drawn).

Impact cases register theirs here by adding to :data:`ADAPTERS`.
"""

from __future__ import annotations

import copy
import dataclasses
import json
from pathlib import Path
from typing import Protocol

import numpy as np

from ..errors import InputError
from ..input.sweep_spec import get_dotted, set_dotted
from ..input.toml import naming
from ..output.files import strain_peaks

__all__ = ["CaseAdapter", "BeamCase", "BarCase", "PlateCase", "ADAPTERS", "adapter_for", "flatten"]


class CaseAdapter(Protocol):
    name: str

    def detect(self, data: dict) -> bool: ...
    def problem(self, data: dict, base: Path): ...
    def structure(self, data: dict) -> str: ...
    def prepare(self, data: dict, base: Path, runs: int, outputs: tuple[str, ...] = ()): ...
    def run(self, prepared, data: dict, base: Path, outputs: tuple[str, ...]) -> dict: ...
    def output_keys(self, problem) -> tuple[str, ...]: ...
    def expand(self, data: dict, key: str) -> None: ...


def flatten(tree: dict, prefix: str = "") -> dict:
    """Nested dict → {dotted key: leaf}."""
    out = {}
    for k, v in tree.items():
        name = f"{prefix}{k}"
        if isinstance(v, dict):
            out.update(flatten(v, name + "."))
        else:
            out[name] = v
    return out


def _without(data: dict, keys) -> str:
    d = copy.deepcopy(data)
    for key in keys:
        *parents, last = key.split(".")
        node = get_dotted(d, ".".join(parents)) if parents else d
        if isinstance(node, dict):
            node.pop(last, None)
    return json.dumps(d, sort_keys=True, default=str)


_GAUGE_FIELDS = ("peak_tensile_strain", "peak_compressive_strain", "time_of_peak_tensile_strain_s", "time_of_peak_compressive_strain_s")


class BeamCase:
    """``softimpact beam`` cases. Runs differing only in the force history share one
    BeamModel and its impulse responses (the response engine: one convolution a run)."""

    name = "beam"
    LOAD_KEYS = ("load.history", "load.table", "title", "units")  # what does not change the structure

    def detect(self, data):
        return "beam" in data

    def problem(self, data, base):
        from ..input.beam_case import beam_problem

        return beam_problem(data, base)

    def structure(self, data):
        return _without(data, self.LOAD_KEYS)

    def prepare(self, data, base, runs, outputs=()):
        from ..workflows.beam_impact import BeamModel

        model = BeamModel(self.problem(data, base))
        if runs > 1:
            model.engine()
            # Only the kernels, the patch and the problem travel to the workers: the mesh,
            # the matrices and the factorisation stay behind (8 MB → under 1 MB).
            model.stepper = None
            model._engine.stepper = None
            model.plane = None
            model.O = model._engine.O = None
        return model

    def run(self, prepared, data, base, outputs=()):
        from ..input.beam_case import read_history
        from ..input.toml import Table
        from ..models.failure import STRENGTHS
        from ..workflows.beam_impact import BeamResult
        from ..workflows.damage import beam_damage

        model = prepared
        if model.stepper is not None:  # a group of one run: stepping beats building the kernels
            problem = model.problem
            result = model.direct(energy=False)
        else:
            # Only the force history differs within a group: parse it alone, on the group's problem.
            load = Table(data["load"], "load")
            pulse = read_history(load, "history", base)
            with naming({"time_step": "solver.time_step", "history": "load.history"}):
                problem = dataclasses.replace(model.problem, load=dataclasses.replace(model.problem.load, history=pulse))
            F = model.force_samples(pulse)
            if F[0] != 0.0:
                raise InputError("the force must be zero at first contact (t = 0)", "history")
            y = model.engine().convolve(model.nodal_loads(F))
            ng = len(problem.gauges)
            result = BeamResult(problem, problem.solver.times(), F, y[0 : 2 * ng : 2], 0.5 * (y[0 : 2 * ng : 2] - y[1 : 2 * ng : 2]), y[2 * ng])
        t, F = result.time, result.force
        out = {
            "peak_force_N": float(F.max()),
            "impulse_N_s": float(np.trapezoid(F, t)),
            "peak_deflection_under_load_m": float(result.deflection[np.argmax(np.abs(result.deflection))]),
            "gauges": {},
        }
        for g, eps in zip(problem.gauges, result.strain):
            k = int(np.argmax(np.abs(eps)))
            out["gauges"][g.name] = strain_peaks(t, eps)
            out[f"strain_{g.name}"] = {"peak": float(eps[k]), "peak_abs": float(abs(eps[k]))}
        stack = problem.beam.stack
        wanted = not outputs or any(o.startswith("damage.") for o in outputs)
        if wanted and stack is not None and stack.ply.name in STRENGTHS and hasattr(stack, "angles"):
            other = result.strain - 2 * result.bending
            dmg = beam_damage(stack, STRENGTHS[stack.ply.name], problem.beam.plane, result.strain, other, [g.surface for g in problem.gauges], F)
            out["damage"] = dmg.peaks()
            out["damage"]["threshold_force_N"] = dmg.threshold_force
        return out

    def output_keys(self, problem):
        from ..models.failure import CRITERIA, STRENGTHS

        keys = ["peak_force_N", "impulse_N_s", "peak_deflection_under_load_m"]
        for g in problem.gauges:
            keys += [f"gauges.{g.name}.{f}" for f in _GAUGE_FIELDS] + [f"strain_{g.name}.peak", f"strain_{g.name}.peak_abs"]
        stack = problem.beam.stack
        if stack is not None and stack.ply.name in STRENGTHS and hasattr(stack, "angles"):
            keys += [f"damage.{c}" for c in CRITERIA] + ["damage.delamination", "damage.threshold_force_N"]
        return tuple(keys)

    def expand(self, data, key):
        _expand_ply(data, key, "beam.laminate.ply")


class BarCase:
    """``softimpact bar`` cases: a nonlinear contact run each, nothing shared."""

    name = "bar"

    def detect(self, data):
        return "bar" in data

    def problem(self, data, base):
        from ..input.bar_case import bar_problem

        return bar_problem(data)

    def structure(self, data):
        return json.dumps(data, sort_keys=True, default=str)

    def prepare(self, data, base, runs, outputs=()):
        return None

    def run(self, prepared, data, base, outputs=()):
        from ..output.bar import bar_summary
        from ..workflows.bar_impact import simulate_impact

        s = bar_summary(simulate_impact(self.problem(data, base)))
        return {k: v for k, v in s.items() if isinstance(v, (int, float, dict)) and k != "case_SI"}

    def output_keys(self, problem):
        keys = ["peak_force_N", "time_of_peak_s", "contact_duration_s", "impulse_N_s", "rebound_velocity_m_s", "energy_drift_relative", "newton_iterations"]
        for g in problem.gauges:
            keys += [f"gauges.{g.name}.{f}" for f in _GAUGE_FIELDS]
        return tuple(keys)

    def expand(self, data, key):
        pass


DAMAGE_PREFIX = "_damage"  # names of the pseudo-gauges the plate adapter adds
DAMAGE_DIRECTIONS = ("x", "y", 45.0)  # three normal strains give the in-plane strain tensor


def _damage_points(problem) -> dict[str, tuple[float, float]]:
    """Where a plate's damage indices are read: under the impact point and at each gauge's centre."""
    points = {"at_load": tuple(problem.load.position)}
    points.update({f"at_{g.name}": tuple(g.position) for g in problem.gauges})
    return points


def _wants_damage(outputs) -> bool:
    return not outputs or any(o.startswith("damage.") for o in outputs)


def _screenable(stack) -> bool:
    from ..models.failure import STRENGTHS

    return stack is not None and hasattr(stack, "angles") and stack.ply.name in STRENGTHS


class PlateCase:
    """``softimpact plate`` cases. Runs differing only in the force history share one PlateModel
    and its impulse responses (reciprocity: one adjoint run per output, then one FFT product a run).

    For the damage indices the model carries pseudo-gauges: point strains (length 0) in x, y and
    45° on both faces under the impact point and at each gauge's centre (:func:`_damage_points`),
    six engine outputs per point; the indices are those of
    :func:`softimpact.workflows.damage.plate_damage` at each point, and their maximum over the points.
    """

    name = "plate"
    LOAD_KEYS = ("load.history", "load.table", "title", "units")  # what does not change the structure

    def detect(self, data):
        return "plate" in data

    def problem(self, data, base):
        from ..input.plate_case import plate_problem

        return plate_problem(data, base)

    def structure(self, data):
        return _without(data, self.LOAD_KEYS)

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
        if runs > 1:
            engine = model.engine()
            model.nodal_loads(model.force_samples())  # the patch tabulates its distributions once, on the mesh
            # Only the kernels, the patch's tables and the problem travel to the workers: the mesh,
            # the matrices and the factorisation (which does not pickle) stay behind (15 MB → under 1 MB).
            model.stepper = engine.stepper = None
            model.fe = model.patch.fe = None
            model.O = engine.O = None
        return model

    def run(self, prepared, data, base, outputs=()):
        from ..input.beam_case import read_history
        from ..input.toml import Table
        from ..models.failure import STRENGTHS
        from ..workflows.damage import plate_damage, strain_tensor

        model = prepared
        if model.stepper is not None:  # a group of one run: stepping beats building the kernels
            problem = model.problem
            result = model.direct(energy=False, snapshots=())
        else:
            # Only the force history differs within a group: parse it alone, on the group's problem.
            pulse = read_history(Table(data["load"], "load"), "history", base)
            with naming({"time_step": "solver.time_step", "history": "load.history"}):
                problem = dataclasses.replace(model.problem, load=dataclasses.replace(model.problem.load, history=pulse))
            result = model.respond(pulse)
        t, F = result.time, result.force
        w = result.deflection[0]
        k = int(np.argmax(np.abs(w)))
        out = {
            "peak_force_N": float(F.max()),
            "impulse_N_s": float(np.trapezoid(F, t)),
            "peak_deflection_at_load_m": float(w[k]),
            "time_of_peak_deflection_s": float(t[k]),
            "gauges": {},
        }
        strains = dict(zip((g.name for g in problem.gauges), result.strain))
        for g in problem.gauges:
            if g.name.startswith(DAMAGE_PREFIX + "."):
                continue
            eps = strains[g.name]
            j = int(np.argmax(np.abs(eps)))
            out["gauges"][g.name] = strain_peaks(t, eps)
            out[f"strain_{g.name}"] = {"peak": float(eps[j]), "peak_abs": float(abs(eps[j]))}
        stack = problem.plate.stack
        if _wants_damage(outputs) and _screenable(stack) and any(n.startswith(DAMAGE_PREFIX + ".") for n in strains):
            points = [p for p in _damage_points(problem) if f"{DAMAGE_PREFIX}.{p}.top.x" in strains]
            faces = {
                face: np.array([strain_tensor(*(strains[f"{DAMAGE_PREFIX}.{p}.{face}.{d}"] for d in DAMAGE_DIRECTIONS)) for p in points])
                for face in ("top", "bottom")
            }
            dmg = plate_damage(stack, STRENGTHS[stack.ply.name], faces["top"], faces["bottom"], F)
            out["damage"] = dmg.peaks()
            out["damage"]["threshold_force_N"] = dmg.threshold_force
            for i, p in enumerate(points):
                out["damage"][p] = {c: float(v[i].max()) for c, v in dmg.ply.items()}
        return out

    def output_keys(self, problem):
        from ..models.failure import CRITERIA

        keys = ["peak_force_N", "impulse_N_s", "peak_deflection_at_load_m", "time_of_peak_deflection_s"]
        for g in problem.gauges:
            keys += [f"gauges.{g.name}.{f}" for f in _GAUGE_FIELDS] + [f"strain_{g.name}.peak", f"strain_{g.name}.peak_abs"]
        if _screenable(problem.plate.stack):
            keys += [f"damage.{c}" for c in CRITERIA] + ["damage.delamination", "damage.threshold_force_N"]
            keys += [f"damage.{p}.{c}" for p in _damage_points(problem) for c in CRITERIA]
        return tuple(keys)

    def expand(self, data, key):
        _expand_ply(data, key, "plate.laminate.ply")


def _expand_ply(data: dict, key: str, where: str) -> None:
    """A catalogue ply name at ``where`` turned into its inline table, before one of its properties is set."""
    from ..models.laminate import PLIES

    if key.startswith(where + ".") and isinstance(get_dotted(data, where), str):
        name = get_dotted(data, where)
        if name not in PLIES:
            return
        p = PLIES[name]
        inline = {"name": p.name, "source": p.source, "nu12": p.nu12, "nu13": p.nu13, "nu23": p.nu23}
        inline.update({k: f"{getattr(p, k)!r} Pa" for k in ("E1", "E2", "E3", "G12", "G13", "G23")})
        inline["density"] = f"{p.density!r} kg/m^3"
        inline["thickness"] = f"{p.thickness!r} m"
        set_dotted(data, where, inline)


ADAPTERS: dict[str, CaseAdapter] = {"beam": BeamCase(), "bar": BarCase(), "plate": PlateCase()}


def adapter_for(data: dict, where: str) -> CaseAdapter:
    for a in ADAPTERS.values():
        if a.detect(data):
            return a
    raise InputError(f"{where}: not a case type a sweep can run ({', '.join(ADAPTERS)})")
