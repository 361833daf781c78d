"""Direct coupled stepping: the whole structure stepped by Newmark with the impactor
(:mod:`softimpact.fem.impact`'s module docstring), one implementation of :class:`CoupledStepper`.

A step costs one back-substitution for the structure's free response u_free = K_eff⁻¹·predictor(u, v, a),
then u_{k+1} = u_free + G·(F·s(a)) with G = K_eff⁻¹·B solved once for unit loads on the patch nodes. The
structure's state gives its energies (kinetic, strain, the work of the nodal contact forces, the surface
mismatch), its outputs (gauge strains) and, where asked, snapshots of every DOF.
"""

from __future__ import annotations

import numpy as np

from .impact import ContactPatch, ContactStructure, ImpactHistory, PatchCompliance
from .newmark import NewmarkParameters, NewmarkStepper
from .stepping import CoupledStepper, check_time_step

__all__ = ["DirectStepper", "structure_history"]


class DirectStepper(CoupledStepper):
    """:class:`CoupledStepper` of ``structure`` (a :class:`ContactStructure`) by its Newmark stepper ``engine``
    (a :class:`NewmarkStepper` already factored for (M, K, C, dt) to reuse; None: factored here). ``energy``:
    record the structure's kinetic and strain energies (else NaN); ``snapshots``: step indices at which to
    keep the displacement of all DOFs (those past an early stop are dropped).

    ``TAKE_TOP`` stays off: direct stepping keeps the contact Newton's plain bracket test, so that its
    iteration counts (summary.json's ``newton_iterations``) and its histories stay those of the runs before
    the loop was shared; the roots agree with the kernels' to the Newton tolerance.
    """

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
        engine: NewmarkStepper | None = None,
        stop_after: float | None = None,
        energy: bool = True,
        snapshots=(),
    ):
        super().__init__(law, mass, velocity, time_step, steps, stop_after)
        st = engine or NewmarkStepper(structure.M, structure.K, self.dt, C=structure.C, params=newmark)
        check_time_step(st.dt, self.dt)
        self.st, self.params, self.energy = st, st.params, energy
        n = st.n
        self.c = np.asarray(structure.approach_row, float)
        self.dofs = np.asarray(structure.surface_dofs, int)
        self.sign = float(structure.load_sign)
        self.patch = ContactPatch(structure.surface_x, structure.center) if structure.patch is None else structure.patch
        B = np.zeros((n, self.dofs.size))
        B[self.dofs, np.arange(self.dofs.size)] = self.sign
        self.G = st.solve(B).reshape(n, self.dofs.size)  # (n, p): displacement per unit force on each patch node, solved once
        self.compliance = PatchCompliance(self.patch, self.c @ self.G)
        self.O = np.asarray(structure.outputs, float)
        self._keep_snapshots(snapshots, n)

    def _begin(self) -> None:
        super()._begin()
        n = self.st.n
        self._structure_records(self.O.shape[0])
        self.u, self.v, self.acc = np.zeros(n), np.zeros(n), np.zeros(n)
        self.s_prev = np.zeros(self.dofs.size)  # shares × F at the previous step (nodal forces / sign)
        self.u_free = None

    def free_approach(self, k: int) -> float:
        st = self.st
        self.u_free = st.solve(st.predictor(self.u, self.v, self.acc))
        return float(self.c @ self.u_free)

    def apply(self, k: int, f: float, r: float) -> None:
        """u_{k+1} = u_free + G·(f·s(r)), corrected; the structure's records at k + 1."""
        u, dofs, sign = self.u, self.dofs, self.sign
        fs = f * self.patch.shares(r)[0] if f != 0.0 else np.zeros(dofs.size)
        u1 = self.u_free + self.G @ fs if f != 0.0 else self.u_free
        v1, acc1 = self.st.correct(u1, u, self.v, self.acc)
        w, k1 = self.w, k + 1
        w[k1] = float(self.c @ u1)
        self.y[:, k1] = self.O @ u1
        du = u1[dofs] - u[dofs]
        self.work[k1] = self.work[k] + 0.5 * sign * float((self.s_prev + fs) @ du)
        mid = 0.5 * (self.F[k] + f)
        self.mism[k1] = self.mism[k] + 0.5 * sign * float((self.s_prev + fs) @ du) - mid * (w[k1] - w[k])
        if self.energy:
            self.ek[k1] = 0.5 * float(v1 @ (self.st.M @ v1))
            self.es[k1] = 0.5 * float(u1 @ (self.st.K @ u1))
        self.u, self.v, self.acc, self.s_prev = u1, v1, acc1, fs
        if k1 in self.slot:
            self.saved[:, self.slot[k1]] = u1

    def approach_acceleration(self, k: int, a_new: float, impactor_acceleration: float) -> float:
        """α̈_{k+1} = ẍ_{k+1} − c·ü_{k+1}, from the structure's state."""
        return impactor_acceleration - float(self.c @ self.acc)

    def receding(self, k: int) -> bool:
        """ẋ_k < ẇ_k = c·u̇_k, from the structure's state."""
        return self.xv[k] < float(self.c @ self.v)

    def history(self, last: int) -> ImpactHistory:
        return structure_history(self, last, self.st.nsolve)


def structure_history(st, last: int, solves: int) -> ImpactHistory:
    """The :class:`ImpactHistory` of a stepper that steps the whole structure (direct stepping, the von
    Kármán plate's), up to step ``last``: its impactor and contact records, the structure's mid-surface
    displacement, outputs, energies and kept snapshots; ``solves``: its structure solves."""
    sl, keep = slice(0, last + 1), st.keep
    t = np.arange(st.steps + 1) * st.dt

    def arr(v):
        return np.array(v[: last + 1])

    return ImpactHistory(
        time=t[sl],
        force=arr(st.F),
        approach=arr(st.al),
        approach_rate=arr(st.ald),
        contact_radius=arr(st.rad),
        impactor_displacement=arr(st.x),
        impactor_velocity=arr(st.xv),
        target_displacement=st.w[sl],
        strain=st.y[:, sl],
        structure_kinetic=st.ek[sl],
        structure_strain=st.es[sl],
        structure_work=st.work[sl],
        contact_work=arr(st.cwork),
        contact_energy=arr(st.cen),
        surface_mismatch=st.mism[sl],
        newton_iterations=st.newton_iterations,
        solves=solves,
        displacement=st.saved[:, keep <= last] if keep.size else None,
        kept=keep[keep <= last] if keep.size else None,
    )
