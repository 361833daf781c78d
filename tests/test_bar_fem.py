"""The Hermite rod: interpolation, rigid-body mode, free-free frequencies."""

import numpy as np

from softimpact.fem.bar import Rod, assemble_rod

ROD = Rod(length=0.9144, area=1.2667e-4, youngs_modulus=68.95e9, density=2698.8, elements=39)


def test_paper_mesh_has_80_dofs():
    """39 elements with u and du/dx at 40 nodes: 80 DOFs, as in the paper."""
    assert assemble_rod(ROD).n == 80


def test_strain_probe_is_exact_for_cubics():
    """The cubic Hermite field reproduces u = x³ exactly, so du/dx = 3x² anywhere."""
    m = assemble_rod(ROD)
    u = np.zeros(m.n)
    u[m.axial_dofs], u[m.strain_dofs] = m.nodes**3, 3 * m.nodes**2
    x = np.array([0.0, 0.0123, 0.4572, 0.6, ROD.length])
    assert np.allclose(m.strain_probe(x) @ u, 3 * x**2, rtol=1e-10, atol=1e-12)


def test_rigid_translation_has_total_mass_and_no_stiffness():
    """u = 1 (u' = 0): K·u = 0 and uᵀMu = ρAL (+ the lumped end mass)."""
    rod = Rod(**{**ROD.__dict__, "end_mass": 0.0087})
    m = assemble_rod(rod)
    u = np.zeros(m.n)
    u[m.axial_dofs] = 1.0
    assert np.max(np.abs(m.K @ u)) < 1e-6 * abs(m.K).max()
    assert np.isclose(u @ m.M @ u, rod.density * rod.area * rod.length + 0.0087, rtol=1e-12)


def test_free_free_frequencies_converge_at_order_six():
    """First free-free frequency → πc/L; cubic Hermite eigenvalue error falls like h⁶ (fitted rate ≥ 5.5)."""
    import scipy.linalg

    exact = np.pi * ROD.wave_speed / ROD.length
    errs, hs = [], []
    for ne in (4, 8, 16):
        m = assemble_rod(Rod(ROD.length, ROD.area, ROD.youngs_modulus, ROD.density, ne))
        w2 = scipy.linalg.eigh(m.K.toarray(), m.M.toarray(), eigvals_only=True)
        errs.append(abs(np.sqrt(w2[1]) - exact) / exact)
        hs.append(ROD.length / ne)
    rate = np.polyfit(np.log(hs), np.log(errs), 1)[0]
    assert rate > 5.5
