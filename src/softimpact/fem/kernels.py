"""Contact kernels: coupled impact on a linear structure as a Volterra problem.

A linear structure at rest, stepped by Newmark, answers a history of contact-patch
loads q_j = F_j·s(a_j) (p nodal shares, :mod:`softimpact.fem.impact`) with the
discrete convolution

    w_k = Σ_{j=1..k} g_{k−j}·q_j,      y_k = Σ_{j=1..k} H_{k−j}·q_j,

where w is the approach row's displacement (the mid-surface under the impactor),
y the outputs (gauge strains), and g_i (p,), H_i (q, p) the structure's discrete
impulse responses at lag i (:class:`softimpact.fem.response.ImpulseResponse`,
computed once by reciprocity: 1 + q right-hand sides a step). g_0 is the
direct stepper's c·G. A coupled run then steps only the scalar contact equation
of :func:`softimpact.fem.impact.integrate_impact`,

    R(α) = α − α̃ + F(α, α̇(α))·h(a(α)) = 0,   α̃ = x̃ − Σ_{j≤k} g_{k+1−j}·q_j,

with the same Newton iteration, so the histories equal direct coupled stepping to
round-off (the sums are taken in another order). The approach's rate and
acceleration follow from Newmark's rule applied to α itself (x and c·u each obey
it, so their difference does), which needs no structural state.

Cost: while in contact, the history sum runs over the current contact's steps
only (the earlier history is a precomputed "old" response); while apart, no load
is added, so the structure's free response to the whole history so far is one
FFT product with the kernel's cached spectrum, after which each step is a few
scalar operations. The outputs are one FFT convolution at the end.

The structure's own energies (kinetic, strain, the work on the patch nodes) need
its state and are not computed here (NaN); the impactor's energy and the contact
work are.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from ..models.protocols import HistoryLaw
from ..models.specimens import Impactor
from .impact import ContactPatch, ContactStructure, ImpactHistory, _solve_contact
from .newmark import NewmarkParameters, NewmarkStepper
from .response import ImpulseResponse

__all__ = ["ContactKernels"]


class ContactKernels:
    """Discrete impulse responses of ``structure`` for one time step and run length, built once.

    ``approach`` (p, steps): g_i, the approach-row displacement at lag i per unit load on each
    patch node; ``outputs`` (q, p, steps): the output rows' (H_i). Any number of coupled runs
    (other impactors, velocities, laws) then reuse them: :meth:`run`.
    """

    def __init__(self, structure: ContactStructure, time_step: float, steps: int, newmark: NewmarkParameters = NewmarkParameters(), stepper=None):
        if not (isinstance(steps, (int, np.integer)) and steps >= 1):
            raise InputError(f"steps must be a positive integer, got {steps!r}")
        dt = float(time_step)
        st = stepper or NewmarkStepper(structure.M, structure.K, dt, C=structure.C, params=newmark)
        if not math.isclose(st.dt, dt, rel_tol=1e-12):
            raise InputError(f"stepper time step {st.dt!r} differs from time_step {dt!r}")
        self.structure, self.dt, self.steps, self.newmark = structure, dt, int(steps), st.params
        self.patch = ContactPatch(structure.surface_x, structure.center) if structure.patch is None else structure.patch
        dofs = np.asarray(structure.surface_dofs, int)
        n = st.n
        B = np.zeros((n, dofs.size))
        B[dofs, np.arange(dofs.size)] = float(structure.load_sign)
        rows = np.vstack([np.asarray(structure.approach_row, float)[None, :], np.asarray(structure.outputs, float).reshape(-1, n)])
        self.engine = ImpulseResponse.reciprocal(st, B, self.steps, rows)
        self.approach = self.engine.kernel[0]  # (p, steps)
        self.outputs = self.engine.kernel[1:]  # (q, p, steps)
        self._lagged = np.ascontiguousarray(self.approach.T)  # (steps, p): row i is g_i
        self.solves = st.nsolve

    @property
    def output_names(self) -> tuple[str, ...]:
        return tuple(self.structure.output_names)

    def _free_response(self, Q: np.ndarray, upto: int) -> np.ndarray:
        """w_m = Σ_{j ≤ upto} g_{m−j}·q_j for every step m (shape (steps + 1,)): the approach row's
        response to the loads so far, by one product with the kernel's cached spectrum."""
        Hk, nfft = self.engine._spectrum()
        loads = np.zeros((Q.shape[1], self.steps))
        loads[:, :upto] = Q[1 : upto + 1].T
        w = np.zeros(self.steps + 1)
        w[1:] = np.fft.irfft(np.einsum("pk,pk->k", Hk[0], np.fft.rfft(loads, nfft, axis=-1)), nfft)[: self.steps]
        return w

    def run(self, law, mass: float, velocity: float, stop_after: float | None = None) -> ImpactHistory:
        """The coupled impact of a rigid impactor (``mass`` [kg], ``velocity`` [m/s] > 0 toward the
        structure) through contact ``law`` (a ContactLaw or HistoryLaw): the histories of
        :func:`softimpact.fem.impact.integrate_impact` for the same structure, step and run length,
        structure energies NaN. ``stop_after``: stop this long [s] after the impactor has left for good."""
        Impactor(mass, 1.0, velocity)  # validates mass and velocity (> 0, toward the structure): the direct path's rule
        dt, N = self.dt, self.steps
        if hasattr(law, "for_time_step"):
            law = law.for_time_step(dt)
        beta, gamma = self.newmark.beta, self.newmark.gamma
        patch = self.patch
        g = self._lagged
        cG = g[0]
        hm = beta * dt * dt / mass
        kappa = gamma / (beta * dt)
        r1, r2 = 1.0 - gamma / beta, dt * (1.0 - gamma / (2.0 * beta))
        bdt2 = beta * dt * dt

        t = np.arange(N + 1) * dt
        F, al, ald, rad, x, xv = (np.zeros(N + 1) for _ in range(6))
        cwork, cen = np.zeros(N + 1), np.zeros(N + 1)
        Q = np.zeros((N + 1, cG.size))  # q_j = F_j·s_j, row j
        xv[0] = ald[0] = velocity
        xa = ala = 0.0
        state = law.initial_state() if isinstance(law, HistoryLaw) else None  # (a protocol check: once, not per step)
        old = np.zeros(N + 1)  # response to the loads before the current contact (or all, while apart)
        start = None  # first step of the current contact
        iterations, last, left_at = 0, N, None
        for k in range(N):
            branch = law if state is None else law.branch(state)
            x_pred = x[k] + dt * xv[k] + dt * dt * (0.5 - beta) * xa
            w_hist = old[k + 1]
            if start is not None and k >= start:  # the current contact's loads, lags 1 … k + 1 − start
                w_hist += float(np.einsum("ij,ij->", g[1 : k + 2 - start], Q[start : k + 1][::-1]))
            target = x_pred - w_hist
            q = r1 * ald[k] + r2 * ala - kappa * al[k]
            if target > 0.0:
                guess = 2.0 * al[k] - al[k - 1] if k >= 1 else target
                a_new, f, sh, its = _solve_contact(branch, patch, cG, hm, kappa, q, target, guess, k + 1, dt)
                iterations += its
                r = branch.radius(a_new)
            else:
                a_new, f, sh, r = target, 0.0, None, 0.0
            if f != 0.0:
                Q[k + 1] = f * sh
                if start is None:
                    start = k + 1
            elif start is not None:  # contact ended: the free response to everything so far, once
                old = self._free_response(Q, k)
                start = None
            x[k + 1] = x_pred - hm * f
            xa1 = -f / mass
            xv[k + 1] = xv[k] + dt * ((1.0 - gamma) * xa + gamma * xa1)
            F[k + 1], al[k + 1], rad[k + 1] = f, a_new, r
            ald[k + 1] = kappa * a_new + q
            # Newmark's displacement rule on α = x − c·u gives α̈ without the structure's state
            ala = (a_new - al[k] - dt * ald[k] - dt * dt * (0.5 - beta) * ala) / bdt2
            mid = 0.5 * (F[k] + f)
            cwork[k + 1] = cwork[k] + mid * (a_new - al[k])
            if state is not None:
                state = law.advance(state, a_new, ald[k + 1])
                cen[k + 1] = law.branch(state).energy(a_new)
            else:
                cen[k + 1] = branch.energy(a_new)
            xa = xa1
            if stop_after is not None:
                # moving apart: the impactor slower than the target point, ẋ < ẇ = ẋ − α̇
                away = f == 0.0 and a_new < 0.0 and ald[k + 1] < 0.0
                if away and left_at is None:
                    left_at = t[k + 1]
                elif not away:
                    left_at = None
                if left_at is not None and t[k + 1] - left_at >= stop_after:
                    last = k + 1
                    break
        y = self.engine.respond(Q.T)  # (1 + q, N + 1): approach row, then the outputs
        sl = slice(0, last + 1)
        nan = np.full(last + 1, np.nan)
        return ImpactHistory(
            time=t[sl],
            force=F[sl],
            approach=al[sl],
            approach_rate=ald[sl],
            contact_radius=rad[sl],
            impactor_displacement=x[sl],
            impactor_velocity=xv[sl],
            target_displacement=y[0, sl],
            outputs=y[1:, sl],
            structure_kinetic=nan,
            structure_strain=nan.copy(),
            structure_work=nan.copy(),
            contact_work=cwork[sl],
            contact_energy=cen[sl],
            surface_mismatch=nan.copy(),
            newton_iterations=iterations,
            solves=0,
        )
