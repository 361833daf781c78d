"""Large deflection of the plane beam (fem.plane_tl): consistency of force and tangent, objectivity,
the linear limit (static and dynamic), and large static deflection of a clamped–clamped beam
against an independent von Kármán Euler–Bernoulli beam (``_support.vk_beam``: the axial field
eliminated, cubic Hermite bending elements).
"""

import numpy as np
import pytest

from softimpact.fem.newmark import NewmarkStepper
from softimpact.fem.plane import PlaneBeam, PlaneModel
from softimpact.fem.plane_tl import PlaneTL
from softimpact.fem.plate_vk import VonKarmanNewmark, solve_static

from _support.vk_beam import clamped_centre_deflections

E, RHO = 70e9, 2700.0  # an aluminium-like isotropic beam with ν = 0: plane stress = plane strain = uniaxial
D_ISO = np.diag([E, E, E / 2])
D_ORTHO = np.array([[120e9, 3e9, 0.0], [3e9, 9e9, 0.0], [0.0, 0.0, 5e9]])  # a laminate-like orthotropic layer


def model(support="clamped-free", nx=40, nz=4, layers=(D_ISO,), length=0.2, thickness=0.005):
    """A small plane beam and its total Lagrangian model."""
    pm = PlaneModel(PlaneBeam(length, thickness, 0.02, nx, nz, layers, RHO, support))
    return pm, PlaneTL(pm)


@pytest.mark.parametrize("support", ["clamped-free", "clamped-clamped", "simply-supported"])
def test_force_and_tangent_are_the_energy_gradient_and_hessian(support):
    """Central differences of the strain energy give the internal force, and of the force the tangent (layered D)."""
    pm, tl = model(support, nx=12, nz=4, layers=(D_ISO, D_ORTHO, D_ORTHO, D_ISO))
    rng = np.random.default_rng(1)
    d, dd = rng.standard_normal((2, tl.n)) * 1e-3
    eps = 1e-6
    dU = (tl.strain_energy(d + eps * dd) - tl.strain_energy(d - eps * dd)) / (2 * eps)
    assert dU == pytest.approx(tl.internal_force(d) @ dd, rel=1e-6)
    df = (tl.internal_force(d + eps * dd) - tl.internal_force(d - eps * dd)) / (2 * eps)
    Kdd = tl.tangent(d) @ dd
    assert np.linalg.norm(df - Kdd) <= 1e-6 * np.linalg.norm(Kdd)


def test_linear_part_is_the_plane_models_stiffness():
    """The model's own quadrature of b∫B_LᵀDB_L reproduces scikit-fem's assembled K to round-off (same elements, layers, supports)."""
    pm, tl = model("clamped-clamped", nx=10, nz=4, layers=(D_ISO, D_ORTHO, D_ISO, D_ORTHO))
    assert abs(tl.linear_stiffness() - pm.K).max() <= 1e-12 * abs(pm.K).max()


def test_rigid_rotation_is_strain_free():
    """A rigid rotation by 60° (H = R − I) has zero Green–Lagrange strain, while its linear strain is of order one."""
    c, s = np.cos(np.pi / 3), np.sin(np.pi / 3)
    H = (np.array([[c, -s], [s, c]]) - np.eye(2))[None, None]
    eL, eN = PlaneTL._strains(H)
    assert np.abs(eL + eN).max() < 1e-15
    assert np.abs(eL).max() > 0.4


def test_small_static_load_recovers_the_linear_beam():
    """At a tip deflection of 1e-5 h the cantilever's nonlinear static solution equals the linear one to 1e-6."""
    pm, tl = model()
    f = np.zeros(tl.n)
    tip = np.flatnonzero(np.isclose(pm.node_x, 0.2))
    f[[pm.dof(k, 1) for k in tip]] = 1.0 / tip.size
    u_lin = solve_static(tl, f, load_steps=1, kinematics="linear").u[-1]
    f *= 1e-5 * 0.005 / np.abs(u_lin).max()  # scale: the largest displacement 1e-5 h
    u_lin = solve_static(tl, f, load_steps=1, kinematics="linear").u[-1]
    res = solve_static(tl, f, load_steps=1, rtol=1e-6)  # a residual of round-off of K u (membrane stiffness ≫ bending) against the small load
    assert res.converged
    assert np.abs(res.u[-1] - u_lin).max() <= 1e-6 * np.abs(u_lin).max()


def test_small_dynamic_load_recovers_the_linear_beam():
    """Newmark–Newton on the nonlinear beam under a small tip pulse (w ~ 1e-5 h) follows linear Newmark to 1e-6 over 200 steps."""
    pm, tl = model()
    dt, steps = 2e-6, 200
    tip = pm.dof(int(np.flatnonzero(np.isclose(pm.node_x, 0.2) & np.isclose(pm.node_z, 0.005))[0]), 1)
    t = np.arange(steps + 1) * dt
    amplitude = 0.02  # N: a tip deflection of about 1e-5 h within the run
    pulse = amplitude * np.sin(np.pi * np.minimum(t / 100e-6, 1.0)) ** 2
    load = np.zeros((tl.n, steps + 1))
    load[tip] = pulse
    u_lin, _, _ = NewmarkStepper(pm.M, pm.K, dt).run(load)
    nm = VonKarmanNewmark(tl, dt, rtol=1e-10, tangent="modified")
    res = nm.run(lambda time: load[:, int(round(time / dt))], steps, rows=np.eye(tl.n)[[tip]])
    w_lin = u_lin[tip]
    assert 1e-6 < np.abs(w_lin).max() / 0.005 < 1e-4
    assert np.abs(res.outputs[0] - w_lin).max() <= 1e-6 * np.abs(w_lin).max()


def clamped_beam(nx):
    """A 0.5 m × 10 mm clamped–clamped beam (L/h = 50), the central load spread over the mid-span nodes, and its mid-thickness deflection row."""
    L, h, nz = 0.5, 0.01, 2
    pm, tl = model("clamped-clamped", nx=nx, nz=nz, length=L, thickness=h)
    mid = np.flatnonzero(np.isclose(pm.node_x, L / 2))
    mid = mid[np.argsort(pm.node_z[mid])]
    f = np.zeros(tl.n)
    share = np.full(nz + 1, 1.0 / nz)
    share[[0, -1]] *= 0.5  # a line load's consistent shares over the section's nodes
    f[[pm.dof(k, 1) for k in mid]] = share
    row = np.zeros(tl.n)
    row[pm.dof(mid[nz // 2], 1)] = 1.0
    return tl, f, row, L, h


def test_clamped_beam_large_deflection_follows_the_von_karman_beam():
    """Mid-span deflection of the immovable clamped–clamped beam under central loads up to 8× the load of w = h in
    linear theory (w/h to 2.07) within 0.5 % of the von Kármán Euler–Bernoulli beam, which stiffens 3.9× over linear theory there."""
    tl, f, row, L, h = clamped_beam(nx=500)  # elements 1 mm × 5 mm: Q4's parasitic shear and the beam's shear strain ≈ 0.2 %
    b = 0.02
    EI, EA = E * b * h**3 / 12, E * b * h
    k1 = 192 * EI / L**3  # the linear clamped–clamped beam under a central load
    P = k1 * h * np.array([0.01, 0.5, 1.0, 2.0, 4.0, 8.0])
    res = solve_static(tl, f * P[-1], load_factors=P / P[-1], rtol=1e-8)
    assert res.converged
    w = res.u @ row
    oracle = clamped_centre_deflections(P, length=L, EI=EI, EA=EA, elements=40)
    assert clamped_centre_deflections([1e-6 * k1 * h], length=L, EI=EI, EA=EA)[0] == pytest.approx(1e-6 * h, rel=1e-9)  # the oracle's linear limit
    assert P[-1] / k1 / oracle[-1] > 3.5  # deep in the membrane regime
    assert w / oracle == pytest.approx(np.ones(P.size), abs=5e-3)


def test_von_karman_beam_oracle_has_converged():
    """The oracle's mid-span deflections with 20 and 40 Hermite elements agree to 1e-4 at w/h ≈ 2."""
    h, L, b = 0.01, 0.5, 0.02
    EI, EA = E * b * h**3 / 12, E * b * h
    P = 192 * EI / L**3 * h * np.array([1.0, 8.0])
    coarse = clamped_centre_deflections(P, length=L, EI=EI, EA=EA, elements=20)
    fine = clamped_centre_deflections(P, length=L, EI=EI, EA=EA, elements=40)
    assert coarse == pytest.approx(fine, rel=1e-4)


def test_newmark_newton_conserves_energy_of_a_large_free_vibration():
    """Free vibration of the cantilever launched with a transverse velocity growing linearly to 12 m/s at the tip (w/h past 2):
    kinetic + strain energy stays within 1e-5 of the initial (average acceleration conserves it up to the Newton tolerance)."""
    pm, tl = model(nx=40, nz=2)
    v0 = np.zeros(tl.n)
    for node in range(pm.node_x.size):
        k = pm.dof(node, 1)
        if k >= 0:
            v0[k] = 12.0 * pm.node_x[node] / 0.2
    res = VonKarmanNewmark(tl, 5e-6, rtol=1e-9, tangent="modified").run(None, 200, rows=np.eye(tl.n)[[pm.dof(int(np.argmax(pm.node_x)), 1)]], v0=v0)
    assert np.abs(res.outputs[0]).max() > 2 * 0.005
    total = res.kinetic + res.strain
    assert np.abs(total / total[0] - 1).max() < 1e-5
