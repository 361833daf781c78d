"""Large deflection of the uniformly loaded square plate against Levy's series solutions (NACA 1942).

The published numbers, load parameter P = q a⁴/(E h⁴) (a the side) against the centre deflection w_c/h, for ν = 0.316:

- clamped edges held against in-plane displacement: Levy, NACA TN 847 (= Report 740, 1942), Table 5, all nine rows;
- simply supported edges held against in-plane displacement ("edge displacement zero"): Levy, NACA TN 846 (= Report
  737, 1942), one point, P = 278.5 → w_c/h = 1.83 (read between 1.827 and 1.846).

Neither NACA scan could be read here: the numbers are as re-typed, with their sources named, in two public codes that
test against them, GitHub l-s-campos/BEM_gmsh (scripts/plates/tran2015/run_static.jl, ``LEVY_Q``/``LEVY_W``, "Levy,
NACA Report 740 / TN 847, Table 5 (ν = 0.316)") and AnatoDu/plate-solver (src/plate_solver/benchmarks.py,
``_LEVY_SQUARE_CLAMPED`` and ``LEVY_SQUARE_SS_IMMOVABLE``); the two transcriptions of Table 5 agree (17.79 / 17.8 for
the first load). Levy's solutions are Kirchhoff plates: the FSDT plate here is thin (a/h = 100), where its shear
flexibility adds about 0.1 % to the linear deflection.

Measured (MITC9 quarter, 4 × 4; 2 × 2 to 6 × 6 move it by under 0.3 %): Table 5's first seven rows (w_c/h up to 1.52)
within 1.9 %, the last two 2.1 % and 2.5 % below the table (stiffer). The independent Ritz series of the same
equations (``_support.plate_vk_ritz``, Kirchhoff, 3² to 6² deflection terms) sits 2.3–2.8 % below the table there,
within 0.5 % of the elements: the difference at the largest loads is between the table and the von Kármán equations
as both our solutions discretise them, not a discretisation error of the elements. Its source (the truncation of
Levy's series, or an in-plane edge condition the transcriptions do not state — releasing the edges' tangential
displacement brings the last row to 2.0 %) is not known here.
"""

import numpy as np
import pytest

from softimpact.fem.plate import Plate
from softimpact.fem.plate_vk import PlateVK, solve_static
from softimpact.models.plate_laminate import PlateSection

from _support import plate_vk_ritz as ritz

SIDE, H, E, NU, RHO = 1.0, 0.01, 70e9, 0.316, 2700.0  # Levy's Poisson's ratio; a/h = 100
LOAD_UNIT = E * H**4 / SIDE**4  # P = q a⁴/(E h⁴) = 1

LEVY_CLAMPED = (  # NACA TN 847, Table 5: (P, w_c/h)
    (17.79, 0.237),
    (38.3, 0.471),
    (63.4, 0.695),
    (95.0, 0.912),
    (134.9, 1.121),
    (184.0, 1.323),
    (245.0, 1.521),
    (318.0, 1.714),
    (402.0, 1.902),
)
LEVY_SS_IMMOVABLE = (278.5, 1.83)  # NACA TN 846, edge displacement zero
LEVY_SS_READING = 0.01  # the point is read between 1.827 and 1.846


def isotropic(h=H):
    """Homogeneous isotropic FSDT section (k = 5/6) with Levy's ν."""
    Q = E * h / (1 - NU**2) * np.array([[1, NU, 0], [NU, 1, 0], [0, 0, (1 - NU) / 2]])
    return PlateSection(Q, np.zeros((3, 3)), Q * h * h / 12, 5 / 6 * E / (2 * (1 + NU)) * h * np.eye(2), RHO * h, 0.0, RHO * h**3 / 12, h)


def centre_deflections(kind: str, P: np.ndarray, n: int = 4) -> np.ndarray:
    """w_c/h of a quarter of the square plate (MITC9 n × n, immovable edges) at the loads ``P`` (increasing)."""
    plate = Plate(SIDE / 2, SIDE / 2, n, n, isotropic(), supports=("symmetry", kind, "symmetry", kind), element="mitc9")
    model = PlateVK(plate, in_plane="immovable")
    factors = np.concatenate((np.linspace(0.1, 0.9, 5) * P[0], P)) / P[-1]
    res = solve_static(model, P[-1] * LOAD_UNIT * model.load_vector(1.0), load_factors=factors)
    assert res.converged, res.message
    return (res.u @ model.deflection(0.0, 0.0))[-P.size :] / H


@pytest.fixture(scope="module")
def clamped():
    """Levy's Table 5 (P, w_c/h) and the elements' w_c/h at its loads."""
    P, w = np.array(LEVY_CLAMPED).T
    return P, w, centre_deflections("clamped", P)


def test_clamped_square_plate_reproduces_levys_table(clamped):
    """Levy's Table 5 (clamped, immovable edges) within 2 % up to w_c/h = 1.6 (seven rows; measured 1.9 % at most), and within 2.5 % at its last two: the 2 % plus the 0.5 % by which the Ritz series and the elements differ there (measured 2.1 and 2.45 %: module docstring)."""
    P, w, ours = clamped
    small = w <= 1.6
    np.testing.assert_allclose(ours[small], w[small], rtol=0.02)
    np.testing.assert_allclose(ours[~small], w[~small], rtol=0.025)


def test_the_tables_last_rows_differ_from_the_equations_not_the_mesh(clamped):
    """At Table 5's last rows the independent Ritz series agrees with the elements to 0.5 % and lies on the same side of Levy's numbers."""
    P, w, ours = clamped
    series = ritz.centre_deflections(P * LOAD_UNIT, a=SIDE, h=H, E=E, nu=NU, clamped=True, n_w=3, n_u=6, n_quad=32) / H
    np.testing.assert_allclose(ours[-2:], series[-2:], rtol=0.005)
    assert np.all(series[-2:] < w[-2:]) and np.all(ours[-2:] < w[-2:])


def test_simply_supported_square_plate_reproduces_levys_point():
    """Levy's simply supported plate with immovable edges at P = 278.5: w_c/h = 1.83 within 2 % (plus the reading's ±0.01)."""
    P, w = LEVY_SS_IMMOVABLE
    ours = centre_deflections("simply-supported", np.array([P]))[0]
    assert abs(ours - w) <= 0.02 * w + LEVY_SS_READING


def test_levys_table_is_the_nonlinear_regime():
    """The table tests the membrane terms: the same plate solved linearly gives Levy's linear coefficient (0.001263 q a⁴/D) within 1 % and overestimates Table 5's last row 2.9-fold."""
    P, w = LEVY_CLAMPED[-1]
    plate = Plate(SIDE / 2, SIDE / 2, 4, 4, isotropic(), supports=("symmetry", "clamped", "symmetry", "clamped"), element="mitc9")
    model = PlateVK(plate, in_plane="immovable")
    res = solve_static(model, P * LOAD_UNIT * model.load_vector(1.0), kinematics="linear")
    linear = res.u[-1] @ model.deflection(0.0, 0.0) / H
    D = E * H**3 / (12 * (1 - NU**2))
    assert linear == pytest.approx(0.001263 * P * LOAD_UNIT * SIDE**4 / D / H, rel=0.01)
    assert linear > 2.5 * w
