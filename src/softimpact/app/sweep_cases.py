"""Case types a sweep can run: one small adapter per type, registered in :data:`ADAPTERS`.

An adapter (see :class:`CaseAdapter`) tells the sweep

- ``detect(data)``: whether a parsed case file is of its type;
- ``problem(data, base)``: the case parsed and checked (raises InputError);
- ``structure(data)``: a text equal for two cases exactly when they share the
  expensive part (mesh, factorisation, impulse responses): runs are grouped by it;
- ``prepare(data, base, runs)``: that expensive part, built once per group and
  sent to the workers (so it must pickle);
- ``run(prepared, data, base, outputs)``: one run → a nested dict of outputs
  (the ``summary.json`` keys of the case's command, plus sweep extras), which
  may skip work none of the dotted ``outputs`` asked for;
- ``output_keys(problem)``: the dotted output names a spec may ask for;
- ``expand(data, key)``: make ``key`` settable (e.g. a catalogue name turned
  into its inline table before one of its properties is drawn).

Plate and impact cases register theirs here by adding to :data:`ADAPTERS`.
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

__all__ = ["CaseAdapter", "BeamCase", "BarCase", "ADAPTERS", "adapter_for", "flatten"]


class CaseAdapter(Protocol):
    name: str

    def detect(self, data: dict) -> bool: ...
    def problem(self, data: dict, base: Path): ...
    def structure(self, data: dict) -> str: ...
    def prepare(self, data: dict, base: Path, runs: int): ...
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

    def prepare(self, data, base, runs):
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
        from ..models.laminate import PLIES

        if key.startswith("beam.laminate.ply.") and isinstance(get_dotted(data, "beam.laminate.ply"), str):
            name = get_dotted(data, "beam.laminate.ply")
            if name not in PLIES:
                return
            p = PLIES[name]
            inline = {"name": p.name, "source": p.source, "nu12": p.nu12, "nu13": p.nu13, "nu23": p.nu23}
            inline.update({k: f"{getattr(p, k)!r} Pa" for k in ("E1", "E2", "E3", "G12", "G13", "G23")})
            inline["density"] = f"{p.density!r} kg/m^3"
            inline["thickness"] = f"{p.thickness!r} m"
            set_dotted(data, "beam.laminate.ply", inline)


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

    def prepare(self, data, base, runs):
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


ADAPTERS: dict[str, CaseAdapter] = {"beam": BeamCase(), "bar": BarCase()}


def adapter_for(data: dict, where: str) -> CaseAdapter:
    for a in ADAPTERS.values():
        if a.detect(data):
            return a
    raise InputError(f"{where}: not a case type a sweep can run ({', '.join(ADAPTERS)})")
