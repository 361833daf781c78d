"""Impact cases (``softimpact impact``): a rigid impactor on a beam or plate target through a contact law (coupled)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from ._common import GAUGE_FIELDS, magnitude_and_history, without
from .bar import BarKind

__all__ = ["ImpactKind", "SharedModel", "bar_target"]

_BAR = BarKind()  # a bar target runs as the bar case with the impact case's impactor and law

# Keys of an impact case that leave the target's model (mesh, step, factorisation) unchanged: the
# impactor's velocity, mass and material and the contact law. Its diameter stays in the key: it
# sets a plate's patch radius and reach.
NOT_STRUCTURE = ("impactor.velocity", "impactor.mass", "impactor.material", "contact", "title", "units")


class SharedModel:
    """The target's model shared by the runs of a sweep group, built on first use where the runs
    are (in a Dask worker, or in the plain loop) and never pickled: a factorisation does not travel."""

    def __init__(self, data: dict, base: str):
        self.data, self.base, self.model = data, base, None

    def __getstate__(self):
        return {"data": self.data, "base": self.base, "model": None}

    def get(self, problem):
        from ..workflows.coupled import impact_model

        if self.model is None:
            self.model = impact_model(problem)
        return self.model


def bar_target(data: dict, base: Path):
    """An impact case whose target is a bar case, as that bar case with the impact case's impactor
    (``[projectile]``), contact law, solver, gauges (if given), title and units: a
    :class:`softimpact.workflows.bar_impact.BarImpactProblem` and the bar case's path; None for a
    beam or plate target. ``contact.law = "hertz"`` is the bar's own Hertz law (eq 3: the sphere on
    the flat end of the bar), so ``target_modulus`` has no meaning there and is refused."""
    from ..errors import InputError
    from ..input.bar_case import bar_problem
    from ..input.toml import load_toml, locate

    target = data.get("target")
    case = target.get("case") if isinstance(target, dict) else None
    if not isinstance(case, str):
        return None
    path = base / case if (base / case).is_file() else locate(case)
    bar = load_toml(path)
    if "projectile" not in bar:
        return None
    if set(target) != {"case"}:
        raise InputError(f"target.{sorted(set(target) - {'case'})[0]}: unknown key")
    contact = dict(data.get("contact", {}))
    if "target_modulus" in contact:
        raise InputError(f"contact.target_modulus: not for a bar target ({path.name}): Hertz's law uses the bar's own material")
    merged = {k: v for k, v in bar.items() if k not in ("output", "contact")}
    merged["projectile"] = data.get("impactor", {})
    merged["contact"] = contact
    for key in ("title", "units", "solver", "gauges"):
        if key in data:
            merged[key] = data[key]
    unknown = sorted(set(data) - {"target", "impactor", "contact", "title", "units", "solver", "gauges"})
    if unknown:
        raise InputError(f"{unknown[0]}: unknown key")
    try:
        problem = bar_problem(merged, base)
    except InputError as exc:
        text = str(exc).replace("projectile.", "impactor.").replace("projectile:", "impactor:")
        raise InputError(f"{text} (target.case {path.name} is a bar case)") from None
    return problem, path


def _is_bar(problem) -> bool:
    return hasattr(problem, "projectile")


class ImpactKind:
    """Impact cases. A coupled run is nonlinear in the velocity, so sweep runs share only the
    target's model (mesh, matrices, the factorised Newmark step): runs that differ only in the
    impactor's velocity, mass or material or in the contact law form one group.

    A bar case as the target (:func:`bar_target`) runs as that bar case with the impact case's
    impactor and law: its problem, checks, refinement, study and outputs are the bar kind's."""

    name = "impact"
    table = "target"

    def detect(self, data):
        return "target" in data

    def load(self, case, history=None):
        from ..errors import InputError
        from ..input.impact_case import load_impact_case
        from ..input.toml import load_toml, locate

        if history is not None:
            raise InputError("--history: an impact case has no table of histories (its force comes from the contact)", "history")
        path = locate(case)
        bar = bar_target(load_toml(path), path.parent)
        if bar is not None:
            return bar[0], (path, bar[1])
        return load_impact_case(case)

    def problem(self, data, base):
        from ..input.impact_case import impact_problem

        bar = bar_target(data, Path(base))
        return bar[0] if bar is not None else impact_problem(data, Path(base))[0]

    def check(self, problem):
        if _is_bar(problem):
            return _BAR.check(problem)
        from ..workflows.beam_impact import check_problem as check_beam
        from ..workflows.plate_impact import check_problem as check_plate

        (check_plate if problem.on_plate else check_beam)(problem.target)

    def refine(self, problem, factor):
        """The target refined (mesh and step; see :mod:`softimpact.workflows.refinement`); impactor and law unchanged."""
        from ..workflows.refinement import refine_beam, refine_plate

        if _is_bar(problem):
            return _BAR.refine(problem, factor)
        return dataclasses.replace(problem, target=(refine_plate if problem.on_plate else refine_beam)(problem.target, factor))

    def study(self, problem, stride, progress=None):
        """First contact's scalars, the force history, gauge peaks and histories; the target model's size."""
        from ..workflows.coupled import run_impact

        if _is_bar(problem):
            return _BAR.study(problem, stride, progress)
        model, r = run_impact(problem, energy=False)
        out = {
            "peak_force_N": r.peak_force,
            "time_of_peak_s": r.time_of_peak,
            "contact_duration_s": r.contact_duration,
            "impulse_N_s": r.impulse,
            "contact_force_history_N": r.force[::stride],
        }
        magnitude_and_history(out, r.strain_names, r.strain, stride)
        t = problem.target
        elements = list(t.plate.elements) if problem.on_plate else [t.beam.nx, t.beam.nz]
        return out, {"elements": elements, "time_step_s": problem.solver.time_step, "dofs": int(model.size)}

    def structure_key(self, data):
        return without(data, NOT_STRUCTURE)

    def prepare(self, data, base, runs, outputs=()):
        return SharedModel(data, str(base))

    def run(self, prepared, data, base, outputs=()):
        from ..workflows.coupled import run_impact

        problem = self.problem(data, base)
        if _is_bar(problem):
            return _BAR.run(None, None, base, outputs, problem)
        if not outputs or any(o.startswith("damage.") for o in outputs):
            from ..output.impact import damage_problem

            problem = damage_problem(problem)  # + the pseudo-gauges of the damage indices
        model = prepared.get(problem) if isinstance(prepared, SharedModel) else None
        model, result = run_impact(problem, model)
        return self.summary(problem, result, model)

    def summary(self, problem, result, model=None):
        """The scalars of ``softimpact impact``'s summary.json (:func:`softimpact.output.impact.impact_summary`):
        lists, texts and the resolved case left out, null (not separated) as NaN."""
        from ..output.impact import impact_summary

        def scalars(tree):
            out = {}
            for k, v in tree.items():
                if isinstance(v, dict):
                    out[k] = scalars(v)
                elif v is None:
                    out[k] = float("nan")
                elif isinstance(v, (int, float, np.floating, np.integer)) and not isinstance(v, bool):
                    out[k] = v
            return out

        s = impact_summary(problem, result, model)
        s.pop("case_SI", None)
        return scalars(s)

    def output_keys(self, problem):
        if _is_bar(problem):
            return _BAR.output_keys(problem)
        keys = [
            "peak_force_N",
            "time_of_peak_s",
            "contact_duration_s",
            "impulse_N_s",
            "rebound_velocity_m_s",
            "max_approach_m",
            "max_contact_radius_m",
            "number_of_contacts",
            "total_impulse_N_s",
            "final_impactor_velocity_m_s",
            "impactor_mass_kg",
            "impactor_kinetic_energy_J",
            "energy_balance_relative",
            "newton_iterations",
        ]
        for g in problem.target.gauges:
            keys += [f"gauges.{g.name}.{f}" for f in GAUGE_FIELDS] + [f"gauges.{g.name}.peak_abs_strain"]
        if problem.on_plate:
            keys += ["target.peak_deflection_at_impact_m", "target.time_of_peak_deflection_s"]
        from ..output.impact import damage_keys

        return tuple(keys) + damage_keys(problem)

    def expand(self, data, key):
        pass
