"""The patch compliance of a contact: h_s(r) = c·G·s(r) [m/N] and dh_s/dr, the only way the patch enters the
contact Newton (:func:`softimpact.fem.impact.newton_contact`), and the nodal loads f·s(r) of a converged step.

Every evaluator has ``__call__(r) -> (h_s, dh_s/dr)``, ``half_spacing`` [m] (below it the nearest node takes
all of the force), ``value``: ``value(r) -> h_s`` alone where it has an exact cheaper sum, else None, and
``load(r, f, out)``: out ← f·s(r). :func:`compliance` picks the evaluator of a patch once (the cosine line
patch, a plate's tabulated disc, any other patch through its shares); :class:`PatchCompliance`
(:mod:`softimpact.fem.impact`) is the general one.
"""

from __future__ import annotations

import math
from bisect import bisect_left, bisect_right

import numpy as np

from ..errors import ContactOutgrewRoom
from .impact import ContactPatch, PatchCompliance
from .plate_loads import DiscShares

__all__ = ["compliance", "LineCompliance", "TableCompliance", "ShareCompliance", "MappedCompliance"]


class LineCompliance:
    """h_s(r) = c·G·s(r) [m/N] and dh_s/dr [1/N] of the cosine line patch (:class:`ContactPatch`) as
    plain floats, exact. Over the nodes i0 … i1 − 1 the disc of radius r reaches, the outer ends are
    clipped to ±r (sin = ±1) and each inner segment end m_j is shared by two nodes, so

        h_s = ½·[c_{i0} + c_{i1−1} + Σ_j (c_j − c_{j+1})·sin(π·m_j/(2r))],
        dh_s/dr = −½·(π/(2r))/r·Σ_j (c_j − c_{j+1})·m_j·cos(π·m_j/(2r)),

    one sine and one cosine per reached node."""

    def __init__(self, patch: ContactPatch, cG: np.ndarray):
        self.patch, self.half_spacing = patch, float(patch.half_spacing)
        c = np.asarray(cG, float)
        self.lo, self.hi, self.c = patch.lo.tolist(), patch.hi.tolist(), c.tolist()
        self.dc = (c[:-1] - c[1:]).tolist()  # c_j − c_{j+1}: the weight of the end shared by nodes j and j + 1
        self.ends = [(d, m, d * m) for d, m in zip(self.dc, self.hi)]  # (weight, position, their product) of each inner segment end
        self.x0, self.x1 = self.extent = patch.extent
        self.point = self.c[patch.nearest]
        self._kept = None  # (r, i0, i1, π/(2r), the inner ends' sines) of the last :meth:`value`

    def __call__(self, r: float) -> tuple[float, float]:
        if r < self.half_spacing:
            return self.point, 0.0
        if -r < self.x0 - 1e-12 * r or r > self.x1 + 1e-12 * r:
            raise ContactOutgrewRoom(f"contact radius {r:.4g} m runs past the loadable surface nodes")
        i0, i1 = bisect_right(self.hi, -r), bisect_left(self.lo, r)
        w = math.pi / (2.0 * r)
        sin, cos = math.sin, math.cos
        h = self.c[i0] + self.c[i1 - 1]
        dh = 0.0
        for d, m, dm in self.ends[i0 : i1 - 1]:  # the inner segment ends the disc covers
            x = w * m
            h += d * sin(x)
            dh += dm * cos(x)
        return 0.5 * h, -0.5 * w * dh / r

    def value(self, r: float) -> float:
        """h_s(r) alone (the contact iteration's later iterates, :func:`newton_contact`), the same sum as
        :meth:`__call__`'s; its sines are kept for :meth:`load` at the same r (the converged iterate's)."""
        if r < self.half_spacing:
            return self.point
        if -r < self.x0 - 1e-12 * r or r > self.x1 + 1e-12 * r:
            raise ContactOutgrewRoom(f"contact radius {r:.4g} m runs past the loadable surface nodes")
        i0, i1 = bisect_right(self.hi, -r), bisect_left(self.lo, r)
        w = math.pi / (2.0 * r)
        sin = math.sin
        h = self.c[i0] + self.c[i1 - 1]
        sines = []
        keep = sines.append
        for d, m, _ in self.ends[i0 : i1 - 1]:
            x = sin(w * m)
            keep(x)
            h += d * x
        self._kept = (r, i0, i1, w, sines)
        return 0.5 * h

    def load(self, r: float, f: float, out: np.ndarray) -> None:
        """out ← f·s(r) (out zero on entry): the nodal loads of the converged step."""
        if r < self.half_spacing:
            out[self.patch.nearest] = f
            return
        lo, hi, sin = self.lo, self.hi, math.sin
        kept = self._kept
        if kept is not None and kept[0] == r:  # the sines of the inner ends, from :meth:`value` at this r
            _, i0, i1, w, inner = kept
        else:
            w = math.pi / (2.0 * r)
            i0, i1 = bisect_right(hi, -r), bisect_left(lo, r)
            inner = [sin(w * m) for m in hi[i0 : i1 - 1]]
        # the segment ends the disc covers, each shared by two nodes (lo[j + 1] is hi[j]), the outer two clipped to ±r
        half = 0.5 * f
        below = sin(w * min(max(lo[i0], -r), r))
        loads = []
        for above in inner:
            loads.append(half * (above - below))
            below = above
        loads.append(half * (sin(w * min(max(hi[i1 - 1], -r), r)) - below))
        out[i0:i1] = loads


class TableCompliance:
    """h_s(r) and dh_s/dr of a plate's contact disc (:class:`DiscShares`): its shares are the linear
    interpolation of a table in r, so c·G·s(r) is the same interpolation of the table's c·G·s_k
    (each computed once, when first reached), exact to round-off."""

    value = None  # no cheaper h_s alone: every iterate takes the full evaluation

    def __init__(self, patch: DiscShares, cG: np.ndarray):
        self.patch, self.half_spacing, self.cG = patch, float(patch.half_spacing), np.asarray(cG, float)
        self.step, self.radius = patch.step, patch.patch.radius
        self.last = int(round(self.radius / self.step))  # TABLE − 1
        self.h: list = [None] * (self.last + 1)

    def _h(self, k: int) -> float:
        h = self.h[k]
        if h is None:
            h = self.h[k] = float(self.patch.row(k) @ self.cG)
        return h

    def __call__(self, r: float) -> tuple[float, float]:
        if r > self.radius * (1 + 1e-12):
            raise ContactOutgrewRoom(f"contact radius {r:.4g} m runs past the loadable disc ({self.radius:.4g} m)")
        pos = min(max(r / self.step, 0.0), self.last)
        k = min(int(pos), self.last - 1)
        frac = pos - k
        h0, h1 = self._h(k), self._h(k + 1)
        return h0 * (1 - frac) + h1 * frac, (h1 - h0) / self.step

    def load(self, r: float, f: float, out: np.ndarray) -> None:
        """out ← f·s(r): the nodal loads of the converged step."""
        out[:] = f * self.patch.shares(r)[0]


class ShareCompliance(PatchCompliance):
    """:class:`softimpact.fem.impact.PatchCompliance` of any other patch, with the loads of a converged step."""

    def load(self, r: float, f: float, out: np.ndarray) -> None:
        """out ← f·s(r): the nodal loads of the converged step."""
        out[:] = f * self.patch.shares(r)[0]


class MappedCompliance:
    """A smaller structure's compliance on the kernels' patch columns ``index`` (its surface DOFs among
    the kernels'): h_s from its own patch, its loads written into those columns."""

    value = None  # full evaluations at every iterate, as the structure's direct run takes them

    def __init__(self, comp, index: np.ndarray, width: int):
        self.comp, self.index, self.half_spacing, self.patch = comp, index, comp.half_spacing, comp.patch
        self._row = np.zeros(width)

    def __call__(self, r: float) -> tuple[float, float]:
        return self.comp(r)

    def load(self, r: float, f: float, out: np.ndarray) -> None:
        row = self._row
        row[:] = 0.0
        self.comp.load(r, f, row)
        out[self.index] = row[: self.index.size]


def compliance(patch, cG: np.ndarray):
    """The patch's h_s(r) = c·G·s(r) evaluator (chosen once per kernel build, not per step)."""
    if isinstance(patch, ContactPatch):
        return LineCompliance(patch, cG)
    if isinstance(patch, DiscShares):
        return TableCompliance(patch, cG)
    return ShareCompliance(patch, cG)
