"""A circular contact patch on a plate: eqs (10)–(11) of the paper, in two dimensions.

The contact pressure on a disc of radius r(t) about the impact point has the
cosine shape of eq (11) in the radial distance ρ,

    p(ρ, t) = F(t) · cos(π ρ / (2 r)) / (4 r² (1 − 2/π)),   ρ < r,

normalised so that it integrates to F(t) (∫₀^r cos(πρ/2r) 2πρ dρ = 4r²(1 − 2/π)).
The radius is fixed, r = r0, or grows with the force as r(t) = r0·sqrt(F/F0),
eq (10), F0 the peak of the history (docs/modelling-notes.md, errata: eq (14) is meant over the
instantaneous radius).

The nodal forces are the consistent ones, f_i = ∫ N_i p dA with the shape
functions N_i of the plate mesh (bilinear for MITC4, biquadratic for MITC9, whose
corner-node shares of a small patch are negative, as consistent loads of
quadratic elements are). The integral is taken over the square
[c − r, c + r]², cut along the grid lines (so N_i is one polynomial on each
cell) and into SUBCELLS × SUBCELLS pieces, with a 4 × 4 Gauss rule on each
cell; only the kink of p at ρ = r is not resolved exactly (nodal forces within
3e-5 of a 96-piece reference on the 0.25-in patch). Because Σ N_i = 1, the forces are then rescaled to sum to F(t)
exactly (a correction of that size).

For a growing radius the distribution over the nodes is tabulated once at
``TABLE`` radii r_k = r0·k/(TABLE − 1) and interpolated linearly in r between
them: the interpolant is a convex combination of distributions that each sum to
one, so the forces still sum to F(t) exactly, and a new force history costs one
``np.interp``-like gather (for the response engine, milliseconds).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ContactOutgrewRoom, InputError, NoContactRoom
from .plate import PlateFE, W

__all__ = ["CircularPatch", "DiscShares", "cosine_pressure"]

SUBCELLS = 12  # pieces per diameter, besides the grid lines: resolves the disc edge to a few 1e-5
TABLE = 129  # radii tabulated for a growing patch: linear interpolation error ~ (1/128)² of the shape change
_G4, _W4 = np.polynomial.legendre.leggauss(4)


def cosine_pressure(rho: np.ndarray, radius: float) -> np.ndarray:
    """Eq (11) over a disc, normalised to unit total force [1/m²]."""
    rho = np.asarray(rho, float)
    return np.where(rho < radius, np.cos(np.pi * rho / (2 * radius)), 0.0) / (4 * radius**2 * (1 - 2 / math.pi))


class CircularPatch:
    """Transverse nodal forces of a cosine pressure on a disc about ``center`` (x, y) [m].

    ``nodes``: the mesh nodes the largest disc (``radius``) can load; ``dofs``:
    their w DOFs in the reduced system (all free: the patch must not touch a
    supported edge's w). ``forces(F, r0)`` gives shape (n_nodes, n_t), compression
    (pushing the plate down, −z) positive. A disc centred on a ``symmetry`` edge
    (or corner) loads the plate with its share ``share`` of the force (1/2, 1/4).
    """

    def __init__(self, fe: PlateFE, center: tuple[float, float], radius: float, grow: bool = True):
        cx, cy = (float(c) for c in center)
        if not (math.isfinite(radius) and radius > 0):
            raise InputError(f"contact radius must be positive, got {radius!r} m")
        xs, ys = fe.xs, fe.ys
        # A disc centred on a symmetry edge is mirrored there: the plate carries its share
        # (1/2 on an edge, 1/4 at a corner) and the rest belongs to the mirror image.
        tol = 1e-9 * max(xs[-1] - xs[0], ys[-1] - ys[0])
        mirror = dict(zip(("x0", "x1", "y0", "y1"), (abs(cx - xs[0]) <= tol, abs(cx - xs[-1]) <= tol, abs(cy - ys[0]) <= tol, abs(cy - ys[-1]) <= tol)))
        mirror = {e: on and dict(zip(("x0", "x1", "y0", "y1"), fe.plate.supports))[e] == "symmetry" for e, on in mirror.items()}
        inside = {
            "x0": cx - radius >= xs[0] - tol,
            "x1": cx + radius <= xs[-1] + tol,
            "y0": cy - radius >= ys[0] - tol,
            "y1": cy + radius <= ys[-1] + tol,
        }
        if not all(inside[e] or mirror[e] for e in inside):
            raise NoContactRoom(f"contact patch of radius {radius!r} m about ({cx!r}, {cy!r}) m does not fit on the plate")
        self.share = (0.5 if mirror["x0"] or mirror["x1"] else 1.0) * (0.5 if mirror["y0"] or mirror["y1"] else 1.0)
        self.fe, self.center, self.radius, self.grow = fe, (cx, cy), float(radius), grow
        # Nodes of every element the largest disc overlaps: the smaller discs load a subset.
        self.nodes = self._candidate_nodes()
        self.dofs = np.array([fe.dof(n, W) for n in self.nodes])
        if np.any(self.dofs < 0):
            raise NoContactRoom(f"contact patch about ({cx!r}, {cy!r}) m reaches a supported edge")
        self._table_r = self.radius * np.linspace(0.0, 1.0, TABLE) if grow else None
        self._table = None
        self._full = None

    def _candidate_nodes(self) -> np.ndarray:
        fe, (cx, cy), r = self.fe, self.center, self.radius
        i0 = max(int(np.searchsorted(fe.xs, cx - r, side="right")) - 1, 0)
        i1 = min(int(np.searchsorted(fe.xs, cx + r, side="left")), fe.xs.size - 1)
        j0 = max(int(np.searchsorted(fe.ys, cy - r, side="right")) - 1, 0)
        j1 = min(int(np.searchsorted(fe.ys, cy + r, side="left")), fe.ys.size - 1)
        p = fe.order
        return np.sort(fe.grid_node[p * i0 : p * i1 + 1, p * j0 : p * j1 + 1].ravel())

    def _distribution(self, r: float, all_nodes: bool = False) -> np.ndarray:
        """∫ N_i p dA for unit force on a disc of radius r: over all nodes, or over ``self.nodes``."""
        fe, (cx, cy) = self.fe, self.center
        n_all = fe.grid_node.size
        out = np.zeros(n_all)
        if r <= 0.0:
            i, j, s, t = fe._locate(cx, cy)[0]  # a point force: F·N_i(c)
            nodes, N = fe.shape(i, j, s, t)
            out[nodes] = N
        else:
            bx = np.unique(np.concatenate((np.linspace(cx - r, cx + r, SUBCELLS + 1), fe.xs[(fe.xs > cx - r) & (fe.xs < cx + r)])))
            by = np.unique(np.concatenate((np.linspace(cy - r, cy + r, SUBCELLS + 1), fe.ys[(fe.ys > cy - r) & (fe.ys < cy + r)])))
            gx = (0.5 * (bx[:-1, None] + bx[1:, None]) + 0.5 * (bx[1:, None] - bx[:-1, None]) * _G4).ravel()
            wx = (0.5 * (bx[1:, None] - bx[:-1, None]) * _W4).ravel()
            gy = (0.5 * (by[:-1, None] + by[1:, None]) + 0.5 * (by[1:, None] - by[:-1, None]) * _G4).ravel()
            wy = (0.5 * (by[1:, None] - by[:-1, None]) * _W4).ravel()
            X, Y = np.meshgrid(gx, gy, indexing="ij")
            wgt = np.outer(wx, wy) * cosine_pressure(np.hypot(X - cx, Y - cy), r)
            keep = (wgt > 0) & (X >= fe.xs[0]) & (X <= fe.xs[-1]) & (Y >= fe.ys[0]) & (Y <= fe.ys[-1])
            X, Y, wgt = X[keep], Y[keep], wgt[keep]
            i = np.clip(np.searchsorted(fe.xs, X) - 1, 0, fe.xs.size - 2)
            j = np.clip(np.searchsorted(fe.ys, Y) - 1, 0, fe.ys.size - 2)
            s = (X - fe.xs[i]) / (fe.xs[i + 1] - fe.xs[i])
            t = (Y - fe.ys[j]) / (fe.ys[j + 1] - fe.ys[j])
            nodes, N = fe.shape(i, j, s, t)
            out += np.bincount(nodes.ravel(), weights=(wgt[:, None] * N).ravel(), minlength=n_all)
        out *= self.share / out.sum()  # Σ N_i = 1: the total is the quadrature of p, made exactly the share
        return out if all_nodes else out[self.nodes]

    def table(self) -> np.ndarray:
        """Unit-force distributions at the tabulated radii, shape (TABLE, n_nodes)."""
        if self._table is None:
            self._table = np.array([self._distribution(r) for r in self._table_r])
        return self._table

    def unit(self, radius: float | None = None) -> np.ndarray:
        """Distribution of a unit force on a disc of ``radius`` (default: the patch's), shape (n_nodes,)."""
        return self._distribution(self.radius if radius is None else radius)

    def half_width(self, F: np.ndarray, radius: float | None = None) -> np.ndarray:
        """r(t) = r0·sqrt(F/F0), eq (10) (or r0 if the patch does not grow) [m]."""
        F = np.asarray(F, float)
        r0 = self.radius if radius is None else radius
        if not self.grow:
            return np.full(F.shape, r0)
        F0 = F.max()
        return r0 * np.sqrt(np.maximum(F, 0.0) / F0) if F0 > 0 else np.zeros(F.shape)

    def forces(self, F: np.ndarray, radius: float | None = None) -> np.ndarray:
        """Nodal forces (n_nodes, n_t) [N] for the history F (n_t,) [N]; ``radius``: r0 of this
        history, at most the patch's own. They sum to share·F(t) at every instant."""
        F = np.asarray(F, float)
        r0 = self.radius if radius is None else float(radius)
        if not 0 < r0 <= self.radius * (1 + 1e-12):
            raise InputError(f"contact radius {r0!r} m must be positive and at most the patch's {self.radius!r} m")
        if not self.grow:
            if r0 != self.radius:
                return np.outer(self.unit(r0), F)
            if self._full is None:
                self._full = self.unit()
            return np.outer(self._full, F)
        r = self.half_width(F, r0)
        pos = np.clip(r / self.radius * (TABLE - 1), 0.0, TABLE - 1)
        k = np.minimum(pos.astype(int), TABLE - 2)
        frac = pos - k
        tab = self.table()
        shape = tab[k] * (1 - frac)[:, None] + tab[k + 1] * frac[:, None]  # (n_t, n_nodes)
        return (shape * F[:, None]).T


class DiscShares:
    """Nodal shares of a unit contact force on a growing disc, for the coupled solver
    (:class:`softimpact.fem.impact.ContactStructure`'s ``patch``).

    ``shares(a)`` gives (s, ds/da) over ``patch.nodes`` for a disc of radius a ≤ the
    patch's radius: linear interpolation in a of the tabulated exact distributions
    (each summing to the patch's share), so s sums to the share for every a and
    ds/da is the slope of the table's interval. At a = 0 the force is a point force
    shared by the element's shape functions at the centre.
    """

    half_spacing = 0.0  # the disc's shares are defined for every a > 0

    def __init__(self, patch: CircularPatch):
        if not patch.grow:
            raise InputError("contact shares need a patch tabulated for a growing radius (grow=True)")
        self.patch = patch
        self._rows: dict[int, np.ndarray] = {}  # tabulated distributions, each computed when first needed (a run reaches few)
        self.step = patch.radius / (TABLE - 1)
        self._point = self.row(0)
        self.n = self._point.size

    def row(self, k: int) -> np.ndarray:
        """The distribution at the k-th tabulated radius (shape (n_nodes,)), as the patch's table has it."""
        out = self._rows.get(k)
        if out is None:
            out = self._rows[k] = self.patch.table()[k] if self.patch._table is not None else self.patch._distribution(self.patch._table_r[k])
        return out

    @property
    def table(self) -> np.ndarray:
        """All the tabulated distributions, shape (TABLE, n_nodes)."""
        return np.array([self.row(k) for k in range(TABLE)])

    def shares(self, a: float) -> tuple[np.ndarray, np.ndarray]:
        """(s, ds/da), each of shape (n_nodes,)."""
        if a > self.patch.radius * (1 + 1e-12):
            raise ContactOutgrewRoom(f"contact radius {a:.4g} m runs past the loadable disc ({self.patch.radius:.4g} m)")
        pos = min(max(a / self.step, 0.0), TABLE - 1)
        k = min(int(pos), TABLE - 2)
        frac = pos - k
        lo, hi = self.row(k), self.row(k + 1)
        slope = (hi - lo) / self.step
        return lo * (1 - frac) + hi * frac, slope
