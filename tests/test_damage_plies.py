"""What failed after first-ply failure: Hashin's four modes one by one against the uniaxial strengths, and the plies
that failed over a run, with the mode and the time, against thresholds computed by hand for strain ramps."""

import math

import numpy as np
import pytest

from softimpact.models.failure import HASHIN_MODES, discounted_abd, failure_indices, hashin_modes
from softimpact.models.laminate import PLIES, Stack, abd, ply_stiffness, reduced_stiffness
from softimpact.workflows.damage import impact_damage, plies_failed

PLY = PLIES["T300/934"]
X = PLY.strength
Q = reduced_stiffness(ply_stiffness(PLY))
CROSS = Stack(PLY, (0.0, 90.0, 90.0, 0.0))  # [0/90]s, top ply first


@pytest.mark.parametrize(
    ("stress", "mode"),
    [((X.Xt, 0, 0), "fibre_tension"), ((-X.Xc, 0, 0), "fibre_compression"), ((0, X.Yt, 0), "matrix_tension"), ((0, -X.Yc, 0), "matrix_compression")],
)
def test_each_hashin_mode_is_one_at_its_uniaxial_strength_and_the_others_zero(stress, mode):
    """σ1 = X_t, σ1 = −X_c, σ2 = Y_t and σ2 = −Y_c each put exactly their own mode at 1 (Hashin's matrix compression:
    (Y_c/2S23)² − ((Y_c/2S23)² − 1) = 1) and every other mode at 0."""
    m = hashin_modes(X, np.array(stress, float))
    for k in HASHIN_MODES:
        assert float(m[k]) == pytest.approx(1.0 if k == mode else 0.0, abs=1e-12)


def test_hashin_index_is_the_largest_of_the_modes():
    """Over random plane-stress states the screening's Hashin index equals the largest of the four modes."""
    rng = np.random.default_rng(3)
    s = rng.normal(size=(200, 3)) * np.array([X.Xt, X.Yt, X.S12])
    e = np.linalg.solve(Q, s.T).T
    idx = failure_indices(PLY, X, e, s)["hashin"]
    m = hashin_modes(X, s)
    assert np.allclose(idx, np.max([m[k] for k in HASHIN_MODES], axis=0), rtol=1e-12, atol=0)


def _first_sample(history, threshold):
    """Index of the first sample of an increasing ``history`` at or above ``threshold``."""
    return int(np.flatnonzero(history >= threshold)[0])


def test_tension_ramp_fails_the_90_plies_in_matrix_tension_then_the_0_plies_in_fibre_tension():
    """[0/90]s under a mid-plane strain ε_x = rate·t (ε_y = γ = 0, no curvature): in a 90° ply ε2 = ε_x, σ2 = Q22·ε_x, so
    matrix tension at ε_x = Y_t/Q22; in a 0° ply σ1 = Q11·ε_x, σ2 = Q12·ε_x, so fibre tension at X_t/Q11 (before matrix
    tension at Y_t/Q12). plies_failed lists plies 2, 3 then 1, 4 with those modes at those samples."""
    t = np.linspace(0, 1e-3, 2001)
    ex = 0.03 * t / t[-1]
    e0, k = np.stack([ex, 0 * ex, 0 * ex]), np.zeros((3, t.size))
    assert X.Xt / Q[0, 0] < X.Yt / Q[0, 1]
    failed = plies_failed(CROSS, X, {"at_load": (e0, k)}, t)
    got = [(f.ply, f.angle, f.mode, f.sample) for f in failed]
    i90, i0 = _first_sample(ex * Q[1, 1] / X.Yt, 1.0), _first_sample(ex * Q[0, 0] / X.Xt, 1.0)
    assert got == [(2, 90.0, "matrix_tension", i90), (3, 90.0, "matrix_tension", i90), (1, 0.0, "fibre_tension", i0), (4, 0.0, "fibre_tension", i0)]
    assert failed[0].time == t[i90] and failed[0].point == "at_load"


def test_bending_ramp_names_the_compressed_and_stretched_faces():
    """[0/90]s under a curvature κ_x = −rate·t (top in compression, ε_x = z·κ_x): the top 0° ply fails first in fibre
    compression at its top face when Q11·|κ|·h/2 = X_c if that comes before the bottom 0° ply's fibre tension
    (Q11·|κ|·h/2 = X_t), and each 90° ply at its outer face z = ±t in matrix compression or tension at the |κ| solving
    Hashin's quadratic for σ2 = ∓Q22·|κ|·t (written out here)."""
    t = np.linspace(0, 1e-3, 4001)
    h, tp = CROSS.thickness, PLY.thickness
    kap = 300.0 * t / t[-1]  # |κ| [1/m]: ε_x up to 300·h/2 = 8 % at the faces
    e0, k = np.zeros((3, t.size)), np.stack([-kap, 0 * kap, 0 * kap])
    failed = {f.ply: f for f in plies_failed(CROSS, X, {"p": (e0, k)}, t)}
    # the 0° plies at z = ±h/2: σ1 = Q11·ε_x (σ2 = Q12·ε_x is far from Y_t there)
    i_fc, i_ft = _first_sample(kap * Q[0, 0] * h / 2 / X.Xc, 1.0), _first_sample(kap * Q[0, 0] * h / 2 / X.Xt, 1.0)
    assert (failed[1].mode, failed[1].face, failed[1].sample) == ("fibre_compression", "top", i_fc)
    assert (failed[4].mode, failed[4].face, failed[4].sample) == ("fibre_tension", "bottom", i_ft)
    # the 90° plies at z = ±t: σ2 = Q22·ε_x (ε2 = ε_x), σ1 = Q12·ε_x far below the fibre strengths
    s2 = kap * Q[1, 1] * tp
    a = X.Yc / (2 * X.S23)
    matrix_c = (s2 / (2 * X.S23)) ** 2 - (a * a - 1) * s2 / X.Yc  # σ2 = −s2
    assert (failed[2].mode, failed[2].face, failed[2].sample) == ("matrix_compression", "top", _first_sample(matrix_c, 1.0))
    assert (failed[3].mode, failed[3].face, failed[3].sample) == ("matrix_tension", "bottom", _first_sample(s2 / X.Yt, 1.0))


def test_the_damage_block_and_the_verdict_list_the_failed_plies():
    """impact_damage of the tension ramp lists every failed ply in summary.json's plies_failed (ply, angle, mode,
    time) in the order they failed, and the verdict names the first ones with their mode and time in ms; an intact
    run says no ply failed."""
    t = np.linspace(0, 1e-3, 2001)
    ex = 0.03 * t / t[-1]
    pts = {"at_load": (np.stack([ex, 0 * ex, 0 * ex]), np.zeros((3, t.size)))}
    force = 100.0 * np.sin(math.pi * t / t[-1])
    d = impact_damage(CROSS, X, pts, force, 1e-3 + 0 * t, None, time=t).summary()
    assert [(p["ply"], p["mode"]) for p in d["plies_failed"]] == [(2, "matrix_tension"), (3, "matrix_tension"), (1, "fibre_tension"), (4, "fibre_tension")]
    first = d["plies_failed"][0]
    assert f"ply 2 (90°) matrix tension at {first['time_s'] * 1e3:.3g} ms" in d["verdict"] and "and 1 more" in d["verdict"]
    small = {"at_load": (np.stack([1e-4 * ex, 0 * ex, 0 * ex]), np.zeros((3, t.size)))}
    d0 = impact_damage(CROSS, X, small, force, 1e-3 + 0 * t, None, time=t).summary()
    assert d0["plies_failed"] == [] and "no ply failed by Hashin's modes" in d0["verdict"]


def test_discounted_abd_of_an_intact_laminate_is_clt():
    """With no ply failed, the plane-stress ABD from the engineering constants equals lamination theory's from the
    plies' 3-D stiffnesses (models.laminate.abd), to 1e-9, for a layup with ±45° plies."""
    stack = Stack(PLY, (45.0, -45.0, 0.0, 90.0, 30.0))
    for mine, ref in zip(discounted_abd(stack, {}), abd(stack.ply_stiffnesses(), [PLY.thickness] * 5)):
        assert np.allclose(mine, ref, rtol=1e-9, atol=1e-9 * np.abs(ref).max())


def test_ply_discount_by_mode_against_hand_sums():
    """[0/90]s with both 90° plies failed in matrix tension (retained 0): a 90° ply keeps only its fibre, E1 along y, so
    A11 = 2t·Q11, A22 = 2t·(Q22 + E1), A66 = 2t·G12, and D11 = Q11·(2/3)((h/2)³ − (h/4)³); the top 0° ply's fibre failure
    then removes its share of D11, (2/3)·Q11·((h/2)³ − (h/4)³)/2."""
    t, h = PLY.thickness, 4 * PLY.thickness
    A, _, D = discounted_abd(CROSS, {2: "matrix_tension", 3: "matrix_tension"}, retained=0.0)
    assert A[0, 0] == pytest.approx(2 * t * Q[0, 0], rel=1e-12)
    assert A[1, 1] == pytest.approx(2 * t * (Q[1, 1] + PLY.E1), rel=1e-12)
    assert A[2, 2] == pytest.approx(2 * t * Q[2, 2], rel=1e-12)
    outer = 2 / 3 * ((h / 2) ** 3 - (h / 4) ** 3)
    assert D[0, 0] == pytest.approx(Q[0, 0] * outer, rel=1e-12)
    _, B1, D1 = discounted_abd(CROSS, {1: "fibre_compression", 2: "matrix_tension", 3: "matrix_tension"}, retained=0.0)
    assert D1[0, 0] == pytest.approx(Q[0, 0] * outer / 2, rel=1e-12)
    assert B1[0, 0] == pytest.approx(Q[0, 0] * ((h / 4) ** 2 - (h / 2) ** 2) / 2, rel=1e-12)  # the bottom 0° ply alone (z from −h/2 to −h/4): unsymmetric


def test_verdict_gives_the_bending_stiffness_left():
    """After the tension ramp fails all four plies (90° matrix, then 0° fibre) the damage block's residual D11 and D22
    ratios are the discounted laminate's over the intact one's (about 1e-6: every ply discounted), the verdict says so,
    and an intact run keeps 1."""
    t = np.linspace(0, 1e-3, 2001)
    ex = 0.03 * t / t[-1]
    pts = {"at_load": (np.stack([ex, 0 * ex, 0 * ex]), np.zeros((3, t.size)))}
    d = impact_damage(CROSS, X, pts, np.ones_like(t), 1e-3 + 0 * t, None, time=t).summary()
    D0 = discounted_abd(CROSS, {})[2]
    D = discounted_abd(CROSS, {1: "fibre_tension", 2: "matrix_tension", 3: "matrix_tension", 4: "fibre_tension"})[2]
    assert d["residual_D11_ratio"] == pytest.approx(D[0, 0] / D0[0, 0], rel=1e-12) and d["residual_D11_ratio"] < 1e-5
    assert d["residual_D22_ratio"] == pytest.approx(D[1, 1] / D0[1, 1], rel=1e-12)
    assert "bending stiffness left after the ply discount D11 0%" in d["verdict"]
    small = {"at_load": (np.stack([1e-4 * ex, 0 * ex, 0 * ex]), np.zeros((3, t.size)))}
    d0 = impact_damage(CROSS, X, small, np.ones_like(t), 1e-3 + 0 * t, None, time=t).summary()
    assert (d0["residual_D11_ratio"], d0["residual_D22_ratio"]) == (1.0, 1.0) and "bending stiffness left" not in d0["verdict"]
