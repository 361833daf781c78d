"""The coupled stepper: one per-step loop of a rigid impactor on a linear structure, written once.

In the shape of scipy's ``OdeSolver`` (``scipy/integrate/_ivp/base.py``): :class:`CoupledStepper` holds
the loop that every way of stepping shares — the impactor's Newmark step, the approach α = x − w and
its rate and acceleration, the contact Newton (:func:`softimpact.fem.impact.newton_contact`), the law's
memory and stored energy, the contact work, the separation clock (:class:`SeparationClock`) and the
recorded histories — and counts its work (``newton_iterations``, ``coasted`` steps). An
implementation says only how the structure enters (:mod:`softimpact.fem.impact`'s module docstring for
the equations):

- ``free_approach(k)``: w̃_{k+1} = c·u_{k+1} of the structure's free response (no contact force at
  step k + 1), so that the bracket's top is α̃ = x̃ − w̃;
- ``compliance``: the patch compliance h_s(r) = c·G·s(r) of the contact Newton
  (:mod:`softimpact.fem.compliance`);
- ``apply(k, f, r)``: the step's contact force F_{k+1} = f over a disc of radius r applied to the
  structure (its own records: displacement, outputs, energies);
- ``history(last)``: the :class:`softimpact.fem.impact.ImpactHistory` of steps 0 … ``last``;

and may override ``flight(k)`` (the ballistic steps to the next contact at once, while apart),
``approach_acceleration`` and ``receding`` (from the structure's state where it has one; by default
Newmark's rules on α itself). ``TAKE_TOP``: a step whose force is zero at the bracket's top α̃ takes α̃
without a Newton solve (R(α̃) = 0 there), and a Newton step landing on α̃ is tried once.

The implementations, by name: :data:`softimpact.fem.steppers.STEPPERS` — ``"direct"``
(:class:`softimpact.fem.direct.DirectStepper`, the structure's Newmark stepper) and ``"kernels"``
(:class:`softimpact.fem.kernel_stepping.KernelStepper`, the structure's impulse responses).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from ..models.protocols import HistoryLaw, SettlingLaw, StepBoundLaw
from ..models.specimens import Impactor
from .impact import ImpactHistory, LawCapabilities, newton_contact
from .newmark import NewmarkParameters

__all__ = ["CoupledStepper", "SeparationClock", "check_time_step"]


class SeparationClock:
    """When a run may stop (``stop_after`` [s]): the impactor moving away from the target (no force,
    α < 0, α̇ < 0: slower than the struck point) without a break for ``stop_after``. The one rule of
    every stepper (in contact and apart)."""

    __slots__ = ("stop_after", "left_at")

    def __init__(self, stop_after: float):
        self.stop_after, self.left_at = stop_after, None

    def done(self, t: float, away: bool) -> bool:
        """Record the state at time ``t`` [s]; True once the impactor has been moving away for ``stop_after``."""
        if not away:
            self.left_at = None
            return False
        if self.left_at is None:
            self.left_at = t
        return t - self.left_at >= self.stop_after


class CoupledStepper:
    """A rigid impactor (``mass`` [kg], ``velocity`` [m/s] > 0 toward the structure) striking a linear
    structure through contact ``law`` (a ContactLaw or a HistoryLaw), ``steps`` steps of ``time_step`` [s]
    from first contact (module docstring). ``stop_after``: stop this long [s] after the impactor has left
    for good. A subclass sets ``params`` (its :class:`NewmarkParameters`) and ``compliance`` in its
    ``__init__`` and implements the methods the module docstring names; :meth:`run` steps.

    Plain Python floats and lists carry the scalar state (a step costs microseconds in the kernels).
    """

    TAKE_TOP = False  # a zero force at α̃ is the root without a Newton solve (module docstring)
    progress = None  # a callable told the step reached, every PROGRESS_STRIDE steps (a long run's progress bar), or None
    PROGRESS_STRIDE = 16
    params: NewmarkParameters
    compliance: object

    def __init__(self, law, mass: float, velocity: float, time_step: float, steps: int, stop_after: float | None = None):
        Impactor(mass, 1.0, velocity)  # validates mass and velocity (> 0, toward the structure): one rule on every path
        if not (isinstance(steps, (int, np.integer)) and steps >= 1):
            raise InputError(f"steps must be a positive integer, got {steps!r}")
        self.dt, self.steps = float(time_step), int(steps)
        if isinstance(law, StepBoundLaw):  # a law whose memory evolves in time needs the step
            law = law.for_time_step(self.dt)
        self.law, self.mass, self.velocity, self.stop_after = law, float(mass), float(velocity), stop_after
        self.memory = isinstance(law, HistoryLaw)  # (a runtime protocol check costs microseconds: once, not per step)
        self.settles = self.memory and isinstance(law, SettlingLaw)
        branch = law.branch(law.initial_state()) if self.memory else law
        self.caps = LawCapabilities.of(branch)  # every branch of a law is of one class (models.protocols)
        self.newton_iterations = 0  # the contact Newton's iterations, summed over the run
        self.coasted = 0  # steps taken at once while apart (:meth:`flight`)

    # -- what an implementation provides --------------------------------------------------------------

    def free_approach(self, k: int) -> float:
        """w̃_{k+1}: the structure's displacement along the approach row at step k + 1 with no contact force then [m]."""
        raise NotImplementedError

    def apply(self, k: int, f: float, r: float) -> None:
        """Apply the converged contact force F_{k+1} = ``f`` [N] over a disc of radius ``r`` [m] to the structure."""
        raise NotImplementedError

    def history(self, last: int) -> ImpactHistory:
        """The histories of steps 0 … ``last``."""
        raise NotImplementedError

    def flight(self, k: int) -> tuple[list, list] | None:
        """While apart at step k: the impactor's positions x_{k+1…j} and the approaches α_{k+1…j} of the
        steps up to the next contact (the first whose α̃ is positive), found at once; None: step them one
        by one (the structure must be stepped)."""
        return None

    def approach_acceleration(self, k: int, a_new: float, impactor_acceleration: float) -> float:
        """α̈_{k+1} by Newmark's displacement rule on α = x − c·u (x and c·u each obey it, so α does)."""
        return (a_new - self.al[k] - self.dt * self.ald[k] - self.c2 * self.ala) / self.bdt2

    def receding(self, k: int) -> bool:
        """The impactor slower than the struck point at step k (ẋ < ẇ = ẋ − α̇)."""
        return self.ald[k] < 0.0

    def _keep_snapshots(self, snapshots, n: int) -> None:
        """The steps at which an implementation keeps the structure's displacement (its ``n`` DOFs): ``keep`` (sorted,
        unique), ``slot`` (step → column) and ``saved`` (n, len(keep)); a step outside 0 … steps refused."""
        keep = np.unique(np.asarray(snapshots, int))
        if keep.size and (keep.min() < 0 or keep.max() > self.steps):
            raise InputError(f"snapshots: step indices must lie in 0 … {self.steps}, got {snapshots!r}")
        self.keep, self.slot, self.saved = keep, {int(k): i for i, k in enumerate(keep)}, np.zeros((n, keep.size))

    def _structure_records(self, rows: int) -> None:
        """A stepping structure's histories at rest: the approach row's displacement ``w``, the ``rows`` outputs ``y``,
        its kinetic and strain energies ``ek``, ``es`` (NaN unless ``self.energy``, zero at rest), the contact's work
        ``work`` and the surface mismatch ``mism``."""
        N = self.steps
        self.w, self.y = np.zeros(N + 1), np.zeros((rows, N + 1))
        self.ek, self.es = np.full(N + 1, np.nan), np.full(N + 1, np.nan)
        if self.energy:
            self.ek[0] = self.es[0] = 0.0
        self.work, self.mism = np.zeros(N + 1), np.zeros(N + 1)

    # -- the loop, once ---------------------------------------------------------------------------------

    def _begin(self) -> None:
        """The Newmark constants of ``params`` and the histories at rest, first contact at t = 0."""
        dt, beta, gamma = self.dt, self.params.beta, self.params.gamma
        self.beta, self.gamma = beta, gamma
        self.hm = beta * dt * dt / self.mass
        self.kappa = gamma / (beta * dt)
        self.r1, self.r2 = 1.0 - gamma / beta, dt * (1.0 - gamma / (2.0 * beta))
        self.bdt2, self.c2 = beta * dt * dt, dt * dt * (0.5 - beta)
        N = self.steps
        self.F, self.al, self.ald, self.rad, self.x, self.xv, self.cwork, self.cen = ([0.0] * (N + 1) for _ in range(8))
        self.xv[0] = self.ald[0] = self.velocity
        self.xa = self.ala = 0.0  # ẍ, α̈
        self.state = self.law.initial_state() if self.memory else None
        self.branch = self.law.branch(self.state) if self.memory else self.law
        self.newton_iterations = self.coasted = 0
        self.clock = None if self.stop_after is None else SeparationClock(self.stop_after)
        self._lists = (self.F, self.al, self.ald, self.rad, self.x, self.xv, self.cwork, self.cen)
        self._const = (dt, self.kappa, self.hm, self.r1, self.r2, self.c2, self.bdt2, gamma, self.mass)
        own_acceleration = type(self).approach_acceleration is not CoupledStepper.approach_acceleration
        self._fixed = (self.TAKE_TOP, own_acceleration, self.settles, self.memory, self.law, self.caps, self.compliance, self.clock)

    def run(self) -> ImpactHistory:
        """Step from first contact to the end of the run (or to the separation clock's stop); the histories.

        Step k → k + 1: the impactor's predictor x̃, the bracket's top α̃ = x̃ − w̃ (:meth:`free_approach`), the
        contact Newton (none where α̃ ≤ 0: apart), the force applied (:meth:`apply`), the impactor's corrector,
        α's rate and acceleration, the contact work, the law's memory and stored energy, the separation clock.
        The constants and histories are plain locals (a kernel step costs microseconds)."""
        self._begin()
        F, al, ald, rad, x, xv, cwork, cen = self._lists
        dt, kappa, hm, r1, r2, c2, bdt2, gamma, mass = self._const
        take_top, own_acceleration, settles, memory, law, caps, comp, clock = self._fixed
        free_approach, apply, responds = self.free_approach, self.apply, caps.responds
        ala, xa, state, branch = self.ala, self.xa, self.state, self.branch  # (kept on self across a coast only)
        N, k, last = self.steps, 0, self.steps
        report, stride = self.progress, self.PROGRESS_STRIDE
        while k < N:
            if k > 0 and F[k] == 0.0 and al[k] <= 0.0:  # apart: no force now, none pressing
                flight = self.flight(k)
                if flight is not None:
                    self.ala, self.state, self.branch = ala, state, branch
                    k, stopped = self._coast(k, *flight)
                    ala, state, branch = self.ala, self.state, self.branch
                    if stopped is not None or k >= N:
                        last = N if stopped is None else stopped
                        break
            ak, adk, fk = al[k], ald[k], F[k]
            x_pred = x[k] + dt * xv[k] + c2 * xa
            target = x_pred - free_approach(k)
            q = r1 * adk + r2 * ala - kappa * ak  # α̇_{k+1} = κ·α + q
            if target <= 0.0:
                a_new, f, r = target, 0.0, 0.0  # apart
            elif take_top and fk == 0.0 and (branch.response(target, kappa * target + q)[0] if responds else branch.force(target, kappa * target + q)) == 0.0:
                # no force at the bracket's top α̃ (a force clipped to zero, as by the Maxwell arm's negative
                # stress while unloading): R(α̃) = 0 there, the root (R increases with α), without a Newton iteration
                a_new, f, r = target, 0.0, 0.0  # no contact disc where no force presses
            else:
                guess = 2.0 * ak - al[k - 1] if k >= 1 else target
                a_new, f, r, its = newton_contact(branch, comp, hm, kappa, q, target, guess, k + 1, dt, try_top=take_top, caps=caps)
                self.newton_iterations += its
            apply(k, f, r)
            k += 1
            if report is not None and k % stride == 0:
                report(k)
            xa1 = -f / mass
            x[k] = x_pred - hm * f
            xv[k] = xv[k - 1] + dt * ((1.0 - gamma) * xa + gamma * xa1)
            ad_new = kappa * a_new + q
            F[k], al[k], rad[k], ald[k] = f, a_new, r, ad_new
            if own_acceleration:
                self.ala = ala
                ala = self.approach_acceleration(k - 1, a_new, xa1)
            else:  # Newmark's displacement rule on α (:meth:`approach_acceleration`), inline
                ala = (a_new - ak - dt * adk - c2 * ala) / bdt2
            cwork[k] = cwork[k - 1] + 0.5 * (fk + f) * (a_new - ak)
            # the law's memory after the converged step, and the contact energy at k (the step's branch's: its
            # stress at α_k is the converged one)
            if settles:
                state, branch, cen[k] = law.settle(state, a_new, ad_new)
            elif memory:
                cen[k] = branch.energy(a_new)
                state = law.advance(state, a_new, ad_new)
                branch = law.branch(state)
            else:
                cen[k] = float(branch.energy(a_new))
            xa = xa1
            if clock is not None and clock.done(k * dt, f == 0.0 and a_new < 0.0 and self.receding(k)):
                last = k
                break
        self.ala, self.xa, self.state, self.branch = ala, xa, state, branch
        return self.history(last)

    def _coast(self, k: int, positions: list, approaches: list) -> tuple[int, int | None]:
        """Record the ballistic steps k + 1 … j of :meth:`flight` (no force: the impactor at constant speed;
        the scalar recursions of α̇, α̈ and the law's memory carried); (j, the step where the separation
        clock stopped the run or None)."""
        n = len(approaches)
        j = k + n
        dt, kappa, r1, r2, c2, bdt2 = self.dt, self.kappa, self.r1, self.r2, self.c2, self.bdt2
        rates = []
        a_prev, ad, ala = self.al[k], self.ald[k], self.ala
        for a_new in approaches:  # α̇ and α̈ by Newmark's rules on α (as in contact)
            q = r1 * ad + r2 * ala - kappa * a_prev
            ala = (a_new - a_prev - dt * ad - c2 * ala) / bdt2
            ad = kappa * a_new + q
            rates.append(ad)
            a_prev = a_new
        self.ala = ala
        self.x[k + 1 : j + 1] = positions
        self.xv[k + 1 : j + 1] = [self.xv[k]] * n
        self.al[k + 1 : j + 1] = approaches
        self.ald[k + 1 : j + 1] = rates
        self.cwork[k + 1 : j + 1] = [self.cwork[k]] * n
        law = self.law
        if self.settles:
            self.state, self.cen[k + 1 : j + 1] = law.apart(self.state, n)
            self.branch = law.branch(self.state)
        elif self.memory:
            for i in range(k + 1, j + 1):
                self.cen[i] = self.branch.energy(self.al[i])
                self.state = law.advance(self.state, self.al[i], self.ald[i])
                self.branch = law.branch(self.state)
        # a law without memory stores nothing while apart (α ≤ 0): the contact energy stays 0
        self.coasted += n
        if self.clock is not None:
            for i in range(k + 1, j + 1):
                if self.clock.done(i * dt, self.al[i] < 0.0 and self.ald[i] < 0.0):
                    return j, i
        return j, None


def check_time_step(stepper_dt: float, dt: float) -> None:
    """A factored stepper (or kernels) built for ``stepper_dt`` [s] must run at ``dt`` [s]."""
    if not math.isclose(stepper_dt, dt, rel_tol=1e-12):
        raise InputError(f"stepper time step {stepper_dt!r} differs from time_step {dt!r}")
