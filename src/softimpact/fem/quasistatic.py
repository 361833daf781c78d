"""Quasi-static path following of a structure whose damage is committed between increments.

The model (duck-typed, :class:`CommittedDamage`: a :class:`~softimpact.fem.cohesive_plate.CohesivePlate` is one)
gives its internal force f_int(u) [N] and tangent K_T(u) [N/m] *at its committed damage* and a ``commit(u)``
that stores the damage of the state u (irreversibly: max(committed, d(δ(u))) for a cohesive law). The load is a
force λ [N] along a fixed direction g (f = λ·g, a DOF vector); a control c (a DOF vector) is raised to the
values asked for, cᵀu = c̄; the DOFs ``fixed`` are held at zero (eliminated: point supports and the constraints
that remove the rigid motions). Within an increment, at the committed damage, Newton on the bordered system

    [K_T   −g] [Δu]   [λ·g − f_int(u)]
    [cᵀ     0] [Δλ] = [c̄ − cᵀu       ],

solved by bordering: K_T·a = g and K_T·b = r (two back-substitutions of one factor), Δλ = (r_c − cᵀb)/(cᵀa),
Δu = b + Δλ·a. With c = g this is load-point displacement control; a local control (the opening or sliding at
a crack tip, which grows monotonically) passes the snap-backs of unstable specimens, as
:func:`softimpact.fem.cohesive_beam.solve_quasistatic` does for beams (whose law updates the damage inside the
Newton iterations; here the model holds it fixed within a solve).

The damage within an increment, three ways (``damage``):

- ``"newton"`` (default): Newton on the damage and the equilibrium together. The damage of a state u is the model's
  commit of u from the increment's committed damage, D(u) (irreversible from there), and the force F(u) = f(u; D(u));
  its Jacobian is the tangent at D(u) plus ∂f/∂D·D'(u), the second term a finite difference in the damage alone,
  applied inside GMRES preconditioned by the tangent's factor (it differs from the tangent only at the points whose
  damage grows: a low-rank change, GMRES converges in about as many iterations as there are such points); a
  backtracking line search on the residual after a few full corrections. The converged state is a fixed point: the
  equilibrium of the damage it produces. An increment whose Newton iterations fail (they can cycle across the law's
  kinks, where a point's damage reaches 1 or stops growing) is taken again from its start by the staggered passes.
- ``"iterate"``: equilibrium at the committed damage, then ``commit``, repeated until the largest change of the
  damage in a pass is below ``damage_tol``: the same fixed point (the staggered or alternate-minimisation scheme).
  Damage only grows, so the passes increase it monotonically from the last increment's; each pass costs one
  factorisation, and near a peak the passes converge slowly (hundreds of them: BENCHMARKS.md).
- ``"lagged"``: one equilibrium, one commit — the damage lags one increment, as in the dynamic stepper of
  :mod:`softimpact.fem.cohesive_plate`; its error is of the order of the increment (tests/test_krueger.py).

An increment whose Newton iterations or damage passes do not converge is restored (the model's ``damage`` is set
back) and halved, down to ``MIN_STEP_FRACTION`` of the requested one, then :class:`~softimpact.errors.SolverFailed`.

Energies (when the model has ``K`` and ``stored_energy``): the external work W = ∫λ d(gᵀu) (trapezoid between the
increments' converged states), the elastic energy ½uᵀKu of the linear part and the interfaces' recoverable energy;
W minus both is the energy dissipated (:attr:`QuasiStaticPath.dissipated`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np
import scipy.sparse
import scipy.sparse.linalg

from ..errors import InputError, SolverFailed
from .newmark import spd_factor

__all__ = ["CommittedDamage", "DAMAGE_MODES", "QuasiStatic", "QuasiStaticPath", "linear_response", "quasistatic_path"]

DAMAGE_MODES = ("newton", "iterate", "lagged")
NEWTON_MAX = 25  # Newton iterations at one damage before the increment is halved
NEWTON_TOL = 1e-9  # residual norm relative to the largest of the load and the internal force
STEP_TOL = 1e-12  # a full Newton correction below this fraction of |u|: converged (the penalty's round-off floor)
MAX_PASSES = 400  # damage passes of one increment before it is halved
MIN_STEP_FRACTION = 1.0 / 1024  # of a requested increment: below it the solver gives up
FALLBACK_BELOW = 1.0 / 4  # an increment Newton fails at this fraction of the requested one (two halvings) goes to the staggered passes
FD_STEP = 1e-9  # the finite difference of the damage along v: ε·|v| = FD_STEP·|u| (the law's d(δ) is smooth between its kinks)
KRYLOV_TOL = 1e-10  # GMRES's relative residual of a Newton correction
KRYLOV_MAX = 400  # GMRES iterations of one correction (about the points whose damage grows, at most)
LINE_SEARCH_AFTER = 4  # full Newton corrections before the backtracking starts
LINE_SEARCH_MIN = 1.0 / 64  # smallest fraction of a Newton correction the backtracking tries


class CommittedDamage(Protocol):
    """What :func:`quasistatic_path` needs of a model (module docstring): ``n`` DOFs, the committed ``damage``
    (an array the solver may set back), ``internal_force(u)`` and ``tangent(u)`` at that damage, ``commit(u)``;
    ``K`` and ``stored_energy(u)`` optionally, for the energies."""

    n: int
    damage: np.ndarray

    def internal_force(self, u: np.ndarray) -> np.ndarray: ...

    def tangent(self, u: np.ndarray): ...

    def commit(self, u: np.ndarray) -> None: ...


@dataclass(frozen=True)
class QuasiStaticPath:
    """A quasi-static path at the requested control values (m of them): ``control`` c̄ = cᵀu, ``displacement``
    gᵀu (the load's work-conjugate displacement, in the units that make λ·gᵀu a work [J]), ``force`` λ [N],
    ``external_work`` [J], ``elastic_energy`` ½uᵀKu and ``interface_energy`` (the model's stored energy) [J] (NaN
    when the model has no ``K`` or ``stored_energy``), each (m,); spent reaching each value: ``iterations`` (the damage
    passes, or the Newton iterations of ``"newton"``), ``krylov`` (GMRES iterations) and ``factorisations``;
    ``damage_change`` the largest change of the damage in the last pass or iteration (m,); ``damage`` the committed damage at each value (m, ...);
    ``u`` the final DOFs (n,)."""

    control: np.ndarray
    displacement: np.ndarray
    force: np.ndarray
    external_work: np.ndarray
    elastic_energy: np.ndarray
    interface_energy: np.ndarray
    iterations: np.ndarray
    krylov: np.ndarray
    factorisations: np.ndarray
    damage_change: np.ndarray
    damage: np.ndarray
    u: np.ndarray

    @property
    def dissipated(self) -> np.ndarray:
        """External work minus the recoverable energies [J] (the energy the damage dissipated), (m,)."""
        return self.external_work - self.elastic_energy - self.interface_energy


def _factor(A):
    """A factor with ``solve`` of the symmetric tangent: :func:`~softimpact.fem.newmark.spd_factor` while it is
    positive definite (it is, once the fixed DOFs remove the rigid motions), SuperLU otherwise."""
    csc = scipy.sparse.csc_matrix(A)
    try:
        return spd_factor(csc)
    except np.linalg.LinAlgError:
        return scipy.sparse.linalg.splu(csc, permc_spec="MMD_AT_PLUS_A")


class _Bordered:
    """The reduced (free-DOF) bordered system of a model, its load g and control c (module docstring)."""

    def __init__(self, model, load, control, fixed):
        n = int(model.n)
        g, c = (np.asarray(v, float) for v in (load, control))
        if g.shape != (n,) or c.shape != (n,):
            raise InputError(f"load and control must be DOF vectors of shape ({n},), got {g.shape} and {c.shape}", "load")
        free = np.ones(n, bool)
        free[np.asarray(fixed, int)] = False
        self.model, self.n, self.idx = model, n, np.flatnonzero(free)
        self.g, self.c = g[self.idx], c[self.idx]
        if not np.any(self.g) or not np.any(self.c):
            raise InputError("the load and the control must act on free DOFs", "control")
        self.factors = 0

    def full(self, uf: np.ndarray) -> np.ndarray:
        """The DOF vector (n,) of the free values ``uf``, zero on the fixed DOFs."""
        u = np.zeros(self.n)
        u[self.idx] = uf
        return u

    def factor(self, uf):
        """A factor of the reduced tangent at ``uf`` (committed damage)."""
        self.factors += 1
        return _factor(self.model.tangent(self.full(uf))[self.idx][:, self.idx])

    def orient(self) -> None:
        """Turn c so that raising the control loads the structure (cᵀK_T⁻¹g > 0 at rest): a local control has no
        obvious sign."""
        if self.c @ self.factor(np.zeros(self.idx.size)).solve(self.g) < 0:
            self.c = -self.c

    def residual(self, uf, lam):
        """(r = λg − f_int at the free DOFs, the residual's scale)."""
        fi = self.model.internal_force(self.full(uf))[self.idx]
        return lam * self.g - fi, max(abs(lam) * np.linalg.norm(self.g), np.linalg.norm(fi), 1e-300)

    def newton(self, uf, lam, target):
        """Equilibrium at control ``target`` and the committed damage from (``uf``, ``lam``): (converged, uf, λ,
        iterations). At a fixed damage the model is piecewise linear (its damaged faces open or closed), so this
        converges in one or two corrections unless a face changes side."""
        r, scale = self.residual(uf, lam)
        for it in range(1, NEWTON_MAX + 1):
            F = self.factor(uf)
            a, b = F.solve(self.g), F.solve(r)
            dlam = (target - self.c @ uf - self.c @ b) / (self.c @ a)
            du = b + dlam * a
            uf, lam = uf + du, lam + dlam
            r, scale = self.residual(uf, lam)
            if np.linalg.norm(r) <= NEWTON_TOL * scale or np.linalg.norm(du) <= STEP_TOL * np.linalg.norm(uf):
                return True, uf, lam, it
        return False, uf, lam, NEWTON_MAX


@dataclass
class _State:
    """The committed state: free DOFs, force, control value, work so far, displacement gᵀu."""

    uf: np.ndarray
    lam: float = 0.0
    cbar: float = 0.0
    work: float = 0.0
    disp: float = 0.0


def _staggered(system: _Bordered, state: _State, target: float, mode: str, damage_tol: float):
    """One increment to ``target`` by passes of equilibrium at the committed damage and commits (``"iterate"``: until
    the damage changes by at most ``damage_tol``; ``"lagged"``: one pass): (converged, uf, λ, passes, Newton
    iterations, last damage change); the model's damage is committed at the new state (the caller restores it
    when the increment failed)."""
    model = system.model
    uf, lam, newton, change = state.uf, state.lam, 0, np.inf
    for passes in range(1, MAX_PASSES + 1):
        ok, uf, lam, it = system.newton(uf, lam, target)
        newton += it
        if not ok:
            return False, uf, lam, passes, newton, change
        before = model.damage.copy()
        model.commit(system.full(uf))
        change = float(np.max(np.abs(model.damage - before))) if before.size else 0.0
        if mode == "lagged" or change <= damage_tol:
            return True, uf, lam, passes, newton, change
    return False, uf, lam, MAX_PASSES, newton, change


def _corrections(system: _Bordered, uf, D, damage_at, r, residual_c):
    """(Newton correction, GMRES iterations) of the bordered system at ``uf`` with the damage D = D(u)
    (the model holds it): :func:`_consistent`. ``damage_at(v)`` sets the model's damage to D(v); ``r``, ``residual_c``:
    the force and control residuals."""
    model = system.model
    A = model.tangent(system.full(uf))[system.idx][:, system.idx].tocsr()
    system.factors += 1
    F = _factor(A)
    f0 = model.internal_force(system.full(uf))[system.idx]
    norm_u = max(np.linalg.norm(uf), 1e-300)
    m, g, c = system.idx.size, system.g, system.c

    def jv(v):
        nv = np.linalg.norm(v)
        if nv == 0.0:
            return np.zeros_like(v)
        eps = FD_STEP * norm_u / nv
        damage_at(uf + eps * v)
        f1 = model.internal_force(system.full(uf))[system.idx]
        model.damage = D
        return A @ v + (f1 - f0) / eps

    # The bordered system [J −g; cᵀ 0] by GMRES, preconditioned by the same system with the tangent A (bordering: one
    # back-substitution an application)
    a0 = F.solve(g)
    ca0 = c @ a0

    def bordered(z):
        return np.concatenate((jv(z[:m]) - g * z[m], [c @ z[:m]]))

    def precondition(z):
        x = F.solve(z[:m])
        mu = (z[m] - c @ x) / ca0
        return np.concatenate((x + mu * a0, [mu]))

    op = scipy.sparse.linalg.LinearOperator((m + 1, m + 1), matvec=bordered, dtype=float)
    M = scipy.sparse.linalg.LinearOperator((m + 1, m + 1), matvec=precondition, dtype=float)
    rhs = np.concatenate((r, [residual_c]))
    counter = [0]

    def count(_):
        counter[0] += 1

    guess = precondition(rhs)  # the equilibrium at the damage D(u): one pass of the staggered scheme
    z, _ = scipy.sparse.linalg.gmres(op, rhs, x0=guess, M=M, rtol=KRYLOV_TOL, atol=0.0, restart=KRYLOV_MAX, maxiter=1, callback=count, callback_type="pr_norm")
    return z, counter[0]


def _consistent(system: _Bordered, state: _State, target: float, damage_tol: float, trial_damage=None):
    """One increment to ``target`` by Newton on the damage and the equilibrium together (module docstring, "newton"):
    (converged, uf, λ, Newton iterations, Krylov iterations, damage change of the last iteration). The damage of a
    state u is the model's commit of u from the increment's committed damage d_c, D(u); the force F(u) = f(u; D(u));
    its Jacobian J = ∂f/∂u at D(u) (the model's tangent, which factors) + ∂f/∂D·D'(u), the second term a finite
    difference in the damage alone (f is affine in the damage at a fixed u, so nothing else cancels), applied by GMRES
    preconditioned with the tangent's factor: J differs from it only at the points whose damage grows, a low-rank
    change, so GMRES converges in about as many iterations as there are such points."""
    model = system.model
    d_c = model.damage.copy()
    m = system.idx.size

    def damage_at(uf):
        if trial_damage is not None:
            model.damage = trial_damage(system.full(uf), d_c)
        else:
            model.damage = d_c
            model.commit(system.full(uf))
        return model.damage.copy()

    def residual(uf, lam):
        D = damage_at(uf)  # leaves model.damage = D(u)
        r, scale = system.residual(uf, lam)
        return r, scale, D

    uf, lam = state.uf, state.lam
    r, scale, D = residual(uf, lam)
    krylov, change = 0, np.inf
    for it in range(1, NEWTON_MAX + 1):
        z, k = _corrections(system, uf, D, damage_at, r, target - system.c @ uf)
        krylov += k
        r0 = np.linalg.norm(r)
        alpha = 1.0
        # Backtracking on the residual's norm after LINE_SEARCH_AFTER full corrections (a full one meets the linear
        # control exactly; the first from rest has a zero residual to compare with): the residual is not smooth where a
        # point's damage reaches 1 or stops growing, and full corrections can cycle across such a kink.
        while True:
            step = alpha * z
            r_try, scale_try, D_try = residual(uf + step[:m], lam + step[m])
            if it <= LINE_SEARCH_AFTER or np.linalg.norm(r_try) < r0 or alpha <= LINE_SEARCH_MIN:
                break
            alpha /= 2
        change = float(np.max(np.abs(D_try - D))) if D.size else 0.0
        uf, lam, r, scale, D = uf + step[:m], lam + step[m], r_try, scale_try, D_try
        # converged: the residual below tolerance, or a full correction that no longer moves u (the penalty's round-off
        # floor, K·|u|·ε, can sit above NEWTON_TOL of the force at small loads)
        small = np.linalg.norm(r) <= NEWTON_TOL * scale or (alpha == 1.0 and np.linalg.norm(step[:m]) <= STEP_TOL * np.linalg.norm(uf))
        if small and change <= damage_tol:
            if trial_damage is not None:  # the one commit of the increment, from its start: the model's own bookkeeping
                model.damage = d_c
                model.commit(system.full(uf))
            return True, uf, lam, it, krylov, change
    return False, uf, lam, NEWTON_MAX, krylov, change


def linear_response(model, load, fixed=()) -> np.ndarray:
    """The DOFs (n,) under the unit load ``load`` on the tangent at rest with the committed damage (the elastic response
    of a pre-cracked specimen), ``fixed`` DOFs held at zero."""
    system = _Bordered(model, load, load, fixed)
    return system.full(system.factor(np.zeros(system.idx.size)).solve(system.g))


class QuasiStatic:
    """A quasi-static path on ``model`` (module docstring), raised by :meth:`advance` one control value at a time;
    :meth:`result` the :class:`QuasiStaticPath` so far (scipy's stepper-and-function pattern: :func:`quasistatic_path`
    runs a list of values). ``load`` g and ``control`` c (default g: load-point displacement control) are DOF
    vectors (n,), ``fixed`` the DOFs held at zero; ``damage`` one of :data:`DAMAGE_MODES`, ``damage_tol`` the
    largest change of the damage [-] in a converged increment's last pass or iteration. The model must carry its
    initial damage (e.g. a pre-crack); the path commits the damage on it as it goes. ``trial_damage(u, d)``, when
    given, returns the damage ``commit`` would store at u from d without storing it: Newton's trial states then leave
    the model's commits (and whatever it counts in them, such as the energy a commit releases) to the converged
    state of each increment; without it they are commits, set back after each trial."""

    def __init__(self, model, *, load, control=None, fixed=(), damage: str = "newton", damage_tol: float = 1e-4, trial_damage=None):
        if damage not in DAMAGE_MODES:
            raise InputError(f"damage must be one of {', '.join(DAMAGE_MODES)}, got {damage!r}", "damage")
        if not (np.isfinite(damage_tol) and damage_tol > 0):
            raise InputError(f"damage_tol must be positive, got {damage_tol!r}", "damage_tol")
        self.model, self.mode, self.damage_tol, self.trial_damage = model, damage, float(damage_tol), trial_damage
        self.system = _Bordered(model, load, load if control is None else control, fixed)
        self.system.orient()
        self.energies = hasattr(model, "K") and hasattr(model, "stored_energy")
        self._g = self.system.full(self.system.g)
        self.state = _State(uf=np.zeros(self.system.idx.size))
        self.rows: list[tuple] = []
        self.fallbacks = 0

    def _try(self, trial: float, fallback: bool):
        """One increment (converged, uf, λ, iterations, Krylov iterations, damage change). Under ``"newton"``, when
        ``fallback``, an increment whose Newton iterations fail is taken again from its start by the staggered passes,
        which converge from any state (monotonically in the damage) where Newton's can cycle across the kinks of the law,
        and which also pass a local snap-back of the discrete front under a global control (the damage grows until
        equilibrium is found again, the quasi-static picture of a jump); ``fallbacks`` counts them."""
        if self.mode == "newton":
            saved = self.model.damage.copy()
            out = _consistent(self.system, self.state, trial, self.damage_tol, self.trial_damage)
            if out[0] or not fallback:
                return out
            self.model.damage = saved
            self.fallbacks += 1
            ok, uf, lam, its, _, change = _staggered(self.system, self.state, trial, "iterate", self.damage_tol)
            return ok, uf, lam, its + out[3], out[4], change
        ok, uf, lam, its, _, change = _staggered(self.system, self.state, trial, self.mode, self.damage_tol)
        return ok, uf, lam, its, 0, change

    def advance(self, target: float) -> float:
        """Raise the control to ``target`` (halving an increment that fails, down to ``MIN_STEP_FRACTION`` of it, then
        SolverFailed) and record the state; returns the force λ [N] there."""
        model, system, state = self.model, self.system, self.state
        spent = [0, 0, 0.0]  # iterations (damage passes or Newton's), Krylov iterations, last damage change
        factors = system.factors
        requested = float(target) - state.cbar
        step = requested
        while abs(target - state.cbar) > 1e-14 * max(abs(target), abs(requested), 1e-300):
            trial = state.cbar + step if abs(step) < abs(target - state.cbar) else float(target)
            saved = model.damage.copy()
            # Newton first halves an increment it cannot converge (cheaper than the staggered passes, and often enough);
            # an increment already FALLBACK_BELOW of the requested one goes to the passes
            ok, uf, lam, its, krylov, change = self._try(trial, abs(trial - state.cbar) <= FALLBACK_BELOW * abs(requested) * (1 + 1e-12))
            spent[0] += its
            spent[1] += krylov
            if not ok:
                model.damage = saved
                step = (trial - state.cbar) / 2
                if abs(step) < MIN_STEP_FRACTION * abs(requested):
                    raise SolverFailed(
                        f"quasi-static path: no equilibrium at control {trial:.6g} (damage change {change:.3g} after {its} iterations): "
                        "a local control (a crack-tip opening) may pass a snap-back"
                    )
                continue
            disp = float(self._g @ system.full(uf))
            state.work += 0.5 * (lam + state.lam) * (disp - state.disp)
            state.uf, state.lam, state.cbar, state.disp = uf, lam, trial, disp
            spent[2] = change
            step = np.sign(requested) * min(2 * abs(step), abs(requested))
        u = system.full(state.uf)
        elastic = 0.5 * float(u @ (model.K @ u)) if self.energies else np.nan
        stored = float(model.stored_energy(u)) if self.energies else np.nan
        self.rows.append(
            (state.cbar, state.disp, state.lam, state.work, elastic, stored, spent[0], spent[1], system.factors - factors, spent[2], model.damage.copy())
        )
        return state.lam

    @property
    def u(self) -> np.ndarray:
        """The current DOFs (n,)."""
        return self.system.full(self.state.uf)

    def result(self) -> QuasiStaticPath:
        """The :class:`QuasiStaticPath` of the values reached so far."""
        if not self.rows:
            raise InputError("no control value reached yet", "targets")
        cols = list(zip(*self.rows))
        arrays = [np.asarray(col, float) for col in cols[:6]]
        return QuasiStaticPath(
            *arrays,
            iterations=np.asarray(cols[6], int),
            krylov=np.asarray(cols[7], int),
            factorisations=np.asarray(cols[8], int),
            damage_change=np.asarray(cols[9], float),
            damage=np.asarray(cols[10]),
            u=self.u,
        )


def quasistatic_path(model, targets, *, load, control=None, fixed=(), damage: str = "newton", damage_tol: float = 1e-4, trial_damage=None) -> QuasiStaticPath:
    """Raise the control cᵀu to each of ``targets`` in turn on ``model`` (:class:`QuasiStatic`, whose arguments these
    are); returns the :class:`QuasiStaticPath` at the targets."""
    targets = np.asarray(targets, float)
    if targets.ndim != 1 or targets.size == 0 or not np.all(np.isfinite(targets)):
        raise InputError("targets must be a non-empty 1-D array of finite control values", "targets")
    path = QuasiStatic(model, load=load, control=control, fixed=fixed, damage=damage, damage_tol=damage_tol, trial_damage=trial_damage)
    for target in targets:
        path.advance(target)
    return path.result()
