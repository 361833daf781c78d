"""The C-scan's shapes (workflows/plate/cscan.py) against regions whose area, axes and orientation are known in
closed form: an ellipse's area πab, its axes 2a and 2b and its tilt; a half or quarter model mirrored equals the
whole; the projected envelope is the union of the interfaces' regions."""

import math

import numpy as np
import pytest

from softimpact.workflows.plate.cscan import cscan


def _grid(x0, x1, y0, y1, h):
    """Node lines, numbering and trapezoidal tributary areas of a uniform grid (independent of the package's mesh)."""
    xs = h * np.arange(round(x0 / h), round(x1 / h) + 1)  # integer multiples: a mirror-symmetric grid
    ys = h * np.arange(round(y0 / h), round(y1 / h) + 1)
    wx, wy = np.full(xs.size, h), np.full(ys.size, h)
    wx[[0, -1]] = wy[[0, -1]] = h / 2
    grid = np.arange(xs.size * ys.size).reshape(xs.size, ys.size)
    area = np.outer(wx, wy).ravel()
    return xs, ys, grid, area


def _ellipse(xs, ys, grid, a, b, tilt_deg, c=(0.0, 0.0)):
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    t = math.radians(tilt_deg)
    u = (X - c[0]) * math.cos(t) + (Y - c[1]) * math.sin(t)
    v = -(X - c[0]) * math.sin(t) + (Y - c[1]) * math.cos(t)
    d = np.zeros(grid.size)
    d[grid.ravel()] = ((u / a) ** 2 + (v / b) ** 2 <= 1.0).ravel().astype(float)
    return d


FREE = ("free",) * 4


@pytest.mark.parametrize("tilt", [0.0, 30.0, -45.0, 90.0])
def test_an_ellipse_has_its_area_axes_and_tilt(tilt):
    """a = 20 mm, b = 8 mm on a 0.25-mm grid: area πab within 1 %, axes within 2 %, tilt within 0.5°."""
    a, b = 0.02013, 0.00807  # not on the nodes
    xs, ys, grid, area = _grid(-0.03, 0.03, -0.03, 0.03, 0.00025)
    d = _ellipse(xs, ys, grid, a, b, tilt)
    (i,) = cscan(d[None], xs, ys, grid, area, FREE, ("plies_1_2",), (tilt,)).interfaces
    assert i.area == pytest.approx(math.pi * a * b, rel=0.01)
    assert i.major_axis == pytest.approx(2 * a, rel=0.02)
    assert i.minor_axis == pytest.approx(2 * b, rel=0.02)
    assert ((i.orientation_deg - tilt + 90) % 180) - 90 == pytest.approx(0.0, abs=0.5)
    assert i.misalignment_deg == pytest.approx(0.0, abs=0.5)
    assert i.centroid == pytest.approx((0.0, 0.0), abs=1e-6)


def test_a_rectangle_has_the_moments_of_its_area():
    """A 30 × 10 mm rectangle of whole nodes: its covariance is L²/12 and W²/12 exactly, so the equal-moment ellipse's
    axes are 4·sqrt(L²/12) = 2L/√3 and 2W/√3."""
    h = 0.001
    xs, ys, grid, area = _grid(0.0, 0.1, 0.0, 0.1, h)
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    on = (np.abs(X - 0.05) < 0.015 - 1e-9 + h / 2) & (np.abs(Y - 0.05) < 0.005 - 1e-9 + h / 2)  # 31 × 11 nodes... of cells h
    d = np.zeros(grid.size)
    d[grid.ravel()] = on.ravel()
    (i,) = cscan(d[None], xs, ys, grid, area, FREE, ("plies_1_2",), (0.0,)).interfaces
    L, W = on.any(axis=1).sum() * h, on.any(axis=0).sum() * h
    assert i.area == pytest.approx(L * W, rel=1e-12)
    assert i.major_axis == pytest.approx(2 * L / math.sqrt(3), rel=1e-9)
    assert i.minor_axis == pytest.approx(2 * W / math.sqrt(3), rel=1e-9)
    assert i.orientation_deg == pytest.approx(0.0, abs=1e-9)


def test_a_quarter_model_mirrored_is_the_whole():
    """The quarter x, y ≥ 0 with symmetry edges at x = 0 and y = 0 gives the whole plate's area, axes and centroid."""
    h = 0.0005
    whole = _grid(-0.04, 0.04, -0.03, 0.03, h)
    quarter = _grid(0.0, 0.04, 0.0, 0.03, h)
    d_whole = _ellipse(*whole[:3], 0.02513, 0.01007, 0.0)
    d_quarter = _ellipse(*quarter[:3], 0.02513, 0.01007, 0.0)
    w = cscan(np.stack([d_whole, 0 * d_whole]), *whole, FREE, ("a", "b"), (0.0, 90.0))
    q = cscan(np.stack([d_quarter, 0 * d_quarter]), *quarter, ("symmetry", "free", "symmetry", "free"), ("a", "b"), (0.0, 90.0))
    assert q.interfaces[0].area == pytest.approx(w.interfaces[0].area, rel=1e-12)
    assert q.interfaces[0].major_axis == pytest.approx(w.interfaces[0].major_axis, rel=1e-12)
    assert q.interfaces[0].minor_axis == pytest.approx(w.interfaces[0].minor_axis, rel=1e-12)
    assert q.interfaces[0].centroid == pytest.approx((0.0, 0.0), abs=1e-12)
    assert q.xs == pytest.approx(w.xs) and q.ys == pytest.approx(w.ys)
    assert q.interfaces[1].area == 0.0 and q.projected_area == pytest.approx(w.projected_area, rel=1e-12)


def test_the_projected_envelope_is_the_union():
    """Two crossed ellipses (0° and 90°): projected = A1 + A2 − their overlap, counted on the nodes independently."""
    xs, ys, grid, area = _grid(-0.03, 0.03, -0.03, 0.03, 0.0005)
    d1 = _ellipse(xs, ys, grid, 0.02, 0.006, 0.0)
    d2 = _ellipse(xs, ys, grid, 0.02, 0.006, 90.0)
    scan = cscan(np.stack([d1, d2]), xs, ys, grid, area, FREE, ("a", "b"), (0.0, 90.0))
    union = area @ ((d1 >= 1) | (d2 >= 1))
    assert scan.projected_area == pytest.approx(union, rel=1e-12)
    assert max(i.area for i in scan.interfaces) < scan.projected_area < sum(i.area for i in scan.interfaces)
    assert [i.misalignment_deg for i in scan.interfaces] == pytest.approx([0.0, 0.0], abs=1e-3)
