"""Coupled stepping of a rigid impactor on a geometrically nonlinear structure: one implementation of :class:`CoupledStepper`.

The structure is nonlinear (the von Kármán plate of :mod:`softimpact.fem.plate_vk`, the total Lagrangian plane
beam of :mod:`softimpact.fem.plane_tl`: any model :class:`~softimpact.fem.plate_vk.VonKarmanNewmark` steps), so its deflection under the contact force is no
longer w̃ + h_s(r)·F with a free response w̃ and a compliance h_s fixed for the run, the affine model the
shared loop's contact Newton solves against. Each step therefore solves the coupled step first, monolithically,
in :meth:`VonKarmanStepper.free_approach`: the plate's Newmark–Newton step (:meth:`VonKarmanNewmark.step`)
with the contact on the plate, where for the plate's state u the impactor's Newmark step and the
law give the force,

    α = x̃ − β dt² F / m − c·u,   F = P(α, κα + q),   nodal loads F·s(a(α)) on the contact patch,

(the scalar equation solved by the loop's own :func:`~softimpact.fem.impact.newton_contact`). The contact is
condensed onto each iteration's linearised structure (:meth:`VonKarmanNewmark.step`'s ``contact``): with the
structure's correction d without contact force and its response z to a unit one, the contact Newton solves
the same equation against the compliance c·z (:class:`_StepContact`), bracketed, and the iterate takes its force.
A law whose force goes through the approach rate (the crushing law, the hydrodynamic law: α̇ = γ/(β·dt)·α + q,
slopes of 10¹⁰ N/m, a force clipped to zero where the rate turns negative at the end of a crush) thus converges
where a contact tangent in the plate's Jacobian made the iteration cycle between no force and full force.

The structure may carry internal state (plastic strains, interface damage: a :class:`~softimpact.fem.nonlinear.NonlinearModel`):
:meth:`VonKarmanStepper.apply` commits it after every converged step, counts the energy it dissipated in the
structure's energy (strain + dissipated: the coupled balance closes with it) and writes the scalars it records
(:attr:`~softimpact.fem.nonlinear.NonlinearModel.history_names`: areas, energies) into the structure's last output
rows, placeholders kept for them, of the whole plate (divided by the share of it the model is: ¼ for a quarter).

The converged step (u*, F*, r*) then fixes the affine model the loop sees: the bracket's top α̃ = x̃ − w̃ with w̃ = c·u* − h_s(r*)·F*, and any positive compliance
h_s (here the linear structure's effective one, c·K_eff⁻¹·B, solved once) makes the loop's contact Newton land on
α* = x̃ − β dt² F*/m − c·u* again (R(α*) = 0 exactly), to its tolerance. :meth:`apply` takes u* (the loop's
force differs from F* by the contact Newton's tolerance only) and records the structure's energies (kinetic,
its nonlinear strain energy), the work of the nodal contact forces, outputs and snapshots, as
:class:`softimpact.fem.direct.DirectStepper` does for a linear structure.

The patch: the structure's own (a plate's contact disc, :class:`softimpact.fem.plate_loads.DiscShares`) or,
without one, the cosine line patch over the struck face's nodes (:class:`~softimpact.fem.impact.ContactPatch`, a
beam's), as :class:`softimpact.fem.direct.DirectStepper` takes it.

A contact law with memory (a HistoryLaw: the identified law's Maxwell arm) enters the coupled step as the branch
the loop's contact Newton uses for that step (:meth:`VonKarmanStepper._branch`): its state is advanced here from
the loop's converged α and α̇ with the loop's own calls (``settle``'s state, or ``advance``), and taken again from
the loop after each coast, so the plate's Newton and the loop's contact Newton solve the same law.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse

from ..errors import InputError
from .direct import structure_history
from .impact import ContactPatch, ContactStructure, ImpactHistory, PatchCompliance, newton_contact
from .newmark import NewmarkParameters, spd_factor
from .nonlinear import NonlinearNewmark
from .stepping import CoupledStepper, check_time_step

__all__ = ["VonKarmanStepper"]


class _Compliance:
    """A patch compliance fixed for one structure iteration, h [m/N] at every radius (zero: the impactor against
    the structure held still): the contact Newton of the impactor against the linearised structure."""

    value = None

    def __init__(self, h: float, half_spacing: float):
        self.h, self.half_spacing = h, half_spacing

    def __call__(self, r: float) -> tuple[float, float]:
        return self.h, 0.0


class _StepContact:
    """The contact of one coupled step as :meth:`VonKarmanNewmark.step` takes it (its ``contact``: ``load``, ``solve``),
    the impactor's predictor ``x_pred`` and the rate's offset ``q`` fixed for the step to ``index``."""

    def __init__(self, stepper: VonKarmanStepper, x_pred: float, q: float, index: int):
        self.st, self.x_pred, self.q, self.index = stepper, x_pred, q, index
        self.law = stepper._branch(index - 1)
        self.guess = x_pred

    def load(self, u: np.ndarray) -> tuple[float, np.ndarray]:
        """(F, b): the contact force at u and the nodal shape of a unit force over its disc (the nearest node where apart)."""
        st = self.st
        a, f, r = st._contact(u, self.x_pred, self.q, self.index)
        if f > 0.0:
            self.guess = a
        shape = np.zeros(st._n)
        shape[st.dofs] = st.sign * st.patch.shares(r)[0]
        return f, shape

    def solve(self, u: np.ndarray, z: np.ndarray) -> float:
        """F' of α = x̃ − β·dt²·F'/m − c·(u + F'·z), F' = P(α, κα + q): the loop's contact Newton against the compliance c·z."""
        st = self.st
        top = self.x_pred - float(st.c @ u)
        if top <= 0.0:
            return 0.0
        comp = _Compliance(max(float(st.c @ z), 0.0), st.compliance.half_spacing)
        guess = min(self.guess, top)
        _, f, _, _ = newton_contact(self.law, comp, st.hm, st.kappa, self.q, top, guess, self.index, st.dt, caps=st.caps)
        return f


class VonKarmanStepper(CoupledStepper):
    """:class:`CoupledStepper` of a nonlinear structure (module docstring): ``structure`` a
    :class:`ContactStructure` over the structure's free DOFs (``M``, ``K`` its linear part, a plate's contact
    disc as ``patch`` or a beam's surface nodes), ``engine`` its :class:`~softimpact.fem.plate_vk.VonKarmanNewmark`
    (required: it carries the nonlinear structure); ``energy``: record the structure's kinetic and strain
    energies (else NaN); ``snapshots``: step indices at which to keep the displacement of the free DOFs."""

    def __init__(
        self,
        structure: ContactStructure,
        law,
        mass: float,
        velocity: float,
        time_step: float,
        steps: int,
        newmark: NewmarkParameters = NewmarkParameters(),
        *,
        engine: NonlinearNewmark | None = None,
        stop_after: float | None = None,
        energy: bool = True,
        snapshots=(),
    ):
        super().__init__(law, mass, velocity, time_step, steps, stop_after)
        if not isinstance(engine, NonlinearNewmark):
            raise InputError("the nonlinear stepper needs the structure's NonlinearNewmark as its engine (a linear structure steps 'direct' or 'kernels')")
        check_time_step(engine.dt, self.dt)
        self.nm, self.vk, self.params, self.energy = engine, engine.model, engine.params, energy
        n = self.vk.n
        self.c = np.asarray(structure.approach_row, float)
        self.dofs = np.asarray(structure.surface_dofs, int)
        self.sign = float(structure.load_sign)
        self.patch = ContactPatch(structure.surface_x, structure.center) if structure.patch is None else structure.patch
        # The loop's affine model needs a positive compliance only (module docstring): the linear structure's, by one solve
        z = spd_factor(scipy.sparse.csc_matrix(engine._keff)).solve(self.c)
        self.compliance = PatchCompliance(self.patch, self.sign * z[self.dofs])
        self._rigid = _Compliance(0.0, self.compliance.half_spacing)
        self.O = np.asarray(structure.outputs, float)
        # a plane beam's output rows are gauge strains: read as their chords' stretch (fem.plane_tl), the plate's as rows
        self.Oz = self.vk.transverse_rows(self.O) if hasattr(self.vk, "transverse_rows") else None
        self._keep_snapshots(snapshots, self.vk.n)
        self.structure_iterations = 0  # the structure's Newton iterations, summed over the run
        self._n = n
        # the scalars the structure records (its history rows: the last output rows), of the whole plate
        self.rows = len(self.vk.history_names)
        self.share = float(self.patch.patch.share) if self.rows else 1.0

    def _begin(self) -> None:
        super()._begin()
        self.vk.reset()
        n = self._n
        self._structure_records(self.O.shape[0])
        self.u, self.v, self.acc = np.zeros(n), np.zeros(n), np.zeros(n)
        self.s_prev = np.zeros(self.dofs.size)
        self._ala = 0.0  # α̈ at the step's start (the loop's local, kept by approach_acceleration)
        self._zero = np.zeros(n)
        self.structure_iterations = 0
        # a law with memory: its state at step _law_k (the loop's, mirrored), resynchronised after each coast
        self._law_state, self._law_k, self._law_coasted, self._law_branch = self.state, 0, self.coasted, self.branch

    def _branch(self, k: int):
        """The law's branch for the step from k (the loop's: the state after its converged step k, module docstring)."""
        if not self.memory:
            return self.law
        if self.coasted != self._law_coasted:  # a coast: the loop keeps its state on self across it
            self._law_state, self._law_k, self._law_coasted = self.state, k, self.coasted
            self._law_branch = self.branch
        law = self.law
        while self._law_k < k:
            i = self._law_k + 1
            if self.settles:
                self._law_state, self._law_branch, _ = law.settle(self._law_state, self.al[i], self.ald[i])
            else:
                self._law_state = law.advance(self._law_state, self.al[i], self.ald[i])
                self._law_branch = law.branch(self._law_state)
            self._law_k = i
        return self._law_branch

    def _contact(self, u: np.ndarray, x_pred: float, q: float, index: int):
        """(α, F, r) of the impactor against the structure held at ``u`` (zero force and radius where apart)."""
        top = x_pred - float(self.c @ u)
        if top <= 0.0:
            return top, 0.0, 0.0
        a, f, r, _ = newton_contact(self._branch(index - 1), self._rigid, self.hm, self.kappa, q, top, top, index, self.dt, caps=self.caps)
        return a, f, r

    def free_approach(self, k: int) -> float:
        """The coupled step to k + 1 (module docstring); w̃ = c·u* − h_s(r*)·F*."""
        x_pred = self.x[k] + self.dt * self.xv[k] + self.c2 * (-self.F[k] / self.mass)
        q = self.r1 * self.ald[k] + self.r2 * self._ala - self.kappa * self.al[k]
        u1, v1, a1, its = self.nm.step(self.u, self.v, self.acc, self._zero, contact=_StepContact(self, x_pred, q, k + 1))
        self.structure_iterations += its
        _, f, r = self._contact(u1, x_pred, q, k + 1)
        self._step = (u1, v1, a1, f, r)
        return float(self.c @ u1) - (self.compliance(r)[0] * f if f > 0.0 else 0.0)

    def apply(self, k: int, f: float, r: float) -> None:
        """The coupled step's state at k + 1 (the loop's f, r agree with its F*, r* to the contact Newton's tolerance)."""
        u1, v1, acc1, f_star, r_star = self._step
        u, dofs, sign = self.u, self.dofs, self.sign
        fs = f_star * self.patch.shares(r_star)[0] if f_star != 0.0 else np.zeros(dofs.size)
        w, k1 = self.w, k + 1
        w[k1] = float(self.c @ u1)
        self.y[:, k1] = self.O @ u1 if self.Oz is None else self.vk.gauge_strains(self.O, self.Oz, u1)
        du = u1[dofs] - u[dofs]
        self.work[k1] = self.work[k] + 0.5 * sign * float((self.s_prev + fs) @ du)
        mid = 0.5 * (self.F[k] + f)
        self.mism[k1] = self.mism[k] + 0.5 * sign * float((self.s_prev + fs) @ du) - mid * (w[k1] - w[k])
        model = self.vk
        acc1 = self.nm.commit(u1, acc1)
        if self.energy:
            self.ek[k1] = 0.5 * float(v1 @ (model.M @ v1))
            self.es[k1] = model.strain_energy(u1) + model.dissipated_energy()
        if self.rows:
            self.y[-self.rows :, k1] = model.history(u1) / self.share
        self.u, self.v, self.acc, self.s_prev = u1, v1, acc1, fs
        if k1 in self.slot:
            self.saved[:, self.slot[k1]] = u1

    def approach_acceleration(self, k: int, a_new: float, impactor_acceleration: float) -> float:
        """α̈_{k+1} = ẍ_{k+1} − c·ü_{k+1}, from the structure's state (kept for the next coupled step)."""
        self._ala = impactor_acceleration - float(self.c @ self.acc)
        return self._ala

    def receding(self, k: int) -> bool:
        """ẋ_k < ẇ_k = c·u̇_k, from the structure's state."""
        return self.xv[k] < float(self.c @ self.v)

    def history(self, last: int) -> ImpactHistory:
        return structure_history(self, last, self.structure_iterations)
