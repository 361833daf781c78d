"""A rigid impactor on a linear structure through a contact law: Newmark + scalar Newton.

The structure M·ü + C·u̇ + K·u = f is any linear FE model (beam, plate, bar).
The contact force F ≥ 0 acts along the impact direction on the surface nodes
near the impact point, spread over the contact half-width a = law.radius(α)
with the cosine distribution of eq (11) and exact nodal integrals (eq 14 with
the errata of docs/modelling-notes.md): node i with tributary segment [lo_i, hi_i] (relative
to the impact point, clipped at ±a) receives F·s_i(a),

    s_i(a) = ½·[sin(π·hi_i/(2a)) − sin(π·lo_i/(2a))],   Σ s_i = 1,

and the nearest node takes all of F while a is below half a node spacing. The
approach is α = x − w, x the impactor's displacement and w the structure's
displacement along the impact direction at the impact point as given by the
``approach_row`` (for a beam or plate: the MID-SURFACE, so that the local
indentation is the contact law's and not counted twice).

One step of Newmark (β, γ) from t_k to t_{k+1}:

1. u_free = K_eff⁻¹·predictor(u_k, v_k, a_k): the structure with no contact force
   (one back-substitution, as in a prescribed-force step);
2. the structure's response to unit forces on the patch nodes, G = K_eff⁻¹·B
   (solved ONCE), gives u_{k+1} = u_free + F·G·s(a);
3. the impactor, m·ẍ = −F, gives x_{k+1} = x̃ − β·dt²·F/m;
4. hence one scalar equation in α_{k+1}:

       R(α) = α − α̃ + F(α, α̇(α))·h(a(α)) = 0,   h = β·dt²/m + c·G·s(a),

   with α̃ = x̃ − c·u_free and, because impactor and structure share the Newmark
   rule, α̇_{k+1} = κ·(α − α_k) + (1 − γ/β)·α̇_k + dt·(1 − γ/(2β))·α̈_k, κ = γ/(β·dt).
   R(0) = −α̃ < 0 ≤ R(α̃) when α̃ > 0, so the root is bracketed in (0, α̃];
   Newton with R' = 1 + (∂F/∂α + κ·∂F/∂α̇)·h + F·c·G·(ds/da)·(da/dα), safeguarded
   by bisection (laws with kinks: clipping, unloading branches). When α̃ ≤ 0 the
   bodies are apart: F = 0, α = α̃. Separation and re-contact need no special case.

Energy bookkeeping (exact for average acceleration, undamped): the impactor's
kinetic energy change equals −Σ½(F_k + F_{k+1})·Δx; the structure's kinetic +
strain energy equals the work Σ½(f_k + f_{k+1})·Δu of the nodal forces; the
contact work is Σ½(F_k + F_{k+1})·Δα. These close except for the difference
between the work of F on the loaded (top) surface nodes and on the mid-surface,
Σ½(F_k + F_{k+1})·(s̄·Δu_patch − Δw): the structure's own through-thickness
squeeze under the patch, reported as ``surface_mismatch``.

This module holds what every way of stepping shares: the structure's contract (:class:`ContactStructure`,
the line :class:`ContactPatch`), the contact Newton (:func:`newton_contact`) and the results. The loop
itself is written once, :class:`softimpact.fem.stepping.CoupledStepper`; direct stepping
(:class:`softimpact.fem.direct.DirectStepper`) and the contact kernels
(:class:`softimpact.fem.kernel_stepping.KernelStepper`) implement it, by name in
:data:`softimpact.fem.steppers.STEPPERS`. Bar, beam and plate all run through
:func:`simulate_coupled` (direct) or the kernels, and get one :class:`CoupledResult`. One separation
rule (:func:`contact_intervals`: a contact ends where α crosses zero within the
step, else where F reaches zero, for laws clipped at F = 0), one peak refinement
(:func:`refine_peak`, the parabola through three samples). A Newton iteration that
does not converge is a :class:`softimpact.errors.SolverFailed` (time, step,
residual, bracket).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ContactOutgrewRoom, InputError, SolverFailed
from ..models.protocols import PowerRadiusLaw, RespondingLaw
from ..models.specimens import Impactor
from .energies import Energies
from .newmark import NewmarkParameters, NewmarkStepper, SolverSpec

__all__ = [
    "PatchCompliance",
    "LawCapabilities",
    "newton_contact",
    "ContactStructure",
    "ContactPatch",
    "ImpactHistory",
    "integrate_impact",
    "NEWTON_TOL",
    "ContactInterval",
    "CoupledResult",
    "refine_peak",
    "contact_intervals",
    "simulate_coupled",
    "coupled_result",
]

NEWTON_TOL = 1e-12  # relative tolerance on α (and on R) in the contact iteration
NEWTON_MAXITER = 60  # Newton with bisection safeguard; typically 3–6 iterations
RADIUS_STEP = 1e-7  # relative step of the finite difference da/dα


@dataclass(frozen=True)
class ContactStructure:
    """What the coupled solver needs from a linear structure (SI; n DOFs).

    ``M``, ``K`` (n, n) sparse or dense, ``C`` optional damping.
    ``surface_x`` (p,): sorted positions [m] along the struck surface of the nodes
    the contact may load; ``surface_dofs`` (p,): their DOF along the impact line;
    ``load_sign``: +1 if a positive DOF displacement points along the impact
    direction (away from the impactor), −1 if against it.
    ``center``: the impact point on that surface coordinate [m].
    ``approach_row`` (n,): w = approach_row·u, the displacement along the impact
    direction used in α (mid-surface for beams and plates).
    ``outputs`` (n_out, n): rows for output histories (gauge strains); ``output_names``.
    ``groups``: named groups of those rows, name → row indices (``"gauges"``: the user's gauges;
    ``"damage"``: the strains the damage indices need); None: every row is a gauge.
    ``patch``: the shares of the surface nodes for a two-dimensional contact (an object
    with ``shares(a) -> (s, ds/da)``, ``half_spacing`` and ``_point``, e.g. a plate's
    disc, :class:`softimpact.fem.plate_loads.DiscShares`); None: the cosine line patch
    :class:`ContactPatch` over ``surface_x``.
    """

    M: object
    K: object
    surface_x: np.ndarray
    surface_dofs: np.ndarray
    load_sign: float
    center: float
    approach_row: np.ndarray
    outputs: np.ndarray
    output_names: tuple[str, ...] = ()
    C: object = None
    patch: object = None
    groups: dict[str, tuple[int, ...]] | None = None

    def __post_init__(self):
        n = self.M.shape[0]
        x = np.asarray(self.surface_x, float)
        if self.patch is None and (x.ndim != 1 or x.size < 1 or np.any(np.diff(x) <= 0)):
            raise InputError("structure.surface_x must be a sorted 1-D array of node positions")
        if np.shape(self.surface_dofs) != x.shape:
            raise InputError("structure.surface_dofs must have one DOF per surface node")
        if self.load_sign not in (1.0, -1.0, 1, -1):
            raise InputError(f"structure.load_sign must be +1 or -1, got {self.load_sign!r}")
        if np.shape(self.approach_row) != (n,):
            raise InputError(f"structure.approach_row must have shape ({n},)")
        if np.ndim(self.outputs) != 2 or np.shape(self.outputs)[1] != n:
            raise InputError(f"structure.outputs must have shape (n_out, {n})")


class ContactPatch:
    """Nodal shares s(a) of a unit contact force over half-width a, and ds/da (module docstring)."""

    def __init__(self, node_x: np.ndarray, center: float):
        x = np.asarray(node_x, float)
        if x.size == 1:
            lo, hi = np.array([-np.inf]), np.array([np.inf])
        else:
            mid = 0.5 * (x[1:] + x[:-1])
            lo = np.concatenate(([x[0]], mid)) - center
            hi = np.concatenate((mid, [x[-1]])) - center
        self.lo, self.hi = lo, hi
        self.n = x.size
        self.nearest = int(np.argmin(np.abs(x - center)))
        self.half_spacing = math.inf if x.size == 1 else 0.5 * float(np.min(np.diff(x)))
        self.extent = (x[0] - center, x[-1] - center)
        self._point = np.zeros(self.n)
        self._point[self.nearest] = 1.0

    def shares(self, a: float) -> tuple[np.ndarray, np.ndarray]:
        """(s, ds/da), each of shape (p,)."""
        if a < self.half_spacing:
            return self._point, np.zeros(self.n)
        if -a < self.extent[0] - 1e-12 * a or a > self.extent[1] + 1e-12 * a:
            raise ContactOutgrewRoom(f"contact radius {a:.4g} m runs past the loadable surface nodes")
        lo, hi = np.clip(self.lo, -a, a), np.clip(self.hi, -a, a)
        w = math.pi / (2.0 * a)
        s = 0.5 * (np.sin(w * hi) - np.sin(w * lo))
        # d/da sin(π b/(2a)) = −cos(π b/(2a))·π b/(2a²); zero where b is clipped to ±a.
        ds = 0.5 * (-np.cos(w * hi) * w * hi + np.cos(w * lo) * w * lo) / a
        return s, ds


@dataclass(frozen=True)
class ImpactHistory:
    """Histories at t_k = k·dt (shape (steps + 1,) unless stated); SI; compression +."""

    time: np.ndarray
    force: np.ndarray  # contact force [N], compression +
    approach: np.ndarray
    approach_rate: np.ndarray
    contact_radius: np.ndarray  # of the pressed disc [m]; 0 where the force is zero (apart, or a clipped force with the bodies still overlapping)
    impactor_displacement: np.ndarray  # along the impact direction
    impactor_velocity: np.ndarray  # positive toward the structure
    target_displacement: np.ndarray  # w = approach_row·u
    strain: np.ndarray  # (n_out, steps + 1): the structure's output rows (gauge strains, then any output groups)
    structure_kinetic: np.ndarray  # ½vᵀMv (nan when energies were not asked for)
    structure_strain: np.ndarray  # ½uᵀKu
    structure_work: np.ndarray  # Σ½(f_k + f_{k+1})·Δu, work of the nodal contact forces
    contact_work: np.ndarray  # Σ½(F_k + F_{k+1})·Δα
    contact_energy: np.ndarray  # recoverable energy stored in the contact law
    surface_mismatch: np.ndarray  # structure_work − Σ½(F_k + F_{k+1})·Δw
    newton_iterations: int
    solves: int
    displacement: np.ndarray | None = None  # (n, n_kept): all DOFs at the steps ``kept`` (snapshots)
    kept: np.ndarray | None = None  # step indices of the columns of ``displacement``


def integrate_impact(
    structure: ContactStructure,
    law,
    mass: float,
    velocity: float,
    time_step: float,
    steps: int,
    newmark: NewmarkParameters = NewmarkParameters(),
    energy: bool = True,
    stepper: NewmarkStepper | None = None,
    stop_after: float | None = None,
    snapshots=(),
) -> ImpactHistory:
    """March the impactor and the structure together (module docstring): the direct stepper,
    :class:`softimpact.fem.direct.DirectStepper`, of the one coupled loop (:mod:`softimpact.fem.stepping`).

    Time zero is first contact: α = 0, impactor at ``velocity`` > 0 toward the
    structure, structure at rest. ``law``: a ContactLaw or a HistoryLaw.
    ``stepper``: a NewmarkStepper already factored for (M, K, C, dt) to reuse.
    ``stop_after``: stop this long [s] after the impactor has left for good
    (separated and moving away faster than the target point), else run ``steps``.
    ``snapshots``: step indices at which to keep the displacement of all DOFs
    (for figures of the deflected shape); those past an early stop are dropped.
    """
    from .direct import DirectStepper  # (it steps with this module's contact Newton: imported here, not above)

    return DirectStepper(
        structure, law, mass, velocity, time_step, steps, newmark, engine=stepper, stop_after=stop_after, energy=energy, snapshots=snapshots
    ).run()


class PatchCompliance:
    """h_s(r) = c·G·s(r) and dh_s/dr of a patch (``shares(r) -> (s, ds/dr)``, ``half_spacing``), by two
    dot products with the structure's response c·G to unit loads on the patch nodes."""

    value = None  # no cheaper h_s alone (:func:`newton_contact`): every iterate takes the full evaluation

    def __init__(self, patch, cG: np.ndarray):
        self.patch, self.half_spacing, self.cG = patch, float(patch.half_spacing), np.asarray(cG, float)

    def __call__(self, r: float) -> tuple[float, float]:
        s, ds = self.patch.shares(r)
        return float(self.cG @ s), float(self.cG @ ds)


@dataclass(frozen=True)
class LawCapabilities:
    """What the contact Newton may use of a memoryless law beyond :class:`ContactLaw` (its optional
    capabilities, declared in :mod:`softimpact.models.protocols`), asked once per run: ``responds``
    (:class:`RespondingLaw`: F, ∂F/∂α and ∂F/∂α̇ in one call) and ``radius_power`` n
    (:class:`PowerRadiusLaw`: a = c·α^n), None where the law has none."""

    responds: bool
    radius_power: float | None

    @classmethod
    def of(cls, law) -> LawCapabilities:
        """The capabilities ``law`` (a ContactLaw, or the branch of a HistoryLaw) declares."""
        return cls(isinstance(law, RespondingLaw), law.radius_power if isinstance(law, PowerRadiusLaw) else None)


def newton_contact(
    law,
    comp,
    hm: float,
    kappa: float,
    q: float,
    target: float,
    guess: float,
    index: int,
    dt: float,
    *,
    try_top: bool = False,
    caps: LawCapabilities | None = None,
):
    """Root of R(α) = α − α̃ + F(α, κα + q)·(β·dt²/m + h_s(a(α))) in (0, α̃] (module docstring) at step
    ``index``: Newton safeguarded by bisection on plain floats, the one contact iteration of every stepper.

    ``comp(r) -> (h_s, dh_s/dr)``: the patch compliance c·G·s(r), with ``comp.half_spacing`` and ``comp.value``
    (:mod:`softimpact.fem.compliance`). Where ``comp.value(r) -> h_s`` exists (the kernels' line patch; else
    None), iterates after the first full evaluation take the exact h_s from it and keep that evaluation's
    slope, which only shapes the Newton step; the residual R, which locates the root, is exact at every
    iterate. Starts from ``guess`` (α's linear extrapolation) when in the bracket, else α̃; ends at the first
    iterate whose Newton step is within the tolerance (its force and radius as evaluated), or at the midpoint
    of a bracket closed by bisection. ``caps``: the law's :class:`LawCapabilities` (asked here when None; a
    stepper asks once per run): with ``radius_power`` n, da/dα = n·a/α, else a central difference.
    ``try_top``: a Newton step landing exactly on α̃ is tried once (an iterate where the force is clipped to
    zero steps there; the root is there when it stays zero) instead of bisecting (the kernels take it; direct
    stepping keeps the plain bracket test, so its iteration counts in summary.json do not move). Returns (α,
    F, contact radius — 0 where F is — iterations); :class:`SolverFailed` (time, step, residual and
    bracket) after :data:`NEWTON_MAXITER` iterations."""
    # One function on purpose (91 lines, most of them the docstring): it runs at every step of every coupled
    # run, and its iterate's state (bracket, slope, force, radius) lives in plain locals; split into calls, the
    # kernels' millisecond runs would pay a Python call and a tuple per iterate.
    lo, hi = 0.0, target
    a = guess if 0.0 < guess < target else target
    half = comp.half_spacing
    its = 0
    R = math.nan
    top = False  # α̃ evaluated
    caps = caps or LawCapabilities.of(law)
    response = law.response if caps.responds else None  # (F, ∂F/∂α, ∂F/∂α̇) at once, where the law offers it
    power = caps.radius_power  # a = c·α^n: da/dα = n·a/α exactly (else a central difference)
    value = comp.value  # h_s(r) alone, where the patch offers it
    slope = None  # dh_s/dr of the last full evaluation
    for its in range(1, NEWTON_MAXITER + 1):  # noqa: B007 (the count is returned after the loop)
        rate = kappa * a + q
        if response is not None:
            f, stiff, damp = response(a, rate)
        else:
            f = law.force(a, rate)
            stiff, damp = law.stiffness(a, rate), law.damping(a, rate)
        r = law.radius(a)
        # h_s enters only multiplied by F, ∂F/∂α, ∂F/∂α̇: not evaluated where all three vanish (a clipped force)
        if f == 0.0 and stiff == 0.0 and damp == 0.0:
            hs = 0.0
        elif value is not None and slope is not None:
            hs = value(r)  # exact; its slope kept from an earlier iterate (a nearby r: the step estimate only)
        else:
            hs, slope = comp(r)
        dhs = 0.0 if slope is None else slope
        h = hm + hs
        R = a - target + f * h
        if R > 0.0:
            hi = a
        else:
            lo = a
        dR = 1.0 + (stiff + kappa * damp) * h
        if f != 0.0 and r >= half:
            if power is not None:
                dr = power * r / a
            else:
                da = RADIUS_STEP * a
                dr = (law.radius(a + da) - law.radius(a - da)) / (2.0 * da)
            dR += f * dhs * dr
        step = R / dR
        if abs(step) <= NEWTON_TOL * target:
            return a, float(f), r if f != 0.0 else 0.0, its  # this iterate is the root within the tolerance: its force and disc
        top = top or a == target
        a_next = a - step
        # a step onto α̃ itself (an iterate where the force is clipped to zero steps there: R = α − α̃)
        # tries that bracket end once, where the root lies when the clipped force is zero there
        if not (lo < a_next < hi or (try_top and a_next == target and not top and lo < a_next)):
            a_next = 0.5 * (lo + hi)  # bisection safeguard
            if hi - lo <= NEWTON_TOL * target:
                a = a_next
                break
        a = a_next
    else:
        raise SolverFailed(
            f"the contact Newton iteration did not converge at t = {index * dt:.6g} s (step {index}) in {NEWTON_MAXITER} iterations: "
            f"residual {R:.3g} m, approach bracket [{lo:.6g}, {hi:.6g}] m"
        )
    f = float(law.force(a, kappa * a + q))  # the bracket closed: its midpoint
    return a, f, law.radius(a) if f != 0.0 else 0.0, its


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
class CoupledResult:
    """Histories (time on the last axis) and first-contact scalars; SI, compression +."""

    impactor: Impactor
    time: np.ndarray
    force: np.ndarray  # contact force [N], compression +
    impactor_velocity: np.ndarray  # positive toward the structure
    impactor_displacement: np.ndarray
    approach: np.ndarray
    approach_rate: np.ndarray
    contact_radius: np.ndarray  # of the pressed disc [m]; 0 where the force is zero
    target_displacement: np.ndarray  # (n,) m, mid-surface under the impact point, along the impact direction (into the target +)
    strain: np.ndarray  # (n_outputs, n): the structure's output rows (gauge strains)
    strain_names: tuple[str, ...]  # names of the rows of ``strain``
    energies: Energies
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
    groups: dict[str, tuple[tuple[str, ...], np.ndarray]] | None = None  # output groups besides the gauges: name → (row names, (n_rows, n))

    @property
    def total_impulse(self) -> float:
        """∫F dt over the run (trapezoid, the rule of the integration) [N·s]."""
        return float(np.sum(0.5 * (self.force[1:] + self.force[:-1])) * (self.time[1] - self.time[0]))

    @property
    def separated(self) -> bool:
        """The first contact ended within the run."""
        return math.isfinite(self.contact_duration)


def refine_peak(t: np.ndarray, y: np.ndarray, k: int | None = None) -> tuple[float, float]:
    """(peak, time) of sampled y(t) at its largest sample (or at index ``k``), refined by the
    parabola through that sample and its neighbours (offset |s| ≤ ½ sample)."""
    if k is None:
        k = int(np.argmax(y))
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
        pk, tp = refine_peak(ts, Fs)
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
    return coupled_result(h, impactor, tuple(structure.output_names))


def coupled_result(h: ImpactHistory, impactor: Impactor, strain_names: tuple[str, ...]) -> CoupledResult:
    """The :class:`CoupledResult` of histories ``h`` (direct stepping, :func:`integrate_impact`, or
    contact kernels, :class:`softimpact.fem.kernels.ContactKernels`): contact intervals (one
    separation rule), first-contact scalars and the energy terms."""
    t, F, al = h.time, h.force, h.approach
    contacts = contact_intervals(t, F, al)
    first = contacts[0]
    rebound = math.nan
    if math.isfinite(first.end):
        k = int(np.searchsorted(t, first.end))  # first sample after separation: F = 0 there
        rebound = float(h.impactor_velocity[min(k, len(t) - 1)])
    energies = Energies(
        step=np.arange(t.size),
        kinetic=h.structure_kinetic,
        strain=h.structure_strain,
        work=h.structure_work,
        impactor_kinetic=0.5 * impactor.mass * h.impactor_velocity**2,
        contact_work=h.contact_work,
        contact_energy=h.contact_energy,
        surface_mismatch=h.surface_mismatch,
    )
    return CoupledResult(
        impactor=impactor,
        time=t,
        force=F,
        impactor_velocity=h.impactor_velocity,
        impactor_displacement=h.impactor_displacement,
        approach=al,
        approach_rate=h.approach_rate,
        contact_radius=h.contact_radius,
        target_displacement=h.target_displacement,
        strain=h.strain,
        strain_names=tuple(strain_names),
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
