"""J2 plane-stress plasticity (models/plasticity.py) and its through-thickness section (fem/plate_plastic.py) against
closed forms: the elastic limit, uniaxial, pure-shear and equibiaxial yield and hardening, the consistent tangent
against finite differences, and the elastic–plastic moment–curvature of an equibiaxially bent section."""

from __future__ import annotations

import math

import numpy as np
import pytest

from softimpact.errors import InputError
from softimpact.models.plasticity import J2PlaneStress, LinearHardening, PowerHardening, von_mises

E, NU, SY = 70e9, 0.33, 300e6


def _uniaxial(material, strains):
    """σ_xx along a uniaxial-stress path ε_xx = ``strains`` (σ_yy = τ_xy = 0 by a secant iteration on ε_yy at each
    increment, the state committed between increments): (σ_xx, residual σ_yy)."""
    ep, alpha = np.zeros((1, 3)), np.zeros(1)
    eyy, out, res = 0.0, [], []
    for exx in strains:
        a, b = -NU * exx, eyy  # two guesses of ε_yy, then secant on σ_yy(ε_yy) = 0
        fa = material.return_map(np.array([[exx, a, 0.0]]), ep, alpha).stress[0, 1]
        fb = material.return_map(np.array([[exx, b, 0.0]]), ep, alpha).stress[0, 1]
        for _ in range(60):
            if fb == fa:
                break
            a, fa, b = b, fb, b - fb * (b - a) / (fb - fa)
            fb = material.return_map(np.array([[exx, b, 0.0]]), ep, alpha).stress[0, 1]
            if abs(fb) < 1e-9 * SY:
                break
        rm = material.return_map(np.array([[exx, b, 0.0]]), ep, alpha)
        ep, alpha, eyy = rm.plastic_strain, rm.equivalent_plastic_strain, b
        out.append(rm.stress[0, 0])
        res.append(rm.stress[0, 1])
    return np.array(out), np.array(res)


@pytest.mark.parametrize("H", [0.0, 1e9])
def test_uniaxial_stress_strain_is_the_bilinear_closed_form(H):
    """Under uniaxial stress σ_xx follows E·ε up to σ_y, then σ_y + E_t(ε − σ_y/E) with E_t = E·H/(E + H) (the equivalent
    plastic strain of a uniaxial path is ε_xxᵖ), to 1e-8."""
    m = J2PlaneStress(E, NU, LinearHardening(SY, H))
    strains = np.linspace(0.0, 5 * SY / E, 41)[1:]
    sigma, residual = _uniaxial(m, strains)
    Et = E * H / (E + H)
    expected = np.where(strains <= SY / E, E * strains, SY + Et * (strains - SY / E))
    assert np.max(np.abs(residual)) < 1e-6 * SY
    assert np.max(np.abs(sigma - expected)) < 1e-8 * SY


@pytest.mark.parametrize(
    "direction, saturates",
    [
        ((0.0, 0.0, 1.0), (0.0, 0.0, SY / math.sqrt(3))),  # pure shear: τ = σ_y/√3
        ((1.0, 1.0, 0.0), (SY, SY, 0.0)),  # equibiaxial: σ_xx = σ_yy = σ_y
    ],
)
def test_perfectly_plastic_paths_saturate_at_the_von_mises_stress(direction, saturates):
    """A perfectly plastic material strained far along pure shear or equibiaxial stretch (paths that keep the stress
    proportional by symmetry) carries τ = σ_y/√3 or σ_xx = σ_yy = σ_y."""
    m = J2PlaneStress(E, NU, LinearHardening(SY, 0.0))
    rm = m.return_map(20 * SY / E * np.array([direction]), np.zeros((1, 3)), np.zeros(1))
    assert np.allclose(rm.stress[0], saturates, rtol=1e-10, atol=1e-6 * SY)


def test_small_strains_are_elastic():
    """Below yield the return mapping is plane-stress elasticity: σ = Cₑ ε and the tangent Cₑ, no plastic strain."""
    m = J2PlaneStress(E, NU, LinearHardening(SY, 1e9))
    eps = np.array([[1e-4, -2e-4, 3e-4], [0.0, 0.0, 0.0]])
    rm = m.return_map(eps, np.zeros((2, 3)), np.zeros(2))
    Ce = E / (1 - NU**2) * np.array([[1, NU, 0], [NU, 1, 0], [0, 0, (1 - NU) / 2]])
    assert np.allclose(rm.stress, eps @ Ce.T, rtol=1e-14, atol=0)
    assert np.allclose(rm.tangent, Ce, rtol=1e-14) and not np.any(rm.plastic_strain) and not np.any(rm.multiplier)


@pytest.fixture(scope="module")
def random_states():
    """2000 random strains and committed plastic states, most of them plastic."""
    rng = np.random.default_rng(1)
    n = 2000
    return rng.normal(size=(n, 3)) * 0.01, rng.normal(size=(n, 3)) * 1e-3, np.abs(rng.normal(size=n)) * 0.01


@pytest.mark.parametrize("hardening", [LinearHardening(SY, 0.0), LinearHardening(SY, 2e9), PowerHardening(SY, 600e6, 0.5)], ids=["perfect", "linear", "power"])
def test_returned_stress_is_on_the_yield_surface_and_the_flow_normal(random_states, hardening):
    """Every plastic point returns onto σ_vm = σ_y(ε̄ᵖ), with σ = Cₑ(ε − εᵖ), a plastic strain increment along the normal
    P·σ and ε̄ᵖ increased by Δγ·sqrt(⅔ σᵀPσ) (associative flow)."""
    from softimpact.models.plasticity import P

    eps, ep0, a0 = random_states
    m = J2PlaneStress(E, NU, hardening)
    rm = m.return_map(eps, ep0, a0)
    plastic = rm.multiplier > 0
    assert plastic.sum() > 1500
    sy, _ = hardening(rm.equivalent_plastic_strain[plastic])
    assert np.max(np.abs(von_mises(rm.stress[plastic]) / sy - 1)) < 1e-10
    assert np.allclose(rm.stress, (eps - rm.plastic_strain) @ m.elastic.T, rtol=0, atol=1e-6 * SY)
    Ps = rm.stress[plastic] @ P.T
    dg = rm.multiplier[plastic]
    assert np.allclose(rm.plastic_strain[plastic] - ep0[plastic], dg[:, None] * Ps, rtol=0, atol=1e-12)
    grown = dg * np.sqrt(2.0 / 3.0 * np.einsum("pi,pi->p", rm.stress[plastic], Ps))
    assert np.allclose(rm.equivalent_plastic_strain[plastic] - a0[plastic], grown, rtol=1e-10, atol=1e-14)


@pytest.mark.parametrize("hardening", [LinearHardening(SY, 0.0), LinearHardening(SY, 2e9), PowerHardening(SY, 600e6, 0.5)], ids=["perfect", "linear", "power"])
def test_consistent_tangent_is_the_derivative_of_the_return_mapping(random_states, hardening):
    """The consistent tangent equals central finite differences of the stress to O(h²): the error falls ~100× when h
    falls 10× (from round-off-free sizes), and is below 1e-7 of E at h = 1e-7."""
    eps, ep0, a0 = random_states
    m = J2PlaneStress(E, NU, hardening)
    D = m.return_map(eps, ep0, a0).tangent

    def fd(h):
        out = np.empty_like(D)
        for j in range(3):
            e = np.zeros(3)
            e[j] = h
            out[:, :, j] = (m.return_map(eps + e, ep0, a0).stress - m.return_map(eps - e, ep0, a0).stress) / (2 * h)
        return np.max(np.abs(out - D)) / E

    coarse, fine = fd(1e-5), fd(1e-6)
    assert fine < coarse / 30 or fine < 1e-9
    assert fd(1e-7) < 1e-7


def test_hardening_laws_refuse_unphysical_constants():
    """A negative or infinite yield stress, a negative hardening modulus and a power exponent outside (0, 1] are refused."""
    for bad in (lambda: LinearHardening(-1.0), lambda: LinearHardening(math.inf), lambda: LinearHardening(SY, -1.0), lambda: PowerHardening(SY, 1e8, 1.5)):
        with pytest.raises(InputError):
            bad()


# ---- the section: the plate's through-thickness integration ------------------------------------------------------


@pytest.fixture(scope="module")
def bent_plate():
    """A small elastic–perfectly plastic MITC9 plate (its section under test) and a displacement builder of uniform
    equibiaxial curvature κ (φx = κx, φy = κy, membrane and deflection zero)."""
    from softimpact.fem.plate import PHI_X, PHI_Y, Plate
    from softimpact.fem.plate_plastic import PlasticPlate
    from softimpact.models.plate_laminate import isotropic_section

    h = 2e-3
    plate = Plate(0.05, 0.05, 2, 2, isotropic_section(E, NU, 2700.0, h), ("free",) * 4, element="mitc9")
    pp = PlasticPlate(plate, J2PlaneStress(E, NU, LinearHardening(SY, 0.0)), kinematics="linear")
    xy = pp.fe.node_xy()

    def curvature(kappa):
        d = np.zeros(pp.n)
        nd = pp.fe.basis.nodal_dofs
        full = np.zeros(pp.fe.basis.N)
        full[nd[PHI_X]], full[nd[PHI_Y]] = kappa * xy[0], kappa * xy[1]
        d[:] = full[pp.free]
        return d

    return pp, h, curvature


@pytest.mark.parametrize("ratio", [0.5, 1.0, 1.2, 1.5, 2.0, 3.0, 5.0, 10.0, 50.0])
def test_moment_curvature_of_the_section_is_the_closed_form(bent_plate, ratio):
    """Equibiaxial bending κ_x = κ_y = κ keeps σ_xx = σ_yy (τ = 0) at every height, so von Mises reduces to |σ_xx| = σ_y and
    the section is a rectangular one of modulus E/(1 − ν) (derived here): M = E h³κ/(12(1 − ν)) up to κ_y = 2σ_y(1 − ν)/(E h),
    then M = M_p(1 − (κ_y/κ)²/3), M_p = σ_y h²/4 — the plate's 8 × 2-point layered rule within 0.5 % (its bound: 0.33 %)."""
    pp, h, curvature = bent_plate
    ky = 2 * SY * (1 - NU) / (E * h)
    kappa = ratio * ky
    N, M = pp.resultants(curvature(kappa))
    Mp = SY * h * h / 4
    expected = E * h**3 * kappa / (12 * (1 - NU)) if ratio <= 1 else Mp * (1 - 1 / (3 * ratio**2))
    assert np.allclose(M[..., 0], expected, rtol=5e-3) and np.allclose(M[..., 1], expected, rtol=5e-3)
    assert np.max(np.abs(N)) < 1e-9 * SY * h  # symmetric stresses: no membrane force


def test_fully_plastic_moment_is_sigma_y_h_squared_over_four(bent_plate):
    """Far past yield (κ = 10⁴ κ_y) the section carries M_p = σ_y h²/4 to 1e-6: z = 0 is a layer boundary, so the rule
    integrates the step of σ(z) exactly."""
    pp, h, curvature = bent_plate
    M = pp.resultants(curvature(1e4 * 2 * SY * (1 - NU) / (E * h)))[1]
    assert np.allclose(M[..., :2], SY * h * h / 4, rtol=1e-6)
