"""The pluggable parts of softimpact, named once (:class:`typing.Protocol`, runtime-checkable).

- :class:`ContactLaw` — a memoryless contact law: the approach α [m] (positive when the
  bodies overlap) and its rate α̇ [m/s] to a compressive force F ≥ 0 [N]
  (:mod:`softimpact.models.contact_laws`).
- :class:`HistoryLaw` — a contact law with memory, kept in an explicit frozen state.
- A law's optional capabilities, each a small protocol a law has by having its members (the coupled
  steppers, :mod:`softimpact.fem.stepping`, ask ``isinstance`` once per run, never probe a law):
  :class:`RespondingLaw` (F, ∂F/∂α, ∂F/∂α̇ in one call), :class:`PowerRadiusLaw` (a = c·α^n),
  :class:`StepBoundLaw` (memory that evolves in time, bound to the solver's step) and
  :class:`SettlingLaw` (a history law's converged step and free flight in one call each).
- :class:`Pulse` — a force history F(t) [N] of a given impulse and duration
  (:mod:`softimpact.models.pulses`).
- :class:`ContactPatch` — how a unit contact force of half-width a [m] is shared among
  the loadable surface nodes: ``shares(a) -> (s, ds/da)``, each (p,), Σ s = 1
  (:class:`softimpact.fem.impact.ContactPatch`, :class:`softimpact.fem.plate_loads.DiscShares`).
- :class:`StructureModel` — a linear structure ready for a run at one time step
  (:class:`softimpact.fem.linear.LinearModel`: the bar's rod, the plane beam, the plate).

Objects satisfy a protocol by having its methods; nothing here imports fem.
"""

from __future__ import annotations

from typing import Protocol, runtime_checkable

import numpy as np

__all__ = [
    "ContactLaw",
    "HistoryLaw",
    "RespondingLaw",
    "PowerRadiusLaw",
    "StepBoundLaw",
    "EnvelopedLaw",
    "SettlingLaw",
    "Pulse",
    "ContactPatch",
    "StructureModel",
    "MeshedModel",
]


@runtime_checkable
class ContactLaw(Protocol):
    """A memoryless contact law; SI scalars in and out, F = 0 for α ≤ 0 (no tension).

    ``force`` F [N], ``stiffness`` ∂F/∂α [N/m] (Newton's tangent), ``damping`` ∂F/∂α̇ [N·s/m]
    (zero for rate-independent laws), ``radius`` the contact radius a [m], ``energy`` the
    recoverable energy stored at α [J].
    """

    def force(self, alpha: float, rate: float = 0.0) -> float: ...

    def stiffness(self, alpha: float, rate: float = 0.0) -> float: ...

    def damping(self, alpha: float, rate: float = 0.0) -> float: ...

    def radius(self, alpha: float) -> float: ...

    def energy(self, alpha: float) -> float: ...


@runtime_checkable
class HistoryLaw(Protocol):
    """A law with memory: ``initial_state()``; ``branch(state)``, the memoryless law valid within
    one step; ``advance(state, alpha, rate)``, the state after a converged step. Nothing mutates."""

    def initial_state(self): ...

    def branch(self, state) -> ContactLaw: ...

    def advance(self, state, alpha: float, rate: float): ...


# A law's optional capabilities. Why small protocols rather than optional members of ContactLaw or a
# ``capabilities`` attribute: a law written as five plain methods stays a ContactLaw (nothing to declare,
# ``resolve_law`` accepts it as before), a capability is stated by the members that provide it (a type
# checker verifies them where a law subclasses the protocol), and the steppers ask ``isinstance`` once
# per run instead of reading attributes that may be missing. For a HistoryLaw the capabilities of
# :class:`ContactLaw` are those of its branches: every branch of one law is of one class.


@runtime_checkable
class RespondingLaw(Protocol):
    """``response(alpha, rate) -> (F [N], ∂F/∂α [N/m], ∂F/∂α̇ [N·s/m])``: the values of ``force``,
    ``stiffness`` and ``damping`` in one call (one evaluation of a power law; the contact Newton's need)."""

    def response(self, alpha: float, rate: float = 0.0) -> tuple[float, float, float]: ...


@runtime_checkable
class PowerRadiusLaw(Protocol):
    """A contact radius a = c·α^n: ``radius_power`` n, so that da/dα = n·a/α exactly (without it the
    contact Newton takes a central difference of ``radius``)."""

    radius_power: float


@runtime_checkable
class StepBoundLaw(Protocol):
    """A law whose memory evolves in time: ``for_time_step(dt)`` [s], the same law bound to the solver's
    step, called once before stepping."""

    def for_time_step(self, dt: float): ...


@runtime_checkable
class EnvelopedLaw(Protocol):
    """A law with its own validity envelope beyond the approach and contact radius every law is checked on:
    ``validity(velocity) -> Validity`` (:mod:`softimpact.models.validity`) at the run's impact velocity [m/s]
    (the crushing law's strain rate, the hydrodynamic law's shock release)."""

    def validity(self, velocity: float): ...


@runtime_checkable
class SettlingLaw(Protocol):
    """A :class:`HistoryLaw` that does a step's bookkeeping in one call, the same arithmetic as the
    general path: ``settle(state, alpha, rate) -> (advance(state, α, α̇), branch of it, the contact
    energy at the end of the step [J], the step's own branch's ``energy(α)``)``; ``apart(state, steps)
    -> (state, energies)``: ``steps`` steps with the bodies apart (α ≤ 0), the energy after each."""

    def settle(self, state, alpha: float, rate: float) -> tuple[object, ContactLaw, float]: ...

    def apart(self, state, steps: int) -> tuple[object, list[float]]: ...


@runtime_checkable
class Pulse(Protocol):
    """A force history: ``pulse(t)`` [N] for t [s] (scalar or array), its ``impulse`` ∫F dt [N·s],
    ``duration`` [s] and ``time_of_peak`` [s] (where F is largest: the end of its rise)."""

    def __call__(self, t): ...

    @property
    def impulse(self) -> float: ...

    @property
    def duration(self) -> float: ...

    @property
    def time_of_peak(self) -> float: ...


@runtime_checkable
class ContactPatch(Protocol):
    """Shares of a unit contact force of half-width a [m] among the p loadable nodes:
    ``shares(a) -> (s, ds/da)``, shapes (p,), Σ s = 1; ``half_spacing`` [m]: below it the nearest
    node takes all of the force."""

    half_spacing: float

    def shares(self, a: float) -> tuple[np.ndarray, np.ndarray]: ...


@runtime_checkable
class StructureModel(Protocol):
    """A linear structure M·ü + C·u̇ + K·u = B·f(t) at one time step (SI, n = ``size`` DOFs).

    ``M``, ``K`` (n, n), ``C`` (n, n) or None; ``stepper`` the Newmark stepper factored once for
    (model, dt); ``O`` (n_out, n) the output rows; ``nodal_loads(force, radius)`` the patch loads
    (p, n_t) of a force history; ``engine()`` the response engine (impulse responses of the
    outputs, built once); ``respond`` and ``direct`` the same outputs through the engine or by
    stepping every DOF (with energies); ``contact_structure(point, reach)`` the structure as
    the coupled stepper sees it; ``for_workers()`` a light copy that pickles small. A beam's or
    plate's model is also a :class:`MeshedModel` (its fields go to a field file).
    """

    @property
    def size(self) -> int: ...

    def nodal_loads(self, force: np.ndarray, radius: float | None = None) -> np.ndarray: ...

    def engine(self): ...

    def respond(self, history=None, radius: float | None = None): ...

    def direct(self, history=None, *args, **kwargs): ...

    def contact_structure(self, point, reach: float): ...

    def for_workers(self): ...


@runtime_checkable
class MeshedModel(Protocol):
    """A :class:`StructureModel` whose displacements make fields (a beam's, a plate's; not the bar's): ``mesh``
    the fem object of its mesh, with ``expand(u)`` the full DOF vectors of reduced ones and ``field_frames(full)``
    (points, cells, point data, cell data) of a field file (:mod:`softimpact.output.fields`)."""

    @property
    def size(self) -> int: ...

    @property
    def mesh(self): ...


@runtime_checkable
class Target(Protocol):
    """The structure an impactor strikes, at problem level (:class:`softimpact.workflows.beam_impact.BeamProblem`,
    :class:`softimpact.workflows.plate.PlateProblem`): everything above ``fem`` asks it, never its type.

    - ``load`` (its ``position``: the impact point, ``contact_radius``), ``solver``, ``gauges``, ``title`` (its display system is the edges': a case's ``units``, read by the app and the API);
    - ``model(patch_radius, damage=False)`` its :class:`StructureModel` (with ``damage``, the contact structure's
      outputs carry the ``"damage"`` group after the ``"gauges"``); ``check()`` resolution and resource guards;
      ``refine(factor)`` the same target with mesh and time step refined; ``elements`` its mesh (a list);
      ``for_impact(solver, gauges)`` the target of a coupled run (force history dropped);
    - ``stack`` its laminate (or None), ``material`` its isotropic material (or None), ``thickness`` [m],
      ``mass`` [kg] of the whole structure (a half or quarter model's mirrored parts included), ``laminate_key``
      where a case gives the laminate's ply;
    - damage: ``has_damage_outputs`` (a layup with strengths), ``damage_points()`` where the indices are
      read ("at_load", "at_<gauge>"), ``damage_gauges()`` the ``"damage"`` output group, ``damage_faces(gauges, damage)`` each damage point's (top, bottom) face strains,
      ``damage_section`` (plane, width) of a beam section or (None, None);
    - ``validity(max_deflection)`` the deflection envelope of its theory (``theory``: its label); ``kinematics``
      ``"linear"`` or ``"von-karman"``; ``coupled_stepper`` the stepper of a nonlinear target (von Kármán kinematics,
      an elastic–plastic section, cohesive interfaces: a name of :data:`softimpact.fem.steppers.STEPPERS`) or None
      for a linear one (direct stepping or contact kernels);
    - summary.json: ``gauge_summary(gauge)`` a gauge's entries, ``summary_extras(model, result)`` the target's
      own block (``target``: a plate's model and deflection, a beam's kinematics), ``summary_keys`` its sweep outputs; ``deflected_shapes`` whether the
      impact command draws its deflected shapes.
    """

    load: object
    solver: object
    gauges: tuple
    theory: str
    kinematics: str
    coupled_stepper: str | None
    laminate_key: str
    deflected_shapes: bool
    summary_keys: tuple

    def model(self, patch_radius: float | None = None, damage: bool = False) -> StructureModel: ...

    def check(self) -> None: ...

    def refine(self, factor: int): ...

    def for_impact(self, solver, gauges=None): ...

    @property
    def elements(self) -> list[int]: ...

    @property
    def stack(self): ...

    @property
    def material(self): ...

    @property
    def thickness(self) -> float: ...

    @property
    def mass(self) -> float: ...

    @property
    def has_damage_outputs(self) -> bool: ...

    def damage_points(self) -> dict: ...

    def damage_gauges(self) -> tuple: ...

    def damage_faces(self, gauges: np.ndarray, damage: dict) -> dict: ...

    @property
    def damage_section(self) -> tuple: ...

    def validity(self, max_deflection: float): ...

    def gauge_summary(self, gauge) -> dict: ...

    def summary_extras(self, model, result) -> dict: ...


__all__ += ["Target"]  # appended here, not in the list above, so this block stays apart from the contact laws' part
