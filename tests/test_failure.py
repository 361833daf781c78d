"""Damage screening: ply stresses against classical lamination theory, failure indices at their
strengths, the Davies–Zhang force, and the beam's section strains."""

import math

import numpy as np
import pytest

from softimpact.models.failure import STRENGTHS, PlyStrength, davies_zhang_force, failure_indices, ply_stresses
from softimpact.models.laminate import PLIES, Stack, abd, parse_layup, ply_stiffness, reduced_stiffness

PLY = PLIES["T300/934"]
STACK = Stack(PLY, parse_layup("[90/0]5s"))


def _faces(stack):
    t = stack.ply.thickness
    tops = stack.thickness / 2 - t * np.arange(len(stack.angles))
    return tops, tops - t


def _to_laminate(angle, s12):
    """Ply (1, 2, 12) stresses → laminate (x, y, xy), rotating back by the fibre angle."""
    c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
    T_inv = np.array([[c * c, s * s, -2 * c * s], [s * s, c * c, 2 * c * s], [c * s, -c * s, c * c - s * s]])
    return T_inv @ s12


@pytest.mark.parametrize("layup", ["[90/0]5s", "[0/45/-45/90]s", "[30/-60/0]"])
@pytest.mark.parametrize("load", [(0, 0, 0, 12.0, 0, 0), (2e4, 0, 0, 0, 0, 0), (1e4, -3e3, 500, 4.0, -2.0, 1.0)])
def test_ply_stresses_return_the_applied_resultants(layup, load):
    """For N, M applied to a laminate, mid-plane strains and curvatures from CLT's ABD inverse give
    ply stresses whose through-thickness integrals are N and M again (exactly: linear in each ply)."""
    stack = Stack(PLY, parse_layup(layup))
    t = PLY.thickness
    A, B, D = abd(stack.ply_stiffnesses(), [t] * len(stack.angles))
    e = np.linalg.solve(np.block([[A, B], [B, D]]), np.array(load, float))
    zt, zb = _faces(stack)
    z = np.concatenate((zt, zb))
    _, stress = ply_stresses(PLY, tuple(stack.angles) * 2, e[:3], e[3:], z)
    n = len(stack.angles)
    N, M = np.zeros(3), np.zeros(3)
    for k, a in enumerate(stack.angles):
        st, sb = _to_laminate(a, stress[k]), _to_laminate(a, stress[n + k])
        N += t * (st + sb) / 2
        M += t / 6 * (st * (2 * zt[k] + zb[k]) + sb * (zt[k] + 2 * zb[k]))
    scale = max(abs(x) for x in load)
    assert np.concatenate((N, M)) == pytest.approx(load, abs=1e-9 * scale * 1e3)


def test_single_ply_bending_closed_form():
    """A 0° ply in pure curvature κ_x: σ1 = Q11·κ·z and σ2 = Q12·κ·z (Q from the ply's compliance)."""
    S = np.linalg.inv(ply_stiffness(PLY))[np.ix_([0, 1, 5], [0, 1, 5])]
    Q = np.linalg.inv(S)
    strain, stress = ply_stresses(PLY, [0.0], [0, 0, 0], [2.0, 0, 0], [1e-3])
    assert strain[0] == pytest.approx([2e-3, 0, 0])
    assert stress[0] == pytest.approx([Q[0, 0] * 2e-3, Q[0, 1] * 2e-3, 0], rel=1e-12, abs=1e-6)
    assert Q == pytest.approx(reduced_stiffness(ply_stiffness(PLY)))


X = STRENGTHS["T300/934"]


@pytest.mark.parametrize(
    "stress, criteria",
    [
        ((X.Xt, 0, 0), ("tsai_wu", "hashin")),
        ((-X.Xc, 0, 0), ("tsai_wu", "hashin")),
        ((0, X.Yt, 0), ("tsai_wu", "hashin")),
        ((0, -X.Yc, 0), ("tsai_wu", "hashin")),
        ((0, 0, X.S12), ("tsai_wu", "hashin")),
    ],
)
def test_indices_are_one_at_the_uniaxial_strengths(stress, criteria):
    """Each criterion reaches exactly 1 at a uniaxial strength (Tsai–Wu's F12 vanishes there;
    Hashin's matrix-compression mode with S23 gives (Yc/2S23)² − ((Yc/2S23)² − 1) = 1)."""
    s = np.array(stress, float)[:, None]
    Q = reduced_stiffness(ply_stiffness(PLY))
    e = np.linalg.solve(Q, s)
    idx = failure_indices(PLY, X, e[None], s[None])
    for c in criteria:
        assert float(idx[c].ravel()[0]) == pytest.approx(1.0, rel=1e-12)


def test_max_strain_index_and_proportionality():
    """Maximum strain: the strain of a unidirectional ply stressed to X_t along the fibre (σ2 = 0)
    gives index 1; all indices but Hashin's are proportional to the load."""
    Q = reduced_stiffness(ply_stiffness(PLY))
    E1 = 1 / np.linalg.inv(Q)[0, 0]
    e = np.linalg.solve(Q, np.array([X.Xt, 0, 0]))
    assert e[0] == pytest.approx(X.Xt / E1)
    s = np.array([300e6, 12e6, 20e6])
    e = np.linalg.solve(Q, s)
    i1 = failure_indices(PLY, X, e[None, :, None], s[None, :, None])
    i2 = failure_indices(PLY, X, 2 * e[None, :, None], 2 * s[None, :, None])
    for c in ("max_strain", "tsai_wu"):
        assert float(i2[c].ravel()[0]) == pytest.approx(2 * float(i1[c].ravel()[0]))


def test_davies_zhang_force():
    """P_c = π·sqrt(8Eh³G_IIc/(9(1−ν²))): a 4-mm quasi-isotropic CFRP plate (E = 50 GPa, ν = 0.3,
    G_IIc = 1 kJ/m²) gives 5.55 kN (by hand: 8·50e9·6.4e-8·1e3 = 2.56e7, /8.19 = 3.126e6,
    sqrt = 1768, ×π = 5554 N); P_c grows as h^1.5."""
    hand = 5554.0
    assert davies_zhang_force(50e9, 0.3, 0.004, 1000) == pytest.approx(hand, rel=1e-3)
    assert davies_zhang_force(50e9, 0.3, 0.008, 1000) / davies_zhang_force(50e9, 0.3, 0.004, 1000) == pytest.approx(2**1.5)


def test_strengths_are_validated():
    """A non-positive strength is refused with its name."""
    with pytest.raises(Exception, match="Yt"):
        PlyStrength(1, 1, -1, 1, 1, 1, 1)


def test_plane_stress_section_is_free_across_the_width():
    """Plane stress: the section strains make N_y = N_xy = M_y = M_xy = 0 through CLT's ABD."""
    from softimpact.workflows.damage import section_strains

    top, bottom = np.array([-1e-3, 2e-4]), np.array([1.2e-3, -1e-4])
    e0, k = section_strains(STACK, "stress", top, bottom)
    A, B, D = abd(STACK.ply_stiffnesses(), [PLY.thickness] * len(STACK.angles))
    NM = np.block([[A, B], [B, D]]) @ np.vstack((e0, k))
    assert np.abs(NM[[1, 2, 4, 5]]).max() < 1e-9 * np.abs(NM[[0, 3]]).max()
    h = STACK.thickness
    assert e0[0] + h / 2 * k[0] == pytest.approx(top) and e0[0] - h / 2 * k[0] == pytest.approx(bottom)


@pytest.mark.parametrize("layup", ["[90/0]5s", "[0/90/0/90]", "[0_2/90_3/0]"])
def test_extreme_faces_give_the_worst_ply(layup):
    """The worst index over the extreme faces of each angle equals the worst over every ply face."""
    from softimpact.workflows.damage import extreme_faces

    stack = Stack(PLY, parse_layup(layup))
    rng = np.random.default_rng(4)
    e0, k = rng.normal(0, 2e-3, (3, 50)) * np.array([[1], [0.3], [0]]), rng.normal(0, 4.0, (3, 50)) * np.array([[1], [0.3], [0]])
    zt, zb = _faces(stack)
    z_all, a_all = np.concatenate((zt, zb)), tuple(stack.angles) * 2
    z_ext, a_ext = extreme_faces(stack)
    for z, a, out in ((z_all, a_all, []), (z_ext, a_ext, [])):
        strain, stress = ply_stresses(PLY, a, e0, k, z)
        idx = failure_indices(PLY, X, strain, stress)
        out.append({c: v.max(axis=0) for c, v in idx.items()})
        if len(z) == len(z_all):
            every = out[0]
        else:
            ext = out[0]
    for c in every:
        assert ext[c] == pytest.approx(every[c], rel=1e-12)
