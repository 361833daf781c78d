"""Newmark stepping against the exact single-DOF oscillator."""

import numpy as np
import pytest

from softimpact.errors import InputError
from softimpact.fem.newmark import NewmarkParameters, NewmarkStepper

OMEGA = 2 * np.pi * 1000.0  # rad/s


def _free_vibration(dt, T=5e-3):
    M, K = np.array([[1.0]]), np.array([[OMEGA**2]])
    steps = int(round(T / dt))
    stepper = NewmarkStepper(M, K, dt)
    u, v, _ = stepper.run(np.zeros((1, steps + 1)), u0=np.array([1.0]))
    t = np.arange(steps + 1) * dt
    return t, u[0], v[0]


def test_second_order_convergence():
    """Average acceleration converges at order 2 to u = cos(ωt) (fitted rate 1.9-2.1)."""
    errs, dts = [], [2e-5, 1e-5, 5e-6, 2.5e-6]
    for dt in dts:
        t, u, _ = _free_vibration(dt)
        errs.append(np.max(np.abs(u - np.cos(OMEGA * t))))
    rate = np.polyfit(np.log(dts), np.log(errs), 1)[0]
    assert 1.9 < rate < 2.1


def test_energy_is_conserved_exactly_for_linear_undamped():
    """Average acceleration conserves ½kv²... ½v² + ½ω²u² to round-off."""
    _, u, v = _free_vibration(2e-5)
    E = 0.5 * v**2 + 0.5 * OMEGA**2 * u**2
    assert np.max(np.abs(E / E[0] - 1)) < 1e-12


def test_unstable_parameters_are_refused():
    """β < γ/2 is only conditionally stable and is refused."""
    with pytest.raises(InputError, match="beta"):
        NewmarkParameters(beta=0.1, gamma=0.5)


def test_band_solve_without_the_gil_is_lapacks_and_runs_in_threads():
    """The band solve called without the GIL (SciPy's Cython LAPACK through ctypes) gives f2py's dpbtrs numbers to
    the last bit, one or several right-hand sides, also when threads solve at once; and it solves the system."""
    import scipy.sparse

    from softimpact.fem import newmark

    n = 600
    rng = np.random.default_rng(3)
    offsets = (0, 1, -1, 9, -9)
    diagonals = [np.full(n, 30.0), *[np.full(n - abs(o), -1.0 - rng.random()) for o in offsets[1:]]]
    diagonals[2], diagonals[4] = diagonals[1], diagonals[3]  # symmetric
    A = scipy.sparse.diags(diagonals, offsets).tocsc()
    shuffle = rng.permutation(n)
    numberings = [_check_band_solve(newmark, M, rng).identity for M in (A, A[shuffle][:, shuffle].tocsc())]
    assert numberings == [True, False]  # as numbered, and renumbered by RCM (a permuted right-hand side)


def _check_band_solve(newmark, A, rng):
    from concurrent.futures import ThreadPoolExecutor

    n = A.shape[0]
    factor = newmark.BandedCholesky(A)
    assert newmark._PBTRS is not None  # SciPy's Cython LAPACK capsule was read
    b = rng.standard_normal((n, 3))
    permuted = b if factor.identity else b[factor.perm]
    reference, info = factor._pbtrs(factor.factor, permuted, lower=0)  # f2py's wrapper
    assert info == 0
    reference = reference if factor.identity else reference[factor.inverse_perm]
    assert np.array_equal(factor.solve(b), reference)
    assert np.array_equal(factor.solve(b[:, 1]), reference[:, 1])
    with ThreadPoolExecutor(3) as pool:
        columns = list(pool.map(lambda j: [factor.solve(b[:, j]) for _ in range(50)][-1], range(3)))
    assert all(np.array_equal(columns[j], reference[:, j]) for j in range(3))
    assert np.max(np.abs(A @ reference - b)) <= 1e-12 * np.max(np.abs(b))
    with pytest.raises(ValueError, match="right-hand side"):  # a short right-hand side is refused, not read past
        factor.solve(b[:-3, 0])
    return factor


def test_sparse_solves_in_threads_equal_serial_solves():
    """SuperLU's solve (the factor of the large plates' kernel builds) releases the GIL: three threads solving with one
    factor at once give the serial solves' numbers to the last bit, and the system is solved."""
    from concurrent.futures import ThreadPoolExecutor

    import scipy.sparse

    from softimpact.fem.newmark import MinimumDegreeLU

    n = 2000
    rng = np.random.default_rng(5)
    A = scipy.sparse.random(n, n, density=0.002, random_state=rng, format="csr")
    A = (A + A.T + scipy.sparse.identity(n) * 20.0).tocsc()
    factor = MinimumDegreeLU(A)
    b = rng.standard_normal((n, 3))
    serial = [factor.solve(b[:, j]) for j in range(3)]
    with ThreadPoolExecutor(3) as pool:
        threaded = list(pool.map(lambda j: [factor.solve(b[:, j]) for _ in range(30)][-1], range(3)))
    assert all(np.array_equal(threaded[j], serial[j]) for j in range(3))
    assert np.max(np.abs(A @ np.column_stack(serial) - b)) <= 1e-10 * np.max(np.abs(b))
