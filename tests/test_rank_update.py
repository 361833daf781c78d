"""The kept factor updated on the rows that changed (softimpact.fem.rank_update) against a direct solve of the changed
matrix, and the one engine's cohesive steps with it against steps refactored every time."""

import numpy as np
import pytest
import scipy.sparse
import scipy.sparse.linalg

from softimpact.fem.newmark import spd_factor
from softimpact.fem.rank_update import RankUpdate


def _system(n=400, rows=300, seed=3):
    """An SPD J₀ = A + Gᵀ diag(s₀) G with a sparse G (rows of an interface-like ±1 pattern) and stiff rows s₀."""
    rng = np.random.default_rng(seed)
    A = scipy.sparse.diags([-1.0, 2.5, -1.0], [-1, 0, 1], shape=(n, n)).tocsr()
    i = np.arange(rows)
    a, b = rng.integers(0, n, rows), rng.integers(0, n, rows)
    b = np.where(a == b, (b + 1) % n, b)
    G = scipy.sparse.csr_matrix((np.r_[np.ones(rows), -np.ones(rows)], (np.r_[i, i], np.r_[a, b])), shape=(rows, n))
    s0 = 1e4 * rng.uniform(0.5, 1.5, rows)
    return A, G, s0, rng


def _matrix(A, G, s):
    return (A + G.T @ scipy.sparse.diags(s) @ G).tocsc()


@pytest.mark.parametrize("fraction", [0.0, 1.0, 0.5])  # rows that lose all, or half, of their stiffness
def test_updated_solve_is_the_changed_matrix_s_solve(fraction):
    """Rows softened (to zero: a point fully delaminated), stiffened back, in two batches: each solve equals
    scipy's direct solve of the changed matrix (SuperLU on the assembled J), to 1e-9."""
    A, G, s0, rng = _system()
    upd = RankUpdate(spd_factor(_matrix(A, G, s0)), G, s0)
    s = s0.copy()
    b = rng.standard_normal((A.shape[0], 2))
    for batch in (rng.choice(G.shape[0], 40, replace=False), rng.choice(G.shape[0], 25, replace=False)):
        s[batch] = fraction * s0[batch]
        x = upd.solver(s)(b)
        ref = scipy.sparse.linalg.spsolve(_matrix(A, G, s), b)
        assert np.max(np.abs(x - ref)) <= 1e-9 * np.max(np.abs(ref))
    s[batch] = s0[batch]  # some rows back to where the factor was: they leave the update
    x = upd.solver(s)(b[:, 0])
    assert np.max(np.abs(x - scipy.sparse.linalg.spsolve(_matrix(A, G, s), b[:, 0]))) <= 1e-9 * np.max(np.abs(x))


def test_no_change_is_the_factor_and_too_many_rows_ask_for_a_refactor():
    A, G, s0, rng = _system()
    upd = RankUpdate(spd_factor(_matrix(A, G, s0)), G, s0)
    b = rng.standard_normal(A.shape[0])
    assert np.allclose(upd.solver(s0)(b), scipy.sparse.linalg.spsolve(_matrix(A, G, s0), b), rtol=1e-9, atol=0)
    upd.max_rows = 10
    s = s0.copy()
    s[:11] *= 0.5
    assert upd.solver(s) is None


def test_cohesive_run_with_the_update_equals_one_refactored_every_time(monkeypatch):
    """The built-in cohesive case's growth (tests/test_cohesive_plate.py's weak interfaces, 4 × 4 MITC9, 150 µs): the
    force history, the interfaces' damaged area and dissipated energy with the kept factor updated (the default) equal
    those of a run that refactors wherever a row changed (the update refused), to the Newton tolerance."""
    from test_cohesive_plate import WEAK, _problem

    from softimpact.fem import rank_update
    from softimpact.workflows.coupled import run_impact

    problem = _problem(WEAK, duration=150e-6)

    def run():
        result = run_impact(problem, method="cohesive")[1]
        names = list(result.strain_names)
        return result.force, result.strain[names.index("process_zone_area_m2")], result.strain[names.index("fracture_energy_dissipated_J")]

    seen = []
    original = rank_update.RankUpdate.solver

    def counting(self, s):
        solve = original(self, s)
        seen.append(self.active if solve is not None else 0)
        return solve

    monkeypatch.setattr(rank_update.RankUpdate, "solver", counting)
    kept = run()
    assert max(seen) > 0  # the kept factor was updated on changed rows (not refactored)
    monkeypatch.setattr(rank_update.RankUpdate, "solver", lambda self, s: None if np.any(s != self.s0) else self.factor.solve)
    fresh = run()
    assert np.max(kept[1]) > 0  # the interfaces did soften
    for a, b in zip(kept, fresh):
        assert np.max(np.abs(a - b)) <= 1e-5 * np.max(np.abs(b))
