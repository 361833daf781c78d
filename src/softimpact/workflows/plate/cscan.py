"""What an ultrasonic C-scan of a struck laminate shows, from the committed damage of its cohesive interfaces:
each interface's delaminated region (damage d = 1) — its area, its centroid, the length and orientation of its
major axis — and the projected envelope (the union over the interfaces, as a through-transmission scan sees it).

The shape of a region is that of the ellipse with the same second moments (the definition image analysis uses for a
region's "major axis length": scikit-image's ``regionprops``, "the length of the major axis of the ellipse that
has the same normalized second central moments as the region"): for an ellipse of semi-axes a ≥ b the central
second moments per unit area are a²/4 and b²/4 along its axes, so the major axis is 4·sqrt(λ₁) and the minor
4·sqrt(λ₂), λ the eigenvalues of the region's covariance. Each node stands for its tributary area (the mesh's
Newton–Cotes weights, :func:`~softimpact.fem.cohesive_plate.nodal_areas`) spread over a square of that area (its
own second moment a/12 a direction added), so a uniform grid gives a rectangle's moments exactly.

A half or quarter model (symmetry edges) is mirrored first: areas, shapes and maps are the whole plate's. The
classic observation these shapes are compared with: an impact delamination is elongated ("peanut"-shaped) along
the fibres of the ply below its interface (Aymerich, Dore & Priolo 2009, Compos. Sci. Technol. 69:1383, abstract:
"the major axis along the fibre direction of the lower ply"), so each interface carries the lower ply's angle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Delamination", "CScan", "cscan", "mirror_grid"]


@dataclass(frozen=True)
class Delamination:
    """One interface's delaminated region (d ≥ ``threshold``) of the whole plate, SI: ``area`` [m²], ``centroid``
    (x, y) [m], ``major_axis`` and ``minor_axis`` [m] (the equal-moment ellipse's full lengths), ``orientation_deg``
    (the major axis from +x, in (−90°, 90°]), ``lower_ply_deg`` (the fibre angle of the ply below the interface)."""

    label: str
    area: float
    centroid: tuple[float, float]
    major_axis: float
    minor_axis: float
    orientation_deg: float
    lower_ply_deg: float

    @property
    def words(self) -> str:
        """The interface in words: ``plies_3_4`` → ``plies 3/4``."""
        return self.label.replace("_", " ", 1).replace("_", "/")

    @property
    def misalignment_deg(self) -> float:
        """The angle between the major axis and the lower ply's fibres, in [0°, 90°] (nan without an area)."""
        if self.area <= 0.0:
            return math.nan
        diff = (self.orientation_deg - self.lower_ply_deg) % 180.0
        return min(diff, 180.0 - diff)

    def summary(self) -> dict:
        """summary.json's entry (SI), nulls where the interface did not delaminate."""
        grown = self.area > 0.0
        return {
            "delaminated_area_m2": self.area,
            "major_axis_m": self.major_axis if grown else None,
            "minor_axis_m": self.minor_axis if grown else None,
            "orientation_deg": self.orientation_deg if grown else None,
            "lower_ply_deg": self.lower_ply_deg,
            "major_axis_from_lower_ply_deg": self.misalignment_deg if grown else None,
            "centroid_m": list(self.centroid) if grown else None,
        }


@dataclass(frozen=True)
class CScan:
    """Per interface (top first) its :class:`Delamination`, the projected envelope's area [m²], and the whole plate's
    grids the maps draw: ``xs``, ``ys`` [m] (grid lines) and ``damage`` (interfaces, x, y)."""

    interfaces: tuple[Delamination, ...]
    projected_area: float
    xs: np.ndarray
    ys: np.ndarray
    damage: np.ndarray

    def summary(self) -> dict:
        """summary.json's ``damage`` entries: the projected area and each interface's shape by its label."""
        grown = [i for i in self.interfaces if i.area > 0.0]
        largest = max(grown, key=lambda i: i.area, default=None)
        return {
            "projected_delamination_area_m2": self.projected_area,
            "delamination_shapes": {i.label: i.summary() for i in self.interfaces},
            "largest_delamination": None if largest is None else largest.label,
            "delamination_shape_note": "the delaminated region (damage 1) of each interface, of the whole plate: the major and "
            "minor axes of the ellipse with its second moments (4·sqrt of the covariance's eigenvalues), the orientation of "
            "the major axis from +x, beside the fibre angle of the ply below the interface; projected: the union over the "
            "interfaces",
        }


def mirror_grid(xs: np.ndarray, ys: np.ndarray, grids: np.ndarray, supports: tuple[str, str, str, str], line_factor: float | None = None):
    """The grid lines and ``grids`` (…, x, y) of a model mirrored across its symmetry edges (supports in the order
    x0, x1, y0, y1) to the whole plate. ``line_factor``: the values on a mirror line multiplied by it (2 for nodal
    areas, whose model share on the line is half a node's); None leaves them."""
    xs, ys, g = np.asarray(xs, float), np.asarray(ys, float), np.array(grids, float)
    for axis, (lo, hi) in ((0, supports[0:2]), (1, supports[2:4])):
        lines = xs if axis == 0 else ys
        ax = g.ndim - 2 + axis
        for side, kind in (("lo", lo), ("hi", hi)):
            if kind != "symmetry":
                continue
            if line_factor is not None:
                idx = [slice(None)] * g.ndim
                idx[ax] = 0 if side == "lo" else -1
                g[tuple(idx)] *= line_factor
            flipped = np.flip(g, axis=ax)
            if side == "lo":
                lines = np.concatenate((2 * lines[0] - lines[::-1][:-1], lines))
                g = np.concatenate((np.take(flipped, range(flipped.shape[ax] - 1), axis=ax), g), axis=ax)
            else:
                lines = np.concatenate((lines, 2 * lines[-1] - lines[::-1][1:]))
                g = np.concatenate((g, np.take(flipped, range(1, flipped.shape[ax]), axis=ax)), axis=ax)
        if axis == 0:
            xs = lines
        else:
            ys = lines
    return xs, ys, g


def _shape(label: str, on: np.ndarray, x: np.ndarray, y: np.ndarray, a: np.ndarray, lower: float) -> Delamination:
    """The region of the nodes ``on`` (bool, flattened grid) with tributary areas ``a`` (module docstring)."""
    w = np.where(on, a, 0.0)
    area = float(w.sum())
    if area <= 0.0:
        return Delamination(label, 0.0, (math.nan, math.nan), 0.0, 0.0, math.nan, lower)
    cx, cy = float(w @ x / area), float(w @ y / area)
    dx, dy = x - cx, y - cy
    own = float(w @ a) / 12.0 / area  # each node's square of its area: a/12 a direction
    cov = np.array([[w @ (dx * dx), w @ (dx * dy)], [w @ (dx * dy), w @ (dy * dy)]]) / area + own * np.eye(2)
    lam, vec = np.linalg.eigh(cov)
    major = vec[:, 1]
    angle = math.degrees(math.atan2(major[1], major[0]))
    angle = angle - 180.0 if angle > 90.0 else angle + 180.0 if angle <= -90.0 else angle
    if abs(lam[1] - lam[0]) <= 1e-9 * lam[1]:  # a circle (or a square): no major axis
        angle = math.nan
    return Delamination(label, area, (cx, cy), 4.0 * math.sqrt(max(lam[1], 0.0)), 4.0 * math.sqrt(max(lam[0], 0.0)), angle, lower)


def cscan(
    damage: np.ndarray,
    xs: np.ndarray,
    ys: np.ndarray,
    grid_node: np.ndarray,
    area: np.ndarray,
    supports: tuple[str, str, str, str],
    labels: tuple[str, ...],
    lower_ply_deg: tuple[float, ...],
    threshold: float = 1.0,
) -> CScan:
    """The C-scan of ``damage`` (interfaces, nodes) on a structured mesh: node grid lines ``xs``, ``ys`` [m], node
    numbering ``grid_node`` (x, y), tributary ``area`` [m²] per node (of this model), ``supports`` (x0, x1, y0, y1;
    symmetry edges are mirrored), each interface's ``labels`` and the fibre angle of the ply below it
    ``lower_ply_deg`` [°]; delaminated where d ≥ ``threshold`` (module docstring)."""
    damage = np.atleast_2d(np.asarray(damage, float))
    grid_node = np.asarray(grid_node)
    if len(labels) != damage.shape[0] or len(lower_ply_deg) != damage.shape[0]:
        raise ValueError(f"{damage.shape[0]} interfaces, {len(labels)} labels and {len(lower_ply_deg)} ply angles")
    d_grid = damage[:, grid_node]  # (interfaces, x, y)
    xs_full, ys_full, d_full = mirror_grid(xs, ys, d_grid, supports)
    _, _, a_full = mirror_grid(xs, ys, np.asarray(area, float)[grid_node], supports, line_factor=2.0)
    X, Y = np.meshgrid(xs_full, ys_full, indexing="ij")
    x, y, a = X.ravel(), Y.ravel(), a_full.ravel()
    cracked = d_full.reshape(d_full.shape[0], -1) >= threshold
    shapes = tuple(_shape(lab, c, x, y, a, low) for lab, c, low in zip(labels, cracked, lower_ply_deg, strict=True))
    projected = float(a[cracked.any(axis=0)].sum()) if cracked.size else 0.0
    return CScan(shapes, projected, xs_full, ys_full, d_full)
