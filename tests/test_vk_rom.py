"""The reduced-order von Kármán plate (fem.vk_rom) against the full PlateVK it reduces."""

from dataclasses import replace

import numpy as np
import pytest
import scipy.sparse.linalg as spl

from softimpact.errors import InputError
from softimpact.fem.newmark import SolverSpec
from softimpact.fem.plate_vk import PlateVK
from softimpact.fem.vk_rom import PlateVKROM
from softimpact.input.impact_case import load_impact_case
from softimpact.workflows.coupled import impact_model, run_impact

INCH = 0.0254


def _impact(elements: int, velocity_in_s: float, steps: int, dt: float = 1e-6):
    """The built-in plate impact on an elements × elements MITC9 mesh with von Kármán kinematics."""
    p, _ = load_impact_case("plate-ss-8in-impact")
    t = p.target
    t = replace(t, plate=replace(t.plate, elements=(elements, elements)), solver=SolverSpec(dt, steps * dt, t.solver.newmark), kinematics="von-karman")
    return replace(p, target=t, impactor=replace(p.impactor, velocity=velocity_in_s * INCH))


@pytest.fixture(scope="module")
def small():
    """(PlateVK, approach row, its reduced plate with every vector nonlinear) on the 4 × 4 mesh."""
    p = _impact(4, 100.0, 10)
    m = impact_model(p)
    c = -m.vk.deflection(*p.position)
    return m.vk, c, PlateVKROM(m.vk, c, vectors=10, nonlinear=10)


def _state(rom: PlateVKROM, c: np.ndarray, w_over_h: float) -> np.ndarray:
    """Reduced coordinates of a random deflection scaled to w/h at the impact point."""
    q = np.random.default_rng(3).normal(size=rom.r) * np.sqrt(rom.lam[0] / rom.lam)
    w = float(rom.c @ q)
    return q * w_over_h * rom.vk.plate.section.thickness / w


@pytest.mark.parametrize("w_over_h", [0.01, 1.5])
def test_the_reduced_energy_and_force_are_the_full_plates_on_its_manifold(small, w_over_h):
    """At d(q) the full plate's strain energy is Π(q), its membrane forces vanish (the in-plane field is condensed
    exactly) and its internal force projected on the basis is ∂Π/∂q: the reduced model is the full one restricted."""
    vk, c, rom = small
    q = _state(rom, c, w_over_h)
    d = rom.expand(q)
    f = vk.internal_force(d)
    assert vk.strain_energy(d) == pytest.approx(rom.energy(q), rel=1e-10)
    assert np.linalg.norm(f[rom.mset]) <= 1e-9 * np.linalg.norm(vk.K[rom.mset][:, rom.mset] @ d[rom.mset]) + 1e-300
    fr = rom.basis.T @ f
    assert np.linalg.norm(fr - rom.force(q)) <= 1e-9 * np.linalg.norm(fr)


def test_the_reduced_tangent_is_the_derivative_of_the_reduced_force(small):
    """Central differences of ∂Π/∂q at w/h = 1.5 match the tangent to the differences' truncation (O(h²))."""
    _, c, rom = small
    q = _state(rom, c, 1.5)
    dq = np.random.default_rng(5).normal(size=rom.r) * 1e-6 * np.linalg.norm(q)
    T = rom.tangent(q)
    assert np.linalg.norm(rom.force(q + dq) - rom.force(q - dq) - 2.0 * T @ dq) <= 1e-7 * np.linalg.norm(2.0 * T @ dq)
    assert np.allclose(T, T.T, rtol=0.0, atol=1e-10 * np.abs(T).max())


def test_the_contact_points_static_compliance_is_exact(small):
    """Σ c_r²/λ_r equals c·K⁻¹c solved on the full plate (the first Ritz vector is the static deflection), and the
    residual flexibility at the point is zero."""
    vk, c, rom = small
    exact = float(c @ spl.spsolve(vk.K.tocsc(), c))
    assert float(np.sum(rom.c**2 / rom.lam)) == pytest.approx(exact, rel=1e-10)
    assert abs(float(c @ rom.residual)) <= 1e-10 * exact


def test_the_lowest_ritz_frequency_is_the_plates_fundamental(small):
    """The first Ritz value equals the plate's lowest eigenvalue of (K, M) by shift-invert Lanczos (the doubly
    symmetric fundamental is in the central load's Krylov space)."""
    vk, _, rom = small
    lowest = spl.eigsh(vk.K.tocsc(), k=1, M=vk.M.tocsc(), sigma=0.0, which="LM", return_eigenvectors=False)[0]
    assert rom.lam[0] == pytest.approx(lowest, rel=1e-8)


def test_a_coupled_laminate_is_refused():
    """A laminate with bending–extension coupling (B ≠ 0) cannot be condensed this way: an InputError."""
    spec = _impact(2, 100.0, 10).target.plate
    vk = PlateVK(replace(spec, stack=replace(spec.stack, angles=(0.0, 90.0))).plate())
    assert vk.coupled
    with pytest.raises(InputError, match="bending-extension coupling"):
        PlateVKROM(vk, -vk.deflection(4 * INCH, 4 * INCH))


@pytest.mark.slow
def test_the_reduced_coupled_impact_matches_the_full_plate():
    """A 1500 in/s steel ball on the 6 × 6 plate (w/h ≈ 0.7 under the ball): the reduced run's peak force and contact
    time are within 0.5 % of the full von Kármán run's, closer than the linear plate's, and its energy balances."""
    p = _impact(6, 1500.0, 400)
    m = impact_model(p)
    _, full = run_impact(p, m, energy=False, method="von-karman", stop_after=10e-6)
    _, red = run_impact(p, m, energy=True, method="von-karman-rom", stop_after=10e-6)
    _, lin = run_impact(replace(p, target=replace(p.target, kinematics="linear")), energy=False, method="direct", stop_after=10e-6)
    for attr in ("peak_force", "contact_duration"):
        err = abs(getattr(red, attr) / getattr(full, attr) - 1)
        assert err <= 5e-3
        assert err <= 0.25 * abs(getattr(lin, attr) / getattr(full, attr) - 1)
    E = red.energies
    assert np.max(np.abs(E.kinetic + E.strain - E.work)) <= 1e-3 * 0.5 * p.impactor.mass * p.impactor.velocity**2
