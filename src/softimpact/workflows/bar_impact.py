"""Longitudinal impact of a sphere on an instrumented, free–free bar (paper Figs 4–6).

The bar is the Hermite rod of :mod:`softimpact.fem.bar`; the impactor a lumped
mass m joined to the struck end by a contact law F(α), α = x_impactor − u(0)
(eqs 1–3). Both are integrated together by Newmark's implicit method with a
Newton iteration on the contact force at each step. Time zero is first contact:
α(0) = 0, the impactor moving at V toward the bar, which is at rest.

Because the contact acts on one DOF of a linear bar, each step reduces to one
scalar equation. The bar's end displacement is the discrete convolution of the
force history with the end's Newmark impulse response h (computed once, see
:mod:`softimpact.fem.response`): u0 = ũ0 + h0·F, where ũ0 is the part due to the
forces of earlier steps. With the impactor x = x̃ − β·dt²·F/m, the approach solves

    α + c·F(α) = α̃,   c = β·dt²/m + g0,

which Newton's method solves to round-off from α = α̃, where F(α) ≥ 0 makes
α ≤ α̃ and the convex left side makes the iteration monotone. Contact opens
(F = 0) whenever α̃ ≤ 0 and closes again by itself if the bar end comes back.

Sign conventions: compressive contact force positive; strain tension positive,
so the incident compressive pulse gives negative gauge strain.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..errors import InputError
from ..fem.bar import Rod, assemble_rod
from ..fem.newmark import NewmarkStepper, SolverSpec
from ..fem.response import ImpulseResponse
from ..models.contact import Hertz
from ..models.specimens import BarSpec, Gauge, Projectile

__all__ = [
    "CONTACT_LAWS",
    "BarImpactProblem",
    "BarImpactResult",
    "BarForceResult",
    "simulate_impact",
    "simulate_force",
    "refine_peak",
    "without_end_cap",
    "force_from_gauge",
    "check_problem",
]

CONTACT_LAWS = ("hertz", "hertz-unloading", "hunt-crossley", "identified")  # laws of the impactor–bar contact
NEWTON_TOL = 1e-13  # relative tolerance on the approach α in the contact Newton iteration
NEWTON_MAXITER = 50  # the monotone Newton converges in < 10; this only guards bugs
MIN_ELEMENTS_PER_PULSE = (2.0, 6.0)  # elements per contact pulse length c·T_c: floor, comfortable (paper: 14)
MIN_STEPS_PER_CONTACT = (10.0, 20.0)  # time steps per contact duration T_c: floor, comfortable (paper: 132)


@dataclass(frozen=True)
class BarImpactProblem:
    """Everything that defines a bar impact run (SI)."""

    bar: BarSpec
    projectile: Projectile
    solver: SolverSpec
    gauges: tuple[Gauge, ...]
    contact: str = "hertz"
    title: str = ""
    units: str = "in-lbf-s"
    snapshots: tuple[float, ...] = ()  # instants [s] at which the strain along the bar is reported (those in the run)
    law: object = None  # the contact law object (models.contact_laws) of any law but the default "hertz"

    def __post_init__(self):
        for g in self.gauges:
            if not (0.0 <= g.position <= self.bar.length):
                raise InputError(f"gauge {g.name!r}: position {g.position!r} m is outside the bar (length {self.bar.length!r} m)", "gauges")
        if self.contact not in CONTACT_LAWS:
            raise InputError(f"unknown contact law {self.contact!r} (known: {', '.join(CONTACT_LAWS)})", "contact")
        if (self.law is None) != (self.contact == "hertz"):
            raise InputError(f"contact law {self.contact!r} needs its law object (and 'hertz' none)", "contact")

    def contact_law(self) -> Hertz:
        """Eq (3): the sphere on the flat end of the bar (or of the end cap)."""
        target = self.bar.material if self.bar.end_cap is None else self.bar.end_cap.material
        return Hertz.sphere_on_flat(self.projectile.diameter / 2.0, self.projectile.material, target)


@dataclass(frozen=True)
class Energies:
    """Energy terms [J] at each step, shape (n_steps + 1,)."""

    impactor_kinetic: np.ndarray
    bar_kinetic: np.ndarray
    bar_strain: np.ndarray
    contact: np.ndarray

    @property
    def total(self) -> np.ndarray:
        return self.impactor_kinetic + self.bar_kinetic + self.bar_strain + self.contact


@dataclass(frozen=True)
class BarImpactResult:
    """Histories (time on the last axis) and pulse scalars of a bar impact run."""

    problem: BarImpactProblem
    time: np.ndarray  # (n,) s, zero at first contact
    contact_force: np.ndarray  # (n,) N, compression positive
    approach: np.ndarray  # (n,) m
    impactor_displacement: np.ndarray  # (n,) m
    impactor_velocity: np.ndarray  # (n,) m/s, positive toward the bar
    gauge_strain: np.ndarray  # (n_gauges, n), tension positive
    bar_x: np.ndarray  # (n_x,) m, where the strain field is sampled
    bar_strain: np.ndarray  # (n_x, n)
    energies: Energies
    peak_force: float
    time_of_peak: float
    contact_duration: float  # nan if the impactor has not separated by the end of the run
    impulse: float  # ∫F dt over the run, N·s
    rebound_velocity: float  # impactor velocity after separation, positive toward the bar; nan if no separation
    contacts: int  # number of separate contact intervals
    newton_iterations: int

    @property
    def separated(self) -> bool:
        return math.isfinite(self.contact_duration)


@dataclass(frozen=True)
class BarForceResult:
    """Bar response to a prescribed end force."""

    time: np.ndarray
    force: np.ndarray
    gauge_strain: np.ndarray  # (n_gauges, n)
    bar_x: np.ndarray
    bar_strain: np.ndarray  # (n_x, n)


def refine_peak(t: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    """Peak of sampled y(t) refined by the parabola through the largest sample and its neighbours."""
    k = int(np.argmax(y))
    if k == 0 or k == len(y) - 1:
        return float(y[k]), float(t[k])
    y0, y1, y2 = y[k - 1], y[k], y[k + 1]
    denom = y0 - 2.0 * y1 + y2
    if denom >= 0:
        return float(y1), float(t[k])
    s = 0.5 * (y0 - y2) / denom  # offset in samples, |s| ≤ 1/2
    dt = t[k + 1] - t[k]
    return float(y1 - 0.25 * (y0 - y2) * s), float(t[k] + s * dt)


def _field_points(rod: Rod, per_element: int = 4) -> np.ndarray:
    return np.linspace(0.0, rod.length, rod.elements * per_element + 1)


def simulate_impact(problem: BarImpactProblem) -> BarImpactResult:
    """Run the coupled impactor–bar Newmark integration (see module docstring).

    Laws other than the default Hertz (``problem.law``) go through the general
    coupled stepping of :func:`softimpact.fem.impact.integrate_impact`, the
    same Newmark rule with the law's rate and memory.
    """
    if problem.law is not None:
        return _simulate_with_law(problem)
    rod = problem.bar.rod()
    model = assemble_rod(rod)
    solver = problem.solver
    dt, steps = solver.time_step, solver.steps
    beta = solver.newmark.beta
    gamma = solver.newmark.gamma
    stepper = NewmarkStepper(model.M, model.K, dt, params=solver.newmark)
    law = problem.contact_law()
    m, V = problem.projectile.mass, problem.projectile.velocity

    e0 = np.zeros(model.n)
    e0[model.end_dof] = 1.0
    # The bar is linear: its end displacement is a convolution of the contact force
    # history with the end's impulse response (fem/response.py).
    engine = ImpulseResponse(stepper, e0, steps, velocity_outputs=True)
    h_end = engine.kernel[model.end_dof, 0, :]
    h_rev = h_end[::-1].copy()
    c = float(beta * dt * dt / m + h_end[0])
    force, stiffness = law.force, law.stiffness

    x = np.zeros(steps + 1)
    xv = np.zeros(steps + 1)
    xa = np.zeros(steps + 1)
    F = np.zeros(steps + 1)
    alpha = np.zeros(steps + 1)
    xv[0] = V
    iterations = 0
    for k in range(steps):
        # End displacement at step k+1 from the forces already known (steps 1..k).
        u_past = float(np.dot(h_rev[steps - 1 - k : steps - 1], F[1 : k + 1])) if k else 0.0
        x_pred = x[k] + dt * xv[k] + dt * dt * (0.5 - beta) * xa[k]
        target = x_pred - u_past
        al, f = target, 0.0
        if target > 0.0:
            for _ in range(NEWTON_MAXITER):
                iterations += 1
                step = (al + c * force(al) - target) / (1.0 + c * stiffness(al))
                al -= step
                if abs(step) <= NEWTON_TOL * target:
                    break
            else:
                raise RuntimeError(f"contact Newton iteration did not converge at step {k + 1}")
            f = force(al)
        F[k + 1], alpha[k + 1] = f, al
        x[k + 1] = x_pred - beta * dt * dt * f / m
        xa[k + 1] = -f / m
        xv[k + 1] = xv[k] + dt * ((1.0 - gamma) * xa[k] + gamma * xa[k + 1])
    u = engine.respond(F)
    v = engine.respond(F, velocity=True)

    t = np.arange(steps + 1) * dt
    gauges = problem.gauges
    P = model.strain_probe(np.array([gg.position for gg in gauges])).toarray() if gauges else None
    gauge_strain = P @ u if P is not None else np.zeros((0, steps + 1))
    bar_x = _field_points(rod)
    bar_strain = model.strain_probe(bar_x).toarray() @ u

    M, K = model.M.toarray(), model.K.toarray()  # 80 DOFs: dense products are fastest
    energies = Energies(
        impactor_kinetic=0.5 * m * xv**2,
        bar_kinetic=0.5 * np.einsum("it,it->t", v, M @ v),
        bar_strain=0.5 * np.einsum("it,it->t", u, K @ u),
        contact=law.energy(alpha),
    )

    peak, t_peak = refine_peak(t, F)
    in_contact = alpha > 0.0
    in_contact[0] = True  # first contact is at t = 0 by definition (α = 0, closing)
    contacts = 1 + np.count_nonzero(in_contact[1:] & ~in_contact[:-1])
    ends = np.flatnonzero(in_contact[:-1] & ~in_contact[1:])
    duration = math.nan
    rebound = math.nan
    if len(ends):
        k = int(ends[0])  # alpha[k] > 0 >= alpha[k+1]; the first separation
        duration = float(t[k] + dt * alpha[k] / (alpha[k] - alpha[k + 1]))
        rebound = float(xv[k + 1])
    return BarImpactResult(
        problem=problem,
        time=t,
        contact_force=F,
        approach=alpha,
        impactor_displacement=x,
        impactor_velocity=xv,
        gauge_strain=gauge_strain,
        bar_x=bar_x,
        bar_strain=bar_strain,
        energies=energies,
        peak_force=peak,
        time_of_peak=t_peak,
        contact_duration=duration,
        impulse=float(np.trapezoid(F, t)),
        rebound_velocity=rebound,
        contacts=contacts,
        newton_iterations=iterations,
    )


def _simulate_with_law(problem: BarImpactProblem) -> BarImpactResult:
    """simulate_impact for any contact law, by fem.impact's coupled stepping on the same rod."""
    from ..fem.impact import ContactStructure, integrate_impact

    rod = problem.bar.rod()
    model = assemble_rod(rod)
    solver = problem.solver
    dt, steps = solver.time_step, solver.steps
    m, V = problem.projectile.mass, problem.projectile.velocity
    gauges = problem.gauges
    bar_x = _field_points(rod)
    probes = [model.strain_probe(np.array([g.position for g in gauges])).toarray()] if gauges else []
    outputs = np.vstack(probes + [model.strain_probe(bar_x).toarray()])
    end = np.zeros(model.n)
    end[model.end_dof] = 1.0
    structure = ContactStructure(model.M, model.K, np.array([0.0]), np.array([model.end_dof]), 1.0, 0.0, end, outputs)
    stepper = NewmarkStepper(model.M, model.K, dt, params=solver.newmark)
    h = integrate_impact(structure, problem.law, m, V, dt, steps, newmark=solver.newmark, stepper=stepper)
    t, F, alpha, xv = h.time, h.contact_force, h.approach, h.impactor_velocity
    ng = len(gauges)
    energies = Energies(0.5 * m * xv**2, h.structure_kinetic, h.structure_strain, h.contact_energy)
    peak, t_peak = refine_peak(t, F)
    on = F > 0.0
    on[0] = True  # first contact is at t = 0 by definition
    contacts = 1 + np.count_nonzero(on[1:] & ~on[:-1])
    ends = np.flatnonzero(on[:-1] & ~on[1:])
    duration = rebound = math.nan
    if len(ends):
        k = int(ends[0])  # F[k] > 0 = F[k+1]: the first separation, at α's zero crossing when it is in the step
        a0, a1 = alpha[k], alpha[k + 1]
        # a law clipped at F = 0 (a rate term) may let go before α reaches zero: then at t[k+1]
        duration = float(t[k] + dt * a0 / (a0 - a1)) if a0 > 0.0 >= a1 else float(t[k + 1])
        rebound = float(xv[k + 1])
    return BarImpactResult(
        problem=problem,
        time=t,
        contact_force=F,
        approach=alpha,
        impactor_displacement=h.impactor_displacement,
        impactor_velocity=xv,
        gauge_strain=h.outputs[:ng],
        bar_x=bar_x,
        bar_strain=h.outputs[ng:],
        energies=energies,
        peak_force=peak,
        time_of_peak=t_peak,
        contact_duration=duration,
        impulse=float(np.trapezoid(F, t)),
        rebound_velocity=rebound,
        contacts=contacts,
        newton_iterations=h.newton_iterations,
    )


def simulate_force(bar: BarSpec, solver: SolverSpec, gauges, force) -> BarForceResult:
    """Bar response to a prescribed compressive end force.

    ``force`` is a callable F(t) [N] (a pulse) or an array of F at the
    solver's time steps, shape (n_steps + 1,).
    """
    rod = bar.rod()
    model = assemble_rod(rod)
    dt, steps = solver.time_step, solver.steps
    t = np.arange(steps + 1) * dt
    f = np.asarray(force(t) if callable(force) else force, dtype=float)
    if f.shape != t.shape:
        raise InputError(f"force history has {f.shape} samples, expected {t.shape}")
    for gg in gauges:
        if not 0.0 <= gg.position <= bar.length:
            raise InputError(f"gauge {gg.name!r}: position {gg.position!r} m is outside the bar (length {bar.length!r} m)", "gauges")
    stepper = NewmarkStepper(model.M, model.K, dt, params=solver.newmark)
    e0 = np.zeros(model.n)
    e0[model.end_dof] = 1.0
    u, _, _ = stepper.run(np.outer(e0, f))
    gauge_strain = model.strain_probe([gg.position for gg in gauges]) @ u if gauges else np.zeros((0, t.size))
    bar_x = _field_points(rod)
    return BarForceResult(t, f, gauge_strain, bar_x, model.strain_probe(bar_x) @ u)


def force_from_gauge(result: BarImpactResult, gauge_index: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """F(t) = −EA·ε(t + x/c): the force at the struck end read from a gauge (paper, Fig 5).

    Returns (time, force) on the result's grid, NaN where t + x/c is past the record.
    """
    bar = result.problem.bar
    rod = bar.rod()
    x = result.problem.gauges[gauge_index].position
    t = result.time
    shifted = np.interp(t + x / rod.wave_speed, t, result.gauge_strain[gauge_index], right=np.nan)
    return t, -rod.axial_stiffness * shifted


def without_end_cap(problem: BarImpactProblem) -> BarImpactProblem:
    """The same problem on the plain bar (for the comparison of Fig 5)."""
    return replace(problem, bar=replace(problem.bar, end_cap=None))


def check_problem(problem: BarImpactProblem) -> None:
    """Refuse, before anything is built, a run that is too coarse to mean anything or too big for the machine.

    The contact duration T_c is estimated by Hertz's rigid-wall closed form
    (the bar's compliance only lengthens it, so the checks err on the safe
    side). Resolution: elements per pulse length c·T_c/h and time steps per
    T_c (:data:`MIN_ELEMENTS_PER_PULSE`, :data:`MIN_STEPS_PER_CONTACT`; an
    InputError naming ``elements`` or ``time_step``, or a warning). Resources:
    the dense mass, stiffness and strain-probe matrices (n² with n = 2(e + 1)
    Hermite DOFs) and the histories of n DOFs over the run.
    """
    from ..guards import require_resolution, require_resources

    e, steps = problem.bar.elements, problem.solver.steps
    n = 2 * (e + 1)
    n_x = 4 * e + 1
    memory = 8.0 * (2 * n * n + n_x * n + 4 * n * (steps + 1) + n_x * (steps + 1))
    flops = 4.0 * n * n * (steps + 1) + 0.5 * steps * steps
    require_resources(f"a bar of {e} elements over {steps} steps", memory, flops)
    law = problem.contact_law()
    try:
        *_, duration = law.rigid_impact(problem.projectile.mass, problem.projectile.velocity)
    except ValueError:
        return
    wave = problem.bar.rod().wave_speed * duration
    require_resolution(
        "elements per contact pulse length",
        wave / (problem.bar.length / e),
        *MIN_ELEMENTS_PER_PULSE,
        f"the pulse ({duration * 1e6:.3g} us long) spans {wave:.3g} m of bar: the bar needs at least {math.ceil(MIN_ELEMENTS_PER_PULSE[0] * problem.bar.length / wave)} elements "
        f"({math.ceil(MIN_ELEMENTS_PER_PULSE[1] * problem.bar.length / wave)} advised)",
        "elements",
    )
    require_resolution(
        "time steps per contact duration",
        duration / problem.solver.time_step,
        *MIN_STEPS_PER_CONTACT,
        f"contact lasts about {duration * 1e6:.3g} us; use a time step of at most {duration / MIN_STEPS_PER_CONTACT[0] * 1e6:.3g} us "
        f"({duration / MIN_STEPS_PER_CONTACT[1] * 1e6:.3g} us advised)",
        "time_step",
    )
