"""The PARDISO factor (fem/newmark.PardisoCholesky, the ``fast`` extra) against SuperLU's on a 3-D graph, and its refusal of a matrix that is not positive definite (as the band Cholesky refuses it)."""

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spl

pytest.importorskip("pypardiso")

from softimpact.fem import newmark  # noqa: E402
from softimpact.fem.newmark import PardisoCholesky, spd_factor  # noqa: E402


def _stack_matrix():
    """A 3-D graph like a cohesive stack's (a 20 × 20 × 15 grid Laplacian, shifted as a0·M shifts K): SPD."""
    lap = [sp.diags([-np.ones(n - 1), 2 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1]) for n in (20, 20, 15)]
    eye = [sp.identity(n) for n in (20, 20, 15)]
    A = sp.kron(sp.kron(lap[0], eye[1]), eye[2]) + sp.kron(sp.kron(eye[0], lap[1]), eye[2]) + sp.kron(sp.kron(eye[0], eye[1]), lap[2])
    return (A + 1e-3 * sp.identity(A.shape[0])).tocsr()


def test_pardiso_solves_as_superlu_does():
    A = _stack_matrix()
    b = np.random.default_rng(1).standard_normal(A.shape[0])
    x = PardisoCholesky(A).solve(b)
    ref = spl.splu(A.tocsc()).solve(b)
    assert np.linalg.norm(x - ref) <= 1e-8 * np.linalg.norm(ref)
    assert np.linalg.norm(A @ x - b) <= 1e-9 * np.linalg.norm(b)


def test_an_indefinite_matrix_is_refused():
    n = 500
    d = np.full(n, 2.5)
    d[7] = -1.0
    A = sp.diags([-np.ones(n - 1), d, -np.ones(n - 1)], [-1, 0, 1]).tocsr()
    with pytest.raises(np.linalg.LinAlgError):
        PardisoCholesky(A)


def test_large_systems_go_to_pardiso(monkeypatch):
    A = _stack_matrix()
    monkeypatch.setattr(newmark, "PARDISO_MIN_DOF", A.shape[0])
    assert isinstance(spd_factor(A), PardisoCholesky)
    monkeypatch.setattr(newmark, "PARDISO_MIN_DOF", A.shape[0] + 1)
    assert not isinstance(spd_factor(A), PardisoCholesky)
