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

from dataclasses import dataclass, replace

from ..errors import InputError
from ..fem.impact import ContactInterval, CoupledResult, contact_intervals, simulate_coupled
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
]


@dataclass(frozen=True)
class ImpactProblem:
    """A coupled impact case, resolved (SI): the target beam or plate (its solver and gauges those
    of the impact run, its force history dropped), the impactor, its material and the contact law."""

    target: object  # a BeamProblem or PlateProblem: anything with load, solver, gauges and model(patch_radius)
    target_case: str
    impactor: Impactor
    impactor_material: Material
    law_name: str
    law: object
    title: str = ""
    units: str = "in-lbf-s"

    @property
    def solver(self) -> SolverSpec:
        return self.target.solver

    @property
    def position(self) -> float | tuple[float, float]:
        """The impact point: x [m] along a beam, (x, y) [m] on a plate."""
        return self.target.load.position

    @property
    def on_plate(self) -> bool:
        return hasattr(self.target, "plate")


def impact_model(problem: ImpactProblem) -> StructureModel:
    """The target's model for the impact run (:meth:`BeamProblem.model`, :meth:`PlateProblem.model`),
    checked for room about the impact point (errors name the target case's load.position)."""
    try:
        model = problem.target.model(patch_radius=min(problem.target.load.contact_radius, problem.impactor.diameter))
        model.contact_reach(problem.position, problem.impactor.diameter)
    except InputError as exc:
        if "patch" not in str(exc) and "contact disc" not in str(exc):
            raise
        raise InputError(f"target.case ({problem.target_case}): load.position {tuple(problem.position)!r} m: {exc}") from None
    return model


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


def run_impact(
    problem: ImpactProblem, model: StructureModel | None = None, energy: bool = True, stop_after: float | None = None, snapshots=()
) -> tuple[StructureModel, CoupledResult]:
    """The coupled run of an impact problem on a beam or plate; ``model``: a BeamModel or PlateModel
    of the same structure and step to reuse; ``energy``: keep the energy histories; ``stop_after``:
    end the run this long [s] after the impactor has left for good; ``snapshots``: step indices at
    which to keep the structure's displacement.

    Loadable nodes reach one impactor diameter from the impact point: a Hertz radius
    sqrt(R·α) and a flattened sphere's sqrt(d·α) stay within it while α < d (on a plate,
    cut by the edges: ``model.contact_reach``).
    """
    model = model or impact_model(problem)
    structure = model.contact_structure(problem.position, model.contact_reach(problem.position, problem.impactor.diameter))
    try:
        result = simulate_coupled(structure, problem.law, problem.impactor, problem.solver, energy, model.stepper, stop_after, snapshots)
    except InputError as exc:
        if "runs past" not in str(exc):
            raise
        raise InputError(f"{exc}: the contact outgrew the room about the impact point (target.case: load.position)") from None
    if structure.patch is not None:  # a plate's contact disc: a half or quarter model carries its share
        result = _whole_plate(result, structure.patch.patch.share)
    return model, result
