"""Laminate homogenisation (uniform in-plane strain, uniform through-thickness stress), layups, CLT."""

import numpy as np
import pytest

from softimpact.errors import InputError
from softimpact.models.laminate import PLIES, Blend, Ply, Stack, abd, homogenise, parse_layup, ply_stiffness, rotate

T300 = PLIES["T300/934"]


@pytest.mark.parametrize(
    "text, angles",
    [
        ("[90/0]5s", (90.0, 0.0) * 5 + (0.0, 90.0) * 5),
        ("[0/±45/90]2s", (0, 45, -45, 90) * 2 + (90, -45, 45, 0) * 2),
        ("[0_2/90]s", (0, 0, 90, 90, 0, 0)),
        ("[0/90]", (0, 90)),
        ("[ 45 / -45 ]", (45, -45)),
    ],
)
def test_layup_parser(text, angles):
    """Layup strings expand to the ply angles, top ply first."""
    assert parse_layup(text) == tuple(float(a) for a in angles)


@pytest.mark.parametrize("text", ["90/0", "[90/x]", "[90//0]", "[0_0/90]", "[0/90]0s"])
def test_bad_layup(text):
    """Malformed layups are refused with the text quoted."""
    with pytest.raises(InputError, match="layup"):
        parse_layup(text)


def test_isotropic_stack_returns_isotropic_stiffness():
    """Plies of an isotropic material, at any angles, homogenise to that material."""
    E, nu = 70e9, 0.3
    G = E / (2 * (1 + nu))
    iso = Ply("iso", E, E, E, G, G, G, nu, nu, nu, 2700.0, 1e-4)
    C = ply_stiffness(iso)
    stack = Stack(iso, parse_layup("[0/±45/90/30]s"))
    assert np.allclose(stack.effective(), C, rtol=1e-10, atol=1e-3)
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    assert C[0, 0] == pytest.approx(lam + 2 * G) and C[0, 1] == pytest.approx(lam) and C[5, 5] == pytest.approx(G)


def test_zero_degree_stack_returns_the_ply():
    """A stack of 0° plies is the ply itself."""
    assert np.allclose(Stack(T300, (0.0,) * 7).effective(), ply_stiffness(T300), rtol=1e-12)


def test_cross_ply_against_sun_li_closed_form():
    """[0/90]: the Sun & Li (1988) closed forms for orthotropic layers, written out here."""
    layers = [rotate(ply_stiffness(T300), a) for a in (0.0, 90.0)]
    v = [0.5, 0.5]
    c = lambda i, j: [L[i - 1, j - 1] for L in layers]  # noqa: E731  (1-based Voigt indices)
    s = lambda vals: sum(w * x for w, x in zip(v, vals))  # noqa: E731
    C33 = 1 / s([1 / x for x in c(3, 3)])
    r13 = s([a / b for a, b in zip(c(1, 3), c(3, 3))])
    r23 = s([a / b for a, b in zip(c(2, 3), c(3, 3))])
    expected = {
        (3, 3): C33,
        (1, 3): C33 * r13,
        (2, 3): C33 * r23,
        (1, 1): s([a - b**2 / d for a, b, d in zip(c(1, 1), c(1, 3), c(3, 3))]) + r13**2 * C33,
        (2, 2): s([a - b**2 / d for a, b, d in zip(c(2, 2), c(2, 3), c(3, 3))]) + r23**2 * C33,
        (1, 2): s([a - b * e / d for a, b, e, d in zip(c(1, 2), c(1, 3), c(2, 3), c(3, 3))]) + r13 * r23 * C33,
        (4, 4): 1 / s([1 / x for x in c(4, 4)]),
        (5, 5): 1 / s([1 / x for x in c(5, 5)]),
        (6, 6): s(c(6, 6)),
    }
    C = homogenise(layers, v)
    for (i, j), value in expected.items():
        assert C[i - 1, j - 1] == pytest.approx(value, rel=1e-10)


def test_fractions_must_add_up():
    """Ply fractions that do not sum to one are refused."""
    with pytest.raises(InputError, match="add up"):
        Blend(T300, ((0.0, 0.5), (90.0, 0.4)), 1e-3)


def test_rotation_by_90_swaps_axes():
    """A 90° ply has E1 and E2 swapped (C11 ↔ C22, C13 ↔ C23)."""
    C, R = ply_stiffness(T300), rotate(ply_stiffness(T300), 90.0)
    assert R[0, 0] == pytest.approx(C[1, 1]) and R[1, 1] == pytest.approx(C[0, 0]) and R[0, 2] == pytest.approx(C[1, 2])


def test_clt_of_unidirectional_stack():
    """All 0° plies: D11 = Q11·h³/12, B = 0; the smeared plane-stress EI equals 1/d11 = E1·h³/12."""
    stack = Stack(T300, (0.0,) * 10)
    h = stack.thickness
    A, B, D = abd(stack.ply_stiffnesses(), [T300.thickness] * 10)
    Q11 = T300.E1 / (1 - T300.nu12**2 * T300.E2 / T300.E1)  # E1/(1 − ν12·ν21), the textbook reduced stiffness
    assert np.allclose(B, 0, atol=1e-9 * D.max())
    assert D[0, 0] == pytest.approx(Q11 * h**3 / 12, rel=1e-12)
    bs = stack.bending_stiffness("stress")
    assert bs["clt_1_over_d11"] == pytest.approx(T300.E1 * h**3 / 12, rel=1e-9)
    assert bs["smeared_EI_per_width"] == pytest.approx(T300.E1 * h**3 / 12, rel=1e-9)


def test_smearing_overstates_bending_stiffness_of_90_outside():
    """[90/0]5s has its weak 90° plies outside: the smeared EI exceeds CLT's D11."""
    bs = Stack(T300, parse_layup("[90/0]5s")).bending_stiffness("strain")
    assert bs["smeared_EI_per_width"] > 1.1 * bs["clt_D11"]
