"""Plane-strain beam FE, contact patch, response engine (paper Figs 16-22)."""

import math
from dataclasses import replace

import numpy as np
import pytest
import scipy.sparse.linalg as spl
from scipy.integrate import quad
from scipy.linalg import expm
from scipy.optimize import brentq

from softimpact.fem.loads import PatchLoad
from softimpact.fem.newmark import SolverSpec as BeamSolver
from softimpact.fem.plane import PlaneBeam, PlaneModel
from softimpact.input.beam_case import load_beam_case
from softimpact.models.laminate import PLIES, Stack, parse_layup, plane_matrix
from softimpact.models.pulses import SkewedPulse
from softimpact.workflows.beam_impact import BeamModel

from _support.constants import INCH

STACK = Stack(PLIES["T300/934"], parse_layup("[90/0]5s"))
D = plane_matrix(STACK.effective())
H, B, RHO = STACK.thickness, 1.0 * INCH, PLIES["T300/934"].density
E_BEAM, G13 = 1 / np.linalg.inv(D)[0, 0], D[2, 2]  # beam theory: σzz = 0
KAPPA = 5 / 6


def _tip_loaded(model, P):
    """Parabolic shear P over the free end face (the Timoshenko load), as consistent nodal forces."""
    f = np.zeros(model.n)
    zs, L = model.zs, model.beam.length
    tau = lambda z: 6 * P / (B * H**3) * z * (H - z)  # noqa: E731
    nodes = [np.flatnonzero(np.isclose(model.node_x, L) & np.isclose(model.node_z, z))[0] for z in zs]
    for j, node in enumerate(nodes):
        val = 0.0
        if j > 0:
            val += quad(lambda z: tau(z) * B * (z - zs[j - 1]) / (zs[j] - zs[j - 1]), zs[j - 1], zs[j])[0]
        if j < len(zs) - 1:
            val += quad(lambda z: tau(z) * B * (zs[j + 1] - z) / (zs[j + 1] - zs[j]), zs[j], zs[j + 1])[0]
        f[model.dof(node, 1)] -= val
    return f, nodes[len(zs) // 2]


def test_static_cantilever_against_timoshenko():
    """Tip deflection PL³/3EI + PL/κGA and strain −M·(h/2)/EI near the root, within 1 % (fine mesh)."""
    L, P = 3 * INCH, 10.0
    model = PlaneModel(PlaneBeam(L, H, B, 400, 8, (D,), RHO))
    f, mid = _tip_loaded(model, P)
    u = spl.spsolve(model.K.tocsc(), f)
    I, A = B * H**3 / 12, B * H
    assert -u[model.dof(mid, 1)] == pytest.approx(P * L**3 / (3 * E_BEAM * I) + P * L / (KAPPA * G13 * A), rel=0.01)
    x = 20 * H
    strain = model.surface_strain(x, "bottom", L / 400) @ u
    assert strain == pytest.approx(-P * (L - x) * (H / 2) / (E_BEAM * I), rel=0.01)


def test_layered_model_bends_like_the_real_stacking():
    """Layered (one element layer per ply) tip deflection follows CLT's D11 within 1.5 %; smeared is stiffer by EI/D11."""
    L, P = 3 * INCH, 10.0
    layers = tuple(plane_matrix(STACK.layer_stiffness(j * H / 20, (j + 1) * H / 20)) for j in range(20))
    layered = PlaneModel(PlaneBeam(L, H, B, 300, 20, layers, RHO))
    f, mid = _tip_loaded(layered, P)
    u = spl.spsolve(layered.K.tocsc(), f)
    D11 = STACK.bending_stiffness("strain")["clt_D11"] * B
    expected = P * L**3 / (3 * D11) + P * L / (KAPPA * G13 * B * H)
    assert -u[layered.dof(mid, 1)] == pytest.approx(expected, rel=0.015)


def _timoshenko_frequencies(L, count):
    """Clamped-free Timoshenko beam: roots of the free-end block of the transfer matrix expm(A(ω)L)."""
    I, A = B * H**3 / 12, B * H

    def det(w):
        Am = np.array([[0, 1, 0, 1 / (KAPPA * G13 * A)], [0, 0, 1 / (E_BEAM * I), 0], [0, -RHO * I * w**2, 0, -1], [-RHO * A * w**2, 0, 0, 0]])
        return np.linalg.det(expm(Am * L)[2:4, 2:4])

    ws = np.linspace(10.0, 2 * np.pi * 3000, 3000)
    d = [det(w) for w in ws]
    roots = [brentq(det, ws[i], ws[i + 1]) for i in range(len(ws) - 1) if np.sign(d[i]) != np.sign(d[i + 1])]
    return np.array(roots[:count]) / (2 * np.pi)


def test_first_three_bending_frequencies_against_timoshenko():
    """The paper mesh (200 × 6) gives the first three cantilever frequencies within 0.5 %."""
    L = 6 * INCH
    model = PlaneModel(PlaneBeam(L, H, B, 200, 6, (D,), RHO))
    w2 = spl.eigsh(model.K.tocsc(), k=3, M=model.M.tocsc(), sigma=0, which="LM", return_eigenvectors=False)
    fem = np.sort(np.sqrt(w2)) / (2 * np.pi)
    assert fem == pytest.approx(_timoshenko_frequencies(L, 3), rel=0.005)


def test_paper_mesh_has_2800_dofs():
    """200 × 6 elements, clamped at x = 0: 7 × 201 × 2 − 14 = 2800 DOFs."""
    problem, _ = load_beam_case("paper-long-beam")
    assert BeamModel(problem).plane.n == 2800


PATCH_X = np.linspace(0, 6 * INCH, 201)


def test_patch_forces_sum_to_F_and_are_symmetric():
    """At every step the nodal forces sum to F(t) (1e-12) and mirror about the impact point."""
    pulse = SkewedPulse(200.0, 30e-6, 355e-6)
    t = np.arange(0, 400e-6, 1e-6)
    F = pulse(t)
    patch = PatchLoad(PATCH_X, 3 * INCH, 0.25 * INCH)
    f = patch.forces(F)
    assert np.max(np.abs(f.sum(axis=0) - F)) <= 1e-12 * F.max()
    assert np.allclose(f, f[::-1], rtol=0, atol=1e-12 * F.max())


def test_eq14_recovered_at_full_radius():
    """At the peak (r = r0) the nodal forces are eq (14): F/2·[sin(π(2rᵢ+Δr)/4r0) − sin(π(2rᵢ−Δr)/4r0)]."""
    r0, dr = 0.25 * INCH, PATCH_X[1] - PATCH_X[0]
    patch = PatchLoad(PATCH_X, 3 * INCH, r0)
    F = np.array([0.0, 100.0])
    f = patch.forces(F)[:, 1]
    ri = patch.x - 3 * INCH
    inside = np.abs(ri) + dr / 2 <= r0
    eq14 = 0.5 * 100.0 * (np.sin(np.pi / (4 * r0) * (2 * ri + dr)) - np.sin(np.pi / (4 * r0) * (2 * ri - dr)))
    assert np.allclose(f[inside], eq14[inside], rtol=1e-12)


def test_small_patch_goes_to_nearest_node():
    """When r(t) is under half a node spacing, the whole force sits on the node nearest the impact."""
    patch = PatchLoad(PATCH_X, 3 * INCH + 0.004 * INCH, 0.25 * INCH)
    f = patch.forces(np.array([0.0, 1e-4, 100.0]))
    nearest = np.argmin(np.abs(patch.x - 3 * INCH))
    assert f[nearest, 1] == pytest.approx(1e-4) and np.sum(np.abs(f[:, 1])) == pytest.approx(1e-4)


@pytest.fixture(scope="module")
def short_run():
    """The long paper beam, history 1, 400 µs: direct stepping and the response engine."""
    problem, _ = load_beam_case("paper-long-beam")
    problem = replace(problem, solver=BeamSolver(1e-6, 400e-6))
    model = BeamModel(problem)
    return model, model.direct(), model.respond()


def test_energy_balance(short_run):
    """No damping: work done by the load (summed over every step) equals kinetic + strain energy to 1e-6 relative at the sampled steps."""
    _, r, _ = short_run
    e = r.energies
    assert np.max(np.abs(e.kinetic + e.strain - e.work)) < 1e-6 * np.max(e.work)


def test_engine_equals_direct_stepping(short_run):
    """The response engine's gauge strains equal direct stepping to 1e-9 relative."""
    _, direct, engine = short_run
    scale = np.max(np.abs(direct.strain))
    assert np.max(np.abs(direct.strain - engine.strain)) < 1e-9 * scale
    assert np.max(np.abs(direct.deflection - engine.deflection)) < 1e-9 * np.max(np.abs(direct.deflection))


def test_mesh_convergence_rate():
    """Peak strain at gauge 1 over 150 µs on 100×3, 200×6, 400×12 meshes: observed rate ≈ 2 (Q4)."""
    problem, _ = load_beam_case("paper-long-beam")
    peaks = []
    for nx, nz in ((100, 3), (200, 6), (400, 12)):
        q = replace(problem, beam=replace(problem.beam, nx=nx, nz=nz), solver=BeamSolver(0.5e-6, 150e-6))
        s = BeamModel(q).direct(energy=False).strain[0]
        peaks.append(s[np.argmax(np.abs(s))])
    rate = math.log2(abs(peaks[1] - peaks[0]) / abs(peaks[2] - peaks[1]))
    assert 1.7 < rate < 2.8
