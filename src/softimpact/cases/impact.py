"""Impact cases (``softimpact impact``): a rigid impactor on a beam or plate target through a contact law (coupled)."""

from __future__ import annotations

import dataclasses
import hashlib
from pathlib import Path

import numpy as np

from ._common import GAUGE_FIELDS, magnitude_and_history, without

__all__ = ["ImpactKind", "SharedModel", "bar_target", "KERNEL_MIN_RUNS", "with_identified_envelope"]

# Keys of an impact case that leave the target's model (mesh, step, factorisation) unchanged: the impactor's velocity
# (or a drop weight's energy), threat (a hailstone's size, a bird's mass), mass, material and diameter and the contact
# law. The diameter sets only the contact's reach (the loadable nodes, per run): a group's kernels load the widest of
# its runs' (a wider run than the kernels were built for builds them again, SharedModel.kernels).
NOT_STRUCTURE = (
    "impactor.velocity",
    "impactor.energy",
    "impactor.threat",
    "impactor.mass",
    "impactor.material",
    "impactor.diameter",
    "contact",
    "title",
    "units",
)
# The sweep outputs of a metal plate's damage (workflows.damage.metal_damage): a plastic plate's dent and plastic
# state at rest, an elastic one's stresses against yield; and of cohesive interfaces (delamination_growth, the C-scan's
# projected area). Scalars only: a sweep keeps floats (yield_onset_time_s is None when it never yields).
METAL_PLASTIC_KEYS = tuple(
    f"damage.{k}" for k in ("dent_depth_m", "permanent_deflection_max_m", "plastic_work_J", "plastic_zone_area_m2", "max_equivalent_plastic_strain")
)
METAL_ELASTIC_KEYS = ("damage.max_von_mises_Pa", "damage.max_von_mises_over_yield")
COHESIVE_KEYS = tuple(
    f"damage.{k}"
    for k in (
        "delaminated_area_m2",
        "projected_delamination_area_m2",
        "process_zone_area_max_m2",
        "process_zone_area_final_m2",
        "fracture_energy_dissipated_J",
        "cohesive_stored_energy_J",
    )
)


# A group of at least this many runs builds the target's contact kernels once (about 1.5-4 direct
# runs' cost) and runs each impact on them in milliseconds; a smaller group steps each run directly.
KERNEL_MIN_RUNS = 4
# Outputs that need the structure's own state (its energies): a group asking for one steps directly.
NEEDS_STRUCTURE = ("energy_balance_relative", "energy_error_after_first_contact_relative")
# The ratios of every coupled run's validity (output.impact.impact_validity): sweep outputs validity.<ratio>.
VALIDITY_RATIOS = ("approach_over_diameter", "contact_radius_over_projectile_radius", "deflection_over_thickness")


def _wants_damage(outputs) -> bool:
    """Whether a run computes the damage indices (its target's ``"damage"`` output group): no outputs named (all
    of them), a ``damage.*`` one or the maximum-strain index of the validity envelope."""
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
            if _other_kind(problem) is None and problem.target.coupled_stepper is None:  # kernels: a linear target's only
                # the kernels' outputs: the model's, with the damage group when the runs want it
                self.kernels(problem, self.data)
        except InputError:  # the runs meet it again and record it, one by one
            return

    def widen(self, cases) -> None:
        """Note the impactor diameters of the group's ``cases`` (case dicts; unreadable ones are left to
        their runs), so the kernels are built once for the widest contact."""
        from .. import units
        from ..errors import InputError

        for data in cases:
            impactor = data.get("impactor") if isinstance(data.get("impactor"), dict) else {}
            threat = impactor.get("threat") if isinstance(impactor.get("threat"), dict) else {}
            d = impactor.get("diameter", threat.get("hail"))  # a hailstone's diameter (a bird's is its mass's: left to its run)
            try:
                self.widest = max(self.widest, units.parse(d, "length", "impactor.diameter"))
            except (InputError, TypeError, ValueError):
                continue

    def get(self, problem):
        """The group's model (with the target's ``"damage"`` output group when the runs compute damage), built once."""
        if self.model is None:
            self.model = problem.model(damage=self.damage)
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


def _nonlinearity(target) -> str:
    """What makes a target nonlinear, in words (naming its case key)."""
    if target.kinematics == "von-karman":
        return f'{target.laminate_key.split(".")[0]}.kinematics = "von-karman"'
    if target.coupled_stepper == "cohesive":
        return "cohesive interfaces"
    return "an elastic-plastic metal section"


PENALTY_RATIO = 1e4  # a cohesive penalty K above this many times the plies' E3/t adds no accuracy, only ill-conditioning


def _penalty_cause(target) -> str:
    """Words naming the cohesive interfaces' penalty as the likely cause of a failed step when it is more than
    :data:`PENALTY_RATIO` times the thinnest sublaminate's through-thickness stiffness E3/t: the intact stack's extra
    compliance is of order E3/(t·K), 1e-4 there (the built-in case's 1e15 N/m³ is about 40 times E3/t and agrees
    with 1e17 to 1e-3 in peak force), so a stiffer penalty changes nothing but the step's conditioning. '' otherwise."""
    law, stack = target.law, target.plate.stack
    bounds = (0, *target.splits, len(stack.angles))
    thinnest = min(b - a for a, b in zip(bounds[:-1], bounds[1:])) * stack.ply.thickness
    stiffness = stack.ply.E3 / thinnest
    ratio = law.K / stiffness
    if ratio <= PENALTY_RATIO:
        return ""
    return (
        f"the interfaces' penalty (damage.penalty = {law.K:.3g} N/m^3) is {ratio:.3g} times the thinnest sublaminate's through-thickness "
        f"stiffness E3/t ({stiffness:.3g} N/m^3): that stiff a penalty adds no accuracy, only ill-conditioning; give damage.penalty "
        f"of 10 to {PENALTY_RATIO:g} times E3/t (before refining the mesh or the step)"
    )


def require_crossing_steps(velocity: float, diameter: float, time_step: float) -> None:
    """Refuse a coupled run whose impactor crosses its own diameter in fewer than
    :data:`softimpact.fem.linear.MIN_STEPS_PER_RISE` steps: d/V bounds what any contact can last while the impactor
    crushes or flows (a crushing ice sphere is consumed in about d/V; an elastic one's approach stays far below d), so a
    coarser step can carry the sphere through its whole contact between two steps (an ice sphere at 2000 m/s stepped at
    20 us: peak force 0, as if it had passed through the plate). InputError naming solver.time_step with the step that
    resolves it. The rise of a law's force has its own check (:func:`softimpact.guards.require_contact_steps`)."""
    import math

    from ..errors import InputError
    from ..fem.linear import MIN_STEPS_PER_RISE

    crossing = diameter / velocity
    if crossing < MIN_STEPS_PER_RISE * time_step:
        advised = crossing / MIN_STEPS_PER_RISE * 1e6
        scale = 10.0 ** (2 - math.floor(math.log10(advised)))
        raise InputError(
            f"a time step of {time_step * 1e6:.4g} us cannot follow the impactor: at {velocity:.4g} m/s it crosses its own diameter "
            f"({diameter * 1e3:.4g} mm, the longest a crushing contact can last) in {crossing * 1e6:.4g} us, fewer than {MIN_STEPS_PER_RISE} steps; "
            f"give solver.time_step = {math.floor(advised * scale) / scale:g} us or less",  # rounded down: the advice taken as written passes
            "time_step",
        )


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


def _other_kind(problem):
    """The kind that runs ``problem`` when it is not an impact problem (an impact case on a bar target reads
    as that bar case, :func:`bar_target`), None for an impact problem."""
    from . import kind_for

    kind = kind_for(problem)
    return None if isinstance(kind, ImpactKind) else kind


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
        from ..input.sweep_spec import case_files

        if bar is not None:
            return bar[0], case_files(path)
        problem, files = load_impact_case(case)
        return problem, case_files(path, files[1:])  # the case, its target case, a law.json, and what those name

    def problem(self, data, base):
        from ..input.impact_case import impact_problem

        bar = bar_target(data, Path(base))
        return bar[0] if bar is not None else impact_problem(data, Path(base))[0]

    def problem_class(self):
        from ..workflows.coupled import ImpactProblem

        return ImpactProblem

    def check(self, problem):
        """The target's checks (mesh, resources) and the coupled run's time step against its contact force's rise
        (:func:`softimpact.guards.require_contact_steps`: the beam and plate commands' floor of steps per rise)."""
        from ..guards import require_contact_steps

        other = _other_kind(problem)
        if other:
            return other.check(problem)
        problem.target.check()
        i = problem.impactor
        require_crossing_steps(i.velocity, i.diameter, problem.solver.time_step)
        require_contact_steps(problem.law, i.mass, i.velocity, i.diameter, problem.solver.time_step)

    def refine(self, problem, factor):
        """The target refined (mesh and step, :meth:`~softimpact.models.protocols.Target.refine`); impactor and law unchanged."""
        other = _other_kind(problem)
        return other.refine(problem, factor) if other else dataclasses.replace(problem, target=problem.target.refine(factor))

    def study(self, problem, stride, progress=None):
        """First contact's scalars, the force history, gauge peaks and histories; the target model's size."""
        other = _other_kind(problem)
        if other:
            return other.study(problem, stride, progress)
        run = self.execute(problem, damage=False, energy=False)
        r = run.result
        out = {
            "peak_force_N": r.peak_force,
            "time_of_peak_s": r.time_of_peak,
            "contact_duration_s": r.contact_duration,
            "impulse_N_s": r.impulse,
            "contact_force_history_N": r.force[::stride],
        }
        magnitude_and_history(out, r.strain_names, r.strain, stride)
        return out, {"elements": problem.target.elements, "time_step_s": problem.solver.time_step, "dofs": int(run.model.size)}

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
    ):
        """The coupled run (:func:`softimpact.cases.run.execute`): the target's model (with its ``"damage"`` output
        group when ``damage`` and its laminate allow the indices), the snapshots the figures and fields draw, the run
        (``method``: direct stepping, or kernel runs), the damage indices, the validity and summary.json's content."""
        from ..errors import InputError, SolverFailed
        from ..output.fields import FRAMES, sampled_steps
        from ..output.impact import snapshot_steps
        from ..workflows.coupled import run_impact

        own = problem.target.coupled_stepper  # a nonlinear target's stepper (the one engine's: fem.vk_stepping), None for a linear one
        if own is not None:
            if method == "kernels":
                raise InputError(
                    f"contact kernels need a linear target: this {problem.target.laminate_key.split('.')[0]} is nonlinear ({_nonlinearity(problem.target)}) "
                    "and runs stepped directly (a sweep of it steps every run; use a linear elastic target for kernel runs)"
                )
            method = own
        damage = damage and problem.target.has_damage_outputs
        steps = problem.solver.steps
        shown = snapshot_steps(steps) if figures and problem.target.deflected_shapes else ()
        kept = sampled_steps(steps, FRAMES if frames is None else frames) if fields else ()
        snaps = np.union1d(shown, kept).astype(int) if fields else shown
        model = model or problem.model(damage=damage)
        if progress is not None:
            progress(0)
        try:
            model, result = run_impact(problem, model, energy, stop_after, snaps, method=method, kernels=kernels, progress=progress)
        except SolverFailed as exc:  # the stepper knows its residual, not the case: say what in the case may cause it
            cause = _penalty_cause(problem.target) if own == "cohesive" else ""
            if not cause:
                raise
            raise SolverFailed(f"{exc}; {cause}") from None
        if progress is not None:
            progress(steps)
        return self._finish(problem, result, model, damage, shown, kept)

    def _finish(self, problem, result, model, damage, shown=(), kept=()):
        """The :class:`~softimpact.cases.run.Run` of a coupled ``result``: its output groups split (the gauges
        from the damage strains), the damage indices (with ``damage``), the validity, summary.json's content."""
        from ..fem.contact import group_outputs
        from ..models.metals import Metal
        from ..output.impact import impact_summary
        from ..workflows.damage import coupled_damage, damage_refusal, delamination_growth, delamination_shapes, metal_damage
        from .run import Run, impact_validity

        target = problem.target
        result = group_outputs(result, model.contact_groups())
        if isinstance(target.material, Metal) and target.stack is None:  # a metal plate: its dent, or its stresses against yield
            dmg = metal_damage(target, result, model.rest() if target.plastic else None) if (damage or target.plastic) else None
        else:
            dmg = coupled_damage(target, result, impactor_mass=problem.impactor.mass).summary() if damage else None
            dmg = delamination_growth(dmg, result)  # cohesive interfaces: the delaminated area, in the verdict
            if target.coupled_stepper == "cohesive":
                dmg = delamination_shapes(dmg, model.cscan())
        note = None if dmg is not None else damage_refusal(target, "target.case: ")
        validity = impact_validity(problem, result, dmg) + _criterion_validity(dmg)
        summary = impact_summary(problem, result, validity, dmg, note, target.summary_extras(model, result))
        return Run(result, model, summary, validity, problem, shown, kept)

    def structure_key(self, data):
        return without(data, NOT_STRUCTURE)

    def prepare(self, data, base, runs, outputs=(), cases=()):
        """The group's shared model; contact kernels when the group has :data:`KERNEL_MIN_RUNS` runs or
        more and none of ``outputs`` needs the structure's energies (kernel runs have none), built here
        for the widest impactor of the group's ``cases`` when they are given (else on first use)."""
        kernels = runs >= KERNEL_MIN_RUNS and not any(o in NEEDS_STRUCTURE for o in outputs)
        shared = SharedModel(data, str(base), kernels, damage=_wants_damage(outputs))
        if cases:
            shared.widen(cases)
            shared.build()
        return shared

    def run(self, prepared, data, base, outputs=()):
        problem = self.problem(data, base)
        other = _other_kind(problem)
        if other:
            return other.run(None, data, base, outputs, problem)
        contact = data.get("contact") if isinstance(data.get("contact"), dict) else {}
        law_file = Path(base) / contact["law_file"] if isinstance(contact.get("law_file"), str) else None
        damage = _wants_damage(outputs)
        shared = isinstance(prepared, SharedModel)
        model = prepared.get(problem) if shared else None
        if shared and prepared.use_kernels and problem.target.coupled_stepper is None:  # a nonlinear target steps every run
            run = self.execute(problem, damage=damage, model=model, energy=False, method="kernels", kernels=prepared.kernels(problem, data))
        else:
            run = self.execute(problem, damage=damage, model=model, method="direct")
        return _scalars(with_identified_envelope(run, law_file))

    def summary(self, problem, result, model=None):
        """The scalars of ``softimpact impact``'s summary.json (:meth:`execute`'s) of a coupled ``result`` of
        ``model``: lists, texts and the resolved case left out, null (not separated) as NaN; ``validity_flags``:
        the names of the run's validity flags (as the command's)."""
        damage = len(model.contact_groups().get("damage", ())) > 0  # the model ran with the damage group
        return _scalars(self._finish(problem, result, model, damage))

    def refusal(self, problem, study):
        """An impact on a bar target: the bar kind's answer; every impact on a beam or plate sweeps and converges
        (the target's own kinematics and interfaces step each run)."""
        other = _other_kind(problem)
        return other.refusal(problem, study) if other else None

    def damage_refusal(self, problem):
        """Why an impact has no damage outputs (its target's laminate), None when it has them."""
        from ..workflows.damage import damage_refusal

        other = _other_kind(problem)
        return other.damage_refusal(problem) if other else damage_refusal(problem.target, "target.case: ")

    def output_keys(self, problem):
        other = _other_kind(problem)
        if other:
            return other.output_keys(problem)
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
        keys += list(problem.target.summary_keys)
        from ..output.impact import damage_keys

        # the envelopes' ratios (summary.json's validity, models.validity): a sweep may keep them per run
        keys += [f"validity.{k}" for k in VALIDITY_RATIOS]
        target = problem.target
        from ..models.metals import Metal

        if isinstance(target.material, Metal) and target.stack is None:  # a metal plate: its dent (plastic) or its stresses (elastic), _finish
            return tuple(keys) + (METAL_PLASTIC_KEYS if target.plastic else METAL_ELASTIC_KEYS)
        damage = damage_keys(target.damage_points()) if target.has_damage_outputs else ()
        if target.coupled_stepper == "cohesive":  # the delaminated areas of its interfaces (workflows.damage.delamination_growth, shapes)
            damage += COHESIVE_KEYS
        return tuple(keys) + damage + (("validity.max_strain_index",) if target.has_damage_outputs else ())

    def expand(self, data, key):
        pass


def with_identified_envelope(run, law_file):
    """``run`` (a coupled :class:`~softimpact.cases.run.Run`) with the geometric envelope of its identified law: the
    approach over the diameter its bar tests reached (law.json ``law_file``'s ``identified_on``,
    :func:`softimpact.models.validity.identified_contact_validity`) in its validity and summary.json's; unchanged for
    another law, no file, or a law.json that does not record it. The law object a run steps holds no record of what
    it was identified on: the file does, and every caller that read one passes it here (the impact command, the API,
    a sweep's runs; the maps check it with their law)."""
    import dataclasses

    from ..formats.law_json import read_law
    from ..models.validity import identified_contact_validity

    if law_file is None or run.problem.law_name != "identified" or not hasattr(run.result, "approach"):
        return run
    r = run.result
    extra = identified_contact_validity(
        read_law(law_file).identified_on, float(np.max(r.approach)), run.problem.impactor.diameter, float(np.max(r.contact_radius))
    )
    if not extra.values and not extra.flags:
        return run
    validity = run.warnings + extra
    return dataclasses.replace(run, warnings=validity, summary={**run.summary, "validity": validity.summary()} if run.summary else run.summary)


def _criterion_validity(damage: dict | None):
    """What the coupled run's own checks (:func:`softimpact.cases.run.impact_validity`) leave out: with the damage block,
    a delamination criterion applied outside the response regime it was derived for
    (:func:`softimpact.models.delamination.criterion_validity`)."""
    from ..models.delamination import criterion_validity
    from ..models.validity import Validity

    v = Validity({})
    if damage is not None and damage.get("regime"):
        v += criterion_validity(damage["regime"], ("olsson", "delamination"))
    return v


def _scalars(run) -> dict:
    """The sweep's scalars of an impact :class:`~softimpact.cases.run.Run`: its summary.json's numbers (lists, texts
    and the resolved case left out, null as NaN) and ``validity_flags``, the names of its validity flags."""

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

    s = dict(run.summary)
    s.pop("case_SI", None)
    return {**scalars(s), "validity_flags": run.warnings.names}
