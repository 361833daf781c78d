"""The plate problem: a laminated or metal plate, its load, gauges and solver (the beam workflow in two dimensions).

The laminate is a first-order shear deformation (FSDT) plate section (A, B, D,
transverse shear with k = 5/6, rotary inertia), meshed with MITC9 or MITC4 elements
(:mod:`softimpact.fem.plate`), loaded on its top face by the force history
spread over a circular contact patch with the cosine distribution of eq (11)
and the radius of eq (10) (:mod:`softimpact.fem.plate_loads`), and integrated
by Newmark average acceleration. Gauges read the surface strain in a direction,
averaged over their length, on the top or bottom face; the deflection is read
under the impact point and at chosen points.

Its models live beside it in this package: the linear plate (:class:`~softimpact.workflows.plate.linear.PlateModel`,
direct stepping and the response engine), the nonlinear plate of the one engine (von Kármán kinematics, an
elastic–plastic metal section: :class:`~softimpact.workflows.plate.nonlinear.NonlinearPlateModel`) and the
sublaminates tied by cohesive interfaces (:mod:`softimpact.workflows.plate.cohesive`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ...errors import InputError
from ...fem.linear import MIN_STEPS_PER_RISE
from ...fem.newmark import SolverSpec
from ...fem.plate import EDGES, ELEMENTS, SUPPORT_KINDS, Plate
from ...models.laminate import Stack
from ...models.metals import Metal
from ...models.plate_laminate import SHEAR_CORRECTION, PlateSection, isotropic_section, plate_section
from ...models.specimens import GAUGE_LENGTH
from ...models.validity import Validity, deflection_validity

if TYPE_CHECKING:
    from ...fem.energies import Energies
    from .linear import PlateModel
    from .nonlinear import NonlinearPlateModel

__all__ = [
    "PlateSpec",
    "PlateLoad",
    "PlateGauge",
    "PlateProblem",
    "PlateResult",
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
    supports of the edges (x0, x1, y0, y1), the laminate ``stack`` — or, for a metal skin, the ``material``
    (a :class:`~softimpact.models.metals.Metal`) and ``thickness`` [m] with ``stack`` None —, the shear
    correction factor, Rayleigh damping (α [1/s], β [s]: C = αM + βK) and the
    element, ``"mitc9"`` (the default, as in case files: 2 % on the issue's plate at
    48 × 48 where MITC4 needs ~360 × 360) or ``"mitc4"`` (:mod:`softimpact.fem.plate`)."""

    length_x: float
    length_y: float
    elements: tuple[int, int]
    stack: Stack | None
    supports: tuple[str, str, str, str] = ("simply-supported",) * 4
    shear_correction: float = SHEAR_CORRECTION
    damping: tuple[float, float] = (0.0, 0.0)
    element: str = "mitc9"
    material: Metal | None = None
    thickness: float | None = None

    def __post_init__(self):
        _positive("length_x", self.length_x)
        if self.element not in ELEMENTS:
            raise InputError(f"element must be one of {', '.join(ELEMENTS)}, got {self.element!r}")
        _positive("length_y", self.length_y)
        if not (len(self.elements) == 2 and all(isinstance(n, (int, np.integer)) and n >= 1 for n in self.elements)):
            raise InputError(f"elements must be two positive integers (nx, ny), got {self.elements!r}")
        if len(self.supports) != 4 or any(s not in SUPPORT_KINDS for s in self.supports):
            raise InputError(f"supports must give one of {', '.join(SUPPORT_KINDS)} for each edge {', '.join(EDGES)}, got {self.supports!r}")
        if self.material is None:
            if not isinstance(self.stack, Stack):
                raise InputError(f"stack must be a Stack (ply and angles), got {type(self.stack).__name__}")
            if self.thickness is not None:
                raise InputError("thickness: a laminate's thickness is its plies'; thickness goes with a metal's material", "thickness")
        else:
            if self.stack is not None:
                raise InputError("a plate is a laminate (stack) or a metal (material and thickness), not both", "material")
            if not isinstance(self.material, Metal):
                raise InputError(f"material must be a Metal (elastic constants, yield), got {type(self.material).__name__}", "material")
            _positive("thickness", self.thickness)
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
        if self.material is not None:
            m = self.material
            return isotropic_section(m.youngs_modulus, m.poisson_ratio, m.density, self.thickness, self.shear_correction)
        return plate_section(self.stack, self.shear_correction)

    @property
    def total_thickness(self) -> float:
        """The plate's thickness [m]: the laminate's, or the metal's."""
        return self.stack.thickness if self.material is None else float(self.thickness)

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

    ``plasticity``: a metal plate's section is elastic–plastic (J2 through the thickness,
    :mod:`softimpact.fem.plate_plastic`) unless False (elastic: its runs are then checked against yield);
    a laminate's is elastic (None or False).

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
    plasticity: bool | None = None

    def __post_init__(self):
        from ...fem.plate_vk import IN_PLANE, KINEMATICS

        if self.plasticity not in (None, True, False):
            raise InputError(f"plasticity must be true or false, got {self.plasticity!r}", "plasticity")
        if self.plasticity and self.plate.material is None:
            raise InputError("plasticity: an elastic–plastic section needs a metal plate (material and thickness); a laminate is elastic", "plasticity")

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

    def model(self, patch_radius: float | None = None, damage: bool = False) -> PlateModel | NonlinearPlateModel:
        """The assembled :class:`~softimpact.workflows.plate.linear.PlateModel` of this problem (``patch_radius``: the
        widest contact radius it loads; ``damage``: it also outputs the ``"damage"`` group, :meth:`damage_gauges`);
        with von Kármán kinematics the :class:`~softimpact.workflows.plate.nonlinear.NonlinearPlateModel` (a coupled
        impact's target; ``patch_radius`` unused: its disc is the contact's)."""
        if self.coupled_stepper is not None:
            from .nonlinear import NonlinearPlateModel

            return NonlinearPlateModel(self, damage=damage)
        from .linear import PlateModel

        return PlateModel(self, patch_radius, damage=damage)

    # --- the Target protocol (softimpact.models.protocols.Target) ---

    theory = "linear plate theory (FSDT)"  # the deflection envelope's label (models.validity.deflection_validity)
    laminate_key = "plate.laminate.ply"  # where a case gives the laminate's ply (messages)
    deflected_shapes = True  # the impact command draws the plate's mesh and deflected shapes
    summary_keys = ("target.peak_deflection_at_impact_m", "target.time_of_peak_deflection_s")  # the sweep outputs of its summary extras

    @property
    def stack(self) -> Stack | None:
        """The laminate (None for a metal plate)."""
        return self.plate.stack

    @property
    def material(self) -> Metal | None:
        """A metal plate's metal (None for a laminate)."""
        return self.plate.material

    @property
    def plastic(self) -> bool:
        """The section is elastic–plastic: a metal plate unless ``plasticity`` is False."""
        return self.plate.material is not None and self.plasticity is not False

    @property
    def coupled_stepper(self) -> str | None:
        """The coupled stepper of a nonlinear plate (von Kármán kinematics or a plastic section: the one engine's,
        :data:`softimpact.fem.steppers.STEPPERS`), None for a linear one (direct stepping or kernels)."""
        return "von-karman" if (self.kinematics == "von-karman" or self.plastic) else None

    @property
    def thickness(self) -> float:
        return self.plate.total_thickness

    @property
    def mass(self) -> float:
        """The whole plate's mass [kg]: areal density × area, doubled about each symmetry edge (a half or quarter model)."""
        density = self.plate.stack.ply.density if self.plate.material is None else self.plate.material.density
        mirrors = sum(s == "symmetry" for s in self.plate.supports)
        return density * self.thickness * self.plate.length_x * self.plate.length_y * 2**mirrors

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
        """Its laminate is a layup (ply stacking) whose ply has strengths (the damage indices apply), or it is an elastic
        metal plate (its face strains against yield); a plastic plate's damage is its own state (dent, plastic zone)."""
        if self.plate.material is not None:
            return not self.plastic
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
            return Validity({"deflection_over_thickness": abs(max_deflection) / self.thickness})
        return deflection_validity(self.theory, max_deflection, self.thickness)

    def gauge_summary(self, gauge: PlateGauge) -> dict:
        """A gauge's entries in an impact's summary.json besides its peaks: where it is and what it reads."""
        return {"position_m": list(gauge.position), "surface": gauge.surface, "direction": gauge.direction, "length_m": gauge.length}

    def summary_extras(self, model, result) -> dict:
        """An impact's summary.json ``target``: the plate model, and the mid-surface deflection under the
        impact point (along the impact direction, down +) of ``result`` (a CoupledResult's ``target_displacement``)."""
        w = result.target_displacement
        k = int(np.argmax(np.abs(w)))
        section = ""
        if self.plate.material is not None:
            m = self.plate.material
            section = f", {m.name} {self.thickness * 1e3:.4g} mm, " + ("elastic-plastic (J2 through the thickness)" if self.plastic else "elastic")
        target = {
            "model": f"fsdt ({self.plate.element.upper()}){section}",
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
    permanent_deflection: float = math.nan  # a plastic plate's largest deflection once the pressure is removed [m] (nan: elastic)
    plastic_work: float = math.nan  # a plastic plate's plastic work [J] (nan: elastic)
    plastic_zone_area: float = math.nan  # a plastic plate's yielded area [m²] (nan: elastic)
    max_von_mises_over_yield: float = math.nan  # an elastic metal plate's largest von Mises stress over its yield stress (nan: a laminate or plastic)


def membrane_strain_index(stack, strain: np.ndarray) -> float:
    """The largest maximum-strain index over every ply angle of ``stack`` (a layup whose ply has strengths) under the
    mid-surface strains ``strain`` (..., 3) [(ε_x0, ε_y0, γ_xy0)]; nan for a laminate without them. With no
    curvature this is a lower bound of the faces' index: ε(z) = ε0 + z·κ, and a convex index at the faces' mean
    strain is at most the larger of its values at the faces."""
    from ...models.failure import failure_indices, ply_stresses

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
    from ...fem.nonlinear import relax
    from ...fem.plate import W
    from ...fem.plate_vk import PlateVK, solve_static

    if problem.analysis != "static":
        raise InputError("solve_plate_static: the problem is not a static one (analysis = 'static')", "analysis")
    if model is None:
        metal = problem.plate.material is not None
        model = plastic_plate(problem) if problem.plastic else PlateVK(problem.plate.plate(), problem.in_plane, curvatures=metal)
    res = solve_static(model, model.load_vector(-problem.pressure), load_steps=problem.load_steps, kinematics=problem.kinematics)
    rows = model.fe.basis.nodal_dofs[W]

    def largest(u):
        return float(np.abs(model.expand(u)[rows]).max())

    w = np.array([largest(u) for u in res.u])
    pressure = problem.pressure * res.load_factors
    # the mid-surface strains bound the faces' index from below where stretching carries the load (von Kármán); on a linear
    # symmetric plate they are zero and would say nothing (its deflection flag speaks there)
    index = membrane_strain_index(problem.plate.stack, model.membrane_strain(res.u[-1])) if problem.kinematics != "linear" else math.nan
    metal = {}
    if problem.plastic and res.converged:
        work, zone, _ = model.history(res.u[-1])
        rest, _ = relax(model, res.u[-1])  # the pressure removed: the plate springs back to its permanent shape
        metal = {"permanent_deflection": largest(rest), "plastic_work": float(work), "plastic_zone_area": float(zone)}
    elif problem.plate.material is not None and not problem.plastic:
        metal = {"max_von_mises_over_yield": elastic_von_mises(problem, model, res.u[-1]) / problem.plate.material.yield_stress}
    return model, PlateStaticResult(
        problem, pressure, w, res.iterations, res.residuals, res.converged, res.message, res.u[-1], problem.kinematics, index, **metal
    )


def plastic_plate(problem: PlateProblem):
    """The elastic–plastic plate (:class:`~softimpact.fem.plate_plastic.PlasticPlate`) of a metal plate problem."""
    from ...fem.plate_plastic import PlasticPlate

    m = problem.plate.material
    return PlasticPlate(problem.plate.plate(), m.plasticity(), kinematics=problem.kinematics, in_plane=problem.in_plane, rate=m.rate)


def elastic_von_mises(problem: PlateProblem, model, u: np.ndarray) -> float:
    """The largest von Mises stress [Pa] over the quadrature points and both faces of an elastic metal plate's state
    ``u`` (of its :class:`~softimpact.fem.plate_vk.PlateVK` ``model``): σ = Q(ε0 ± h/2·κ), Q the plane-stress stiffness."""
    from ...models.plasticity import von_mises

    m, h = problem.plate.material, problem.thickness
    Q = m.plasticity().elastic
    e0 = model.membrane_strain(u) if problem.kinematics == "von-karman" else model._fields(u)[0]
    kappa = model.curvatures(u)
    return float(max(von_mises((e0 + sign * 0.5 * h * kappa) @ Q.T).max() for sign in (1.0, -1.0)))


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
    from ...guards import require_resources

    spec = problem.plate
    nx, ny = (int(n) for n in spec.elements)
    k = 2 if spec.element == "mitc9" else 1
    # von Kármán keeps the membrane DOFs that a symmetric section's linear model drops
    per_node = 3 if spec.section().is_symmetric() and problem.coupled_stepper is None else 5
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
