"""Sparse assembly of element matrices whose element DOFs stay fixed: the CSR pattern of their scatter
computed once (:class:`ElementScatter`), then each assembly one ``bincount`` over it. Used by the nonlinear
structures' tangents (:mod:`softimpact.fem.plate_vk`, :mod:`softimpact.fem.plane_tl`), assembled every Newton
iteration on the same mesh.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse

__all__ = ["ElementScatter", "ElementTangents"]


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


class ElementTangents:
    """The tangent K_T(d) = K + Σ_e K_e(d) of a nonlinear structure whose element tangents stay on one mesh: a base of
    :class:`~softimpact.fem.plate_vk.PlateVK` and :class:`~softimpact.fem.plane_tl.PlaneTL`. The structure gives ``K``
    (its linear stiffness over the n reduced DOFs), ``n``, ``_gdofs`` (ne, ..., the element DOFs), ``_index`` (a DOF's
    position among the reduced ones, −1 where supported) and ``_element_tangents(d)`` (ne, nd, nd), the nonlinear part."""

    _pattern: ElementScatter | None = None  # the element tangents' scatter, built on first use

    def _scatter_tangents(self) -> ElementScatter:
        """The element tangents' scatter (:class:`ElementScatter`), built once."""
        if self._pattern is None:
            ne = self._gdofs.shape[0]
            self._pattern = ElementScatter(self._index[self._gdofs.reshape(ne, -1)], self.n)
        return self._pattern

    def tangent_nonlinear(self, d: np.ndarray) -> scipy.sparse.csr_matrix:
        """K_T(d) − K: the nonlinear part of the tangent (zero at d = 0)."""
        return self._scatter_tangents().assemble(self._element_tangents(d))

    def tangent(self, d: np.ndarray) -> scipy.sparse.csr_matrix:
        """K_T(d) = ∂f_int/∂d."""
        return (self.K + self.tangent_nonlinear(d)).tocsr()
