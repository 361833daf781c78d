"""The contact patch: nodal forces of a force history spread over a strip, eqs (8)–(14).

The contact half-width follows the force, r(t) = r0·sqrt(F(t)/F0), eq (10), with
F0 the peak of the history. Over the strip the pressure has the cosine shape of
eq (11), f(s, t) = Fmax(t)·cos(π s / (2 r(t))), |s| < r(t), s = x − x_c, with
Fmax = π F/(4 r) so that it integrates to F(t), eq (13). (Eq (14) writes r0;
the distribution is meant over the instantaneous r(t): docs/modelling-notes.md, errata.)

Node i receives the exact integral of f over its tributary segment [a_i, b_i]
(half-way to its neighbours), clipped at ±r(t):

    f_i(t) = F(t)/2 · [sin(π b_i/(2r)) − sin(π a_i/(2r))],

which is eq (14) when r = r0 and the segment lies inside the strip. The nodal
forces sum to F(t) exactly at every instant. When r(t) is below half a node
spacing the whole F(t) goes to the node nearest x_c.
"""

from __future__ import annotations

import numpy as np

from ..errors import InputError, NoContactRoom

__all__ = ["PatchLoad"]


def _tributaries(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    mid = 0.5 * (x[1:] + x[:-1])
    return np.concatenate(([x[0]], mid)), np.concatenate((mid, [x[-1]]))


class PatchLoad:
    """Nodal force histories on the surface nodes at positions ``node_x`` (sorted)."""

    def __init__(self, node_x: np.ndarray, center: float, radius: float):
        x = np.asarray(node_x, float)
        if not radius > 0:
            raise InputError(f"contact radius must be positive, got {radius!r}", "contact_radius")
        if center - radius < x[0] - 1e-12 or center + radius > x[-1] + 1e-12:
            raise NoContactRoom(
                f"load: the contact patch {center - radius:.4g} to {center + radius:.4g} m is wider than the beam ({x[0]:.4g} to {x[-1]:.4g} m)"
            )
        lo, hi = _tributaries(x)
        self.nodes = np.flatnonzero((hi > center - radius) & (lo < center + radius))
        self.lo, self.hi = lo[self.nodes] - center, hi[self.nodes] - center
        self.x = x[self.nodes]
        self.center, self.radius = center, radius
        self.nearest = int(np.argmin(np.abs(self.x - center)))
        self.half_spacing = 0.5 * float(np.min(np.diff(x)))

    def forces(self, F: np.ndarray, radius: float | None = None) -> np.ndarray:
        """Nodal forces, shape (n_patch_nodes, n_t), for the history F (n_t,) [N], compression +.

        ``radius``: r0 of this history, at most the patch's own (its nodes cover that).
        """
        F = np.asarray(F, float)
        r0 = self.radius if radius is None else radius
        if not 0 < r0 <= self.radius * (1 + 1e-12):
            raise InputError(f"contact radius {r0!r} m must be positive and at most the patch's {self.radius!r} m")
        F0 = F.max()
        out = np.zeros((self.nodes.size, F.size))
        if F0 <= 0:
            return out
        r = r0 * np.sqrt(np.maximum(F, 0.0) / F0)
        wide = r >= self.half_spacing
        rw = r[wide]
        a = np.clip(self.lo[:, None], -rw, rw)
        b = np.clip(self.hi[:, None], -rw, rw)
        out[:, wide] = 0.5 * F[wide] * (np.sin(np.pi * b / (2 * rw)) - np.sin(np.pi * a / (2 * rw)))
        out[self.nearest, ~wide] = F[~wide]
        return out

    def half_width(self, F: np.ndarray, radius: float | None = None) -> np.ndarray:
        """r(t) = r0·sqrt(F/F0), eq (10)."""
        F = np.asarray(F, float)
        return (self.radius if radius is None else radius) * np.sqrt(np.maximum(F, 0.0) / F.max())
