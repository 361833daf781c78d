"""Longitudinal impact of a sphere on an instrumented, free–free bar (paper Figs 4–6).

The bar is the Hermite rod of :mod:`softimpact.fem.bar`; the impactor a lumped
mass m joined to the struck end by a contact law F(α), α = x_impactor − u(0)
(eqs 1–3 for the default Hertz law). Both are integrated together by the one
coupled stepper of :mod:`softimpact.fem.impact` (Newmark on the rod, Newton on
the scalar contact equation each step), as for a beam or a plate. Time zero is
first contact: α(0) = 0, the impactor moving at V toward the bar, which is at rest.

Sign conventions: compressive contact force positive; strain tension positive,
so the incident compressive pulse gives negative gauge strain.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..errors import InputError
from ..fem.bar import BarModel, Rod
from ..fem.impact import CoupledResult, simulate_coupled
from ..fem.newmark import SolverSpec
from ..models.contact_laws import HertzLaw, law_name, resolve_law
from ..models.specimens import BarSpec, Gauge, Impactor

__all__ = [
    "BarImpactProblem",
    "BarImpactResult",
    "BarForceResult",
    "simulate_impact",
    "simulate_force",
    "without_end_cap",
    "force_from_gauge",
    "check_problem",
]

MIN_ELEMENTS_PER_PULSE = (2.0, 6.0)  # elements per contact pulse length c·T_c: floor, comfortable (paper: 14)
MIN_STEPS_PER_CONTACT = (10.0, 20.0)  # time steps per contact duration T_c: floor, comfortable (paper: 132)


@dataclass(frozen=True)
class BarImpactProblem:
    """Everything that defines a bar impact run (SI). ``law``: a name of
    :data:`softimpact.models.contact_laws.CONTACT_LAWS` ("hertz", the sphere on the bar's end) or a
    contact law object (:func:`softimpact.models.contact_laws.resolve_law`)."""

    bar: BarSpec
    projectile: Impactor  # the sphere, with its material (the Hertz law on the bar's end needs it)
    solver: SolverSpec
    gauges: tuple[Gauge, ...]
    law: object = "hertz"
    title: str = ""
    snapshots: tuple[float, ...] = ()  # instants [s] at which the strain along the bar is reported (those in the run)

    def __post_init__(self):
        for g in self.gauges:
            if not (0.0 <= g.position <= self.bar.length):
                raise InputError(f"gauge {g.name!r}: position {g.position!r} m is outside the bar (length {self.bar.length!r} m)", "gauges")
        self.contact_law()  # a name or an object, resolved (and refused) here

    def with_solver(self, solver: SolverSpec) -> BarImpactProblem:
        """This problem stepped by ``solver`` (a one-factor refinement swaps the time step alone)."""
        return replace(self, solver=solver)

    def hertz(self) -> HertzLaw:
        """Eq (3): the sphere on the flat end of the bar (or of the end cap)."""
        target = self.bar.material if self.bar.end_cap is None else self.bar.end_cap.material
        return HertzLaw.sphere_on_flat(self.projectile.diameter / 2.0, self.projectile.material, target)

    def contact_law(self):
        """The contact law of the run: ``law`` resolved (a name: the sphere on the bar's end)."""
        return resolve_law(self.law, self.hertz)

    @property
    def law_name(self) -> str:
        return law_name(self.law)


@dataclass(frozen=True)
class BarImpactResult(CoupledResult):
    """A coupled result (:class:`softimpact.fem.impact.CoupledResult`: histories with time on the last
    axis, first-contact scalars) of a bar run, with the problem and the strain along the bar."""

    problem: BarImpactProblem | None = None
    bar_x: np.ndarray | None = None  # (n_x,) m, where the strain field is sampled
    bar_strain: np.ndarray | None = None  # (n_x, n)


@dataclass(frozen=True)
class BarForceResult:
    """Bar response to a prescribed end force."""

    time: np.ndarray
    force: np.ndarray
    strain: np.ndarray  # (n_gauges, n)
    bar_x: np.ndarray
    bar_strain: np.ndarray  # (n_x, n)


def simulate_impact(problem: BarImpactProblem) -> BarImpactResult:
    """Run the coupled impactor–bar integration (module docstring) with the problem's contact law."""
    p = problem.projectile
    model = BarModel(Rod.of(problem.bar), problem.solver, [g.position for g in problem.gauges])
    r = simulate_coupled(model.contact_structure(), problem.contact_law(), Impactor(p.mass, p.diameter, p.velocity), problem.solver, stepper=model.stepper)
    ng = len(problem.gauges)
    fields = {f.name: getattr(r, f.name) for f in CoupledResult.__dataclass_fields__.values()}
    fields.update(strain=r.strain[:ng], strain_names=tuple(g.name for g in problem.gauges))
    return BarImpactResult(**fields, problem=problem, bar_x=model.field, bar_strain=r.strain[ng:])


def simulate_force(bar: BarSpec, solver: SolverSpec, gauges, force) -> BarForceResult:
    """Bar response to a prescribed compressive end force.

    ``force`` is a callable F(t) [N] (a pulse) or an array of F at the
    solver's time steps, shape (n_steps + 1,).
    """
    t = solver.times()
    f = np.asarray(force(t) if callable(force) else force, dtype=float)
    if f.shape != t.shape:
        raise InputError(f"force history has {f.shape} samples, expected {t.shape}")
    for gg in gauges:
        if not 0.0 <= gg.position <= bar.length:
            raise InputError(f"gauge {gg.name!r}: position {gg.position!r} m is outside the bar (length {bar.length!r} m)", "gauges")
    model = BarModel(Rod.of(bar), solver, [gg.position for gg in gauges])
    y, _, _ = model.march(f, energy=False)
    return BarForceResult(t, f, y[: len(gauges)], model.field, y[len(gauges) :])


def force_from_gauge(result: BarImpactResult, gauge_index: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """F(t) = −EA·ε(t + x/c): the force at the struck end read from a gauge (paper, Fig 5).

    Returns (time, force) on the result's grid, NaN where t + x/c is past the record.
    """
    rod = Rod.of(result.problem.bar)
    x = result.problem.gauges[gauge_index].position
    t = result.time
    shifted = np.interp(t + x / rod.wave_speed, t, result.strain[gauge_index], right=np.nan)
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
    law = problem.hertz()
    try:
        *_, duration = law.rigid_impact(problem.projectile.mass, problem.projectile.velocity)
    except ValueError:
        return
    wave = Rod.of(problem.bar).wave_speed * duration
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
