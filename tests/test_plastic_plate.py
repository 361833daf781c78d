"""The elastic–plastic plate (fem/plate_plastic.py) under static pressure against closed forms: the onset of yield
against Navier's elastic series, the collapse pressure between the limit-analysis bounds, and the large-deflection
plastic membrane; and its small-load limit against the elastic plate."""

from __future__ import annotations

import math

import numpy as np
import pytest

from softimpact.fem.nonlinear import solve_static
from softimpact.fem.plate import Plate
from softimpact.fem.plate_plastic import PlasticPlate
from softimpact.fem.plate_vk import PlateVK
from softimpact.models.plasticity import J2PlaneStress, LinearHardening
from softimpact.models.plate_laminate import isotropic_section

E, NU, SY = 70e9, 0.3, 300e6
H, L = 2e-3, 0.2  # thickness and span [m]: L/h = 100, a thin plate (FSDT within (h/L)² of Kirchhoff)
QUARTER_SS = ("symmetry", "simply-supported", "symmetry", "simply-supported")


def _plate(supports, n: int = 6, kinematics: str = "linear", lx: float = L / 2, ly: float = L / 2, ny: int | None = None, in_plane="immovable") -> PlasticPlate:
    plate = Plate(lx, ly, n, n if ny is None else ny, isotropic_section(E, NU, 2700.0, H), supports, element="mitc9")
    return PlasticPlate(plate, J2PlaneStress(E, NU, LinearHardening(SY, 0.0)), kinematics=kinematics, in_plane=in_plane)


def _navier_centre_moment(nu: float, terms: int = 199) -> float:
    """M_x = M_y at the centre of a simply supported square plate of side a under unit uniform pressure, over a²
    (Navier's double series of Kirchhoff's plate: w = Σ 16q/(π⁶D) sin(mπx/a) sin(nπy/a)/(mn(m² + n²)²/a⁴), m, n odd,
    so M_x = D(κ_x + νκ_y) = Σ 16q a²/π⁴ · (m² + νn²)/(mn(m² + n²)²) · sin(mπ/2) sin(nπ/2))."""
    m = np.arange(1, terms + 1, 2)[:, None]
    n = np.arange(1, terms + 1, 2)[None, :]
    sign = np.sin(m * np.pi / 2) * np.sin(n * np.pi / 2)
    return float(np.sum(16 / np.pi**4 * (m**2 + nu * n**2) / (m * n * (m**2 + n**2) ** 2) * sign))


def test_elastic_centre_moment_is_navier_s():
    """The simply supported square plate's centre moment (the largest M_x at the quadrature points, at the centre) is
    Navier's within 1 %: the elastic solution the yield onset is judged against."""
    pp = _plate(QUARTER_SS)
    q = 1e3
    u = solve_static(pp, pp.load_vector(-q), load_steps=1, kinematics="linear").u[-1]
    mx = -pp.resultants(u)[1][..., 0].min() / (q * L * L)  # sagging: M_x < 0 with z up and w down
    assert mx == pytest.approx(_navier_centre_moment(NU), rel=0.01)


@pytest.mark.parametrize("factor, yields", [(0.99, False), (1.01, True)])
def test_plastic_plate_first_yields_where_the_elastic_solution_says(factor, yields):
    """The elastic solution's largest von Mises stress (both faces, every quadrature point: the corners' twist of a
    simply supported plate exceeds its centre moment) reaches σ_y at q_y; the plastic plate stays elastic (no plastic
    strain anywhere) at 0.99 q_y and yields at 1.01 q_y: its face points see the elastic stress exactly."""
    from softimpact.models.plasticity import von_mises

    pp = _plate(QUARTER_SS)
    u = solve_static(pp, pp.load_vector(-1e3), load_steps=1, kinematics="linear").u[-1]
    sec = pp._section(u)
    Q = pp.material.elastic
    e0, k = sec.e0.reshape(-1, 3), sec.kappa.reshape(-1, 3)
    peak = max(von_mises((e0 + sign * H / 2 * k) @ Q.T).max() for sign in (1.0, -1.0)) / 1e3  # per pascal
    pp = _plate(QUARTER_SS)
    res = solve_static(pp, pp.load_vector(-factor * SY / peak), load_steps=1, kinematics="linear")
    assert res.converged
    assert bool(pp.yielded().any()) is yields


def test_small_loads_are_the_elastic_plate():
    """Below yield the plastic plate is the elastic plate: the same static deflection (linear and von Kármán) to 1e-10."""
    for kinematics in ("linear", "von-karman"):
        pp = _plate(QUARTER_SS, n=4, kinematics=kinematics)
        vk = PlateVK(pp.plate, "immovable")
        load = pp.load_vector(-2e3)
        a = solve_static(pp, load, load_steps=2, kinematics=kinematics).u[-1]
        b = solve_static(vk, load, load_steps=2, kinematics=kinematics).u[-1]
        assert np.allclose(a, b, rtol=0, atol=1e-10 * np.abs(b).max())


def test_collapse_pressure_lies_between_the_limit_analysis_bounds():
    """Perfectly plastic, small deflection: the simply supported square plate carries the lower bound 16 M_p/L² (the
    statically admissible field m_x = M_p(1 − 4x²/L²), m_y = M_p(1 − 4y²/L²), m_xy = 0 satisfies equilibrium with
    p = 16 M_p/L² and von Mises' m_x² − m_x m_y + m_y² ≤ M_p² everywhere) and collapses below the yield-line upper
    bound of the diagonal mechanism, 24 M_p*/L² with the von Mises hinge moment M_p* = (2/√3) M_p (a hinge line bends
    with no curvature along it): 27.7 M_p/L². Both bounds derived here (the yield-line method of Johansen; sources
    not retrieved); M_p = σ_y h²/4."""
    unit = SY * H * H / 4 / L**2
    pp = _plate(QUARTER_SS, n=4)
    lower = solve_static(pp, pp.load_vector(-16 * unit), load_steps=2, kinematics="linear", max_iterations=40)
    assert lower.converged
    pp = _plate(QUARTER_SS, n=4)
    upper = 24 * 2 / math.sqrt(3)
    factors = np.array([16, 20, 22, 24, upper]) / upper
    past = solve_static(pp, pp.load_vector(-upper * unit), load_factors=factors, kinematics="linear", max_iterations=40)
    assert not past.converged  # no equilibrium at the upper bound: the plate has collapsed before it


def test_large_deflection_tends_to_the_plastic_membrane():
    """A clamped strip in cylindrical bending (symmetry edges in y) with immovable ends, pressed to W/h ≈ 10, carries the
    load as a perfectly plastic membrane: N w'' = −p with N = N_0 = (2/√3)σ_y h (plane strain, von Mises: σ_yy = σ_xx/2)
    gives the parabola of centre deflection W = pL²/(8N_0) (derived here; rigid-plastic theory's string limit, its
    textbook statement not retrieved). Within 2 % at W/h ≥ 8 (0.2 % seen): the bending capacity vanishes as N reaches N_0."""
    span = 0.1
    pp = _plate(("symmetry", "clamped", "symmetry", "symmetry"), n=8, kinematics="von-karman", lx=span / 2, ly=0.005, ny=1)
    N0 = 2 / math.sqrt(3) * SY * H
    p_end = 8 * N0 * 12 * H / span**2  # the membrane's pressure at W = 12 h
    res = solve_static(pp, pp.load_vector(-p_end), load_steps=24)
    assert res.converged, res.message
    W = np.array([-float(pp.deflection(0.0, 0.0) @ u) for u in res.u])
    p = p_end * res.load_factors
    far = W / H >= 8
    assert far.sum() >= 4
    assert np.allclose(p[far], 8 * N0 * W[far] / span**2, rtol=0.02)
