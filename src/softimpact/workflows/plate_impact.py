"""Transverse soft impact of a laminated plate: the beam workflow in two dimensions.

The laminate is a first-order shear deformation (FSDT) plate section (A, B, D,
transverse shear with k = 5/6, rotary inertia), meshed with MITC9 or MITC4 elements
(:mod:`softimpact.fem.plate`), loaded on its top face by the force history
spread over a circular contact patch with the cosine distribution of eq (11)
and the radius of eq (10) (:mod:`softimpact.fem.plate_loads`), and integrated
by Newmark average acceleration. Gauges read the surface strain in a direction,
averaged over their length, on the top or bottom face; the deflection is read
under the impact point and at chosen points.

The model is linear and time-invariant, so :class:`PlateModel` offers two ways
to the same outputs: ``direct`` stepping (all DOFs, energies) and ``respond``
through the response engine (impulse responses at the outputs, computed once by
reciprocity; milliseconds per force history).
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..errors import InputError
from ..fem.contact import output_groups, plate_contact_structure, plate_reach
from ..fem.energies import Energies
from ..fem.linear import MIN_STEPS_PER_RISE, LinearModel
from ..fem.newmark import SolverSpec
from ..fem.plate import EDGES, ELEMENTS, SUPPORT_KINDS, Plate, PlateFE
from ..fem.plate_loads import CircularPatch
from ..models.laminate import Stack
from ..models.plate_laminate import SHEAR_CORRECTION, PlateSection, plate_section
from ..models.specimens import GAUGE_LENGTH
from ..models.validity import Validity, deflection_validity

if TYPE_CHECKING:
    from ._plate_vk_model import PlateVKModel

__all__ = [
    "PlateSpec",
    "PlateLoad",
    "PlateGauge",
    "PlateProblem",
    "PlateResult",
    "PlateModel",
    "PlateVKModel",
    "PlateStaticResult",
    "ANALYSES",
    "check_problem",
    "solve_plate_static",
    "DAMAGE_DIRECTIONS",
]

DAMAGE_DIRECTIONS = ("x", "y", 45.0)  # three normal strains give a point's in-plane strain tensor
ANALYSES = ("dynamic", "static")  # a plate run: a force history in time, or a uniform pressure at equilibrium


def _positive(name: str, value) -> None:
    if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
        raise InputError(f"{name} must be positive, got {value!r}")


@dataclass(frozen=True)
class PlateSpec:
    """The plate: lengths along x (the 0° fibres) and y [m], elements (nx, ny),
    supports of the edges (x0, x1, y0, y1), the laminate stack, the shear
    correction factor, Rayleigh damping (α [1/s], β [s]: C = αM + βK) and the
    element, ``"mitc9"`` (the default, as in case files: 2 % on the issue's plate at
    48 × 48 where MITC4 needs ~360 × 360) or ``"mitc4"`` (:mod:`softimpact.fem.plate`)."""

    length_x: float
    length_y: float
    elements: tuple[int, int]
    stack: Stack
    supports: tuple[str, str, str, str] = ("simply-supported",) * 4
    shear_correction: float = SHEAR_CORRECTION
    damping: tuple[float, float] = (0.0, 0.0)
    element: str = "mitc9"

    def __post_init__(self):
        _positive("length_x", self.length_x)
        if self.element not in ELEMENTS:
            raise InputError(f"element must be one of {', '.join(ELEMENTS)}, got {self.element!r}")
        _positive("length_y", self.length_y)
        if not (len(self.elements) == 2 and all(isinstance(n, (int, np.integer)) and n >= 1 for n in self.elements)):
            raise InputError(f"elements must be two positive integers (nx, ny), got {self.elements!r}")
        if len(self.supports) != 4 or any(s not in SUPPORT_KINDS for s in self.supports):
            raise InputError(f"supports must give one of {', '.join(SUPPORT_KINDS)} for each edge {', '.join(EDGES)}, got {self.supports!r}")
        if not isinstance(self.stack, Stack):
            raise InputError(f"stack must be a Stack (ply and angles), got {type(self.stack).__name__}")
        if not (len(self.damping) == 2 and all(math.isfinite(d) and d >= 0 for d in self.damping)):
            raise InputError(f"damping must be two non-negative numbers (alpha, beta), got {self.damping!r}")
        mirrors = [edge for edge, kind in zip(EDGES, self.supports) if kind == "symmetry"]
        coupling = self.section().mirror_coupling() if mirrors else {}
        if coupling:
            terms = ", ".join(f"{name} ({ratio:.2g} of its scale)" for name, ratio in coupling.items())
            raise InputError(
                f"supports: symmetry edge(s) {', '.join(mirrors)} need a laminate orthotropic about the mirror plane, "
                f"but this stack has {terms}: a half or quarter model would be wrong; model the whole plate",
                "supports",
            )

    def section(self) -> PlateSection:
        return plate_section(self.stack, self.shear_correction)

    def plate(self) -> Plate:
        nx, ny = (int(n) for n in self.elements)
        return Plate(self.length_x, self.length_y, nx, ny, self.section(), tuple(self.supports), element=self.element)


@dataclass(frozen=True)
class PlateLoad:
    """Impact point (x, y) [m] on the top face, contact radius r0 [m], force history (a pulse or
    any callable F(t) [N]), and whether the radius grows with the force (eq 10) or stays r0."""

    position: tuple[float, float]
    contact_radius: float
    history: object
    grow: bool = True

    def __post_init__(self):
        _positive("contact_radius", self.contact_radius)
        if len(self.position) != 2:
            raise InputError(f"load position must be (x, y), got {self.position!r}")


@dataclass(frozen=True)
class PlateGauge:
    """A strain gauge: centre (x, y) [m], face (top|bottom), direction ("x", "y" or degrees from x),
    length [m] along that direction."""

    name: str
    position: tuple[float, float]
    surface: str = "bottom"
    direction: str | float = "x"
    length: float = GAUGE_LENGTH

    def __post_init__(self):
        if self.surface not in ("top", "bottom"):
            raise InputError(f"gauge {self.name}: surface {self.surface!r} is not 'top' or 'bottom'")
        if isinstance(self.direction, str) and self.direction not in ("x", "y"):
            raise InputError(f"gauge {self.name}: direction {self.direction!r} is not 'x', 'y' or an angle in degrees")
        if not isinstance(self.direction, str) and not math.isfinite(self.direction):
            raise InputError(f"gauge {self.name}: direction {self.direction!r} is not a finite angle in degrees")
        if not (math.isfinite(self.length) and self.length >= 0):
            raise InputError(f"gauge {self.name}: length must be non-negative, got {self.length!r} m")


@dataclass(frozen=True)
class PlateProblem:
    """Everything that defines a plate run (SI); checks that the load, gauges and time step fit.

    ``points``: extra points (x, y) [m] where the deflection is recorded, after
    the impact point.

    ``kinematics``: ``"linear"`` or ``"von-karman"`` (:mod:`softimpact.fem.plate_vk`), ``in_plane`` the
    restraint of the supported edges in their plane under von Kármán kinematics (``"immovable"``, the
    default: a panel fastened to a stiff frame, and the classical large-deflection benchmarks';
    ``"movable"``). ``analysis``: ``"dynamic"`` (the force history ``load`` over the ``solver``'s steps)
    or ``"static"`` (the uniform ``pressure`` [Pa] on the top face, pushing down, in ``load_steps``
    increments of Newton; ``load`` and ``solver`` are then None).

    A :class:`~softimpact.models.protocols.Target` of a coupled impact: its model, checks and
    refinement, laminate, damage outputs (point strains in x, y and 45° on both faces under the
    load and at each gauge), validity (linear plate theory) and summary extras (its ``target`` block).
    """

    plate: PlateSpec
    load: PlateLoad | None
    solver: SolverSpec | None
    gauges: tuple[PlateGauge, ...] = ()
    points: tuple[tuple[float, float], ...] = ()
    title: str = ""
    kinematics: str = "linear"
    in_plane: str = "immovable"
    analysis: str = "dynamic"
    pressure: float | None = None
    load_steps: int = 10

    def __post_init__(self):
        from ..fem.plate_vk import IN_PLANE, KINEMATICS

        if self.kinematics not in KINEMATICS:
            raise InputError(f"kinematics: {self.kinematics!r} is not one of {', '.join(KINEMATICS)}", "kinematics")
        if self.in_plane not in IN_PLANE:
            raise InputError(f"in_plane: {self.in_plane!r} is not one of {', '.join(IN_PLANE)}", "in_plane")
        if self.analysis not in ANALYSES:
            raise InputError(f"analysis: {self.analysis!r} is not one of {', '.join(ANALYSES)}", "analysis")
        if self.analysis == "static":
            _positive("pressure", self.pressure)
            if isinstance(self.load_steps, bool) or not (isinstance(self.load_steps, (int, np.integer)) and self.load_steps >= 1):
                raise InputError(f"load_steps must be a positive integer, got {self.load_steps!r}", "load_steps")
            if self.gauges or self.points:
                raise InputError("a static plate run records the largest deflection only: gauges and points are for dynamic runs", "gauges")
            return
        if self.pressure is not None:
            raise InputError("pressure: a uniform pressure is a static load (analysis = 'static'); a dynamic run takes a force history", "pressure")
        if self.load is None or self.solver is None:
            raise InputError("a dynamic plate run needs its load (position, contact radius, history) and its solver (time step, duration)", "load")
        Lx, Ly = self.plate.length_x, self.plate.length_y

        tol = 1e-12 * max(Lx, Ly)  # round-off of cos 90°

        def on_plate(p) -> bool:
            return -tol <= p[0] <= Lx + tol and -tol <= p[1] <= Ly + tol

        x, y = self.load.position
        r = self.load.contact_radius
        sx0, sx1, sy0, sy1 = (s == "symmetry" for s in self.plate.supports)
        fits_x = (r <= x or (sx0 and x == 0)) and (x <= Lx - r or (sx1 and x == Lx))
        fits_y = (r <= y or (sy0 and y == 0)) and (y <= Ly - r or (sy1 and y == Ly))
        if not (fits_x and fits_y):
            raise InputError(f"load position {self.load.position!r} m with contact_radius {r!r} m: the patch is not inside the plate ({Lx!r} × {Ly!r} m)")
        for g in self.gauges:
            theta = math.radians(0.0 if g.direction == "x" else 90.0 if g.direction == "y" else float(g.direction))
            d = 0.5 * g.length * np.array([math.cos(theta), math.sin(theta)])
            if not (on_plate(np.asarray(g.position) - d) and on_plate(np.asarray(g.position) + d)):
                raise InputError(f"gauge {g.name}: position {g.position!r} m puts the gauge off the plate")
        for p in self.points:
            if not on_plate(p):
                raise InputError(f"points: {p!r} m is off the plate")
        rise = None if self.load.history is None else self.load.history.time_of_peak  # a Pulse (models.protocols); None: an impact's target
        if rise is not None and rise < MIN_STEPS_PER_RISE * self.solver.time_step:
            raise InputError(
                f"time_step {self.solver.time_step * 1e6:.3g} us cannot resolve a pulse rising in "
                f"{rise * 1e6:.3g} us (need at most time_of_peak/{MIN_STEPS_PER_RISE})"
            )

    def model(self, patch_radius: float | None = None, damage: bool = False) -> PlateModel | PlateVKModel:
        """The assembled :class:`PlateModel` of this problem (``patch_radius``: the widest contact radius it loads;
        ``damage``: it also outputs the ``"damage"`` group, :meth:`damage_gauges`); with von Kármán kinematics the
        :class:`PlateVKModel` (a coupled impact's target; ``patch_radius`` unused: its disc is the contact's)."""
        if self.kinematics == "von-karman":
            from ._plate_vk_model import PlateVKModel

            return PlateVKModel(self, damage=damage)
        return PlateModel(self, patch_radius, damage=damage)

    # --- the Target protocol (softimpact.models.protocols.Target) ---

    theory = "linear plate theory (FSDT)"  # the deflection envelope's label (models.validity.deflection_validity)
    laminate_key = "plate.laminate.ply"  # where a case gives the laminate's ply (messages)
    deflected_shapes = True  # the impact command draws the plate's mesh and deflected shapes
    summary_keys = ("target.peak_deflection_at_impact_m", "target.time_of_peak_deflection_s")  # the sweep outputs of its summary extras

    @property
    def stack(self) -> Stack:
        return self.plate.stack

    @property
    def material(self) -> None:
        """A plate is a laminate: no isotropic material."""
        return None

    @property
    def thickness(self) -> float:
        return self.plate.stack.thickness

    @property
    def mass(self) -> float:
        """The whole plate's mass [kg]: areal density × area, doubled about each symmetry edge (a half or quarter model)."""
        stack, mirrors = self.plate.stack, sum(s == "symmetry" for s in self.plate.supports)
        return stack.ply.density * stack.thickness * self.plate.length_x * self.plate.length_y * 2**mirrors

    @property
    def elements(self) -> list[int]:
        """The mesh: [along x, along y]."""
        return list(self.plate.elements)

    def check(self) -> None:
        """:func:`check_problem`."""
        check_problem(self)

    def with_solver(self, solver: SolverSpec) -> PlateProblem:
        """This problem stepped by ``solver`` (a one-factor refinement swaps the time step alone)."""
        from dataclasses import replace

        return replace(self, solver=solver)

    def refine(self, factor: int) -> PlateProblem:
        """Factor × the elements along x and y and dt/factor (load patch, gauges and points unchanged; a static run: the mesh only)."""
        from dataclasses import replace

        if isinstance(factor, bool) or not isinstance(factor, int) or factor < 1:
            raise InputError(f"refinement factor must be a positive integer, got {factor!r}")
        nx, ny = self.plate.elements
        solver = None if self.solver is None else replace(self.solver, time_step=self.solver.time_step / factor)
        return replace(self, plate=replace(self.plate, elements=(nx * factor, ny * factor)), solver=solver)

    def for_impact(self, solver: SolverSpec, gauges: tuple[PlateGauge, ...] | None = None) -> PlateProblem:
        """This plate as the target of a coupled impact: its load point and contact radius kept, the
        force history dropped (the contact gives it; the disc grows with the force), ``solver`` and
        ``gauges`` (default its own)."""
        from dataclasses import replace

        load = PlateLoad(self.load.position, self.load.contact_radius, None, grow=True)
        return replace(self, load=load, solver=solver, gauges=self.gauges if gauges is None else gauges)

    @property
    def has_damage_outputs(self) -> bool:
        """Its laminate is a layup (ply stacking) whose ply has strengths: the damage indices apply."""
        stack = self.plate.stack
        return isinstance(stack, Stack) and stack.ply.strength is not None  # a layup (not ply fractions) with strengths

    def damage_points(self) -> dict[str, tuple[float, float]]:
        """Where the damage indices are read: under the impact point and at each gauge's centre."""
        return {"at_load": tuple(self.load.position), **{f"at_{g.name}": tuple(g.position) for g in self.gauges}}

    def damage_gauges(self) -> tuple[PlateGauge, ...]:
        """The ``"damage"`` output group: point strains (length 0) along :data:`DAMAGE_DIRECTIONS` on both
        faces at each of :meth:`damage_points` (the in-plane strain tensor of each face); none without
        :attr:`has_damage_outputs`."""
        if not self.has_damage_outputs:
            return ()
        return tuple(
            PlateGauge(f"{n}.{face}.{d}", xy, face, d, 0.0) for n, xy in self.damage_points().items() for face in ("top", "bottom") for d in DAMAGE_DIRECTIONS
        )

    def damage_faces(self, gauges: np.ndarray, damage: dict) -> dict:
        """Per damage point: (top, bottom), each the normal strains along x, y and 45° (3, n) of that
        face, from the ``"damage"`` group's strains by name (``gauges``, the gauges' own, unused)."""
        return {
            p: tuple(np.array([damage[f"{p}.{face}.{d}"] for d in DAMAGE_DIRECTIONS]) for face in ("top", "bottom"))
            for p in self.damage_points()
            if f"{p}.top.x" in damage
        }

    @property
    def damage_section(self) -> tuple[None, None]:
        """(plane, width): none on a plate (a face strain is a point's in-plane tensor)."""
        return None, None

    def validity(self, max_deflection: float) -> Validity:
        """The deflection envelope of linear plate theory (:func:`~softimpact.models.validity.deflection_validity`);
        with von Kármán kinematics, the model past it, the ratio alone (no flag)."""
        if self.kinematics == "von-karman":
            return Validity({"deflection_over_thickness": abs(max_deflection) / self.plate.stack.thickness})
        return deflection_validity(self.theory, max_deflection, self.plate.stack.thickness)

    def gauge_summary(self, gauge: PlateGauge) -> dict:
        """A gauge's entries in an impact's summary.json besides its peaks: where it is and what it reads."""
        return {"position_m": list(gauge.position), "surface": gauge.surface, "direction": gauge.direction, "length_m": gauge.length}

    def summary_extras(self, model, result) -> dict:
        """An impact's summary.json ``target``: the plate model, and the mid-surface deflection under the
        impact point (along the impact direction, down +) of ``result`` (a CoupledResult's ``target_displacement``)."""
        w = result.target_displacement
        k = int(np.argmax(np.abs(w)))
        target = {
            "model": f"fsdt ({self.plate.element.upper()})",
            "kinematics": self.kinematics,
            **({"in_plane": self.in_plane} if self.kinematics == "von-karman" else {}),
            "dofs": int(model.size),
            "elements": list(self.plate.elements),
            "supports": dict(zip(("x0", "x1", "y0", "y1"), self.plate.supports)),
            "impact_point_m": list(self.load.position),
            "peak_deflection_at_impact_m": float(w[k]),
            "time_of_peak_deflection_s": float(result.time[k]),
            "deflection_note": "mid-surface deflection under the impact point, positive along the impact direction (into the plate)",
        }
        return {"target": target}

    def mirrored_edges(self) -> tuple[str, ...]:
        """The symmetry edges (of x0, x1, y0, y1) that miss the load point: about each, the model
        carries the load mirrored too (a second load), which a half or quarter model of one
        central load never means."""
        spec, (x, y) = self.plate, self.load.position
        distance = {"x0": abs(x), "x1": abs(spec.length_x - x), "y0": abs(y), "y1": abs(spec.length_y - y)}
        tol = 1e-9 * max(spec.length_x, spec.length_y)
        return tuple(edge for edge, kind in zip(distance, spec.supports) if kind == "symmetry" and distance[edge] > tol)


@dataclass(frozen=True)
class PlateResult:
    """Histories (time on the last axis) of a plate run."""

    problem: PlateProblem
    time: np.ndarray  # (n,) s
    force: np.ndarray  # (n,) N
    strain: np.ndarray  # (n_gauges, n)
    deflection: np.ndarray  # (1 + n_points, n) m, up +: impact point first, then problem.points
    displacement: np.ndarray | None = None  # (n_dofs, n_kept), free DOFs, direct stepping only
    energies: Energies | None = None  # kinetic, strain, work [J] at every step, direct stepping only
    kept: np.ndarray | None = None  # step indices of the columns of ``displacement``
    damage: np.ndarray | None = None  # (n_damage, n): the "damage" output group (PlateModel(damage=True)), rows of PlateProblem.damage_gauges()


STATIC_ITERATIONS = 5  # full Newton from the previous load step: 3-6 iterations a step past w/h = 1 (tests/test_plate_vk.py)


@dataclass(frozen=True)
class PlateStaticResult:
    """A static plate run (uniform pressure, :func:`solve_plate_static`): per load step the ``pressure`` [Pa],
    the largest mid-surface deflection ``max_deflection`` [m] (its magnitude, along the pressure), Newton's
    ``iterations`` and final relative ``residuals``; ``converged`` (every step), ``message``, the final
    displacement ``u`` over the model's free DOFs and the plate's ``kinematics``."""

    problem: PlateProblem
    pressure: np.ndarray
    max_deflection: np.ndarray
    iterations: np.ndarray
    residuals: np.ndarray
    converged: bool
    message: str
    u: np.ndarray
    kinematics: str
    membrane_strain_index: float = math.nan  # the maximum-strain index of the mid-surface strains (nan: no ply strengths)


def membrane_strain_index(stack, strain: np.ndarray) -> float:
    """The largest maximum-strain index over every ply angle of ``stack`` (a layup whose ply has strengths) under the
    mid-surface strains ``strain`` (..., 3) [(ε_x0, ε_y0, γ_xy0)]; nan for a laminate without them. With no
    curvature this is a lower bound of the faces' index: ε(z) = ε0 + z·κ, and a convex index at the faces' mean
    strain is at most the larger of its values at the faces."""
    from ..models.failure import failure_indices, ply_stresses

    if not isinstance(stack, Stack) or stack.ply.strength is None:
        return math.nan
    e0 = np.asarray(strain, float).reshape(-1, 3).T
    angles = sorted(set(stack.angles))
    eps, sig = ply_stresses(stack.ply, angles, e0, np.zeros_like(e0), np.zeros(len(angles)))
    return float(failure_indices(stack.ply, stack.ply.strength, eps, sig)["max_strain"].max())


def solve_plate_static(problem: PlateProblem, model=None):
    """(model, :class:`PlateStaticResult`) of a static plate problem: the uniform pressure on the top face
    (down), in ``load_steps`` equal increments, by full Newton on the von Kármán plate
    (:func:`softimpact.fem.plate_vk.solve_static`), or one linear solve (``kinematics = "linear"``: the
    same plate's linear stiffness, membrane DOFs included)."""
    from ..fem.plate import W
    from ..fem.plate_vk import PlateVK, solve_static

    if problem.analysis != "static":
        raise InputError("solve_plate_static: the problem is not a static one (analysis = 'static')", "analysis")
    model = model or PlateVK(problem.plate.plate(), problem.in_plane)
    res = solve_static(model, model.load_vector(-problem.pressure), load_steps=problem.load_steps, kinematics=problem.kinematics)
    rows = model.fe.basis.nodal_dofs[W]
    w = np.array([np.abs(model.expand(u)[rows]).max() for u in res.u])
    pressure = problem.pressure * res.load_factors
    # the mid-surface strains bound the faces' index from below where stretching carries the load (von Kármán); on a linear
    # symmetric plate they are zero and would say nothing (its deflection flag speaks there)
    index = membrane_strain_index(problem.plate.stack, model.membrane_strain(res.u[-1])) if problem.kinematics != "linear" else math.nan
    return model, PlateStaticResult(problem, pressure, w, res.iterations, res.residuals, res.converged, res.message, res.u[-1], problem.kinematics, index)


def check_problem(problem: PlateProblem) -> None:
    """Refuse, before anything is built, a plate too big for the machine (:mod:`softimpact.guards`).

    Estimate for direct stepping with the banded factor (an upper bound: the
    stepper keeps a sparse minimum-degree factor instead when it is cheaper):
    n = DOFs per node (3 for a symmetric section, whose stretching is dropped; else
    5) × the nodes ((k·nx + 1)(k·ny + 1), k = 1 for MITC4, 2 for MITC9), band
    b = DOFs per node × (k·(k·ny + 1) + k + 1) in the node numbering along y; memory
    8·n·(b + 1) bytes for the factor and as much again for M, K and the work
    arrays; time 4·n·b flops a step and n·b² for the factorisation.
    """
    from ..guards import require_resources

    spec = problem.plate
    nx, ny = (int(n) for n in spec.elements)
    k = 2 if spec.element == "mitc9" else 1
    # von Kármán keeps the membrane DOFs that a symmetric section's linear model drops
    per_node = 3 if spec.section().is_symmetric() and problem.kinematics == "linear" else 5
    n = per_node * (k * nx + 1) * (k * ny + 1)
    band = per_node * (k * (k * ny + 1) + k + 1)
    memory = 2 * 8.0 * n * (band + 1)
    if problem.analysis == "static":
        # a factorisation per Newton iteration: about STATIC_ITERATIONS a load step
        factorisations = 1 if problem.kinematics == "linear" else STATIC_ITERATIONS * problem.load_steps
        require_resources(f"a {nx} x {ny} {spec.element.upper()} plate over {problem.load_steps} load steps", memory, factorisations * n * band * band)
        return
    steps = problem.solver.steps
    flops = n * band * (band + 4.0 * (steps + 1))
    require_resources(f"a {nx} x {ny} {spec.element.upper()} plate over {steps} steps", memory, flops)


class PlateModel(LinearModel):
    """Assembled plate with its stepper, contact patch and output rows, for one (mesh, dt): the
    plate as a :class:`softimpact.fem.linear.LinearModel` (the structure protocol)."""

    def __init__(self, problem: PlateProblem, patch_radius: float | None = None, damage: bool = False):
        """``patch_radius``: the widest contact radius the model must load (for fits of r0); ``damage``: it also
        outputs the ``"damage"`` group (:meth:`PlateProblem.damage_gauges`), after the gauges."""
        self.problem = problem
        self.damage = problem.damage_gauges() if damage else ()
        self.fe = fe = PlateFE(problem.plate.plate())
        a, b = problem.plate.damping
        C = None if a == 0 and b == 0 else a * fe.M + b * fe.K
        load = problem.load
        patch = CircularPatch(fe, load.position, patch_radius or load.contact_radius, grow=load.grow)
        rows = [fe.surface_strain(*g.position, g.surface, g.direction, g.length) for g in problem.gauges + self.damage]
        rows += [fe.deflection(*p) for p in (load.position,) + tuple(problem.points)]
        # Patch loads push the plate down (−z).
        super().__init__(fe.M, fe.K, C, problem.solver, patch.dofs, -1.0, np.array(rows), patch, load.contact_radius)

    def _split(self, y: np.ndarray):
        """(gauge strains, deflections, the damage group or None) of the output rows."""
        ng, nd = len(self.problem.gauges), len(self.damage)
        return y[:ng], y[ng + nd :], (y[ng : ng + nd] if nd else None)

    def respond(self, history=None, radius: float | None = None) -> PlateResult:
        """Gauge strains and deflections for a force history through the response engine.

        A patch of fixed radius loads one pattern scaled by F(t): the engine then combines its
        impulse responses over the patch once and convolves each output with F alone."""
        F = self.force_samples(history)
        if self.patch.grow:
            y = self.respond_outputs(F, radius)
        else:
            if F[0] != 0.0:
                raise InputError("the force must be zero at first contact (t = 0)", "history")
            r0 = self.load_radius if radius is None else radius
            y = self.engine().respond_pattern(self.nodal_loads(np.ones(1), r0)[:, 0], F)
        strain, defl, damage = self._split(y)
        return PlateResult(self.problem, self.solver.times(), F, strain, defl, damage=damage)

    def direct(self, history=None, progress=None, energy: bool = True, snapshots=None) -> PlateResult:
        """Direct Newmark stepping of all DOFs (:meth:`LinearModel.march`); with ``energy``, the
        energy balance at every step. ``snapshots``: step indices at which to keep the displacement
        of all DOFs (``None``: every step, memory n_dofs × n_steps)."""
        F = self.force_samples(history)
        keep = np.arange(self.steps + 1) if snapshots is None else np.asarray(snapshots, int)
        y, energies, saved = self.march(F, None, energy, None, keep, progress)
        strain, defl, damage = self._split(y)
        return PlateResult(self.problem, self.solver.times(), F, strain, defl, saved, energies, keep, damage)

    def contact_structure(self, point: tuple[float, float], reach: float):
        """The plate struck downward on its top face at ``point`` (x, y) [m], contact discs up to
        ``reach`` [m] (:func:`softimpact.fem.contact.plate_contact_structure`), the gauges as outputs, then the ``"damage"`` group's."""
        gauges = self.problem.gauges + self.damage
        return plate_contact_structure(self.fe, point, reach, self.O[: len(gauges)], tuple(g.name for g in gauges), self.C, self.contact_groups())

    def contact_groups(self) -> dict[str, tuple[int, ...]]:
        """``"gauges"`` (the problem's) and ``"damage"`` (:meth:`PlateProblem.damage_gauges`, when built with it)."""
        return output_groups(gauges=len(self.problem.gauges), damage=len(self.damage))

    def contact_reach(self, point: tuple[float, float], diameter: float) -> float:
        """The impactor's diameter cut by the plate's edges (:func:`softimpact.fem.contact.plate_reach`)."""
        return plate_reach(self.fe, self.problem.plate.supports, point, diameter)

    @property
    def mesh(self):
        """The plate's mesh (:class:`~softimpact.fem.plate.PlateFE`: ``expand``, ``field_frames``)."""
        return self.fe

    def _drop_mesh(self, light) -> None:
        light.fe = None
        light.patch = copy.copy(self.patch)
        light.patch.fe = None


def __getattr__(name: str):
    """:class:`PlateVKModel` lives in its own module (imported with scipy's nonlinear solvers on first use)."""
    if name == "PlateVKModel":
        from ._plate_vk_model import PlateVKModel

        return PlateVKModel
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
