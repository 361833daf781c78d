"""Coupled impact: a rigid impactor striking a linear structure through a contact law.

The impactor (mass m, diameter d, velocity V) hits the structure at one point;
the contact force follows from the approach α = x − w by the chosen contact law
(:mod:`softimpact.models.contact_laws`), w being the structure's mid-surface
displacement under the impact point; the force is spread over the contact patch
(cosine distribution of eq 11, half-width from the law's contact radius). The
integration is Newmark on the structure with Newton on the scalar contact
equation each step (:mod:`softimpact.fem.impact`): the coupled step costs one
back-substitution, like a prescribed-force step.

What the solver needs from a structure is a :class:`~softimpact.fem.impact.ContactStructure`
(M, K, optional C, the loadable surface nodes and their DOFs, the mid-surface
row, output rows); the app layer builds it from a beam or plate model.

Time zero is first contact. Every contact interval is found (separation and
re-contact); the scalars of the result are those of the FIRST contact.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..errors import InputError
from ..fem.contact import beam_contact_structure, plate_structure
from ..fem.impact import ContactStructure, ImpactHistory, integrate_impact
from ..fem.newmark import NewmarkStepper, SolverSpec
from ..models.materials import Material

# TEMPORARY (step 1 of the move): a workflow importing two others; the models will expose their contact structure
from .beam_impact import BeamModel, BeamProblem
from .plate_impact import PlateModel, PlateProblem

__all__ = [
    "Impactor",
    "ImpactProblem",
    "ContactInterval",
    "CoupledEnergies",
    "CoupledResult",
    "simulate_coupled",
    "contact_intervals",
    "run_impact",
    "impact_model",
    "plate_reach",
]


@dataclass(frozen=True)
class Impactor:
    """A rigid impactor: mass [kg], diameter [m], velocity [m/s] toward the structure."""

    mass: float
    diameter: float
    velocity: float

    def __post_init__(self):
        for name in ("mass", "diameter", "velocity"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise InputError(f"impactor.{name} must be positive, got {v!r}")

    @property
    def momentum(self) -> float:
        return self.mass * self.velocity

    @property
    def kinetic_energy(self) -> float:
        return 0.5 * self.mass * self.velocity**2


@dataclass(frozen=True)
class ImpactProblem:
    """A coupled impact case, resolved (SI): the target beam or plate (its solver and gauges those
    of the impact run, its force history dropped), the impactor, its material and the contact law."""

    target: BeamProblem | PlateProblem
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
        return isinstance(self.target, PlateProblem)


@dataclass(frozen=True)
class ContactInterval:
    """One contact: start and end [s] (end nan if still in contact at the end of the run),
    peak force [N], its time [s], impulse [N·s] over the interval."""

    start: float
    end: float
    peak_force: float
    time_of_peak: float
    impulse: float

    @property
    def duration(self) -> float:
        return self.end - self.start


@dataclass(frozen=True)
class CoupledEnergies:
    """Energy histories [J], shape (n,).

    ``balance_error`` = impactor KE + structure KE + strain energy + contact work
    − initial KE − surface mismatch: zero to round-off for average acceleration.
    """

    impactor_kinetic: np.ndarray
    structure_kinetic: np.ndarray
    structure_strain: np.ndarray
    structure_work: np.ndarray
    contact_work: np.ndarray  # ∫F dα: stored (contact_energy) + lost
    contact_energy: np.ndarray  # recoverable part
    surface_mismatch: np.ndarray  # work of F on the top-surface nodes minus on the mid-surface

    @property
    def contact_loss(self) -> np.ndarray:
        return self.contact_work - self.contact_energy

    @property
    def total(self) -> np.ndarray:
        """Impactor KE + structure KE + strain energy + contact work."""
        return self.impactor_kinetic + self.structure_kinetic + self.structure_strain + self.contact_work


@dataclass(frozen=True)
class CoupledResult:
    """Histories (time on the last axis) and first-contact scalars; SI, compression +."""

    impactor: Impactor
    time: np.ndarray
    contact_force: np.ndarray
    impactor_velocity: np.ndarray  # positive toward the structure
    impactor_displacement: np.ndarray
    approach: np.ndarray
    approach_rate: np.ndarray
    contact_radius: np.ndarray
    target_displacement: np.ndarray  # mid-surface, along the impact direction
    gauge_strain: np.ndarray  # (n_outputs, n)
    gauge_names: tuple[str, ...]
    energies: CoupledEnergies
    contacts: tuple[ContactInterval, ...]
    peak_force: float  # first contact
    time_of_peak: float
    contact_duration: float  # first contact; nan if not separated within the run
    impulse: float  # first contact, N·s
    rebound_velocity: float  # after the first contact, + toward the structure (− bounced back); nan if not separated
    final_velocity: float  # impactor velocity at the end of the run
    newton_iterations: int
    solves: int
    displacement: np.ndarray | None = None  # (n_dofs, n_kept) snapshots of the structure, if asked for
    kept: np.ndarray | None = None  # their step indices

    @property
    def total_impulse(self) -> float:
        """∫F dt over the run (trapezoid, the rule of the integration) [N·s]."""
        return float(np.sum(0.5 * (self.contact_force[1:] + self.contact_force[:-1])) * (self.time[1] - self.time[0]))


def _peak(t, y, k):
    """Peak of sampled y near index k refined by the parabola through three samples."""
    if k == 0 or k == len(y) - 1:
        return float(y[k]), float(t[k])
    y0, y1, y2 = y[k - 1], y[k], y[k + 1]
    den = y0 - 2.0 * y1 + y2
    if den >= 0:
        return float(y1), float(t[k])
    s = 0.5 * (y0 - y2) / den
    return float(y1 - 0.25 * (y0 - y2) * s), float(t[k] + s * (t[1] - t[0]))


def contact_intervals(t: np.ndarray, F: np.ndarray, alpha: np.ndarray) -> tuple[ContactInterval, ...]:
    """Intervals with F > 0. Ends are interpolated on α's zero crossing when α leaves
    through zero within the step, else on F's (laws clipped at F = 0, e.g. Hunt–Crossley)."""
    on = F > 0.0
    on[0] = True  # first contact at t = 0 by definition
    dt = t[1] - t[0]
    starts = [0] + list(np.flatnonzero(~on[:-1] & on[1:]) + 1)
    ends = list(np.flatnonzero(on[:-1] & ~on[1:]))
    out = []
    for k0 in starts:
        k1 = next((e for e in ends if e >= k0), None)
        if k0 == 0:
            t0 = 0.0
        else:
            a, b = alpha[k0 - 1], alpha[k0]
            t0 = t[k0 - 1] + dt * (-a / (b - a)) if a <= 0.0 < b else t[k0 - 1] + 0.5 * dt
        if k1 is None:
            t1, seg = math.nan, slice(k0, len(t))
        else:
            a, b = alpha[k1], alpha[k1 + 1]
            if a > 0.0 >= b:
                t1 = t[k1] + dt * a / (a - b)
            else:
                t1 = t[k1] + dt * F[k1] / (F[k1] - F[k1 + 1])
            seg = slice(max(k0 - 1, 0), k1 + 2)
        Fs, ts = F[seg], t[seg]
        pk, tp = _peak(ts, Fs, int(np.argmax(Fs)))
        imp = float(np.sum(0.5 * (Fs[1:] + Fs[:-1])) * dt)
        out.append(ContactInterval(t0, t1, pk, tp, imp))
    return tuple(out)


def simulate_coupled(
    structure: ContactStructure,
    law,
    impactor: Impactor,
    solver: SolverSpec,
    energy: bool = True,
    stepper: NewmarkStepper | None = None,
    stop_after: float | None = None,
    snapshots=(),
) -> CoupledResult:
    """Coupled impact of ``impactor`` on ``structure`` with contact ``law`` (module docstring).

    ``solver``: time step and duration (and Newmark β, γ); ``stepper``: a stepper
    already factored for this structure and step, to reuse; ``stop_after``: end
    the run this long [s] after the impactor has left for good; ``snapshots``: step
    indices at which to keep the structure's displacement (all DOFs).
    """
    h: ImpactHistory = integrate_impact(
        structure,
        law,
        impactor.mass,
        impactor.velocity,
        solver.time_step,
        solver.steps,
        newmark=solver.newmark,
        energy=energy,
        stepper=stepper,
        stop_after=stop_after,
        snapshots=snapshots,
    )
    t, F, al = h.time, h.contact_force, h.approach
    contacts = contact_intervals(t, F, al)
    first = contacts[0]
    rebound = math.nan
    if math.isfinite(first.end):
        k = int(np.searchsorted(t, first.end))  # first sample after separation: F = 0 there
        rebound = float(h.impactor_velocity[min(k, len(t) - 1)])
    energies = CoupledEnergies(
        impactor_kinetic=0.5 * impactor.mass * h.impactor_velocity**2,
        structure_kinetic=h.structure_kinetic,
        structure_strain=h.structure_strain,
        structure_work=h.structure_work,
        contact_work=h.contact_work,
        contact_energy=h.contact_energy,
        surface_mismatch=h.surface_mismatch,
    )
    return CoupledResult(
        impactor=impactor,
        time=t,
        contact_force=F,
        impactor_velocity=h.impactor_velocity,
        impactor_displacement=h.impactor_displacement,
        approach=al,
        approach_rate=h.approach_rate,
        contact_radius=h.contact_radius,
        target_displacement=h.target_displacement,
        gauge_strain=h.outputs,
        gauge_names=tuple(structure.output_names),
        energies=energies,
        contacts=contacts,
        peak_force=first.peak_force,
        time_of_peak=first.time_of_peak,
        contact_duration=first.duration,
        impulse=first.impulse,
        rebound_velocity=rebound,
        final_velocity=float(h.impactor_velocity[-1]),
        newton_iterations=h.newton_iterations,
        solves=h.solves,
        displacement=h.displacement,
        kept=h.kept,
    )


def plate_reach(model: PlateModel, position: tuple[float, float], diameter: float) -> float:
    """The widest contact disc [m] the plate model loads about the impact point: the impactor's
    diameter (a Hertz radius sqrt(R·α) and a flattened sphere's sqrt(d·α) stay within it while
    α < d), cut so the disc stays on the plate and its elements off a supported edge (whose w
    is fixed); a symmetry edge through the impact point does not cut it."""
    fe = model.fe
    x, y = position
    h = (float(np.max(np.diff(fe.xs))), float(np.max(np.diff(fe.ys))))
    room = diameter
    for (dist, hh), kind in zip(((x - fe.xs[0], h[0]), (fe.xs[-1] - x, h[0]), (y - fe.ys[0], h[1]), (fe.ys[-1] - y, h[1])), model.problem.plate.supports):
        if kind == "symmetry" and dist <= 1e-9 * hh:
            continue
        room = min(room, dist - (1.01 * hh if kind in ("clamped", "simply-supported") else 0.0))
    if not room > 0:
        raise InputError("the impact point is within one element of a supported edge: no room for the contact disc")
    return room


def impact_model(problem: ImpactProblem) -> BeamModel | PlateModel:
    """The target's model for the impact run (a plate's checked for room about the impact point
    first: errors name the target case's load.position)."""
    if not problem.on_plate:
        return BeamModel(problem.target)
    try:
        model = PlateModel(problem.target, patch_radius=min(problem.target.load.contact_radius, problem.impactor.diameter))
        plate_reach(model, problem.position, problem.impactor.diameter)
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
    work = E.structure_work / share
    along_w = E.structure_work - E.surface_mismatch  # Σ F·Δw, the same for part and whole
    energies = replace(
        E, structure_kinetic=E.structure_kinetic / share, structure_strain=E.structure_strain / share, structure_work=work, surface_mismatch=work - along_w
    )
    return replace(result, energies=energies)


def run_impact(
    problem: ImpactProblem, model: BeamModel | PlateModel | None = None, energy: bool = True, stop_after: float | None = None, snapshots=()
) -> tuple[BeamModel | PlateModel, CoupledResult]:
    """The coupled run of an impact problem on a beam or plate; ``model``: a BeamModel or PlateModel
    of the same structure and step to reuse; ``energy``: keep the energy histories; ``stop_after``:
    end the run this long [s] after the impactor has left for good; ``snapshots``: step indices at
    which to keep the structure's displacement.

    Loadable nodes reach one impactor diameter from the impact point: a Hertz radius
    sqrt(R·α) and a flattened sphere's sqrt(d·α) stay within it while α < d (on a plate,
    :func:`plate_reach`).
    """
    model = model or impact_model(problem)
    if problem.on_plate:
        structure = plate_structure(model, problem.position, plate_reach(model, problem.position, problem.impactor.diameter))
    else:
        structure = beam_contact_structure(model, problem.position, problem.impactor.diameter)
    try:
        result = simulate_coupled(structure, problem.law, problem.impactor, problem.solver, energy, model.stepper, stop_after, snapshots)
    except InputError as exc:
        if "runs past" not in str(exc):
            raise
        raise InputError(f"{exc}: the contact outgrew the room about the impact point (target.case: load.position)") from None
    if problem.on_plate:
        result = _whole_plate(result, structure.patch.patch.share)
    return model, result
