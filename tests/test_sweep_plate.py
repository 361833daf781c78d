"""softimpact sweep on plate cases: medians against direct stepping, the plate damage indices
against a hand computation of the ply stresses, threshold velocities bracketed by direct runs."""

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact.cli import main

INCH = 0.0254

# The quarter of the built-in 8-in plate (symmetry on the centre lines), coarse: quick to build.
CASE = """
title = "quarter of the 8-in plate, coarse"
units = "in-lbf-s"
[plate]
length = "4 in"
width = "4 in"
elements = [8, 8]
support = { x0 = "simply-supported", x1 = "symmetry", y0 = "simply-supported", y1 = "symmetry" }
[plate.laminate]
ply = "T300/934"
layup = "[90/0]5s"
[load]
position = ["4 in", "4 in"]
contact_radius = "0.25 in"
history = { shape = "empirical", projectile = "rubber-1/2in", velocity = "2000 in/s" }
[solver]
time_step = "1 us"
duration = "300 us"
[[gauges]]
name = "g1"
position = ["3 in", "4 in"]
"""


def _table(out):
    import pyarrow.parquet as pq

    return pq.read_table(out / "runs.parquet").to_pydict()


def _direct(case_text, velocity, alphas=None):
    """Direct Newmark stepping of the case at ``velocity`` [m/s]: (result, damage outputs of one run)."""
    import tomllib
    from pathlib import Path

    from softimpact.cases import PlateKind

    data = tomllib.loads(case_text)
    data["load"]["history"]["velocity"] = f"{velocity!r} m/s"
    if alphas:
        data["load"]["history"].update(alphas)
    adapter = PlateKind()
    model = adapter.prepare(data, Path("."), 1)
    assert model.stepper is not None  # a group of one run steps directly: no response engine
    result = model.direct(energy=False, snapshots=())
    return result, adapter.run(model, data, Path("."))


def test_monte_carlo_of_a_plate_medians_equal_the_deterministic_run(tmp_path):
    """41 draws of V (uniform 1000–5000 in/s) and of α1–α4 (a scaling.json's covariance: the 1/2-in
    ball's law, 1 % standard errors, correlated residuals) through one plate model's response engine:
    the median peak strains equal those of direct stepping at the median velocity with the mean α's
    (peak |strain| is monotone in V; the α's scatter by ~1 %)."""
    from scipy.stats import t as student

    from softimpact.models.empirical import PRESETS, PROJECTILES

    law = PRESETS[PROJECTILES["rubber-1/2in"].law]
    rng = np.random.default_rng(0)
    common = rng.standard_normal(8)
    group = {}
    for i in range(1, 5):
        a = getattr(law, f"alpha{i}")
        half = 0.01 * abs(a) * student.ppf(0.975, 7)
        group[f"alpha{i}"] = {"value": a, "ci95": [a - half, a + half], "residuals": list(common + 0.5 * rng.standard_normal(8))}
    fit = {"groups": {"0.5 in": group}}
    (tmp_path / "scaling.json").write_text(json.dumps(fit))
    (tmp_path / "plate.toml").write_text(CASE)
    (tmp_path / "mc.toml").write_text(
        """
[sweep]
case = "plate.toml"
method = "monte-carlo"
runs = 41
seed = 3
outputs = ["peak_force_N", "strain_g1.peak_abs", "peak_deflection_at_load_m", "damage.tsai_wu", "damage.at_load.hashin"]
[[sweep.parameter]]
key = "load.history.velocity"
distribution = { uniform = ["1000 in/s", "5000 in/s"] }
[[sweep.parameter]]
key = "load.history"
from = "scaling.json"
group = "0.5 in"
"""
    )
    out = tmp_path / "out"
    r = CliRunner().invoke(main, ["sweep", str(tmp_path / "mc.toml"), "--out", str(out), "--no-figures", "--workers", "0"])
    assert r.exit_code == 0, r.output
    summary = json.loads((out / "summary.json").read_text())
    assert summary["case_type"] == "plate" and summary["groups"] == 1 and summary["failed"] == 0
    t = _table(out)
    V = float(np.median(t["load.history.velocity"]))
    mean = {f"alpha{i}": fit["groups"]["0.5 in"][f"alpha{i}"]["value"] for i in range(1, 5)}
    ref, one = _direct(CASE, V, mean)
    assert float(np.median(t["strain_g1.peak_abs"])) == pytest.approx(np.abs(ref.strain[0]).max(), rel=5e-3)
    w = ref.deflection[0]
    assert float(np.median(t["peak_deflection_at_load_m"])) == pytest.approx(w[np.argmax(np.abs(w))], rel=5e-3)
    assert float(np.median(t["peak_force_N"])) == pytest.approx(ref.force.max(), rel=5e-3)
    # The damage outputs of the engine runs are those of direct stepping too.
    assert float(np.median(t["damage.tsai_wu"])) == pytest.approx(one["damage"]["tsai_wu"], rel=5e-3)
    assert float(np.median(t["damage.at_load.hashin"])) == pytest.approx(one["damage"]["at_load"]["hashin"], rel=5e-3)


def _hand_indices(strain_12, ply, X):
    """Max strain, Tsai–Wu and Hashin of one ply from its material-axis strains (ε1, ε2, γ12), by hand."""
    e1, e2, g12 = strain_12
    nu21 = ply.nu12 * ply.E2 / ply.E1
    d = 1 - ply.nu12 * nu21
    s1 = (ply.E1 * e1 + ply.nu12 * ply.E2 * e2) / d
    s2 = (ply.nu12 * ply.E2 * e1 + ply.E2 * e2) / d
    t12 = ply.G12 * g12
    # Allowable strains of the ply under one stress: X/E1, Y/E2, S/G12 (E1, E2 the ply's moduli).
    max_strain = max(
        e1 / (X.Xt / ply.E1) if e1 >= 0 else -e1 / (X.Xc / ply.E1),
        e2 / (X.Yt / ply.E2) if e2 >= 0 else -e2 / (X.Yc / ply.E2),
        abs(g12) / (X.S12 / ply.G12),
    )
    F1, F2 = 1 / X.Xt - 1 / X.Xc, 1 / X.Yt - 1 / X.Yc
    F11, F22, F66 = 1 / (X.Xt * X.Xc), 1 / (X.Yt * X.Yc), 1 / X.S12**2
    F12 = -0.5 * math.sqrt(F11 * F22)
    # Strength ratio R: the stress state times R lies on the Tsai–Wu surface (the positive root).
    roots = np.roots([F11 * s1**2 + F22 * s2**2 + F66 * t12**2 + 2 * F12 * s1 * s2, F1 * s1 + F2 * s2, -1.0])
    R = min(r.real for r in roots if abs(r.imag) < 1e-12 and r.real > 0)
    fibre = (s1 / X.Xt) ** 2 + (t12 / X.S12) ** 2 if s1 >= 0 else (s1 / X.Xc) ** 2
    if s2 >= 0:
        matrix = (s2 / X.Yt) ** 2 + (t12 / X.S12) ** 2
    else:
        matrix = (s2 / (2 * X.S23)) ** 2 + ((X.Yc / (2 * X.S23)) ** 2 - 1) * s2 / X.Yc + (t12 / X.S12) ** 2
    return np.array([max_strain, 1 / R, math.sqrt(max(fibre, matrix))])


@pytest.mark.parametrize("bending", [False, True])
def test_plate_damage_against_hand_computed_ply_stresses(bending):
    """A [90/0]5s laminate, strains read in x, y and 45° on both faces: equal faces (membrane) or
    opposite faces (pure bending). By hand: γxy = 2ε45 − εx − εy; a 0° ply sees (εx, εy, γxy), a 90° ply
    (εy, εx, −γxy); plane-stress Hooke in the ply; the worst ply face is the outer face of the outermost
    ply of each angle (z = h/2 for the 90°, h/2 − t for the 0°, the strain there z/(h/2) of the face's)."""
    from softimpact.models.failure import STRENGTHS
    from softimpact.models.laminate import PLIES, Stack, parse_layup
    from softimpact.workflows.damage import plate_damage

    ply, X = PLIES["T300/934"], STRENGTHS["T300/934"]
    stack = Stack(ply, parse_layup("[90/0]5s"))
    ex, ey, e45 = 2.0e-3, -1.5e-3, 1.2e-3  # x, y and 45° gauge readings on the top face
    top = np.array([ex, ey, e45])
    bottom = -top if bending else top
    gxy = 2 * e45 - ex - ey
    face = np.array([[ex, ey, gxy], [-ex, -ey, -gxy]] if bending else [[ex, ey, gxy]])
    h, t = stack.thickness, ply.thickness
    hand = []
    for f in face:
        for angle, scale in ((90, 1.0), (0, (h / 2 - t) / (h / 2))):
            x, y, g = f * scale
            hand.append(_hand_indices((x, y, g) if angle == 0 else (y, x, -g), ply, X))
    hand = np.max(hand, axis=0)

    def tensor(reading):
        x, y, d45 = reading
        return np.array([x, y, 2 * d45 - x - y])[:, None] * np.ones((1, 2))

    F = np.array([0.0, 1000.0])
    dmg = plate_damage(stack, X, tensor(top)[None], tensor(bottom)[None], F)
    got = [dmg.ply[c][0, 1] for c in ("max_strain", "tsai_wu", "hashin")]
    assert got == pytest.approx(hand, rel=1e-9)
    # Davies–Zhang by hand, with the laminate's smeared in-plane E1, ν12 (its own closed form in the test below).
    assert dmg.delamination[1] == pytest.approx(1000.0 / dmg.threshold_force)


def test_pseudo_gauges_read_the_strain_tensor():
    """The damage pseudo-gauges (x, y, 45° on both faces) recombine to the strain the plate's own
    gauge reads in any other direction: ε_θ = εx cos²θ + εy sin²θ + γxy sinθ cosθ, at θ = 30°."""
    import dataclasses
    import tomllib

    from softimpact.input.plate_case import plate_problem
    from softimpact.models.pulses import SkewedPulse
    from softimpact.workflows.damage import strain_tensor
    from softimpact.workflows.plate_impact import PlateGauge, PlateModel

    data = tomllib.loads(CASE)
    problem = plate_problem(data)
    p = (2.5 * INCH, 3.0 * INCH)
    gauges = tuple(PlateGauge(f"{d}", p, "top", d, 0.0) for d in ("x", "y", 45.0, 30.0))
    problem = dataclasses.replace(problem, gauges=gauges, load=dataclasses.replace(problem.load, history=SkewedPulse(500.0, 20e-6, 100e-6)))
    r = PlateModel(problem).respond()
    e = strain_tensor(*r.strain[:3])
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    np.testing.assert_allclose(e[0] * c * c + e[1] * s * s + e[2] * s * c, r.strain[3], atol=1e-9 * np.abs(r.strain[3]).max())


def test_threshold_velocity_is_bracketed_by_direct_runs(tmp_path):
    """A velocity grid through the engine gives, in thresholds.csv, the velocity at which the
    Tsai–Wu index first reaches 1; direct stepping 2 % below it stays under 1, 2 % above it exceeds 1."""
    (tmp_path / "plate.toml").write_text(CASE)
    (tmp_path / "grid.toml").write_text(
        """
[sweep]
case = "plate.toml"
method = "grid"
outputs = ["damage.tsai_wu", "damage.delamination", "damage.threshold_force_N"]
[[sweep.parameter]]
key = "load.history.velocity"
range = ["3000 in/s", "7000 in/s", 17]
"""
    )
    out = tmp_path / "out"
    r = CliRunner().invoke(main, ["sweep", str(tmp_path / "grid.toml"), "--out", str(out), "--no-figures", "--workers", "0"])
    assert r.exit_code == 0, r.output
    rows = json.loads((out / "summary.json").read_text())["thresholds"]
    th = {row["index"]: row["threshold_velocity_median_m_s"] for row in rows}
    assert 3000 * INCH < th["tsai_wu"] < 7000 * INCH
    for factor, below in ((0.98, True), (1.02, False)):
        _, one = _direct(CASE, factor * th["tsai_wu"])
        assert (one["damage"]["tsai_wu"] < 1.0) == below, (factor, one["damage"]["tsai_wu"])
    # Delamination: the peak force against Davies–Zhang's P_c = π·sqrt(8·E·h³·G_IIc / (9(1 − ν²))).
    t = _table(out)
    from softimpact.models.failure import STRENGTHS
    from softimpact.models.laminate import PLIES, Stack, engineering_constants, parse_layup

    stack = Stack(PLIES["T300/934"], parse_layup("[90/0]5s"))
    ec = engineering_constants(stack.effective())
    pc = math.pi * math.sqrt(8 * ec["E1"] * stack.thickness**3 * STRENGTHS["T300/934"].GIIc / (9 * (1 - ec["nu12"] ** 2)))
    assert t["damage.threshold_force_N"][0] == pytest.approx(pc, rel=1e-12)
    if "delamination" in th and math.isfinite(th["delamination"]):
        _, one = _direct(CASE, 1.02 * th["delamination"])
        assert one["peak_force_N"] > pc


def test_first_order_sobol_indices_from_given_runs():
    """Closed forms: Y = X1 + 2·X2 with X uniform independent has S1 = 1/5, S2 = 4/5, and an unused
    X3 has 0; the Ishigami function (a = 7, b = 0.1) has S1 = 0.3139, S2 = 0.4424, S3 = 0.
    A level input (a grid's few values) is binned by its values."""
    from softimpact.workflows.sweep_stats import sobol_first_order

    rng = np.random.default_rng(2)
    n = 4000
    x1, x2, x3 = rng.uniform(-1, 1, (3, n))
    got = {d["parameter"]: d["S1"] for d in sobol_first_order({"x1": x1, "x2": x2, "x3": x3}, x1 + 2 * x2)}
    assert got["x1"] == pytest.approx(0.2, abs=0.02) and got["x2"] == pytest.approx(0.8, abs=0.02) and got["x3"] < 0.01
    a, b = 7.0, 0.1
    u = rng.uniform(-np.pi, np.pi, (3, n))
    y = np.sin(u[0]) + a * np.sin(u[1]) ** 2 + b * u[2] ** 4 * np.sin(u[0])
    V = a**2 / 8 + b * np.pi**4 / 5 + b**2 * np.pi**8 / 18 + 0.5
    exact = {"u1": 0.5 * (1 + b * np.pi**4 / 5) ** 2 / V, "u2": a**2 / 8 / V, "u3": 0.0}
    got = {d["parameter"]: d["S1"] for d in sobol_first_order(dict(zip(("u1", "u2", "u3"), u)), y)}
    for k, v in exact.items():
        assert got[k] == pytest.approx(v, abs=0.04), (k, got[k], v)
    level = rng.integers(0, 4, n).astype(float)
    got = sobol_first_order({"level": level, "x": x1}, level + 0.5 * x1)
    assert got[0]["parameter"] == "level" and got[0]["bins"] == 4
    # Var(level) = 5/4, Var(0.5·x) = 1/12: S_level = (5/4) / (5/4 + 1/12)
    assert got[0]["S1"] == pytest.approx(1.25 / (1.25 + 1 / 12), abs=0.02)


def test_a_prepared_plate_pickles_small_and_answers_as_direct_stepping():
    """What a Dask worker receives (the group's shared part, pickled) answers a new force history as
    direct stepping of the full model does, and leaves the mesh and factorisation behind."""
    import pickle
    import tomllib
    from pathlib import Path

    from softimpact.cases import PlateKind

    data = tomllib.loads(CASE)
    shipped = pickle.dumps(PlateKind().prepare(data, Path("."), 2))
    assert len(shipped) < 1_000_000
    data["load"]["history"]["velocity"] = "4500 in/s"  # another run of the group
    got = PlateKind().run(pickle.loads(shipped), data, Path("."))
    _, ref = _direct(CASE, 4500 * INCH)
    for key in ("peak_force_N", "peak_deflection_at_load_m"):
        assert got[key] == pytest.approx(ref[key], rel=1e-9)
    assert got["strain_g1"]["peak"] == pytest.approx(ref["strain_g1"]["peak"], rel=1e-9)
    for c in ("max_strain", "tsai_wu", "hashin", "delamination"):
        assert got["damage"][c] == pytest.approx(ref["damage"][c], rel=1e-9)


def test_csv_text_quotes_cells_holding_commas():
    """Threshold labels such as "long beam, rubber-3/8in" read back as one cell (RFC 4180 quoting)."""
    import csv

    from softimpact.output.files import csv_text

    text = csv_text({"levels": np.array(["long beam, rubber-3/8in", 'a "b"'], dtype=object), "v": np.array([1.5, np.nan])})
    assert list(csv.reader(text.splitlines())) == [["levels", "v"], ["long beam, rubber-3/8in", "1.5"], ['a "b"', ""]]
