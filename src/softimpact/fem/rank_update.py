"""A kept factor updated where a few interface points changed: the Woodbury identity on the changed rows.

A model whose tangent is K + Gᵀ diag(s) G with a fixed operator G (``row_operator``: the cohesive interfaces'
openings, three rows per interface point) and a stiffness per row s (``row_stiffness(u)``: the penalty times the
tributary area, lowered by damage) changes between two Newton solves only where s changed: the points whose damage
rose and the damaged faces that closed or opened. With the factor of J₀ = J(s₀) kept and Δ = s − s₀ nonzero on the
rows S only (G_S those rows of G), the Jacobian is J = J₀ + G_Sᵀ diag(Δ_S) G_S, and the Sherman–Morrison–Woodbury
identity (Hager 1989, "Updating the inverse of a matrix", SIAM Review 31(2), eq. (1.1)) gives

    J⁻¹ b = x − W_S (diag(1/Δ_S) + G_S W_S)⁻¹ G_S x,    x = J₀⁻¹ b,  W_S = J₀⁻¹ G_Sᵀ,

one back-substitution with the kept factor and a dense solve of order |S| per right-hand side. The columns W_S are
back-substituted once, when a row first joins S (a block of right-hand sides at a time), and kept until the next
factor; the capacitance matrix is refactored when Δ_S changes (once a step: within a step the damage is held).

Every row whose stiffness changed beyond round-off (:data:`RELATIVE_CHANGE` of the largest) joins S, so the update is
exact and the conjugate gradients it preconditions (:meth:`softimpact.fem.nonlinear.NonlinearNewmark._krylov`) stop at
their first residual check, where the stale factor alone took up to sixteen back-substitutions a solve.

The caller refactors when the columns a solve needs would take the update's CPU past that of the factor it updates
(``factor_seconds``; a column's cost measured on the last block, a fresh update building at most :data:`PROBE` before
it knows): the rule of renting skis until the rent would pass the price, within twice the cost of the best choice
made knowing the future. Damage that spreads over many points in a step is refactored, damage that creeps and faces
that close or open are updated. Past ``max_rows`` rows (the columns' memory, :data:`COLUMN_BYTES`) it refactors too.

Cancellation: a row that lost its whole stiffness has 1/Δ = −1/s₀ and (G W)_ii ≈ 1/s₀ − 1/k (k the structure's own
stiffness at that point), a loss of about log₁₀(s₀/k) digits (3–4 for a stiff penalty): the conjugate gradients
polish it.
"""

from __future__ import annotations

import math
import time

import numpy as np
import scipy.linalg

__all__ = ["RankUpdate", "RELATIVE_CHANGE", "COLUMN_BYTES"]

PROBE = 16  # columns a fresh update may build before it knows what a column costs
RELATIVE_CHANGE = 1e-9  # a row joins the update when its stiffness moved by more than this fraction of the largest (every change but round-off)
COLUMN_BYTES = 1.0e9  # the kept columns W_S at most (8·n bytes each): past it, refactor


class RankUpdate:
    """The solve of J = J₀ + Gᵀ diag(s − s₀) G from ``factor`` (of J₀, with a ``solve`` taking a block of right-hand
    sides) kept at the row stiffness ``s0`` (module docstring). ``G``: the (rows, n) sparse operator."""

    def __init__(self, factor, G, s0: np.ndarray, factor_seconds: float = math.inf, column_seconds: float | None = None):
        self.factor, self.G, self.s0 = factor, G.tocsr(), np.asarray(s0, float).copy()
        self.factor_seconds = factor_seconds  # the CPU the factor cost: the update is worth keeping while it cost less
        self.spent = 0.0  # CPU spent on the update (its columns and capacitance factors)
        self.column_seconds = column_seconds  # CPU a column cost, measured on the last block (of this or the last factor)
        n = G.shape[1]
        self.max_rows = int(max(COLUMN_BYTES // (8 * n), 0))
        self.floor = RELATIVE_CHANGE * float(np.max(np.abs(self.s0), initial=0.0))
        self.rows = np.zeros(0, int)  # the rows with columns, in column order
        self._where = {}  # row -> its column
        self._W = np.zeros((n, 0))  # columns W_S, with spare capacity (grown by doubling)
        self.C = np.zeros((0, 0))  # G_rows W (symmetric)
        self.active = 0  # rows changed at the last solver()
        self._key = None
        self._cap = self._Wact = self._Gact = None

    def solver(self, s: np.ndarray):
        """A solve of J(s) b, or None when a new factor is the cheaper (module docstring): then refactor."""
        delta = np.asarray(s, float) - self.s0
        changed = np.flatnonzero(np.abs(delta) > self.floor)
        self.active = int(changed.size)
        if changed.size == 0:
            return self.factor.solve
        new = np.array([r for r in changed if r not in self._where], int)
        if new.size:
            # the columns' cost foreseen from the last block's (a first block of at most PROBE columns measures it)
            foreseen = (0.0 if new.size <= PROBE else math.inf) if self.column_seconds is None else new.size * self.column_seconds
            if self.rows.size + new.size > self.max_rows or self.spent + foreseen > self.factor_seconds:
                return None
            start = time.process_time()
            self._extend(new)
            self.column_seconds = max(time.process_time() - start, 1e-9) / new.size
        start = time.process_time()
        cols = np.array([self._where[r] for r in changed])
        order = np.argsort(cols)
        changed, cols = changed[order], cols[order]
        key = delta[changed].tobytes() + changed.tobytes()
        if key != self._key:
            cap = self.C[np.ix_(cols, cols)] + np.diag(1.0 / delta[changed])
            self._cap = scipy.linalg.lu_factor(cap, check_finite=False)
            contiguous = np.array_equal(cols, np.arange(cols.size))
            self._Wact = self._W[:, : cols.size] if contiguous else self._W[:, cols]  # a view while every kept row is changed
            self._Gact, self._key = self.G[changed], key
        self.spent += time.process_time() - start + (0.0 if not new.size else self.column_seconds * new.size)
        cap, G_rows, W = self._cap, self._Gact, self._Wact

        def solve(b):
            x = self.factor.solve(b)
            return x - W @ scipy.linalg.lu_solve(cap, G_rows @ x, check_finite=False)

        return solve

    def _extend(self, new: np.ndarray) -> None:
        """Back-substitute the columns of the rows ``new`` (one block) and border C with them."""
        if new.size == 0:
            return
        rhs = self.G[new].T.toarray()
        Wn = self.factor.solve(rhs).reshape(rhs.shape)
        cross = (self.G[self.rows] @ Wn) if self.rows.size else np.zeros((0, new.size))
        corner = self.G[new] @ Wn
        k = self.rows.size
        C = np.empty((k + new.size, k + new.size))
        C[:k, :k] = self.C
        C[:k, k:] = cross
        C[k:, :k] = cross.T
        C[k:, k:] = 0.5 * (corner + corner.T)
        if k + new.size > self._W.shape[1]:
            grown = np.empty((self._W.shape[0], min(self.max_rows, max(2 * (k + new.size), 64))))
            grown[:, :k] = self._W[:, :k]
            self._W = grown
        self._W[:, k : k + new.size] = Wn
        self.C = C
        for i, r in enumerate(new):
            self._where[int(r)] = k + i
        self.rows = np.concatenate([self.rows, new])
