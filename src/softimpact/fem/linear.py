"""One implementation of the structure protocol for linear structures: rod, plane beam, plate.

A linear structure M·ü + C·u̇ + K·u = B·f(t) at one time step dt (SI, n = ``size`` DOFs):
the loads act on the DOFs ``load_dofs`` (p of them) with the sign ``load_sign`` (−1 where a
compressive contact force pushes against the DOF's positive direction), shared among them
by a patch (``patch.forces(F, radius) -> (p, n_t)``); the outputs are the rows ``O``
(n_out, n), outputs y = O·u (gauge strains, deflections).

Two ways to the same outputs of a force history F(t) (:class:`LinearModel`):

- :meth:`LinearModel.respond_outputs`, through the response engine
  (:class:`softimpact.fem.response.ImpulseResponse`: impulse responses of the outputs to
  each loaded DOF, computed once by reciprocity, then a discrete convolution per history:
  milliseconds);
- :meth:`LinearModel.march`, Newmark stepping of every DOF (average acceleration by default),
  with the energies (:class:`softimpact.fem.energies.Energies`) every step or sampled, and
  snapshots of the displacement.

The stepper (the effective matrix factored once per (model, dt)) and the engine (built
lazily, once) belong to the model; :meth:`LinearModel.for_workers` gives a light copy with
the kernels, the patch and the problem but no matrices or factor, which pickles small.
"""

from __future__ import annotations

import copy

import numpy as np
from threadpoolctl import threadpool_limits

from ..errors import InputError
from .energies import Energies
from .newmark import NewmarkStepper, SolverSpec, spd_factor
from .response import ImpulseResponse

__all__ = ["LinearModel", "PointLoad", "MIN_STEPS_PER_RISE"]

MIN_STEPS_PER_RISE = 4  # a prescribed pulse rising in fewer time steps than this is not resolved (beam and plate problems)


class PointLoad:
    """A patch of one node: the whole force F(t) on it (the bar's struck end)."""

    nodes = np.array([0])
    half_spacing = np.inf

    def forces(self, F: np.ndarray, radius: float | None = None) -> np.ndarray:
        """Nodal forces (1, n_t) [N] of the history F (n_t,), compression +; ``radius`` is ignored."""
        return np.asarray(F, float)[None, :]


class LinearModel:
    """A linear structure at one time step: matrices, stepper, loads, outputs, engine (module docstring).

    ``M``, ``K`` (n, n) sparse or dense, ``C`` (n, n) or None; ``solver`` the time step, duration
    and Newmark parameters; ``load_dofs`` (p,) and ``load_sign`` (±1) where a compressive force
    acts; ``O`` (n_out, n) the output rows; ``patch`` the load's shares (``forces(F, radius)``);
    ``load_radius`` the contact radius r0 [m] of a prescribed history (None: no radius).
    Subclasses set ``problem`` and give :meth:`contact_structure`.
    """

    problem = None

    def __init__(self, M, K, C, solver: SolverSpec, load_dofs, load_sign: float, O, patch, load_radius: float | None = None, stepper=None):
        self.solver = solver
        self.stepper = stepper or NewmarkStepper(M, K, solver.time_step, C=C, params=solver.newmark)
        self.load_dofs = np.asarray(load_dofs, int)
        self.load_sign = float(load_sign)
        self.B = np.zeros((M.shape[0], self.load_dofs.size))
        self.B[self.load_dofs, np.arange(self.load_dofs.size)] = self.load_sign
        self.O = np.asarray(O, float).reshape(-1, M.shape[0])
        self.patch = patch
        self.load_radius = load_radius
        self._engine = None

    @property
    def M(self):
        """Mass matrix (n, n) (the stepper's; None in a light copy)."""
        return None if self.stepper is None else self.stepper.M

    @property
    def K(self):
        """Stiffness matrix (n, n) (the stepper's; None in a light copy)."""
        return None if self.stepper is None else self.stepper.K

    @property
    def C(self):
        """Damping matrix (n, n) or None (the stepper's)."""
        return None if self.stepper is None else self.stepper.C

    @property
    def size(self) -> int:
        """The number of DOFs n (free DOFs: supports removed)."""
        return self.B.shape[0]

    @property
    def steps(self) -> int:
        return self.solver.steps

    def force_samples(self, history=None) -> np.ndarray:
        """The force history [N] at the solver's times (n_steps + 1,): ``history`` (a callable F(t)
        or samples), else the problem's load history."""
        h = self.problem.load.history if history is None else history
        return np.asarray(h(self.solver.times()) if callable(h) else h, float)

    def nodal_loads(self, force: np.ndarray, radius: float | None = None) -> np.ndarray:
        """Patch loads (p, n_t) [N], compression +, for a force history sampled at the solver's
        times (r0 = ``radius`` or the model's ``load_radius``)."""
        return self.patch.forces(force, self.load_radius if radius is None else radius)

    def engine(self) -> ImpulseResponse:
        """The response engine (impulse responses of the outputs to each loaded DOF), built once.

        With one BLAS thread: the per-step products are small, and OpenBLAS threads spin on a
        busy machine."""
        if self._engine is None:
            with threadpool_limits(1, user_api="blas"):
                self._engine = ImpulseResponse.reciprocal(self.stepper, self.B, self.steps, self.O)
        return self._engine

    def respond_outputs(self, force: np.ndarray, radius: float | None = None) -> np.ndarray:
        """Outputs y (n_out, n_steps + 1) of a force history through the engine (zero at t = 0)."""
        if force[0] != 0.0:
            raise InputError("the force must be zero at first contact (t = 0)", "history")
        return self.engine().respond(self.nodal_loads(force, radius))

    def march(self, force: np.ndarray, radius: float | None = None, energy: bool = True, energy_samples: int | None = None, keep=(), progress=None):
        """Newmark stepping of all DOFs under the force history (n_steps + 1,) [N].

        Returns (y, energies, saved): the outputs (n_out, n_steps + 1); the energies
        (:class:`Energies`, None without ``energy``) at every step, or at about
        ``energy_samples`` evenly spaced steps (and the last); the displacement (n, len(keep))
        at the step indices ``keep``. The work of the loads is summed over every step as
        ½(f_k + f_{k+1})·(u_{k+1} − u_k), under which average acceleration balances energy
        exactly. Undamped, the loop carries M·u, M·v, M·a along with u, v, a: Newmark's
        corrector is linear, so one product M·u_{k+1} a step gives the next predictor, the
        kinetic energy ½ v·(M·v) and the strain energy ½ u·(K·u) = ½ u·(f − M·a).
        """
        st, N, n = self.stepper, self.steps, self.size
        loads = self.load_sign * self.nodal_loads(force, radius)  # (p, N + 1) along the DOFs
        dofs = self.load_dofs
        keep = np.asarray(keep, int)
        if keep.size and (keep.min() < 0 or keep.max() > N):
            raise InputError(f"snapshots: step indices must lie in 0 … {N}, got {keep.tolist()!r}")
        slot = {int(k): i for i, k in enumerate(keep)}
        saved = np.zeros((n, keep.size))
        stride = 1 if energy_samples is None else max(1, N // max(1, energy_samples))
        sampled = np.unique(np.r_[np.arange(0, N + 1, stride), N]) if energy else np.zeros(0, int)
        at = {int(k): i for i, k in enumerate(sampled)}
        kinetic, strain, work = np.zeros(sampled.size), np.zeros(sampled.size), np.zeros(N + 1)
        cols = np.flatnonzero(np.any(self.O != 0.0, axis=0))  # the few DOFs the outputs read
        O_cols = self.O[:, cols]
        y = np.zeros((N + 1, self.O.shape[0]))  # time-major while stepping
        u, v = np.zeros(n), np.zeros(n)
        f0 = np.zeros(n)
        f0[dofs] = loads[:, 0]
        acc = st.initial_acceleration(u, v, f0)
        M, K = st.M, st.K
        a0, a2, a3, a6, a7 = st.a0, st.a2, st.a3, st.a6, st.a7
        carry = st.C is None
        Mu, Mv, Ma = M @ u, M @ v, M @ acc
        with threadpool_limits(1, user_api="blas"):
            for k in range(N):
                f1 = loads[:, k + 1]
                rhs = a0 * Mu + a2 * Mv + a3 * Ma if carry else st.predictor(u, v, acc)
                rhs[dofs] += f1
                u1 = st.solve(rhs)
                v1, acc = st.correct(u1, u, v, acc)
                if carry:
                    Mu1 = M @ u1
                    Ma1 = a0 * (Mu1 - Mu) - a2 * Mv - a3 * Ma
                    Mv = Mv + a6 * Ma + a7 * Ma1
                    Mu, Ma = Mu1, Ma1
                if energy:
                    work[k + 1] = work[k] + 0.5 * (loads[:, k] + f1) @ (u1[dofs] - u[dofs])
                    i = at.get(k + 1)
                    if i is not None:
                        if carry:
                            kinetic[i] = 0.5 * v1 @ Mv
                            strain[i] = 0.5 * (u1[dofs] @ f1 - u1 @ Ma)
                        else:
                            kinetic[i] = 0.5 * v1 @ (M @ v1)
                            strain[i] = 0.5 * u1 @ (K @ u1)
                u, v = u1, v1
                y[k + 1] = O_cols @ u[cols]
                if k + 1 in slot:
                    saved[:, slot[k + 1]] = u
                if progress is not None and k % 100 == 0:
                    progress(k)
        energies = Energies(sampled, kinetic, strain, work[sampled]) if energy else None
        return y.T, energies, saved

    def respond(self, history=None, radius: float | None = None) -> np.ndarray:
        """Outputs (n_out, n_steps + 1) of a force history (default: the problem's) through the engine."""
        return self.respond_outputs(self.force_samples(history), radius)

    def direct(self, history=None, energy: bool = True, snapshots=()):
        """(outputs (n_out, n_steps + 1), :class:`Energies` or None, displacement at ``snapshots``) of a
        force history (default: the problem's) by direct stepping (:meth:`march`)."""
        return self.march(self.force_samples(history), None, energy, None, snapshots)

    def frequencies(self, count: int = 5) -> np.ndarray:
        """The ``count`` lowest natural frequencies [Hz] of the undamped structure (shift-invert Lanczos)."""
        import scipy.sparse.linalg as spl

        if not (isinstance(count, int) and 1 <= count < self.size - 1):
            raise InputError(f"count must be an integer from 1 to {self.size - 2}, got {count!r}")
        K, M = self.K, self.M
        try:  # a supported structure: K is positive definite, and our factor is the fast K⁻¹
            with threadpool_limits(1, user_api="blas"):
                factor = spd_factor(K)
            op = spl.LinearOperator(K.shape, matvec=factor.solve, dtype=float)
        except np.linalg.LinAlgError:  # rigid modes: let ARPACK factor K − 0·M its own way
            op = None
        # tol 1e-10 (relative, on the shift-inverted values): the frequencies to ~1e-13 and, on the
        # 48 × 48 MITC9 plate, 21 solves instead of ARPACK's default (machine precision) 32.
        ncv = min(max(2 * count + 1, 20), self.size - 1)
        vals = spl.eigsh(K, k=count, M=M, sigma=0.0, which="LM", OPinv=op, ncv=ncv, tol=1e-10, return_eigenvectors=False)
        return np.sqrt(np.abs(np.sort(vals))) / (2 * np.pi)

    def contact_structure(self, point, reach: float):
        """The structure struck at ``point`` as the coupled stepper sees it
        (:class:`softimpact.fem.impact.ContactStructure`), loadable within ``reach`` [m]."""
        raise NotImplementedError

    def contact_groups(self) -> dict[str, tuple[int, ...]] | None:
        """The named groups of the contact structure's output rows (:func:`softimpact.fem.contact.output_groups`:
        ``"gauges"``, and ``"damage"`` when the model was built with its damage outputs); None: all gauges."""
        return None

    def contact_reach(self, point, diameter: float) -> float:
        """The widest contact radius [m] the model loads about ``point`` for an impactor of
        ``diameter`` [m]: the diameter (a Hertz radius sqrt(R·α) and a flattened sphere's
        sqrt(d·α) stay within it while α < d)."""
        return diameter

    def _drop_mesh(self, light) -> None:
        """Subclasses: clear the light copy's mesh (and anything holding it)."""

    def for_workers(self):
        """A light copy for worker processes: the engine's kernels, the patch and the problem, but
        no matrices, mesh or factor (which does not pickle). It can ``respond``, not step."""
        engine = self.engine()
        if self.problem is not None and getattr(self.problem.load, "history", None) is not None:
            self.nodal_loads(self.force_samples())  # a patch that tabulates its distributions does it once, here
        light = copy.copy(self)
        light._engine = copy.copy(engine)
        light._engine.stepper = light._engine.O = None
        light.stepper = light.O = None
        self._drop_mesh(light)
        return light
