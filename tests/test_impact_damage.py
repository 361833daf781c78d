"""Damage from a coupled impact: strengths on the ply (inline or catalogue), closed forms of each
index for simple stress states, interlaminar shear from equilibrium, and `softimpact impact`'s damage."""

import csv
import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact.cli import main
from softimpact.models.failure import failure_indices, interlaminar_shear, strength_of
from softimpact.models.laminate import PLIES, ply_stiffness, reduced_stiffness

from _support.problems import PLATE

PLY = PLIES["T300/934"]
X = PLY.strength


def _indices(stress):
    """The three indices of one ply stress state (σ1, σ2, τ12) [Pa] with its own strains."""
    s = np.array(stress, float)[:, None]
    e = np.linalg.solve(reduced_stiffness(ply_stiffness(PLY)), s)
    idx = failure_indices(PLY, X, e[None], s[None])
    return {c: float(v.ravel()[0]) for c, v in idx.items()}


def test_pure_shear_indices_closed_form():
    """τ12 = S/2 alone: γ12/(S/G12), Tsai–Wu's sqrt(F66)·τ and Hashin's matrix mode τ/S are all 1/2."""
    idx = _indices((0, 0, X.S12 / 2))
    for c in ("max_strain", "tsai_wu", "hashin"):
        assert idx[c] == pytest.approx(0.5, rel=1e-12)


def test_tsai_wu_biaxial_closed_form():
    """σ1 = 600 MPa with σ2 = 20 MPa: 1/R from the quadratic a R² + b R = 1 written out by hand."""
    s1, s2 = 600e6, 20e6
    F1, F2 = 1 / X.Xt - 1 / X.Xc, 1 / X.Yt - 1 / X.Yc
    F11, F22 = 1 / (X.Xt * X.Xc), 1 / (X.Yt * X.Yc)
    a = F11 * s1**2 + F22 * s2**2 - math.sqrt(F11 * F22) * s1 * s2
    b = F1 * s1 + F2 * s2
    R = (-b + math.sqrt(b * b + 4 * a)) / (2 * a)
    assert _indices((s1, s2, 0))["tsai_wu"] == pytest.approx(1 / R, rel=1e-12)


def test_hashin_matrix_compression_closed_form():
    """σ2 = −0.9·Yc: Hashin (1980) matrix compression (σ2/2S23)² + ((Yc/2S23)² − 1)σ2/Yc, square-rooted."""
    s2 = -0.9 * X.Yc
    v = (s2 / (2 * X.S23)) ** 2 + ((X.Yc / (2 * X.S23)) ** 2 - 1) * s2 / X.Yc
    assert _indices((0, s2, 0))["hashin"] == pytest.approx(math.sqrt(v), rel=1e-12)


@pytest.mark.parametrize("n", [2, 4, 10])
def test_interlaminar_shear_of_one_ply_angle_is_jourawski(n):
    """One ply angle through the thickness: τ_xz at the mid-plane is 3Q/(2h) (Jourawski's parabola),
    and its quadratic index is τ/S12 (all the shear along the fibres)."""
    ils = interlaminar_shear(PLY, (0.0,) * n, X)
    h = n * PLY.thickness
    mid = int(np.argmin(np.abs(ils.z)))
    assert ils.z[mid] == pytest.approx(0.0, abs=1e-15)
    assert ils.tau_xz[mid] == pytest.approx(1.5 / h, rel=1e-10)
    assert np.max(np.abs(ils.tau_yz)) < 1e-9 / h
    assert ils.index[mid] == pytest.approx(1.5 / h / X.S12, rel=1e-10)
    # the parabola at the other interfaces: τ(z) = 3Q/(2h)·(1 − 4z²/h²)
    np.testing.assert_allclose(ils.tau_xz, 1.5 / h * (1 - 4 * ils.z**2 / h**2), rtol=1e-10)


def test_interlaminar_shear_of_a_cross_ply_integrates_its_bending_stresses():
    """[0/90]s under Q_x with M_y = M_xy = 0: dκ/dx = D⁻¹(1, 0, 0) (D by hand from the plies' Q), and τ_xz
    at the 0/90 interfaces is −∫ Q̄(0°)·dκ/dx·ζ dζ over the outer ply = (Q·dκ/dx)_x·(3/2)t²."""
    t = PLY.thickness
    Q = reduced_stiffness(ply_stiffness(PLY))
    Q90 = Q[[1, 0, 2]][:, [1, 0, 2]]  # the 90° ply: 1 and 2 swapped
    D = 2 * (Q * ((2 * t) ** 3 - t**3) / 3 + Q90 * t**3 / 3)
    dk = np.linalg.solve(D, [1.0, 0, 0])
    ils = interlaminar_shear(PLY, (0.0, 90.0, 90.0, 0.0), X)
    expected = (Q @ dk)[0] * 1.5 * t**2
    assert ils.z[0] == pytest.approx(t)
    assert ils.tau_xz[0] == pytest.approx(expected, rel=1e-10)
    assert ils.tau_xz[2] == pytest.approx(expected, rel=1e-10)


def test_strengths_unknown_is_one_line_naming_the_keys():
    """A ply without strengths: the damage outputs refuse it naming every key to give."""
    from dataclasses import replace

    with pytest.raises(Exception) as err:
        strength_of(replace(PLY, strength=None), "beam.laminate.ply")
    text = str(err.value)
    assert "\n" not in text
    for k in ("Xt", "Xc", "Yt", "Yc", "S", "G_IIc"):
        assert k in text


def _ply_table(name="T300/934", strengths=True, E1="120e9 Pa"):
    p = PLY
    rows = [
        f'name = "{name}"',
        f'E1 = "{E1}"',
        *(f'{k} = "{getattr(p, k)!r} Pa"' for k in ("E2", "E3", "G12", "G13", "G23")),
        *(f"{k} = {getattr(p, k)!r}" for k in ("nu12", "nu13", "nu23")),
        f'density = "{p.density!r} kg/m^3"',
        f'thickness = "{p.thickness!r} m"',
    ]
    if strengths:
        rows += [f'Xt = "{X.Xt / 1e6!r} MPa"', f'Xc = "{X.Xc / 1e6!r} MPa"', f'Yt = "{X.Yt / 1e6!r} MPa"', f'Yc = "{X.Yc / 1e6!r} MPa"']
        rows += [f'S = "{X.S12 / 1e6!r} MPa"', f'G_IIc = "{X.GIIc / 1e3!r} kJ/m^2"']
    return "\n".join(rows)


def _beam_cases(tmp_path, ply: str | None):
    """An impact case on the paper's long beam, its ply by catalogue name (None) or as an inline table."""
    from softimpact.input.toml import locate

    beam = locate("paper-long-beam").read_text()
    if ply is not None:
        beam = beam.replace('ply = "T300/934"\n', "").replace("[beam.laminate]\n", "[beam.laminate.ply]\n" + ply + "\n\n[beam.laminate]\n")
        assert "[beam.laminate.ply]" in beam
    (tmp_path / "beam.toml").write_text(beam)
    (tmp_path / "case.toml").write_text(
        'units = "in-lbf-s"\n[target]\ncase = "beam.toml"\n[impactor]\nmaterial = "steel"\ndiameter = "0.5 in"\nvelocity = "100 in/s"\n'
        '[contact]\nlaw = "hertz"\ntarget_modulus = "7.9 GPa"\n[solver]\ntime_step = "0.5 us"\nduration = "300 us"\n'
    )
    return tmp_path / "case.toml"


def _impact(case, out):
    r = CliRunner().invoke(main, ["impact", str(case), "--out", str(out), "--no-figures"])
    return r, (json.loads((out / "summary.json").read_text()) if r.exit_code == 0 else None)


def test_inline_ply_with_strengths_gives_the_catalogue_indices(tmp_path):
    """An inline ply with the catalogue ply's moduli and strengths (in MPa and kJ/m²) gives the same
    damage indices as the catalogue ply itself."""
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    r1, cat = _impact(_beam_cases(tmp_path / "a", None), tmp_path / "a" / "out")
    r2, inl = _impact(_beam_cases(tmp_path / "b", _ply_table()), tmp_path / "b" / "out")
    assert r1.exit_code == 0 and r2.exit_code == 0, (r1.output, r2.output)
    assert set(cat["damage"]) == set(inl["damage"])
    for k in ("max_strain", "tsai_wu", "hashin", "delamination", "threshold_force_N", "interlaminar_index"):
        assert inl["damage"][k] == pytest.approx(cat["damage"][k], rel=1e-9)
    assert 0 < cat["damage"]["tsai_wu"] < 1
    # Davies–Zhang against the coupled peak force (the first contact is the largest here)
    assert cat["damage"]["delamination"] == pytest.approx(cat["peak_force_N"] / cat["damage"]["threshold_force_N"], rel=1e-12)


def test_inline_ply_named_like_the_catalogue_gets_no_catalogue_strengths(tmp_path):
    """An inline ply NAMED "T300/934" with other moduli and no strengths: no damage from the catalogue's
    strengths (the summary says how to get them), where the catalogue ply gives damage."""
    from softimpact.input.beam_case import beam_problem
    from softimpact.input.toml import load_toml

    case = _beam_cases(tmp_path, _ply_table(strengths=False, E1="140e9 Pa"))
    problem = beam_problem(load_toml(tmp_path / "beam.toml"), tmp_path)
    assert problem.beam.stack.ply.strength is None
    r, s = _impact(case, tmp_path / "out")
    assert r.exit_code == 0, r.output
    assert "damage" not in s or "tsai_wu" not in s["damage"]


def test_partial_strengths_are_refused_naming_the_missing_keys(tmp_path):
    """An inline ply with some strengths but not all: exit 2, one line naming the missing keys."""
    table = _ply_table().replace('G_IIc = "0.5 kJ/m^2"', "").replace('Yc = "246.0 MPa"', "")
    case = _beam_cases(tmp_path, table)
    r, _ = _impact(case, tmp_path / "out")
    assert r.exit_code == 2
    assert "Yc" in r.output and "G_IIc" in r.output


def test_damage_points_cover_the_load_and_every_gauge(tmp_path):
    """`impact` on a beam reports the indices at the load point and each gauge, by worst ply and face,
    and leaves the damage pseudo-gauges out of history.csv and the gauge table."""
    r, s = _impact(_beam_cases(tmp_path, None), tmp_path / "out")
    assert r.exit_code == 0, r.output
    assert {"at_load", "at_g1", "at_g2"} <= set(s["damage"])
    assert set(s["gauges"]) == {"g1", "g2"}
    assert "_damage" not in (tmp_path / "out" / "history.csv").read_text().splitlines()[0]
    assert s["damage"]["at_load"]["worst_ply"]["max_strain"]["face"] in ("top", "bottom")


def test_an_impact_sweep_carries_the_damage_of_single_impact_runs(tmp_path):
    """A velocity sweep of a beam impact asking for damage outputs gives each run's Tsai–Wu index and
    Davies–Zhang ratio of `softimpact impact` run alone at that velocity; Tsai–Wu grows with velocity."""
    import pyarrow.parquet as pq

    case = _beam_cases(tmp_path, None)
    text = case.read_text()
    (tmp_path / "spec.toml").write_text(
        '[sweep]\ncase = "case.toml"\nmethod = "grid"\noutputs = ["peak_force_N", "damage.tsai_wu", "damage.delamination", "damage.at_g1.hashin"]\n'
        '[[sweep.parameter]]\nkey = "impactor.velocity"\nvalues = ["50 in/s", "150 in/s"]\n'
    )
    r = CliRunner().invoke(main, ["sweep", str(tmp_path / "spec.toml"), "--out", str(tmp_path / "out"), "--workers", "0", "--no-figures"])
    assert r.exit_code == 0, r.output
    t = pq.read_table(tmp_path / "out" / "runs.parquet").to_pydict()
    assert t["damage.tsai_wu"][1] > t["damage.tsai_wu"][0] > 0
    for k, v in enumerate((50, 150)):
        one = tmp_path / f"one-{v}.toml"
        one.write_text(text.replace('velocity = "100 in/s"', f'velocity = "{v} in/s"'))
        _, s = _impact(one, tmp_path / f"out-{v}")
        for key in ("tsai_wu", "delamination"):
            assert t[f"damage.{key}"][k] == pytest.approx(s["damage"][key], rel=1e-9)
        assert t["damage.at_g1.hashin"][k] == pytest.approx(s["damage"]["at_g1"]["hashin"], rel=1e-9)


def test_a_sweep_asking_damage_of_a_ply_without_strengths_names_the_missing_keys(tmp_path):
    """A beam-impact sweep asking damage.tsai_wu of an inline ply without strengths: exit 2, one line naming the
    ply's key and the strengths to give (not "not an output"); the impact's summary says the same in damage_note."""
    case = _beam_cases(tmp_path, _ply_table(strengths=False))
    (tmp_path / "spec.toml").write_text(
        '[sweep]\ncase = "case.toml"\nmethod = "grid"\noutputs = ["damage.tsai_wu"]\n[[sweep.parameter]]\nkey = "impactor.velocity"\nvalues = ["50 in/s", "150 in/s"]\n'
    )
    r = CliRunner().invoke(main, ["sweep", str(tmp_path / "spec.toml"), "--out", str(tmp_path / "out"), "--workers", "0", "--no-figures"])
    assert r.exit_code == 2
    assert "not an output" not in r.output and "beam.laminate.ply" in r.output and "G_IIc" in r.output
    _, s = _impact(case, tmp_path / "one")
    assert "G_IIc" in s["damage_note"]


def test_plate_impact_interlaminar_shear_is_jourawski_under_the_contact_disc(tmp_path):
    """A steel ball on a coarse [0_20] plate: the largest interlaminar shear is 3q/(2h) with q = F/(2π·max(a, h/2)),
    the largest over the run of the force and contact radius in history.csv (one ply angle: Jourawski's parabola
    in every direction); the damage points are the load point and the gauge, and the summary has no pseudo-gauge."""
    import csv

    (tmp_path / "plate.toml").write_text(PLATE.format(layup="[0_20]", force="10 lbf"))
    (tmp_path / "case.toml").write_text(
        'units = "in-lbf-s"\n[target]\ncase = "plate.toml"\n[impactor]\nmaterial = "steel"\ndiameter = "0.5 in"\nvelocity = "100 in/s"\n'
        '[contact]\nlaw = "hertz"\n[solver]\ntime_step = "1 us"\nduration = "300 us"\n'
    )
    r, s = _impact(tmp_path / "case.toml", tmp_path / "out")
    assert r.exit_code == 0, r.output
    with open(tmp_path / "out" / "history.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    F = np.array([float(x["contact_force_N"]) for x in rows])
    a = np.array([float(x["contact_radius_m"]) for x in rows])
    h = 20 * PLY.thickness
    q = np.max(F / (2 * np.pi * np.maximum(a, h / 2)))
    assert s["damage"]["interlaminar_shear_max_Pa"] == pytest.approx(1.5 * q / h, rel=1e-9)
    assert s["damage"]["interlaminar_index"] == pytest.approx(1.5 * q / h / X.S12, rel=1e-9)
    assert set(s["gauges"]) == {"g1"} and {"at_load", "at_g1"} <= set(s["damage"])


def test_delamination_index_takes_the_largest_force_of_any_contact(tmp_path):
    """The built-in steel ball on the long beam bounces three times and a later contact presses harder than the first:
    Davies–Zhang's index is the largest force of the history (any contact can delaminate) over P_c, above F0/P_c,
    and the command's line names it F_max/P_c."""
    out = tmp_path / "out"
    r = CliRunner().invoke(main, ["impact", "paper-long-beam-impact", "--out", str(out), "--no-figures"])
    assert r.exit_code == 0, r.output
    s = json.loads((out / "summary.json").read_text())
    with open(out / "history.csv") as fh:
        rows = list(csv.DictReader(fh))
    force = max(float(row["contact_force_N"]) for row in rows)
    d = s["damage"]
    assert len(s["contacts"]) >= 2 and force > 1.1 * s["peak_force_N"]
    # the command refines each peak between its samples: the sampled maximum is within 1e-5 below it
    assert force / d["threshold_force_N"] <= d["delamination"] <= (1 + 1e-5) * force / d["threshold_force_N"]
    assert "F_max/P_c" in r.output and "F0/P_c" not in r.output


# ---- delamination onset on the run path: Olsson's threshold, the response regime, the interfaces, the verdict ----

ONSET_KEYS = ("olsson_threshold_force_N", "peak_over_olsson", "regime", "impactor_over_target_mass", "target_mass_kg", "regime_note")


def _plate_case(tmp_path, layup="[90/0]5s", mass=None, diameter="0.5 in"):
    """The small 4 × 4 in plate (tests/_support/problems.PLATE) struck by the steel ball of ``diameter`` (``mass``: its mass)."""
    (tmp_path / "plate.toml").write_text(PLATE.format(layup=layup, force="10 lbf"))
    extra = f'mass = "{mass}"\n' if mass else ""
    (tmp_path / "case.toml").write_text(
        f'units = "in-lbf-s"\n[target]\ncase = "plate.toml"\n[impactor]\nmaterial = "steel"\ndiameter = "{diameter}"\nvelocity = "100 in/s"\n'
        + extra
        + '[contact]\nlaw = "hertz"\n[solver]\ntime_step = "2 us"\nduration = "200 us"\n'
    )
    return tmp_path / "case.toml"


def _olsson_by_hand(angles, GIIc):
    """F_d = π·sqrt(32·D*·G_IIc/9), D* = sqrt(D11·D22·(A + 1)/2), A = (D12 + 2·D66)/sqrt(D11·D22), with
    D = Σ Q̄_k·(z_top³ − z_bottom³)/3 written out here for 0° and 90° plies (Q̄ of 90°: 1 and 2 swapped)."""
    t = PLY.thickness
    Q = reduced_stiffness(ply_stiffness(PLY))
    Q90 = Q[[1, 0, 2]][:, [1, 0, 2]]
    h = t * len(angles)
    D = np.zeros((3, 3))
    for k, a in enumerate(angles):  # top ply first
        top, bottom = h / 2 - k * t, h / 2 - (k + 1) * t
        D += {0.0: Q, 90.0: Q90}[a] * (top**3 - bottom**3) / 3
    A = (D[0, 1] + 2 * D[2, 2]) / math.sqrt(D[0, 0] * D[1, 1])
    D_star = math.sqrt(D[0, 0] * D[1, 1] * (A + 1) / 2)
    return math.pi * math.sqrt(32 * D_star * GIIc / 9)


CROSS_PLY = (90.0, 0.0) * 5 + (0.0, 90.0) * 5  # [90/0]5s, top ply first


@pytest.mark.parametrize("target", ["beam", "plate"])
def test_summary_has_olsson_onset_regime_interfaces_and_verdict(tmp_path, target):
    """Beam and plate impacts on [90/0]5s T300/934: Olsson's F_d is the closed form with D summed by hand over the
    plies, peak over F_d is the Davies–Zhang peak over F_d, the interfaces are exactly the 18 between 90° and 0°
    plies at z = h/2 − k·t (not the 0/0 mid-plane), their maximum is listed, and the verdict and line name the regime."""
    case = _beam_cases(tmp_path, None) if target == "beam" else _plate_case(tmp_path)
    r, s = _impact(case, tmp_path / "out")
    assert r.exit_code == 0, r.output
    d = s["damage"]
    assert set(ONSET_KEYS) <= set(d)
    assert d["olsson_threshold_force_N"] == pytest.approx(_olsson_by_hand(CROSS_PLY, X.GIIc), rel=1e-9)
    # the same peak (the largest of any contact) against both thresholds
    assert d["peak_over_olsson"] * d["olsson_threshold_force_N"] == pytest.approx(d["delamination"] * d["threshold_force_N"], rel=1e-12)
    t, h = PLY.thickness, 20 * PLY.thickness
    expected = [k for k in range(1, 20) if CROSS_PLY[k - 1] != CROSS_PLY[k]]
    assert len(d["interfaces"]) == len(expected) == 18
    for i, k in zip(d["interfaces"], expected):
        assert i["z_m"] == pytest.approx(h / 2 - k * t, abs=1e-12 * h)
        assert i["between"].startswith(f"plies {k}/{k + 1} ")
    assert all(abs(i["z_m"]) > t / 2 for i in d["interfaces"])  # the 0/0 mid-plane is not among them
    assert d["interface_shear_max_Pa"] == max(i["shear_max_Pa"] for i in d["interfaces"]) > 0
    assert d["interface_shear_max_Pa"] <= d["interlaminar_shear_max_Pa"]
    assert d["regime"] in d["verdict"] and f"{d['peak_over_olsson']:.2f}" in d["verdict"]
    assert ("below delamination onset" in d["verdict"]) == (d["peak_over_olsson"] < 1)
    assert f"regime {d['regime']}" in r.output and "F_d (Olsson)" in r.output and "verdict:" in r.output


def test_one_ply_angle_has_no_interface_between_orientations(tmp_path):
    """A [0_20] plate: no interface between plies of different orientation, so the list is empty and its maximum 0,
    while the interlaminar shear of all interfaces (Jourawski's parabola) is not."""
    r, s = _impact(_plate_case(tmp_path, layup="[0_20]"), tmp_path / "out")
    assert r.exit_code == 0, r.output
    assert s["damage"]["interfaces"] == [] and s["damage"]["interface_shear_max_Pa"] == 0.0
    assert s["damage"]["interlaminar_shear_max_Pa"] > 0


@pytest.mark.parametrize(("mass", "regime"), [("5 g", "wave-controlled"), ("40 g", "intermediate"), ("300 g", "quasi-static")])
def test_regime_spans_the_bounds_with_the_impactor_mass(tmp_path, mass, regime):
    """Steel impactors of 5, 40 and 300 g (solid balls: d = (6m/(πρ))^(1/3), so that the mass fits the material) on the
    4 × 4 in plate (mass ρ·h·a² by hand = 45.6 g): ratios 0.11, 0.88 and 6.6 fall below, between and above the stand-in
    bounds 0.25 and 2.5, and the summary says so, with the mass by hand."""
    from softimpact.models.delamination import REGIME_BOUNDS

    d = (6 * float(mass.split()[0]) * 1e-3 / (math.pi * 7833.413032987483)) ** (1 / 3)  # the catalogue steel's density
    r, s = _impact(_plate_case(tmp_path, mass=mass, diameter=f"{d!r} m"), tmp_path / "out")
    assert r.exit_code == 0, r.output
    a = 4 * 0.0254
    plate_mass = PLY.density * 20 * PLY.thickness * a * a
    assert s["damage"]["target_mass_kg"] == pytest.approx(plate_mass, rel=1e-12)
    ratio = float(mass.split()[0]) * 1e-3 / plate_mass
    assert s["damage"]["impactor_over_target_mass"] == pytest.approx(ratio, rel=1e-12)
    assert REGIME_BOUNDS == (0.25, 2.5)
    assert s["damage"]["regime"] == regime
    assert "not retrieved" in s["damage"]["regime_note"]


def test_beam_target_mass_is_its_own(tmp_path):
    """On the long beam (6 × 1 in, [90/0]5s T300/934) the target's mass is ρ·h·b·L by hand, and the ratio the ball's over it."""
    from softimpact.models.materials import CATALOGUE

    r, s = _impact(_beam_cases(tmp_path, None), tmp_path / "out")
    assert r.exit_code == 0, r.output
    beam_mass = PLY.density * 20 * PLY.thickness * 0.0254 * 6 * 0.0254
    assert s["damage"]["target_mass_kg"] == pytest.approx(beam_mass, rel=1e-12)
    assert s["damage"]["impactor_over_target_mass"] == pytest.approx(CATALOGUE["steel"].density * math.pi / 6 * (0.5 * 0.0254) ** 3 / beam_mass, rel=1e-9)


def test_an_impact_sweep_carries_olsson_onset(tmp_path):
    """A velocity sweep of the beam impact outputs Olsson's F_d (the same for both velocities: a property of the
    laminate) and the peak over it, equal to `softimpact impact` run alone; the ratio grows with the velocity."""
    import pyarrow.parquet as pq

    case = _beam_cases(tmp_path, None)
    (tmp_path / "spec.toml").write_text(
        '[sweep]\ncase = "case.toml"\nmethod = "grid"\noutputs = ["damage.olsson_threshold_force_N", "damage.peak_over_olsson", '
        '"damage.interface_shear_max_Pa", "damage.impactor_over_target_mass"]\n'
        '[[sweep.parameter]]\nkey = "impactor.velocity"\nvalues = ["50 in/s", "100 in/s"]\n'
    )
    r = CliRunner().invoke(main, ["sweep", str(tmp_path / "spec.toml"), "--out", str(tmp_path / "out"), "--workers", "0", "--no-figures"])
    assert r.exit_code == 0, r.output
    t = pq.read_table(tmp_path / "out" / "runs.parquet").to_pydict()
    fd = t["damage.olsson_threshold_force_N"]
    assert fd[0] == fd[1] == pytest.approx(_olsson_by_hand(CROSS_PLY, X.GIIc), rel=1e-9)
    assert t["damage.peak_over_olsson"][1] > t["damage.peak_over_olsson"][0] > 0
    _, s = _impact(case, tmp_path / "one")  # the case's own velocity, 100 in/s
    for key in ("peak_over_olsson", "interface_shear_max_Pa", "impactor_over_target_mass"):
        assert t[f"damage.{key}"][1] == pytest.approx(s["damage"][key], rel=1e-9)
