"""Coupled impact: a rigid impactor striking a linear structure through a contact law.

The impactor (mass m, diameter d, velocity V) hits the structure at one point;
the contact force follows from the approach α = x − w by the chosen contact law
(:mod:`softimpact.models.contact_laws`), w being the structure's mid-surface
displacement under the impact point; the force is spread over the contact patch
(cosine distribution of eq 11, half-width from the law's contact radius). The
integration is Newmark on the structure with Newton on the scalar contact
equation each step (:mod:`softimpact.fem.impact`, the one coupled stepper, which
the bar uses too): the coupled step costs one back-substitution, like a
prescribed-force step.

What the solver needs from a structure is a :class:`~softimpact.fem.impact.ContactStructure`;
every structure model gives its own, ``model.contact_structure(point, reach)``
(:class:`~softimpact.models.protocols.StructureModel`), so nothing here branches on
beam or plate.

Time zero is first contact. Every contact interval is found (separation and
re-contact); the scalars of the result are those of the FIRST contact.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from ..errors import ContactOutgrewRoom, InputError, NoContactRoom
from ..fem.impact import ContactInterval, CoupledResult, contact_intervals, coupled_result, simulate_coupled
from ..fem.newmark import SolverSpec
from ..models.materials import Material
from ..models.protocols import StructureModel
from ..models.specimens import Impactor

__all__ = [
    "Impactor",
    "ImpactProblem",
    "ContactInterval",
    "CoupledResult",
    "simulate_coupled",
    "contact_intervals",
    "run_impact",
    "impact_model",
    "impact_kernels",
    "METHODS",
]

# run_impact's ways to step a coupled impact (a von Kármán structure's, full and reduced; sublaminates tied by cohesive interfaces)
METHODS = ("auto", "kernels", "direct", "von-karman", "von-karman-rom", "cohesive")


@dataclass(frozen=True)
class ImpactProblem:
    """A coupled impact case, resolved (SI): the target (its solver and gauges those of the impact run,
    its force history dropped: :meth:`~softimpact.models.protocols.Target.for_impact`), the impactor, its
    material and the contact law."""

    target: object  # a Target (softimpact.models.protocols): a BeamProblem or PlateProblem
    target_case: str
    impactor: Impactor
    impactor_material: Material
    law_name: str
    law: object
    title: str = ""
    threat: object = None  # the bird threat's substitute (models.threats.SubstituteBird), None for any other impactor

    @property
    def solver(self) -> SolverSpec:
        return self.target.solver

    def with_solver(self, solver: SolverSpec) -> ImpactProblem:
        """This problem stepped by ``solver``: its target's (a Target's ``solver`` field), which steps the coupled run."""
        return replace(self, target=replace(self.target, solver=solver))

    @property
    def position(self) -> float | tuple[float, float]:
        """The impact point: x [m] along a beam, (x, y) [m] on a plate."""
        return self.target.load.position

    def model(self, damage: bool = False) -> StructureModel:
        """The target's model for the impact run (:meth:`~softimpact.models.protocols.Target.model`), checked
        for room about the impact point (errors name the target case's load.position); ``damage``: its
        contact structure also outputs the target's ``"damage"`` group."""
        try:
            model = self.target.model(patch_radius=min(self.target.load.contact_radius, self.impactor.diameter), damage=damage)
            model.contact_reach(self.position, self.impactor.diameter)
        except NoContactRoom as exc:
            raise NoContactRoom(f"target.case ({self.target_case}): load.position {tuple(self.position)!r} m: {exc}") from None
        return model


def impact_model(problem: ImpactProblem) -> StructureModel:
    """The target's model for the impact run, without the damage group (:meth:`ImpactProblem.model`)."""
    return problem.model()


def _whole_plate(result: CoupledResult, share: float) -> CoupledResult:
    """A half or quarter plate model (symmetry edges through the impact point) carries ``share`` of
    the force: its energies are ``share`` of the whole plate's, and are scaled back so the balance
    against the impactor closes (the mismatch: the whole plate's work minus F·Δw)."""
    if share == 1.0:
        return result
    E = result.energies
    work = E.work / share
    along_w = E.work - E.surface_mismatch  # Σ F·Δw, the same for part and whole
    energies = replace(E, kinetic=E.kinetic / share, strain=E.strain / share, work=work, surface_mismatch=work - along_w)
    return replace(result, energies=energies)


def impact_kernels(problem: ImpactProblem, model: StructureModel | None = None):
    """The contact kernels (:class:`softimpact.fem.kernels.ContactKernels`) of the problem's target
    struck at its impact point, for its time step and duration: built once (about 1.5–4 direct runs),
    then every coupled run on this structure (another velocity, mass, law, or a diameter up to the
    problem's: its contact disc is among the loadable nodes) costs milliseconds.
    ``model``: the target's model to reuse (its factorised stepper)."""
    from ..fem.kernels import ContactKernels  # (scipy.fft and the marches: imported when kernels are built)

    model = model or impact_model(problem)
    reach = model.contact_reach(problem.position, problem.impactor.diameter)
    structure = model.contact_structure(problem.position, reach)
    solver = problem.solver
    # reach: the widest contact they load; smaller impactors run on them too (run_impact)
    return ContactKernels(structure, solver.time_step, solver.steps, solver.newmark, stepper=model.stepper, reach=reach)


def run_impact(
    problem: ImpactProblem,
    model: StructureModel | None = None,
    energy: bool = True,
    stop_after: float | None = None,
    snapshots=(),
    *,
    method: str = "auto",
    kernels=None,
    engine=None,
    progress=None,
) -> tuple[StructureModel, CoupledResult]:
    """The coupled run of an impact problem on a beam or plate; ``model``: a BeamModel or PlateModel
    of the same structure and step to reuse; ``energy``: keep the energy histories; ``stop_after``:
    end the run this long [s] after the impactor has left for good; ``snapshots``: step indices at
    which to keep the structure's displacement.

    ``method``: "direct" steps the whole structure with the impactor (:func:`simulate_coupled`, the
    reference; energies and snapshots need it); "kernels" steps only the scalar contact equation
    against the structure's impulse responses (``kernels`` from :func:`impact_kernels`, built here if
    None; equal to direct stepping to round-off, the structure's energies NaN); "auto": the kernels
    when they are given and neither energies nor snapshots are asked for, else direct stepping (a
    single run costs less stepped directly than building kernels). ``engine``: a stepping engine built once for
    ``method`` and reused (the plate's :class:`~softimpact.fem.vk_rom.PlateVKROM` for "von-karman-rom",
    :func:`softimpact.fem.vk_rom.reduced_plate`); None: the model's stepper (the reduced plate then built for this run).
    ``progress``: a callable told the step reached every few steps (a long run's progress bar), or None.

    Loadable nodes reach one impactor diameter from the impact point: a Hertz radius
    sqrt(R·α) and a flattened sphere's sqrt(d·α) stay within it while α < d (on a plate,
    cut by the edges: ``model.contact_reach``).
    """
    from ..fem.steppers import STEPPERS  # (the kernels' module: imported when a run needs it)

    if method not in METHODS:
        raise InputError(f"method must be one of {', '.join(METHODS)}, got {method!r}")
    if method == "kernels" and (energy or len(snapshots)):
        raise InputError("method 'kernels' gives no structure energies or snapshots: pass energy=False and no snapshots, or use method 'direct'")
    use_kernels = method == "kernels" or (method == "auto" and kernels is not None and not energy and not len(snapshots))
    model = model or impact_model(problem)
    solver, imp = problem.solver, problem.impactor
    reach = model.contact_reach(problem.position, imp.diameter)
    if use_kernels:
        kernels = kernels or impact_kernels(problem, model)
        if kernels.steps != solver.steps or not math.isclose(kernels.dt, solver.time_step, rel_tol=1e-12):
            raise InputError(f"kernels: built for {kernels.steps} steps of {kernels.dt:.6g} s, the problem runs {solver.steps} of {solver.time_step:.6g} s")
        # a smaller impactor: its own contact disc, kept with the kernels for the next run of that diameter
        structure = kernels.structure_for(reach, lambda r: model.contact_structure(problem.position, r))
    else:
        structure = model.contact_structure(problem.position, reach)
    stepper = STEPPERS["kernels" if use_kernels else "direct" if method in ("auto", "direct") else method](
        structure,
        problem.law,
        imp.mass,
        imp.velocity,
        solver.time_step,
        solver.steps,
        solver.newmark,
        engine=kernels if use_kernels else model.stepper if engine is None else engine,
        stop_after=stop_after,
        energy=energy,
        snapshots=snapshots,
    )
    stepper.progress = progress
    try:
        history = stepper.run()
    except ContactOutgrewRoom as exc:
        raise ContactOutgrewRoom(f"{exc}: the contact outgrew the room about the impact point (target.case: load.position)") from None
    result = coupled_result(history, imp, tuple(structure.output_names))
    if structure.patch is not None:  # a plate's contact disc: a half or quarter model carries its share
        result = _whole_plate(result, structure.patch.patch.share)
    return model, result
