"""Sparse assembly of element matrices whose element DOFs stay fixed: the CSR pattern of their scatter
computed once (:class:`ElementScatter`), then each assembly one ``bincount`` over it. Used by the nonlinear
structures' tangents (:mod:`softimpact.fem.plate_vk`, :mod:`softimpact.fem.plane_tl`), assembled every Newton
iteration on the same mesh.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse

__all__ = ["ElementScatter"]


class ElementScatter:
    """The scatter of element matrices (ne, nd, nd) into an (n, n) CSR matrix: ``dofs`` (ne, nd) the element DOFs'
    indices into the n reduced DOFs, −1 for a removed (supported) DOF, whose rows and columns are dropped; entries
    of one (row, column) summed."""

    def __init__(self, dofs: np.ndarray, n: int):
        ne, nd = dofs.shape
        rows = np.broadcast_to(dofs[:, :, None], (ne, nd, nd)).ravel()
        cols = np.broadcast_to(dofs[:, None, :], (ne, nd, nd)).ravel()
        self.keep = (rows >= 0) & (cols >= 0)
        key = rows[self.keep].astype(np.int64) * n + cols[self.keep]
        unique, self.inverse = np.unique(key, return_inverse=True)
        r, c = unique // n, unique % n
        self.indices = c.astype(np.int32)
        self.indptr = np.concatenate(([0], np.cumsum(np.bincount(r, minlength=n))))
        self.n, self.nnz = n, unique.size

    def assemble(self, Ke: np.ndarray) -> scipy.sparse.csr_matrix:
        """Σ_e of the element matrices ``Ke`` (ne, nd, nd) as an (n, n) CSR matrix."""
        data = np.bincount(self.inverse, weights=np.asarray(Ke).ravel()[self.keep], minlength=self.nnz)
        return scipy.sparse.csr_matrix((data, self.indices, self.indptr), shape=(self.n, self.n))
