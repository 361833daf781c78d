"""Impact cases (``softimpact impact``): a rigid impactor on a beam or plate target through a contact law (coupled)."""

from __future__ import annotations

import dataclasses
import hashlib
from pathlib import Path

import numpy as np

from ._common import GAUGE_FIELDS, magnitude_and_history, without
from .bar import BarKind

__all__ = ["ImpactKind", "SharedModel", "bar_target", "KERNEL_MIN_RUNS"]

_BAR = BarKind()  # a bar target runs as the bar case with the impact case's impactor and law

# Keys of an impact case that leave the target's model (mesh, step, factorisation) unchanged: the
# impactor's velocity, mass, material and diameter and the contact law. The diameter sets only the
# contact's reach (the loadable nodes, per run): a group's kernels load the widest of its runs'.
NOT_STRUCTURE = ("impactor.velocity", "impactor.mass", "impactor.material", "impactor.diameter", "contact", "title", "units")


# A group of at least this many runs builds the target's contact kernels once (about 1.5-4 direct
# runs' cost) and runs each impact on them in milliseconds; a smaller group steps each run directly.
KERNEL_MIN_RUNS = 4
# Outputs that need the structure's own state (its energies): a group asking for one steps directly.
NEEDS_STRUCTURE = ("energy_balance_relative", "energy_error_after_first_contact_relative")
# The ratios of every coupled run's validity (output.impact.impact_validity): sweep outputs validity.<ratio>.
VALIDITY_RATIOS = ("approach_over_diameter", "contact_radius_over_projectile_radius", "deflection_over_thickness")


def _wants_damage(outputs) -> bool:
    """Whether a run must carry the damage indices' pseudo-gauges: no outputs named (all of them), a ``damage.*`` one
    or the maximum-strain index of the validity envelope."""
    return not outputs or any(o.startswith("damage.") or o == "validity.max_strain_index" for o in outputs)


class SharedModel:
    """The target's model shared by the runs of a sweep group, built on first use where the runs
    are (in a Dask worker, or in the plain loop) and never pickled: a factorisation does not travel
    (the kernels do: their spectra and the patch's tables, :class:`softimpact.fem.kernels.ContactKernels`).

    With ``kernels``, also the target's contact kernels (:func:`softimpact.workflows.coupled.impact_kernels`),
    built on first use and kept by a hash of the structure (the case without the keys that leave it
    unchanged: mesh, laminate, supports, impact point, impactor diameter, step and duration stay in it),
    so each run of the group is a kernel run."""

    def __init__(self, data: dict, base: str, kernels: bool = False, damage: bool = True):
        self.data, self.base, self.model, self.use_kernels, self.damage = data, base, None, kernels, damage
        self.widest = 0.0  # the largest impactor diameter [m] of the group's runs: the kernels' reach
        self._kernels: dict[str, object] = {}

    def __getstate__(self):
        # the kernels travel (their spectra, not the factorisation); the model is rebuilt where the runs are
        return {
            "data": self.data,
            "base": self.base,
            "model": None,
            "use_kernels": self.use_kernels,
            "damage": self.damage,
            "widest": self.widest,
            "_kernels": self._kernels,
        }

    def build(self) -> None:
        """Build the kernels now (where the group is prepared, once), so that they travel to the workers
        instead of each building its own. A base case that does not parse leaves it to the runs."""
        from ..errors import InputError

        if not self.use_kernels:
            return
        try:
            problem = ImpactKind().problem(self.data, self.base)
            if not _is_bar(problem):
                if self.damage:  # the runs carry the damage indices' pseudo-gauges: so must the kernels' outputs
                    from ..studies.damage import damage_problem

                    problem = damage_problem(problem)
                self.kernels(problem, self.data)
        except InputError:  # the runs meet it again and record it, one by one
            return

    def widen(self, cases) -> None:
        """Note the impactor diameters of the group's ``cases`` (case dicts; unreadable ones are left to
        their runs), so the kernels are built once for the widest contact."""
        from .. import units
        from ..errors import InputError

        for data in cases:
            d = data.get("impactor", {}).get("diameter") if isinstance(data.get("impactor"), dict) else None
            try:
                self.widest = max(self.widest, units.parse(d, "length", "impactor.diameter"))
            except (InputError, TypeError, ValueError):
                continue

    def get(self, problem):
        from ..workflows.coupled import impact_model

        if self.model is None:
            self.model = impact_model(problem)
        return self.model

    def kernels(self, problem, data: dict):
        """The contact kernels of ``problem``'s structure (``data``: its case), built once per structure hash."""
        from ..workflows.coupled import impact_kernels

        key = hashlib.sha256(without(data, NOT_STRUCTURE).encode()).hexdigest()
        widest = max(self.widest, problem.impactor.diameter)
        built = self._kernels.get(key)
        if built is None or built[0] < widest:
            self._kernels.clear()  # one structure per group: keep the last only
            wide = dataclasses.replace(problem, impactor=dataclasses.replace(problem.impactor, diameter=widest))
            self._kernels[key] = (widest, impact_kernels(wide, self.get(problem)))
        return self._kernels[key][1]


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
    """Impact cases. Runs that differ only in the impactor's velocity, mass, material or diameter or
    in the contact law form one sweep group, sharing the target's model (mesh, matrices, the factorised
    Newmark step) and, in a group of :data:`KERNEL_MIN_RUNS` runs or more, its contact kernels (built
    once for the widest contact; each run a kernel run, equal to direct stepping to round-off).

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
        """The group's shared model; contact kernels when the group has :data:`KERNEL_MIN_RUNS` runs or
        more and none of ``outputs`` needs the structure's energies (kernel runs have none)."""
        kernels = runs >= KERNEL_MIN_RUNS and not any(o in NEEDS_STRUCTURE for o in outputs)
        return SharedModel(data, str(base), kernels, damage=_wants_damage(outputs))

    def run(self, prepared, data, base, outputs=()):
        from ..workflows.coupled import run_impact

        problem = self.problem(data, base)
        if _is_bar(problem):
            return _BAR.run(None, None, base, outputs, problem)
        if _wants_damage(outputs):
            from ..studies.damage import damage_problem

            problem = damage_problem(problem)  # + the pseudo-gauges of the damage indices (the kernels' outputs too)
        shared = isinstance(prepared, SharedModel)
        model = prepared.get(problem) if shared else None
        if shared and prepared.use_kernels:
            model, result = run_impact(problem, model, energy=False, method="kernels", kernels=prepared.kernels(problem, data))
        else:
            model, result = run_impact(problem, model, method="direct")
        return self.summary(problem, result, model)

    def summary(self, problem, result, model=None):
        """The scalars of ``softimpact impact``'s summary.json (:func:`softimpact.output.impact.impact_summary`):
        lists, texts and the resolved case left out, null (not separated) as NaN; ``validity_flags``: the names of
        the run's validity flags (:func:`softimpact.output.impact.impact_validity`, as the command's)."""
        from ..output.impact import impact_summary, impact_validity
        from ..studies.damage import split_damage

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
        own, run, _ = split_damage(problem, result)  # impact_summary's split: the envelopes of the impact itself
        return {**scalars(s), "validity_flags": impact_validity(own, run, s.get("damage")).names}

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

        # the envelopes' ratios (summary.json's validity, models.validity): a sweep may keep them per run
        keys += [f"validity.{k}" for k in VALIDITY_RATIOS]
        damage = damage_keys(problem)
        return tuple(keys) + damage + (("validity.max_strain_index",) if damage else ())

    def expand(self, data, key):
        pass
