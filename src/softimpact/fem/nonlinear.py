"""The one nonlinear structure engine: Newmark–Newton stepping and load-stepped statics of any nonlinear model.

A nonlinear structure is one model (:class:`NonlinearModel`) whatever its physics: von Kármán kinematics
(:class:`~softimpact.fem.plate_vk.PlateVK`, the plane beam's :class:`~softimpact.fem.plane_tl.PlaneTL`), an
elastic–plastic section integrated through the thickness (:class:`~softimpact.fem.plate_plastic.PlasticPlate`),
cohesive interfaces between stacked sublaminates (:class:`~softimpact.fem.cohesive_plate.CohesivePlate`). It gives

- ``K`` its linear stiffness (the tangent at rest, undamaged, elastic), ``M``, ``n`` (free DOFs);
- ``nonlinear_force(d)`` = f_int(d) − K d and ``tangent(d)`` = ∂f_int/∂d, both at the *committed* internal state
  (plastic strains, damage) updated to d as the model's own step rule says (a return mapping, or damage held);
- ``strain_energy(d)`` the recoverable (elastic and interface) energy at d [J];
- ``commit(d, dt)`` stores the internal state of a converged step (its increments of dissipated energy counted
  there), ``reset()`` the virgin state, ``dissipated_energy()`` the energy dissipated so far [J] (plastic work,
  fracture energy), and ``history_names`` / ``history(d)`` the scalars it records every step (areas, energies).

So the energy balance of every nonlinear run is one: kinetic + strain + dissipated = work in. :class:`NonlinearModel`
gives the state members' defaults (no internal state), so a purely geometric model needs none of them.

:class:`NonlinearNewmark` is implicit Newmark with Newton iterations per step on u_{n+1}:

    r = f_{n+1} − M a_{n+1} − C v_{n+1} − f_int(u_{n+1}),   J = K_T(u_{n+1}) + a0 M + a1 C,

a_{n+1} = a0 (u_{n+1} − u_n) − a2 v_n − a3 a_n, v_{n+1} = v_n + dt ((1 − γ) a_n + γ a_{n+1}).
``tangent="newton"`` refactors J at every iteration (quadratic convergence); ``tangent="modified"`` keeps a factor
while each iteration cuts the residual by at least ``MODIFIED_RATE`` and refactors otherwise. A correction that does
not reduce the residual's norm is halved (a backtracking line search, at most ``HALVINGS`` times) and the tangent
refactored at the new point: a plastic section's tangent drops where a point yields and an interface's jumps where a
damaged face opens or closes, and full Newton steps can cycle across such kinks. A step has converged when
‖r‖ ≤ ``rtol``·max(‖r_0‖, ‖f_{n+1}‖, ‖M a_n‖), r_0 the residual at the predictor, or when a correction after the
first is below ``rtol`` of the step's increment; a step damped on a kink is accepted below ``STALL_RTOL``. The
default 1e-6 leaves the energy balance to the time integrator. With average acceleration (β = ¼, γ = ½) the kinetic
energy plus the trapezoidal work of the internal forces equals the external work exactly (to the Newton
tolerance). A model whose commit changes its force at the committed point (``LAGGED_STATE``: damage held within a
step and raised after it) has the step's acceleration re-equilibrated with the new force, a_n += M⁻¹(f_old − f_new)
(:meth:`NonlinearNewmark.commit`), so that the damage's rise is an instantaneous release at fixed displacement, the
energy it dissipates exactly the stored energy it removes; without it the next step's trapezoid would carry the old
force and the balance an error of order dt (1.6e-3 of the impact energy on tests/test_cohesive_plate.py's growth).
:class:`DynamicResult` reports the strain and dissipated energies the model computes from its state, so
its balance error measures the time integration of the internal work, a check that can fail.

Contact (the coupled stepper contract, :mod:`softimpact.fem.vk_stepping`): ``contact`` with ``load(u) -> (F, b)``
and ``solve(u, z) -> F'`` is condensed onto each iteration's linearised structure: with J the structure's Jacobian
(no contact term), d = J⁻¹(r − F·b) and z = J⁻¹·b, the new iterate is u + d + F'·z with F' = ``solve(u + d, z)``. A
crushing or flowing law's force goes through the approach rate with slopes of 10¹⁰ N/m within a step and is
clipped at the end of a crush; condensed, that nonsmooth part is the scalar equation the contact Newton brackets
(:func:`softimpact.fem.impact.newton_contact`), and J stays the structure's.

Statics: :func:`solve_static` (load steps, full Newton, the state committed after each) and :func:`relax` (the
equilibrium at zero load reached from a deformed state: the rest shape after an impact, a dent).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from ..errors import InputError, SolverFailed
from .newmark import NewmarkParameters, spd_factor
from .rank_update import RankUpdate


class _KrylovFailed(Exception):
    """Preconditioned conjugate gradients did not converge: the kept factor is too stale."""


__all__ = ["NonlinearModel", "NonlinearNewmark", "VonKarmanNewmark", "DynamicResult", "StaticResult", "solve_static", "relax", "KINEMATICS"]

KINEMATICS = ("linear", "von-karman")


class NonlinearModel:
    """The internal-state members of a nonlinear model (module docstring) with the defaults of a model without
    internal state: nothing to commit or reset, nothing dissipated, no recorded scalars."""

    history_names: tuple[str, ...] = ()
    LINEAR_WITHIN_STEP = False  # with its choices frozen and its state held, the model's force is linear in a step (no tangent change within it)
    LAGGED_STATE = False  # the state a commit stores changes the force at the committed point (damage held within a step, raised after it)
    row_operator = None  # G (rows, n) where the tangent is K + Gᵀ diag(row_stiffness(u)) G with G fixed: the engine updates a kept factor on the rows that changed (softimpact.fem.rank_update)

    def commit(self, d: np.ndarray, dt: float | None = None) -> None:
        """Store the internal state of the converged state ``d`` (``dt``: the step that reached it, None in statics)."""

    def reset(self) -> None:
        """The virgin internal state (a new run on the same model)."""

    def dissipated_energy(self) -> float:
        """The energy dissipated so far [J] (plastic work, fracture energy)."""
        return 0.0

    def freeze(self, u: np.ndarray) -> None:
        """Fix, for a step's Newton iterations, the piecewise choices of the model (a damaged face open or closed) as
        they stand at ``u`` (the step's predictor)."""

    def release(self, u: np.ndarray) -> int:
        """How many frozen choices the converged ``u`` contradicts (updating them to ``u``'s): the step is re-solved
        while any does."""
        return 0

    def thaw(self) -> None:
        """Back to free choices (after a step)."""

    def history(self, d: np.ndarray) -> np.ndarray:
        """The scalars of :attr:`history_names` at the committed state ``d``."""
        return np.zeros(0)


def _factor(A):
    """A factor of the sparse symmetric A with a ``solve``: :func:`~softimpact.fem.newmark.spd_factor`
    (band or minimum-degree Cholesky-like) while A is positive definite, SuperLU with pivoting on
    the minimum-degree ordering of A + Aᵀ otherwise (compressive membrane forces can make the
    static tangent indefinite)."""
    import scipy.sparse
    import scipy.sparse.linalg

    csc = scipy.sparse.csc_matrix(A)
    try:
        return spd_factor(csc)
    except np.linalg.LinAlgError:
        return scipy.sparse.linalg.splu(csc, permc_spec="MMD_AT_PLUS_A")


def _factor_solve(A, b):
    """A⁻¹ b (see :func:`_factor`)."""
    return _factor(A).solve(b)


def _pair(solve, r: np.ndarray, shape: np.ndarray | None) -> tuple[np.ndarray, np.ndarray | None]:
    """(J⁻¹ r, J⁻¹ shape) in one block solve (a large factor is read once for both), or (J⁻¹ r, None) without a contact."""
    if shape is None:
        return solve(r), None
    both = solve(np.column_stack([r, shape]))
    return both[:, 0], both[:, 1]


@dataclass(frozen=True)
class StaticResult:
    """Load-stepped Newton solution: displacements ``u`` (steps, n) at the load factors
    ``load_factors`` (steps,), Newton ``iterations`` per step, the final relative residual
    of each step ``residuals``, ``converged`` (all steps) and ``message``."""

    u: np.ndarray
    load_factors: np.ndarray
    iterations: np.ndarray
    residuals: np.ndarray
    converged: bool
    message: str


GROWTH_LIMIT = 10.0  # a static Newton step whose residual grows more than this factor (or is not finite) is damped


def _newton(model, f, u, scale, rtol, max_iterations, line_search: bool = False):
    """Full Newton on f_int(u) = f from ``u``: (u, iterations, relative residual, converged). Load stepping takes full
    steps (from the previous load step they converge quadratically on the plates' stiffening: a residual-norm line
    search there took 12 iterations where full steps take 8, tests/test_plate_vk.py); with ``line_search`` a
    correction whose residual grows past :data:`GROWTH_LIMIT` times the last (or is not finite) is halved, at most
    :attr:`NonlinearNewmark.HALVINGS` times: a safeguard against divergence that leaves Newton's own path alone
    (a yielding section's first iterate may well raise the residual a few times before converging quadratically;
    damping every rise took 20-40 iterations a load step where full steps take 6, tests/test_plastic_plate.py)."""
    r = f - model.internal_force(u)
    norm = float(np.linalg.norm(r))
    for it in range(1, max_iterations + 1):
        try:
            du = _factor_solve(model.tangent(u), r)
        except RuntimeError:  # SuperLU: "Factor is exactly singular": a mechanism (a plastic collapse), no equilibrium
            return u, it, math.inf, False
        step = 1.0
        for _ in range(NonlinearNewmark.HALVINGS + 1 if line_search else 1):
            trial = u + step * du
            r_new = f - model.internal_force(trial)
            n_new = float(np.linalg.norm(r_new))
            if n_new <= GROWTH_LIMIT * norm:  # (False for NaN: halved)
                break
            step *= 0.5
        u, r, norm = trial, r_new, n_new
        if norm <= rtol * scale:
            return u, it, norm / scale, True
    return u, max_iterations, norm / scale, False


def solve_static(
    model, load: np.ndarray, *, load_steps: int = 10, load_factors=None, rtol: float = 1e-10, max_iterations: int = 30, kinematics: str = "von-karman"
) -> StaticResult:
    """Static equilibrium f_int(u) = λ·load at λ = k/load_steps, k = 1 … load_steps (or at the
    increasing ``load_factors`` given), by full Newton with the consistent tangent, each step
    starting from the previous step's solution and committing the model's state at its end (with a line search
    where the model has internal state: a section yielding between two load steps). A step has
    converged when the residual is below ``rtol`` of the load's norm. With ``kinematics="linear"`` and a
    model without internal state (no :attr:`~NonlinearModel.history_names`): one solve with K."""
    if kinematics not in KINEMATICS:
        raise InputError(f"kinematics: {kinematics!r} is not one of {', '.join(KINEMATICS)}")
    if isinstance(load_steps, bool) or not (isinstance(load_steps, (int, np.integer)) and load_steps >= 1):
        raise InputError(f"load_steps must be a positive integer, got {load_steps!r}")
    load = np.asarray(load, float)
    lams = np.arange(1, load_steps + 1) / load_steps if load_factors is None else np.asarray(load_factors, float)
    if lams.ndim != 1 or lams.size == 0 or np.any(np.diff(lams) <= 0) or lams[0] <= 0:
        raise InputError(f"load_factors must increase from a positive value, got {load_factors!r}")
    load_steps = lams.size
    if kinematics == "linear" and not model.history_names:
        u1 = _factor_solve(model.K, load)
        return StaticResult(np.outer(lams, u1), lams, np.ones(load_steps, int), np.zeros(load_steps), True, "linear")
    u = np.zeros(model.n)
    us, its, res = [], [], []
    converged, message = True, "converged"
    for lam in lams:
        f = lam * load
        # a model with internal state (a yielding section) can make a full step from the last load step overshoot: damp it
        u, it, rel, ok = _newton(model, f, u, max(np.linalg.norm(f), 1e-300), rtol, max_iterations, line_search=bool(model.history_names))
        if not ok:
            why = (
                f"{max_iterations} iterations, residual {rel:.3g}" if math.isfinite(rel) else f"the tangent became singular after {it} iterations: a mechanism"
            )
            converged, message = False, f"Newton did not converge at load factor {lam:g} ({why})"
        else:
            _commit(model, u, None)
        us.append(u.copy())
        its.append(it)
        res.append(rel)
        if not converged:
            break
    return StaticResult(np.array(us), lams[: len(us)], np.array(its), np.array(res), converged, message)


def _commit(model, u, dt) -> None:
    model.commit(u, dt)


def relax(model, u: np.ndarray, *, rtol: float = 1e-9, max_iterations: int = 50, scale: float | None = None) -> tuple[np.ndarray, int]:
    """(u_rest, iterations): the equilibrium f_int(u) = 0 reached by Newton from the deformed state ``u`` with the
    model's committed internal state (its plastic strains, damage), committed again at the end: the shape the
    structure comes to rest in once its motion has died away (a dent). ``scale``: the force the residual is
    measured against (default ‖f_int(u)‖, the unbalanced force at the start)."""
    f = np.zeros(model.n)
    scale = scale if scale is not None else max(float(np.linalg.norm(model.internal_force(u))), 1e-300)
    u, it, rel, ok = _newton(model, f, np.asarray(u, float).copy(), scale, rtol, max_iterations, line_search=True)
    if not ok:
        raise SolverFailed(f"the structure's rest shape: Newton did not converge in {max_iterations} iterations (relative residual {rel:.3g})")
    _commit(model, u, None)
    return u, it


@dataclass(frozen=True)
class DynamicResult:
    """Nonlinear Newmark run: ``t`` (steps + 1,), ``outputs`` (rows, steps + 1), the energies
    ``kinetic``, ``strain`` (recoverable), ``work`` (external, trapezoidal) and ``dissipated`` per time [J],
    Newton ``iterations`` per step, tangent ``factorisations`` in all, final state ``u``, ``v``, ``a``."""

    t: np.ndarray
    outputs: np.ndarray
    kinetic: np.ndarray
    strain: np.ndarray
    work: np.ndarray
    iterations: np.ndarray
    factorisations: int
    u: np.ndarray
    v: np.ndarray
    a: np.ndarray
    dissipated: np.ndarray | None = None

    def balance_error(self) -> np.ndarray:
        """(kinetic + strain + dissipated) − (initial energy + work) [J] per time."""
        lost = 0.0 if self.dissipated is None else self.dissipated
        return self.kinetic + self.strain + lost - (self.kinetic[0] + self.strain[0]) - self.work


class NonlinearNewmark:
    """Implicit Newmark–Newton stepping of a nonlinear ``model`` (module docstring): β, γ of
    :class:`~softimpact.fem.newmark.NewmarkParameters`, damping ``C`` (or None), ``rtol``, ``max_iterations``,
    ``tangent`` ``"newton"`` or ``"modified"``. Loads depending on u: :meth:`step` takes an optional
    ``extra(u) -> (force, stiffness)`` joining the residual and the Jacobian, and the condensed ``contact``."""

    MODIFIED_RATE = 0.25  # a kept factor must cut the residual at least 4× per iteration
    KRYLOV_RTOL = 1e-10  # conjugate gradients on the exact Jacobian, preconditioned by the kept factor: relative residual
    KRYLOV_ITERATIONS = 16  # past this the kept factor is too stale: refactor (16 was the cheapest of 6-40 on the 8-in plate's Turon near field: 28 s against 39 s refactoring, 46 s at 40)
    HALVINGS = 8  # backtracking halvings of a correction that does not lower the residual
    STALL_RTOL = (
        1e-4  # a step damped or stalled on a kink is accepted below this relative residual (its work error, residual × step, is in the energy balance tested)
    )

    def __init__(
        self,
        model,
        dt: float,
        C=None,
        params: NewmarkParameters = NewmarkParameters(),
        *,
        rtol: float = 1e-6,
        max_iterations: int = 30,
        tangent: str = "newton",
    ):
        if not (math.isfinite(dt) and dt > 0):
            raise InputError(f"time_step must be positive, got {dt!r}", "time_step")
        if tangent not in ("newton", "modified"):
            raise InputError(f"tangent: {tangent!r} is not 'newton' or 'modified'")
        b, g = params.beta, params.gamma
        self.model, self.dt, self.params, self.C = model, dt, params, C
        self.a0, self.a1, self.a2, self.a3 = 1.0 / (b * dt * dt), g / (b * dt), 1.0 / (b * dt), 1.0 / (2.0 * b) - 1.0
        self.rtol, self.max_iterations, self.tangent_kind = rtol, max_iterations, tangent
        self._lu = None
        self._update = None  # the kept factor's rank update (models with a row_operator)
        self.rank_updates = 0  # preconditioners built by it
        self._mass = None  # a factor of M, for re-equilibrating a lagged state's commit
        self.factorisations = 0
        self.krylov_solves = 0  # solves by the kept factor's preconditioned conjugate gradients (LINEAR_WITHIN_STEP models)
        # K_eff = K + a0 M + a1 C: the linear part of the residual in one product per iteration
        self._keff = (model.K + self.a0 * model.M + (0.0 if C is None else self.a1 * C)).tocsr()

    def _matrix(self, u, extra_k):
        """J = K_T(u) + a0 M (+ a1 C, + the extra load's stiffness): the step's Jacobian at ``u``."""
        J = self.model.tangent(u) + self.a0 * self.model.M
        if self.C is not None:
            J = J + self.a1 * self.C
        if extra_k is not None:
            J = J + extra_k
        return J

    def _row_stiffness(self, u):
        """The model's ``row_stiffness(u)`` where it has a ``row_operator`` (computed once an iteration, for both the
        preconditioner and the product), else None."""
        return None if getattr(self.model, "row_operator", None) is None else self.model.row_stiffness(u)

    def _operator(self, u, extra_k, s):
        """J as the conjugate gradients use it (products only): K_eff + Gᵀ diag(s) G (+ the extra stiffness) for a model
        with a ``row_operator`` (``s`` its row stiffness at ``u``; no assembly), the assembled :meth:`_matrix` otherwise."""
        if s is None:
            return self._matrix(u, extra_k)
        import scipy.sparse.linalg as spl

        G, keff = self.model.row_operator, self._keff

        def product(x):
            y = keff @ x + G.T @ (s * (G @ x))
            return y if extra_k is None else y + extra_k @ x

        return spl.LinearOperator(keff.shape, matvec=product, dtype=float)

    def _jacobian(self, u, extra_k):
        self.factorisations += 1
        start = time.process_time()
        self._lu = _factor(self._matrix(u, extra_k))
        rows = getattr(self.model, "row_operator", None)
        cost = time.process_time() - start
        known = None if self._update is None else self._update.column_seconds  # the same pattern: a column costs what it did
        self._update = None if (rows is None or extra_k is not None) else RankUpdate(self._lu, rows, self.model.row_stiffness(u), cost, known)

    def _preconditioner(self, extra_k, s):
        """The solve the conjugate gradients are preconditioned with: the kept factor updated on the rows whose stiffness
        changed since it (:class:`~softimpact.fem.rank_update.RankUpdate`) for a model with a ``row_operator``, the kept
        factor alone otherwise; None when too many rows changed (then refactor)."""
        if self._update is None or extra_k is not None:
            return self._lu.solve
        solve = self._update.solver(s)
        self.rank_updates += solve is not None and self._update.active > 0
        return solve

    def _krylov(self, J, pre_solve):
        """A solver of J x = b by conjugate gradients preconditioned with ``pre_solve`` (the factor kept, of an earlier
        J, updated where the model's rows changed: :meth:`_preconditioner`): for a model linear within a step whose
        stiffness changed at a few points since that factor (the interfaces' damage and closure), a handful of
        back-substitutions instead of a new factor; raises :class:`_KrylovFailed` where they do not converge (then
        refactor). Conjugate gradients need J symmetric positive definite: the held-damage tangent plus a0·M is."""
        import scipy.sparse.linalg as spl

        pre = spl.LinearOperator(J.shape, matvec=pre_solve, dtype=float)

        def column(b, x0):
            if not np.any(b):
                return np.zeros_like(b)
            x, info = spl.cg(J, b, x0=x0, rtol=self.KRYLOV_RTOL, atol=0.0, maxiter=self.KRYLOV_ITERATIONS, M=pre)
            if info != 0:
                raise _KrylovFailed
            self.krylov_solves += 1
            return x

        def solve(b):
            """J⁻¹ b for b (n,) or (n, k): the columns' first guesses in one block solve (the factor read once), then
            each column's conjugate gradients (none where the guess is already within the tolerance)."""
            x0 = pre_solve(b)
            if np.ndim(b) == 1:
                return column(b, x0)
            return np.column_stack([column(b[:, j], x0[:, j]) for j in range(b.shape[1])])

        return solve

    def initial_acceleration(self, u, v, f):
        """a_0 from M a = f − C v − f_int(u)."""
        rhs = f - self.model.internal_force(u) - (0.0 if self.C is None else self.C @ v)
        if not np.any(rhs):
            return np.zeros_like(rhs)  # at rest and unloaded (an impact's first contact): no factor of M needed
        return _factor_solve(self.model.M, rhs)

    def commit(self, u: np.ndarray, a: np.ndarray) -> np.ndarray:
        """Commit the model's state at the converged ``u``; the acceleration ``a`` there, re-equilibrated when the
        commit changed the force (module docstring)."""
        model = self.model
        if not model.LAGGED_STATE:
            model.commit(u, self.dt)
            return a
        before = model.nonlinear_force(u)
        model.commit(u, self.dt)
        jump = before - model.nonlinear_force(u)
        if not np.any(jump):
            return a
        if self._mass is None:
            self._mass = _factor(self.model.M)
        return a + self._mass.solve(jump)

    def _finish(self, u1, u, v, a):
        a1 = self.a0 * (u1 - u) - self.a2 * v - self.a3 * a
        return u1, v + self.dt * ((1 - self.params.gamma) * a + self.params.gamma * a1), a1

    SETS = 8  # re-solves of a step whose frozen piecewise choices its answer contradicts

    def step(self, u, v, a, f1, extra=None, contact=None):
        """(u1, v1, a1, iterations) of one step to the load f1, with ``extra`` and ``contact`` (module docstring): the
        model's piecewise choices frozen at the predictor (:meth:`NonlinearModel.freeze`), the step re-solved from its
        answer while that answer contradicts them (:meth:`NonlinearModel.release`), at most :attr:`SETS` times."""
        model = self.model
        start = u + self.dt * v + self.dt * self.dt * (0.5 - self.params.beta) * a
        model.freeze(start)
        total = 0
        try:
            for _ in range(self.SETS):
                u1, v1, a1, its = self._solve(u, v, a, f1, extra, contact, start)
                total += its
                if model.release(u1) == 0:
                    break
                start = u1
            return u1, v1, a1, total
        finally:
            model.thaw()

    def _solve(self, u, v, a, f1, extra, contact, start):
        """(u1, v1, a1, iterations): Newton on the step from ``start`` with the model's choices as frozen."""
        g, dt = self.params.gamma, self.dt
        M, C, model = self.model.M, self.C, self.model
        u1 = start  # the Newmark predictor (zero new acceleration), or the last solve's answer
        # M a1 + C v1 + K u1 = K_eff u1 − p with p from the step's start (Newmark's a1, v1 are affine in u1)
        ma = M @ a
        p = M @ (self.a0 * u + self.a2 * v) + self.a3 * ma
        if C is not None:
            p = p - C @ (v + dt * (1 - g) * a - dt * g * (self.a0 * u + self.a2 * v + self.a3 * a))
        rhs = f1 + p

        def residual(x):
            r = rhs - self._keff @ x - model.nonlinear_force(x)
            ek, load = None, (0.0, None)
            if extra is not None:
                fe, ek = extra(x)
                r = r + fe
            if contact is not None:
                load = contact.load(x)
                r = r + load[0] * load[1]
            return r, ek, load

        r, ek, load = residual(u1)
        norm = np.linalg.norm(r)
        # the forces in balance: load, inertia (at the step's start), the predictor's out-of-balance force
        scale = max(norm, np.linalg.norm(f1), np.linalg.norm(ma), 1e-300)
        last = np.inf
        for it in range(1, self.max_iterations + 1):
            if it > 1 and norm <= self.rtol * scale:
                return self._finish(u1, u, v, a) + (it - 1,)
            solve = None
            pre = rows = None
            if self._lu is not None and self.tangent_kind == "modified" and model.LINEAR_WITHIN_STEP:
                rows = self._row_stiffness(u1)
                pre = self._preconditioner(ek, rows)
            if pre is not None:
                solve = self._krylov(self._operator(u1, ek, rows), pre)  # the exact Jacobian, the kept factor (updated) its preconditioner
            elif self._lu is not None and self.tangent_kind == "modified" and model.LINEAR_WITHIN_STEP:
                self._jacobian(u1, ek)  # too many rows changed since the kept factor
            elif self._lu is None or self.tangent_kind == "newton" or norm > self.MODIFIED_RATE * last:
                self._jacobian(u1, ek)
            try:
                du, z = _pair(solve or self._lu.solve, r, load[1] if contact is not None else None)
            except _KrylovFailed:
                self._jacobian(u1, ek)
                du, z = _pair(self._lu.solve, r, load[1] if contact is not None else None)
            if contact is not None:  # the contact condensed on the linearised structure: u + d + F'·z
                fc, shape = load
                free = u1 + du - fc * z
                du = free + contact.solve(free, z) * z - u1
            step = 1.0
            for _ in range(self.HALVINGS + 1):
                trial = u1 + step * du
                r_new, ek_new, load_new = residual(trial)
                n_new = np.linalg.norm(r_new)
                if n_new < norm or n_new <= self.rtol * scale:
                    break
                step *= 0.5
            else:  # no decrease along the correction: stalled on a kink; done if the residual is already small
                if norm <= self.STALL_RTOL * scale:
                    return self._finish(u1, u, v, a) + (it,)
                self._lu = None
                continue
            last, norm = norm, n_new
            u1, r, ek, load = trial, r_new, ek_new, load_new
            if step < 1.0:
                if norm <= self.STALL_RTOL * scale:  # damped on a kink, and already small: accept
                    return self._finish(u1, u, v, a) + (it,)
                self._lu = None  # refactor at the new point: the tangent there has the new states
            if it > 1 and step == 1.0 and np.linalg.norm(du) <= self.rtol * np.linalg.norm(u1 - u):
                # a correction at round-off of the step's increment (Bathe's displacement criterion): no further force evaluation
                return self._finish(u1, u, v, a) + (it,)
        raise SolverFailed(
            f"the nonlinear Newmark–Newton step did not converge in {self.max_iterations} iterations (residual {norm:.3g} of scale {scale:.3g} N): "
            "try a smaller time step"
        )

    def run(self, load, steps: int, rows: np.ndarray | None = None, u0=None, v0=None, energies: bool = True, extra=None) -> DynamicResult:
        """March ``steps`` steps; ``load(t)`` -> force vector (or None for free vibration);
        ``rows`` (k, n) the outputs recorded (default: none); ``energies=False`` skips the
        strain energy (one more pass over the elements per step) and leaves it zero; ``extra``
        as in :meth:`step` (its work is not in ``work``: a conservative ``extra``'s energy is
        the caller's to add). The model's state is committed after every step."""
        n = self.model.n
        u = np.zeros(n) if u0 is None else np.asarray(u0, float).copy()
        v = np.zeros(n) if v0 is None else np.asarray(v0, float).copy()
        zero = np.zeros(n)

        def force(t):
            return zero if load is None else np.asarray(load(t), float)

        f = force(0.0)
        a = self.initial_acceleration(u, v, f)
        rows = np.zeros((0, n)) if rows is None else np.atleast_2d(rows)
        t = np.arange(steps + 1) * self.dt
        out = np.zeros((rows.shape[0], steps + 1))
        kin, strain, work, lost, its = np.zeros(steps + 1), np.zeros(steps + 1), np.zeros(steps + 1), np.zeros(steps + 1), np.zeros(steps, int)
        out[:, 0] = rows @ u
        kin[0], strain[0] = 0.5 * v @ (self.model.M @ v), self.model.strain_energy(u)
        lost[0] = self.model.dissipated_energy()
        for k in range(steps):
            f1 = force(t[k + 1])
            u1, v1, a1, its[k] = self.step(u, v, a, f1, extra)
            a1 = self.commit(u1, a1)
            work[k + 1] = work[k] + 0.5 * (u1 - u) @ (f + f1)
            u, v, a, f = u1, v1, a1, f1
            out[:, k + 1] = rows @ u
            kin[k + 1] = 0.5 * v @ (self.model.M @ v)
            strain[k + 1] = self.model.strain_energy(u) if energies else 0.0
            lost[k + 1] = self.model.dissipated_energy()
        return DynamicResult(t, out, kin, strain, work, its, self.factorisations, u, v, a, lost - lost[0])


VonKarmanNewmark = NonlinearNewmark  # its name before the engine took every nonlinear model
