"""Impact cases (``softimpact impact``): a rigid impactor on a beam or plate target through a contact law (coupled)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from ._common import GAUGE_FIELDS, magnitude_and_history, without

__all__ = ["ImpactKind", "SharedModel"]

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


class ImpactKind:
    """Impact cases. A coupled run is nonlinear in the velocity, so sweep runs share only the
    target's model (mesh, matrices, the factorised Newmark step): runs that differ only in the
    impactor's velocity, mass or material or in the contact law form one group."""

    name = "impact"
    table = "target"

    def detect(self, data):
        return "target" in data

    def load(self, case, history=None):
        from ..errors import InputError
        from ..input.impact_case import load_impact_case

        if history is not None:
            raise InputError("--history: an impact case has no table of histories (its force comes from the contact)", "history")
        return load_impact_case(case)

    def problem(self, data, base):
        from ..input.impact_case import impact_problem

        return impact_problem(data, Path(base))[0]

    def check(self, problem):
        from ..workflows.beam_impact import check_problem as check_beam
        from ..workflows.plate_impact import check_problem as check_plate

        (check_plate if problem.on_plate else check_beam)(problem.target)

    def refine(self, problem, factor):
        """The target refined (mesh and step; see :mod:`softimpact.workflows.refinement`); impactor and law unchanged."""
        from ..workflows.refinement import refine_beam, refine_plate

        return dataclasses.replace(problem, target=(refine_plate if problem.on_plate else refine_beam)(problem.target, factor))

    def study(self, problem, stride, progress=None):
        """First contact's scalars, the force history, gauge peaks and histories; the target model's size."""
        from ..workflows.coupled import run_impact

        model, r = run_impact(problem, energy=False)
        out = {
            "peak_force_N": r.peak_force,
            "time_of_peak_s": r.time_of_peak,
            "contact_duration_s": r.contact_duration,
            "impulse_N_s": r.impulse,
            "contact_force_history_N": r.contact_force[::stride],
        }
        magnitude_and_history(out, r.gauge_names, r.gauge_strain, stride)
        t = problem.target
        elements = list(t.plate.elements) if problem.on_plate else [t.beam.nx, t.beam.nz]
        dofs = model.fe.n if problem.on_plate else model.plane.n
        return out, {"elements": elements, "time_step_s": problem.solver.time_step, "dofs": int(dofs)}

    def structure_key(self, data):
        return without(data, NOT_STRUCTURE)

    def prepare(self, data, base, runs, outputs=()):
        return SharedModel(data, str(base))

    def run(self, prepared, data, base, outputs=()):
        from ..workflows.coupled import run_impact

        problem = self.problem(data, base)
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
        return tuple(keys)

    def expand(self, data, key):
        pass
