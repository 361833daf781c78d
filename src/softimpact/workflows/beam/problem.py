"""A beam run's problem: the laminated beam, its load, gauges and solver (:class:`BeamProblem`, a
:class:`~softimpact.models.protocols.Target` of a coupled impact), and the checks that refuse one too coarse or too big."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ...errors import InputError
from ...fem.linear import MIN_STEPS_PER_RISE
from ...fem.newmark import SolverSpec
from ...fem.plane import PlaneBeam
from ...models.laminate import Stack, plane_matrix
from ...models.materials import Material
from ...models.specimens import GAUGE_LENGTH
from ...models.validity import Validity, deflection_validity

if TYPE_CHECKING:  # the model is built lazily (linear.py imports this module)
    from .linear import BeamModel

__all__ = ["LAMINATE_MODELS", "BeamGauge", "BeamSpec", "BeamLoad", "BeamProblem", "isotropic_matrix", "check_problem"]

MIN_ELEMENTS_THROUGH = (2, 4)  # element layers through the thickness: floor (one Q4 layer has no bending strain at the faces), comfortable
MIN_ELEMENTS_PER_PATCH = (1.0, 2.0)  # elements across the contact patch 2·r0: floor, comfortable (paper: 16)
LAMINATE_MODELS = ("smeared", "layered")  # homogenised through the thickness, or ply group by ply group


@dataclass(frozen=True)
class BeamGauge:
    """A strain gauge: centre [m] from the support at x = 0, face, length [m]."""

    name: str
    position: float
    surface: str = "bottom"
    length: float = GAUGE_LENGTH


@dataclass(frozen=True)
class BeamSpec:
    """The beam: free length [m] (support at x = 0), width [m], mesh, support, and
    either a laminate (``stack``, ``model`` smeared|layered) or an isotropic
    ``material`` with a ``thickness``. ``kinematics``: ``"linear"`` (small strain, the
    paper's model) or ``"von-karman"``, large deflection: for the plane model it selects
    its total Lagrangian form (Green–Lagrange strain, :mod:`softimpact.fem.plane_tl`), which
    contains the von Kármán beam as its moderate-rotation limit."""

    length: float
    width: float
    nx: int = 200
    nz: int = 6
    support: str = "clamped-free"
    stack: Stack | None = None
    model: str = "smeared"
    material: Material | None = None
    material_thickness: float = 0.0
    plane: str = "strain"
    lumped: bool = False
    damping: tuple[float, float] = (0.0, 0.0)  # Rayleigh α [1/s], β [s]: C = αM + βK
    kinematics: str = "linear"  # "von-karman": large deflection, the plane model's total Lagrangian form (fem.plane_tl)

    def __post_init__(self):
        from ...fem.plate_vk import KINEMATICS

        if self.kinematics not in KINEMATICS:
            raise InputError(f"kinematics: {self.kinematics!r} is not one of {', '.join(KINEMATICS)}", "kinematics")
        if (self.stack is None) == (self.material is None):
            raise InputError("give exactly one of a laminate (stack) and an isotropic material", "stack")
        if self.model not in LAMINATE_MODELS:
            raise InputError(f"model: {self.model!r} is not one of {', '.join(LAMINATE_MODELS)}", "model")

    @property
    def thickness(self) -> float:
        return self.stack.thickness if self.stack is not None else self.material_thickness

    @property
    def density(self) -> float:
        return self.stack.ply.density if self.stack is not None else self.material.density

    def layer_matrices(self) -> tuple:
        """D of each element layer (bottom first), or one D for all."""
        if self.material is not None:
            return (isotropic_matrix(self.material, self.plane),)
        if self.model == "smeared":
            return (plane_matrix(self.stack.effective(), self.plane),)
        h, nz = self.thickness, self.nz
        return tuple(plane_matrix(self.stack.layer_stiffness(j * h / nz, (j + 1) * h / nz), self.plane) for j in range(nz))

    def plane_beam(self) -> PlaneBeam:
        return PlaneBeam(self.length, self.thickness, self.width, self.nx, self.nz, self.layer_matrices(), self.density, self.support, self.lumped)


def isotropic_matrix(m: Material, plane: str = "strain") -> np.ndarray:
    """D of an isotropic material in plane strain or plane stress."""
    E, nu = m.youngs_modulus, m.poisson_ratio
    G = E / (2 * (1 + nu))
    if plane == "strain":
        lam = E * nu / ((1 + nu) * (1 - 2 * nu))
        return np.array([[lam + 2 * G, lam, 0], [lam, lam + 2 * G, 0], [0, 0, G]])
    c = E / (1 - nu**2)
    return np.array([[c, c * nu, 0], [c * nu, c, 0], [0, 0, G]])


@dataclass(frozen=True)
class BeamLoad:
    """Impact point [m] on the top face, contact radius r0 [m], and the force history (a pulse)."""

    position: float
    contact_radius: float
    history: object


def _opposite(surface: str) -> str:
    return "top" if surface == "bottom" else "bottom"


@dataclass(frozen=True)
class BeamProblem:
    """Everything that defines a beam run (SI); checks that the load, gauges and time step fit.

    A :class:`~softimpact.models.protocols.Target` of a coupled impact: its model, checks and
    refinement, laminate, damage outputs (the load point's two faces and the face opposite each
    gauge), validity (linear beam theory) and summary extras (none)."""

    beam: BeamSpec
    load: BeamLoad
    solver: SolverSpec
    gauges: tuple[BeamGauge, ...]
    title: str = ""

    def __post_init__(self):
        L = self.beam.length
        if not 0 < self.load.position < L:
            raise InputError(f"load position {self.load.position!r} m is not on the beam (0 to {L!r} m)", "position")
        for g in self.gauges:
            if not (0 <= g.position - g.length / 2 and g.position + g.length / 2 <= L):
                raise InputError(f"gauge {g.name!r}: position {g.position!r} m puts the gauge off the beam (0 to {L!r} m)", "gauges")
        rise = None if self.load.history is None else self.load.history.time_of_peak  # a Pulse (models.protocols); None: an impact's target
        if rise is not None and rise < MIN_STEPS_PER_RISE * self.solver.time_step:
            raise InputError(
                f"a time step of {self.solver.time_step * 1e6:.4g} us cannot resolve a pulse rising in {rise * 1e6:.4g} us "
                f"(need at most time_of_peak/{MIN_STEPS_PER_RISE} = {rise / MIN_STEPS_PER_RISE * 1e6:.4g} us)",
                "time_step",
            )

    def model(self, patch_radius: float | None = None, damage: bool = False) -> BeamModel:
        """The assembled :class:`BeamModel` of this problem (``patch_radius``: the widest contact radius it loads;
        ``damage``: its contact structure also outputs the ``"damage"`` group, :meth:`damage_gauges`); with
        ``kinematics = "von-karman"`` its total Lagrangian form (:class:`~softimpact.workflows.beam.nonlinear.BeamTLModel`)."""
        if self.kinematics != "linear":
            from .nonlinear import BeamTLModel

            return BeamTLModel(self, patch_radius, damage=damage)
        from .linear import BeamModel

        return BeamModel(self, patch_radius, damage=damage)

    # --- the Target protocol (softimpact.models.protocols.Target) ---

    theory = "linear beam theory"  # the deflection envelope's label (models.validity.deflection_validity)
    laminate_key = "beam.laminate.ply"  # where a case gives the laminate's ply (messages)

    @property
    def coupled_stepper(self) -> str | None:
        """The coupled stepper of a large-deflection beam (the one nonlinear engine's), None for a linear one."""
        return "von-karman" if self.kinematics == "von-karman" else None

    deflected_shapes = False  # the impact command draws no deflected shapes of a beam
    summary_keys = ()  # the sweep outputs of its summary extras (none)

    @property
    def kinematics(self) -> str:
        """``"linear"`` or ``"von-karman"`` (the beam's: :class:`BeamSpec`)."""
        return self.beam.kinematics

    @property
    def stack(self) -> Stack | None:
        return self.beam.stack

    @property
    def material(self) -> Material | None:
        return self.beam.material

    @property
    def thickness(self) -> float:
        return self.beam.thickness

    @property
    def mass(self) -> float:
        """The beam's mass [kg]: density × thickness × width × free length."""
        return self.beam.density * self.beam.thickness * self.beam.width * self.beam.length

    @property
    def elements(self) -> list[int]:
        """The mesh: [along, through the thickness]."""
        return [self.beam.nx, self.beam.nz]

    def check(self) -> None:
        """:func:`check_problem`."""
        check_problem(self)

    def with_solver(self, solver: SolverSpec) -> BeamProblem:
        """This problem stepped by ``solver`` (a one-factor refinement swaps the time step alone)."""
        from dataclasses import replace

        return replace(self, solver=solver)

    def refine(self, factor: int) -> BeamProblem:
        """Factor × the elements along and through the thickness and dt/factor (load, gauges unchanged)."""
        from dataclasses import replace

        return replace(self, beam=replace(self.beam, nx=self.beam.nx * factor, nz=self.beam.nz * factor), solver=_finer(self.solver, factor))

    def for_impact(self, solver: SolverSpec, gauges: tuple[BeamGauge, ...] | None = None) -> BeamProblem:
        """This beam as the target of a coupled impact: its load point and contact radius kept, the
        force history dropped (the contact gives it), ``solver`` and ``gauges`` (default its own)."""
        from dataclasses import replace

        load = BeamLoad(self.load.position, self.load.contact_radius, None)
        return replace(self, load=load, solver=solver, gauges=self.gauges if gauges is None else gauges)

    @property
    def has_damage_outputs(self) -> bool:
        """Its laminate is a layup (ply stacking) whose ply has strengths: the damage indices apply."""
        stack = self.beam.stack
        return isinstance(stack, Stack) and stack.ply.strength is not None  # a layup (not ply fractions) with strengths

    def damage_points(self) -> dict[str, float]:
        """Where the damage indices are read: the section under the load and each gauge's section (x [m])."""
        return {"at_load": self.load.position, **{f"at_{g.name}": g.position for g in self.gauges}}

    def damage_gauges(self) -> tuple[BeamGauge, ...]:
        """The ``"damage"`` output group: the axial strain on the load point's two faces and, over each
        gauge's length, on the face opposite it (a section's two faces give its CLT strains); none
        without :attr:`has_damage_outputs`."""
        if not self.has_damage_outputs:
            return ()
        x = self.load.position
        out = (BeamGauge("at_load.top", x, "top"), BeamGauge("at_load.bottom", x, "bottom"))
        return out + tuple(BeamGauge(f"at_{g.name}.{_opposite(g.surface)}", g.position, _opposite(g.surface), g.length) for g in self.gauges)

    def damage_faces(self, gauges: np.ndarray, damage: dict) -> dict:
        """Per damage point ("at_load", "at_<gauge>"): (top, bottom) axial face strains (n,), from the
        gauges' strains (n_gauges, n) and the ``"damage"`` group's by name."""
        faces = {"at_load": (damage["at_load.top"], damage["at_load.bottom"])}
        for j, g in enumerate(self.gauges):
            other = damage[f"at_{g.name}.{_opposite(g.surface)}"]
            faces[f"at_{g.name}"] = (gauges[j], other) if g.surface == "top" else (other, gauges[j])
        return faces

    @property
    def damage_section(self) -> tuple[str, float]:
        """(plane, width [m]): a face strain is the axial ε_x of a section in plane strain or stress across the width."""
        return self.beam.plane, self.beam.width

    def validity(self, max_deflection: float) -> Validity:
        """The deflection envelope of linear beam theory (:func:`~softimpact.models.validity.deflection_validity`);
        with large-deflection kinematics, the model past it, the ratio alone (no flag)."""
        if self.kinematics != "linear":
            return Validity({"deflection_over_thickness": abs(max_deflection) / self.beam.thickness})
        return deflection_validity(self.theory, max_deflection, self.beam.thickness)

    def gauge_summary(self, gauge: BeamGauge) -> dict:
        """A gauge's entries in an impact's summary.json besides its peaks: none (its case names it)."""
        return {}

    def summary_extras(self, model, result) -> dict:
        """An impact's summary.json ``target``: the beam's kinematics."""
        return {"target": {"kinematics": self.kinematics}}


def _finer(solver: SolverSpec, factor: int) -> SolverSpec:
    """The solver with dt/factor and the same duration."""
    from dataclasses import replace

    if isinstance(factor, bool) or not isinstance(factor, int) or factor < 1:
        raise InputError(f"refinement factor must be a positive integer, got {factor!r}")
    return replace(solver, time_step=solver.time_step / factor)


def check_problem(problem: BeamProblem) -> None:
    """Refuse, before anything is built, a beam too coarse to mean anything or too big for the machine.

    Resolution: element layers through the thickness and elements across the
    contact patch (:data:`MIN_ELEMENTS_THROUGH`, :data:`MIN_ELEMENTS_PER_PATCH`;
    InputError naming ``elements``, or a warning). Resources of direct
    stepping: load, displacement and velocity histories of n DOFs over the run
    (and as much again for the energy balance) and the banded factor
    (bandwidth about 2(min(nx, nz) + 2)).
    """
    from ...guards import require_resolution, require_resources

    b = problem.beam
    steps = problem.solver.steps
    n = 2 * (b.nx + 1) * (b.nz + 1)
    band = 2 * (min(b.nx, b.nz) + 2)
    memory = 8.0 * (6 * n * (steps + 1) + n * (band + 1))
    flops = 4.0 * n * band * (steps + 1)
    require_resources(f"a {b.nx} x {b.nz} beam over {steps} steps", memory, flops)
    require_resolution(
        "element layers through the thickness",
        b.nz,
        *MIN_ELEMENTS_THROUGH,
        f"give beam.elements = [{b.nx}, {max(b.nz, MIN_ELEMENTS_THROUGH[1])}] or more",
        "elements",
    )
    per_patch = 2 * problem.load.contact_radius / (b.length / b.nx)
    # the advice for the case at hand: below the floor (exit 2) the floor's count, between the floor and the comfortable
    # value (a warning) the comfortable one, which is more than the beam already has
    target = MIN_ELEMENTS_PER_PATCH[0] if not per_patch >= MIN_ELEMENTS_PER_PATCH[0] else MIN_ELEMENTS_PER_PATCH[1]
    need = math.ceil(target * b.length / (2 * problem.load.contact_radius))
    require_resolution(
        "elements across the contact patch", per_patch, *MIN_ELEMENTS_PER_PATCH, f"use at least {need} elements along the length (it has {b.nx})", "elements"
    )
