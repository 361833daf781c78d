"""The plane beam with large-deflection kinematics as a structure model (:class:`BeamTLModel`): the beam package's
nonlinear model (:meth:`~softimpact.workflows.beam.problem.BeamProblem.model` builds it when ``beam.kinematics =
"von-karman"``), beside the linear one (:mod:`~softimpact.workflows.beam.linear`)."""

from __future__ import annotations

import numpy as np

from ...errors import InputError
from ...fem.energies import Energies
from .linear import BeamModel, BeamResult

__all__ = ["BeamTLModel", "GreenLagrangeMesh"]


class BeamTLModel(BeamModel):
    """The beam in the total Lagrangian form of its plane model (:class:`~softimpact.fem.plane_tl.PlaneTL` ``tl``:
    Green–Lagrange strain, the same mesh, layers, supports, mass and output rows as :class:`BeamModel`), stepped by
    implicit Newmark–Newton (``stepper``: :class:`~softimpact.fem.plate_vk.VonKarmanNewmark`, modified Newton).
    A coupled impact's structure is :meth:`BeamModel.contact_structure` (``K`` the linear part, loads on the top
    face's nodes along z: dead loads in the reference configuration), stepped by
    :data:`softimpact.fem.steppers.STEPPERS` ``"von-karman"``; a prescribed force history by :meth:`direct`.
    No response engine or kernels: the structure is not linear."""

    coupled_stepper = "von-karman"

    def __init__(self, problem, patch_radius: float | None = None, outputs: str = "all", damage: bool = False):
        super().__init__(problem, patch_radius, outputs, damage)
        # the output rows that read gauge strains (all but the deflection's), read as their chord's stretch
        self._gauges = self.O.shape[0] - (1 if outputs == "all" else 0)
        self._Oz = self.tl.transverse_rows(self.O[: self._gauges])

    def outputs_at(self, u: np.ndarray) -> np.ndarray:
        """The outputs (n_out,) at the displacement u: the gauges' strains as their chords' stretch
        (:meth:`~softimpact.fem.plane_tl.PlaneTL.gauge_strains`), the deflection under the load as its row reads it."""
        y = self.O @ u
        y[: self._gauges] = self.tl.gauge_strains(self.O[: self._gauges], self._Oz, u)
        return y

    def _structure_stepper(self, C):
        from ...fem.plane_tl import PlaneTL
        from ...fem.plate_vk import VonKarmanNewmark

        self.tl = PlaneTL(self.plane)
        self._C = None if C is None else C.tocsr()
        solver = self.problem.solver
        return VonKarmanNewmark(self.tl, solver.time_step, self._C, solver.newmark, tangent="modified")

    @property
    def mesh(self):
        """The plane mesh whose field frames carry the model's own strain, Green–Lagrange (:class:`GreenLagrangeMesh`)."""
        return GreenLagrangeMesh(self.plane)

    @property
    def M(self):
        """Mass matrix (n, n)."""
        return self.tl.M

    @property
    def K(self):
        """The linear part of the stiffness (n, n): the tangent at the undeformed beam."""
        return self.tl.K

    @property
    def C(self):
        """Damping matrix (n, n) or None (Rayleigh, on the linear stiffness)."""
        return self._C

    def engine(self):
        raise InputError('the response engine needs a linear beam: beam.kinematics = "von-karman" runs stepped directly', "kinematics")

    def for_workers(self):
        raise InputError('a beam with beam.kinematics = "von-karman" has no light copy (no response engine): each run builds and steps its model', "kinematics")

    def direct(
        self, history=None, progress=None, energy: bool = True, displacement: bool = True, energy_samples: int = 200, radius: float | None = None
    ) -> BeamResult:
        """Newmark–Newton stepping of all DOFs under the force history (default: the problem's) on the load's patch,
        as :meth:`BeamModel.direct`: the energies (kinetic, the Green–Lagrange strain energy, the loads' work by the
        trapezoidal rule every step) at about ``energy_samples`` evenly spaced steps, the displacement at every step
        with ``displacement``."""
        F = self.force_samples(history)
        st, tl, N, n = self.stepper, self.tl, self.steps, self.size
        loads = self.load_sign * self.nodal_loads(F, radius)  # (p, N + 1) along the DOFs
        dofs = self.load_dofs
        stride = max(1, N // max(1, energy_samples))
        sampled = np.unique(np.r_[np.arange(0, N + 1, stride), N]) if energy else np.zeros(0, int)
        at = {int(k): i for i, k in enumerate(sampled)}
        kinetic, strain, work = np.zeros(sampled.size), np.zeros(sampled.size), np.zeros(N + 1)
        saved = np.zeros((n, N + 1)) if displacement else None
        y = np.zeros((self.O.shape[0], N + 1))
        u, v = np.zeros(n), np.zeros(n)
        f = np.zeros(n)
        f[dofs] = loads[:, 0]
        a = st.initial_acceleration(u, v, f)
        for k in range(N):
            f1 = np.zeros(n)
            f1[dofs] = loads[:, k + 1]
            u1, v, a, _ = st.step(u, v, a, f1)
            work[k + 1] = work[k] + 0.5 * (loads[:, k] + loads[:, k + 1]) @ (u1[dofs] - u[dofs])
            u = u1
            y[:, k + 1] = self.outputs_at(u)
            i = at.get(k + 1)
            if i is not None:
                kinetic[i], strain[i] = 0.5 * v @ (tl.M @ v), tl.strain_energy(u)
            if saved is not None:
                saved[:, k + 1] = u
            if progress is not None and k % 100 == 0:
                progress(k)
        energies = Energies(sampled, kinetic, strain, work[sampled]) if energy else None
        strain_h, bending, defl = self._split(y)
        return BeamResult(self.problem, self.solver.times(), F, strain_h, bending, defl, saved, energies)


class GreenLagrangeMesh:
    """The plane mesh of a total Lagrangian beam for field files: its ``expand`` and its ``field_frames`` with the
    element-centre strains in the Green–Lagrange measure (:func:`softimpact.fem.plane.centre_strain`), the strain the
    model's stresses come from (the linear one reads about −θ²/2 under a rigid rotation θ)."""

    def __init__(self, plane):
        self.plane = plane

    def expand(self, u):
        return self.plane.expand(u)

    def field_frames(self, full):
        return self.plane.field_frames(full, measure="green-lagrange")
