"""Newmark implicit time integration of M·a + C·v + K·u = f (refs 5, 6).

The effective matrix K_eff = K + a0·M + a1·C is factored once per (dt, model);
each step then costs one back-substitution. Average acceleration
(β = 1/4, γ = 1/2) is the default: unconditionally stable, second order, and it
conserves the energy of a linear undamped system exactly.

Arrays: DOF vectors have shape (n,); histories put time on the last axis.
"""

from __future__ import annotations

import ctypes
import functools
import math
import os
import re
from dataclasses import dataclass

import numpy as np
import scipy.linalg
import scipy.sparse
import scipy.sparse.linalg

from ..errors import InputError

__all__ = ["NewmarkParameters", "NewmarkStepper", "BandedCholesky", "MinimumDegreeLU", "PardisoCholesky", "SolverSpec", "spd_factor"]

# Systems up to this many DOFs are factored densely: a dense triangular solve
# beats the sparse machinery's per-call overhead at this size.
DENSE_LIMIT = 400
# Band storage above this many entries: also try a minimum-degree sparse factor and keep the smaller.
BAND_TRY_SPARSE = 1_000_000
# A stored entry of SuperLU's factor costs this much more per solve than one of the band
# (measured on the 48 × 48 MITC9 plate, 27 455 DOF: 2.5 against 2.0 ns an entry).
SPARSE_ENTRY_COST = 1.25
# From this many unknowns a sparse SPD matrix is factored by MKL PARDISO when pypardiso is installed (the ``fast``
# extra): on the stacked sublaminates of a cohesive run, a graph like a 3-D solid's, SuperLU's minimum degree
# factors 85 863 DOF (14 interfaces) in 136 s and its factor does not fit the band it is weighed against, PARDISO's
# nested dissection in 5.5 s (BENCHMARKS.md, "Factorising the cohesive stack"). Below it the band and SuperLU
# are as fast and the runs keep their bits.
PARDISO_MIN_DOF = 20_000


def _pbtrs_without_gil():
    """LAPACK's dpbtrs as exported by :mod:`scipy.linalg.cython_lapack` (SciPy's public Cython-level
    LAPACK), called through :mod:`ctypes`, which releases the GIL for the call; scipy.linalg.lapack's
    f2py wrapper holds it, so two threads' band solves would run one after the other. The same routine
    of the same library: the same numbers, to the last bit. None where the capsule cannot be read
    (the f2py wrapper is used then)."""
    try:
        from scipy.linalg import cython_lapack

        capsule = cython_lapack.__pyx_capi__["dpbtrs"]
        # private prototypes of the C API's capsule calls (ctypes.pythonapi's own attributes are left alone)
        name_of = ctypes.PYFUNCTYPE(ctypes.c_char_p, ctypes.py_object)(("PyCapsule_GetName", ctypes.pythonapi))
        pointer_of = ctypes.PYFUNCTYPE(ctypes.c_void_p, ctypes.py_object, ctypes.c_char_p)(("PyCapsule_GetPointer", ctypes.pythonapi))
        name = name_of(capsule)
        # the signature this call assumes: 32-bit integers, doubles (a 64-bit-integer build is not called this way)
        if not re.fullmatch(rb"void \(char \*, (int \*, ){3}\w+_d \*, int \*, \w+_d \*, int \*, int \*\)", name):
            return None
        integer = ctypes.POINTER(ctypes.c_int)
        # dpbtrs(uplo, n, kd, nrhs, ab, ldab, b, ldb, info)
        return ctypes.CFUNCTYPE(None, ctypes.c_char_p, integer, integer, integer, ctypes.c_void_p, integer, ctypes.c_void_p, integer, integer)(
            pointer_of(capsule, name)
        )
    except Exception:  # noqa: BLE001 (any failure: the f2py wrapper serves)
        return None


_PBTRS = _pbtrs_without_gil()


class BandedCholesky:
    """Cholesky factor of a sparse SPD matrix in LAPACK band storage.

    The DOFs are renumbered by reverse Cuthill–McKee when that narrows the band
    (structured meshes are often narrowest as numbered). The band storage is
    built by one scatter of the matrix entries, so building costs O(nnz) for any
    band: a beam's band of ~20 and a plate's of ~200 alike. For the beam meshes
    here a banded solve is about twice as fast as a general sparse LU solve, for
    the plate meshes 1.6–3.3 times (benchmarks/bench_plate.py).

    The factorisation runs with one BLAS thread: LAPACK's banded Cholesky hands
    OpenBLAS blocks too small to share, and its threads spin waiting for each
    other, so on a busy 2-core machine two threads were 10× (band 400) to 5000×
    (band 17) slower than one (1.6 s against 16.6 s; 1 ms against 6 s).
    """

    def __init__(self, A, plan=None):
        coo = scipy.sparse.coo_matrix(A)
        n = coo.shape[0]
        self.identity, self.perm, self.inverse_perm, bw = self.plan(coo) if plan is None else plan
        row, col = self.inverse_perm[coo.row], self.inverse_perm[coo.col]
        upper = col >= row
        ab = np.zeros((bw + 1, n))
        np.add.at(ab, (bw + row[upper] - col[upper], col[upper]), coo.data[upper])
        from threadpoolctl import threadpool_limits

        with threadpool_limits(1, user_api="blas"):
            self.factor = np.asfortranarray(scipy.linalg.cholesky_banded(ab, lower=False))  # LAPACK's band storage
        self.bandwidth = bw
        (self._pbtrs,) = scipy.linalg.get_lapack_funcs(("pbtrs",), (self.factor,))
        self._sizes = (ctypes.c_int(n), ctypes.c_int(bw), ctypes.c_int(bw + 1))  # dpbtrs's read-only n, kd, ldab, once

    @classmethod
    def plan(cls, A):
        """(identity, perm, inverse_perm, bandwidth): the numbering, as given or by RCM, with the narrower band."""
        from scipy.sparse.csgraph import reverse_cuthill_mckee

        coo = scipy.sparse.coo_matrix(A)
        n = coo.shape[0]
        rcm = reverse_cuthill_mckee(coo.tocsr(), symmetric_mode=True)
        inverse_rcm = np.empty(n, int)
        inverse_rcm[rcm] = np.arange(n)
        natural = cls._bandwidth(coo.row, coo.col)
        renumbered = cls._bandwidth(inverse_rcm[coo.row], inverse_rcm[coo.col])
        identity = natural <= renumbered
        ident = np.arange(n)
        return identity, ident if identity else rcm, ident if identity else inverse_rcm, min(natural, renumbered)

    @staticmethod
    def _bandwidth(row: np.ndarray, col: np.ndarray) -> int:
        return int(np.max(np.abs(row - col))) if row.size else 0

    @property
    def stored(self) -> int:
        """Entries of the factor (band storage)."""
        return int(self.factor.size)

    def solve_flops(self) -> float:
        return 4.0 * self.factor.shape[1] * (self.bandwidth + 1)

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """K⁻¹·rhs, rhs (n,) or (n, k): LAPACK's banded Cholesky solve (dpbtrs) called directly (scipy's
        cho_solve_banded wraps it in checks that cost as much as the solve on small bands), without
        the GIL where SciPy's Cython LAPACK is at hand (:func:`_pbtrs_without_gil`): threads solve at once."""
        n = self.factor.shape[1]
        if np.ndim(rhs) not in (1, 2) or np.shape(rhs)[0] != n:  # (LAPACK would read and write past the array)
            raise ValueError(f"banded Cholesky solve: right-hand side of shape {np.shape(rhs)} for a system of {n} unknowns")
        b = rhs if self.identity else rhs[self.perm]
        if _PBTRS is None or self.factor.dtype != np.float64:
            x, info = self._pbtrs(self.factor, b, lower=0)
        else:
            x = np.array(b, dtype=np.float64, order="F")  # a copy, overwritten with the solution
            n, kd, ldab = self._sizes
            status = ctypes.c_int(0)
            _PBTRS(b"U", n, kd, ctypes.c_int(1 if x.ndim == 1 else x.shape[1]), self.factor.ctypes.data, ldab, x.ctypes.data, n, status)
            info = status.value
        if info != 0:
            raise np.linalg.LinAlgError(f"banded Cholesky solve failed (LAPACK info {info})")
        return x if self.identity else x[self.inverse_perm]


class MinimumDegreeLU:
    """A sparse SPD matrix factored by SuperLU in symmetric mode: minimum-degree ordering of
    A + Aᵀ and no pivoting, so the factor is A = Lᵀ·D·L in LU form, with the fill of a
    minimum-degree Cholesky. Raises ``np.linalg.LinAlgError`` if a pivot is not positive
    (A not positive definite), as :class:`BandedCholesky` does.

    For a plate's band of ~600 (the 48 × 48 MITC9 mesh, 27 455 DOF) it stores 4.9 M
    entries against the band's 16 M and scipy's default ``splu`` (COLAMD) 17.7 M, and
    solves in 12 ms against 33 ms and 31 ms (benchmarks/bench_plate.py, BENCHMARKS.md).
    """

    def __init__(self, A):
        csc = scipy.sparse.csc_matrix(A)
        try:
            self.lu = scipy.sparse.linalg.splu(csc, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options={"SymmetricMode": True})
        except RuntimeError as exc:  # an exactly singular pivot
            raise np.linalg.LinAlgError(f"sparse factorisation failed: {exc}") from exc
        pivots = self.lu.U.diagonal()
        if not np.all(pivots > 0):
            raise np.linalg.LinAlgError("matrix is not positive definite (a non-positive pivot)")
        self.stored = int(self.lu.L.nnz + self.lu.U.nnz)

    def solve_flops(self) -> float:
        return 2.0 * self.stored

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        return self.lu.solve(rhs)


class PardisoCholesky:
    """A sparse SPD matrix factored by MKL PARDISO (pypardiso; real symmetric positive definite, ``mtype`` 2, the
    upper triangle, its default nested-dissection ordering and parallel factorisation). Raises
    ``np.linalg.LinAlgError`` when PARDISO reports the matrix not positive definite (or any error), as
    :class:`BandedCholesky` does."""

    def __init__(self, A):
        import pypardiso

        upper = scipy.sparse.triu(scipy.sparse.csr_matrix(A, dtype=float)).tocsr()
        upper.sort_indices()
        self._upper = upper
        self._solver = pypardiso.PyPardisoSolver(mtype=2)
        try:
            self._solver.factorize(upper)
        except (pypardiso.pardiso_wrapper.PyPardisoError, ValueError) as exc:
            raise np.linalg.LinAlgError(f"PARDISO factorisation failed: {exc}") from exc
        self.stored = int(self._solver.get_iparm(18) or upper.nnz)  # iparm(18): the factor's nonzeros

    def solve_flops(self) -> float:
        return 2.0 * self.stored

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        return self._solver.solve(self._upper, np.asarray(rhs, dtype=float))

    def __del__(self):
        solver = getattr(self, "_solver", None)
        if solver is not None:
            solver.free_memory(everything=True)


@functools.cache
def _pardiso():
    """pypardiso's module when it is installed and MKL loads, else None. Each new PyPardisoSolver looks for MKL's
    runtime by a recursive glob of the environment (0.8 s of CPU, measured: as much as a factorisation of the
    D7136 stack); the library it found is named once in its documented PYPARDISO_MKL_RT (unless the user set it)."""
    try:
        import pypardiso
    except (ImportError, OSError):
        return None
    if "PYPARDISO_MKL_RT" not in os.environ:
        name = getattr(getattr(pypardiso.ps, "libmkl", None), "_name", None)  # the solver its import created
        if name:
            os.environ["PYPARDISO_MKL_RT"] = name
    return pypardiso


def spd_factor(A):
    """The cheaper-to-solve factor of a sparse SPD matrix: :class:`BandedCholesky`, or
    :class:`MinimumDegreeLU` when the band is wide and the sparse factor, weighted by its
    higher cost per stored entry (``SPARSE_ENTRY_COST``), is smaller. Beams and small
    plates keep the band (its storage is under ``BAND_TRY_SPARSE``). From ``PARDISO_MIN_DOF`` unknowns,
    :class:`PardisoCholesky` when pypardiso is installed (the ``fast`` extra)."""
    n = A.shape[0]
    if n >= PARDISO_MIN_DOF and _pardiso() is not None:
        return PardisoCholesky(A)
    plan = BandedCholesky.plan(A)
    band = n * (plan[3] + 1)
    if band > BAND_TRY_SPARSE:
        from threadpoolctl import threadpool_limits

        with threadpool_limits(1, user_api="blas"):
            sparse = MinimumDegreeLU(A)
        if SPARSE_ENTRY_COST * sparse.stored < band:
            return sparse
    return BandedCholesky(A, plan)


@dataclass(frozen=True)
class NewmarkParameters:
    """Newmark's β and γ; stability of the linear scheme needs 2β ≥ γ ≥ 1/2."""

    beta: float = 0.25
    gamma: float = 0.5

    def __post_init__(self):
        if not (self.gamma >= 0.5 and 2.0 * self.beta >= self.gamma):
            raise InputError(f"Newmark parameters beta={self.beta}, gamma={self.gamma} are not unconditionally stable (need 2*beta >= gamma >= 1/2)")


@dataclass(frozen=True)
class SolverSpec:
    """Time step and duration [s], Newmark parameters."""

    time_step: float
    duration: float
    newmark: NewmarkParameters = NewmarkParameters()

    def __post_init__(self):
        if not (math.isfinite(self.time_step) and self.time_step > 0):
            raise InputError(f"time_step must be positive, got {self.time_step!r} s", "time_step")
        if not (math.isfinite(self.duration) and self.duration > self.time_step):
            raise InputError(f"duration must exceed the time step, got {self.duration!r} s", "duration")

    @property
    def steps(self) -> int:
        return int(round(self.duration / self.time_step))

    def times(self) -> np.ndarray:
        """t_k = k·dt, k = 0 … steps [s]."""
        return np.arange(self.steps + 1) * self.time_step


class NewmarkStepper:
    """Newmark stepper for a linear system, with the effective matrix factored once.

    A step from state (u, v, a) at t_n to t_{n+1} with load f_{n+1}:
    ``u1 = solve(f + predictor(u, v, a))`` then ``v1, a1 = correct(u1, u, v, a)``.
    Splitting it this way lets callers add a load that depends on u1 (contact)
    through :meth:`solve` of a unit vector, computed once. ``nsolve`` counts the
    back-substitutions.
    """

    def __init__(self, M, K, dt: float, C=None, params: NewmarkParameters = NewmarkParameters()):
        if not (math.isfinite(dt) and dt > 0):
            raise InputError(f"time_step must be positive, got {dt!r}", "time_step")
        b, g = params.beta, params.gamma
        self.dt, self.params = dt, params
        self.a0 = 1.0 / (b * dt * dt)
        self.a1 = g / (b * dt)
        self.a2 = 1.0 / (b * dt)
        self.a3 = 1.0 / (2.0 * b) - 1.0
        self.a4 = g / b - 1.0
        self.a5 = dt / 2.0 * (g / b - 2.0)
        self.a6 = dt * (1.0 - g)
        self.a7 = g * dt
        n = M.shape[0]
        self.n = n
        self.dense = n <= DENSE_LIMIT
        conv = (lambda A: A.toarray() if scipy.sparse.issparse(A) else np.asarray(A)) if self.dense else (lambda A: scipy.sparse.csc_matrix(A))
        self.M, self.K = conv(M), conv(K)
        self.C = None if C is None else conv(C)
        K_eff = self.K + self.a0 * self.M + (0.0 if self.C is None else self.a1 * self.C)
        if self.dense:
            self._factor = scipy.linalg.cho_factor(K_eff)
            # LAPACK's dpotrs called directly: cho_solve's checks cost more than the solve on a bar's ~80 DOF
            (self._potrs,) = scipy.linalg.get_lapack_funcs(("potrs",), (self._factor[0],))
        else:
            self._factor = spd_factor(K_eff)
        self.nsolve = 0
        self._H = None

    def solve_flops(self) -> float:
        """Floating-point operations of one solve with one right-hand side (for cost estimates)."""
        if self.dense:
            return 2.0 * self.n**2
        return self._factor.solve_flops()

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """K_eff⁻¹·rhs; rhs of shape (n,) or (n, k)."""
        self.nsolve += 1
        return self.factor_solve(rhs)

    @property
    def separate_solves(self) -> bool:
        """True when m right-hand sides cost m one-column solves whether solved together or apart, and apart
        they run in threads at once (a band factor: LAPACK's dpbtrs sweeps the band once per column, called
        without the GIL); False for SuperLU (several columns in one call cost less than apart) and dense factors."""
        return isinstance(self._factor, BandedCholesky) and _PBTRS is not None

    def factor_solve(self, rhs: np.ndarray) -> np.ndarray:
        """K_eff⁻¹·rhs, not counted in ``nsolve``: safe to call from several threads at once (the kernel
        build's marches; the band and SuperLU solves of a sparse system release the GIL, a dense one's holds it)."""
        if self.dense:
            c, lower = self._factor
            x, info = self._potrs(c, rhs, lower=lower)
            if info != 0:
                raise np.linalg.LinAlgError(f"Cholesky solve failed (LAPACK info {info})")
            return x
        return self._factor.solve(rhs)

    def history_operator(self) -> np.ndarray:
        """Dense H, shape (n, 3n), with K_eff⁻¹·predictor(u, v, a) = H @ [u; v; a].

        For small (dense) systems a step is then one matrix–vector product.
        """
        if not self.dense:
            raise ValueError("history_operator is for dense (small) systems only")
        blocks = [self.a0 * self.M, self.a2 * self.M, self.a3 * self.M]
        if self.C is not None:
            blocks = [blocks[0] + self.a1 * self.C, blocks[1] + self.a4 * self.C, blocks[2] + self.a5 * self.C]
        return self.solve(np.hstack(blocks))

    def transition_operator(self) -> np.ndarray:
        """Dense T, shape (3n, 3n): [u; v; a] at t_{n+1} = T @ [u; v; a] at t_n with no load.

        Built from the history operator and the corrector (dense systems only).
        """
        if self._H is None:
            n = self.n
            H = self.history_operator()
            eye = np.eye(n)
            zero = np.zeros((n, n))
            acc = self.a0 * (H - np.hstack((eye, zero, zero))) - np.hstack((zero, self.a2 * eye, self.a3 * eye))
            vel = np.hstack((zero, eye, self.a6 * eye)) + self.a7 * acc
            self._H = np.vstack((H, vel, acc))
        return self._H

    def free_step(self, u, v, a):
        """One step with no load at t_{n+1}: returns (u1, v1, a1)."""
        if self.dense:
            s = self.transition_operator() @ np.concatenate((u, v, a))
            return s[: self.n], s[self.n : 2 * self.n], s[2 * self.n :]
        u1 = self.solve(self.predictor(u, v, a))
        v1, a1 = self.correct(u1, u, v, a)
        return u1, v1, a1

    def predictor(self, u, v, a) -> np.ndarray:
        """The history part of the effective load: M(a0 u + a2 v + a3 a) + C(a1 u + a4 v + a5 a)."""
        r = self.M @ (self.a0 * u + self.a2 * v + self.a3 * a)
        if self.C is not None:
            r = r + self.C @ (self.a1 * u + self.a4 * v + self.a5 * a)
        return r

    def correct(self, u1, u, v, a):
        """Velocity and acceleration at t_{n+1} from the new displacement."""
        a1 = self.a0 * (u1 - u) - self.a2 * v - self.a3 * a
        v1 = v + self.a6 * a + self.a7 * a1
        return v1, a1

    def initial_acceleration(self, u, v, f):
        """a0 = M⁻¹(f − K u − C v), for a consistent start."""
        r = f - self.K @ u - (0.0 if self.C is None else self.C @ v)
        if not np.any(r):
            return np.zeros_like(r)
        if self.dense:
            return np.linalg.solve(self.M, r)
        return spd_factor(self.M).solve(r)

    def run(self, load: np.ndarray, u0=None, v0=None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """March a prescribed load history ``load`` of shape (n, n_steps + 1).

        Returns u, v, a of shape (n, n_steps + 1); column k is time k·dt.
        """
        n, steps = load.shape[0], load.shape[1] - 1
        f = np.ascontiguousarray(load.T)  # time-major: each step reads and writes contiguous rows
        u = np.zeros((steps + 1, n))
        v = np.zeros_like(u)
        acc = np.zeros_like(u)
        if u0 is not None:
            u[0] = u0
        if v0 is not None:
            v[0] = v0
        acc[0] = self.initial_acceleration(u[0], v[0], f[0])
        for k in range(steps):
            u[k + 1] = self.solve(f[k + 1] + self.predictor(u[k], v[k], acc[k]))
            v[k + 1], acc[k + 1] = self.correct(u[k + 1], u[k], v[k], acc[k])
        return u.T, v.T, acc.T
