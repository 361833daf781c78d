"""`softimpact shpb` on the built-in synthetic two-bar series: the hidden rate law recovered, its law.json read back as
a crushing law, and a hail run inside the rates measured not flagged while the catalogue ice's still is."""

import json

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact.app.shpb import shpb
from softimpact.cli import main
from softimpact.fem.split_bar import SpecimenLaw
from softimpact.formats.law_json import read_law

from _support import lab_bars as lb

# The truth of the built-in `ice-shpb-series` (tools/make_shpb_series.py): sigma = 30 MPa*(rate/1000 /s)^0.2.
TRUE_1000, TRUE_M = 30e6, 0.2


@pytest.fixture(scope="module")
def outcome():
    """The built-in series analysed once for the module."""
    return shpb(series_name="ice-shpb-series", figures=False)


@pytest.fixture(scope="module")
def law_file(outcome, tmp_path_factory):
    path = tmp_path_factory.mktemp("shpb") / "law.json"
    path.write_text(outcome.files["law.json"])
    return path


def test_rate_law_recovers_the_hidden_one(outcome):
    """The fitted exponent's 95 % interval holds 0.2, and the law at its reference rate is the hidden one there within its interval."""
    law = json.loads(outcome.files["summary.json"])["rate_law"]
    assert abs(law["rate_exponent"] - TRUE_M) <= law["rate_exponent_ci95_half_width"]
    truth = TRUE_1000 * (law["reference_rate_1_s"] / 1000.0) ** TRUE_M
    assert abs(law["strength_ref_Pa"] - truth) <= law["strength_ref_ci95_half_width_Pa"]
    assert all(g.passed for g in outcome.gates)


def test_law_json_reads_back_as_a_material_law(law_file, outcome):
    """law.json reads back as a crushing law measured on two-bar tests, its strength's validity range the rates measured."""
    law = read_law(law_file)
    summary = json.loads(outcome.files["summary.json"])["rate_law"]
    assert law.family == "crushing" and law.method.startswith("two-bar")
    assert law.strength.rate_range == pytest.approx(tuple(summary["strain_rate_range_1_s"]), rel=1e-12)
    assert law.strength(1000.0)[0] == pytest.approx(
        summary["strength_ref_Pa"] * (1000.0 / summary["reference_rate_1_s"]) ** summary["rate_exponent"], rel=1e-12
    )


def _bar_case(tmp_path, contact):
    """The 50.8-mm ice sphere at 61 m/s on the 2-in bar (the built-in hail-bar-50mm case: V/d = 1201 /s), with ``contact``."""
    text = (
        'units = "SI"\n[bar]\nmaterial = "Al 6061-T6"\nlength = "36 in"\ndiameter = "2 in"\nelements = 39\n'
        '[projectile]\nmaterial = "ice"\ndiameter = "50.8 mm"\nvelocity = "61 m/s"\n'
        f'[contact]\n{contact}\n[solver]\ntime_step = "0.5 us"\nduration = "1200 us"\n[[gauges]]\nname = "g"\nposition = "18 in"\n'
    )
    (tmp_path / "case.toml").write_text(text)
    return tmp_path / "case.toml"


@pytest.mark.parametrize(
    ("contact", "flagged"), [('law = "identified"\nlaw_file = "law.json"', False), ('law = "crushing"', True)], ids=["two-bar-law", "catalogue-ice"]
)
def test_hail_run_inside_the_measured_rates_is_not_extrapolated(tmp_path, law_file, contact, flagged):
    """A hail run at V/d = 1201 /s: with the law fitted on two-bar tests at 297-1996 /s no strain-rate flag; with the catalogue
    ice (Jones 1997, measured at 0.1-10 /s) the run is flagged extrapolated."""
    (tmp_path / "law.json").write_text(law_file.read_text())
    run = CliRunner().invoke(main, ["bar", str(_bar_case(tmp_path, contact)), "--no-figures", "--out", str(tmp_path / "out")])
    assert run.exit_code == 0, run.output
    validity = json.loads((tmp_path / "out" / "summary.json").read_text())["validity"]
    assert any("strain rate" in f and "extrapolation" in f for f in validity["flags"]) is flagged
    assert ("strain rate" in run.output) is flagged


@pytest.mark.slow  # an FE run of a 40-mm specimen (the flag itself: tests/test_shpb.py, quick)
def test_specimen_too_long_exits_3(tmp_path):
    """A series with a 40-mm specimen loaded in 25 us (out of equilibrium at its strength): exit 3, the files written, marked failed."""
    t, inc, tr, _ = lb.split_bar_records(0.040, 9.0e9, SpecimenLaw(), 25e6, 25e-6, elements=40)
    (tmp_path / "long.csv").write_text("time_s,incident,transmitted\n" + "".join(f"{float(a)!r},{float(b)!r},{float(c)!r}\n" for a, b, c in zip(t, inc, tr)))
    bars = ""
    for which, length, pos in (("incident", lb.INCIDENT_LENGTH, lb.INCIDENT_GAUGE), ("transmitted", lb.TRANSMITTED_LENGTH, lb.TRANSMITTED_GAUGE)):
        bars += (
            f'[{which}_bar]\nmaterial = {{ youngs_modulus = "{lb.BAR_E} Pa", poisson_ratio = 0.33, density = "{lb.BAR_RHO} kg/m^3" }}\n'
            f'length = "{length} m"\ndiameter = "{lb.BAR_D} m"\n[{which}_gauge]\nposition = "{pos} m"\n'
        )
    (tmp_path / "s.toml").write_text(
        bars + '[specimen]\nlength = "40 mm"\ndiameter = "12.7 mm"\n[[test]]\nname = "long"\n'
        'incident = { file = "long.csv", channel = "incident", unit = "strain" }\ntransmitted = { file = "long.csv", channel = "transmitted", unit = "strain" }\n'
    )
    run = CliRunner().invoke(main, ["shpb", str(tmp_path / "s.toml"), "--no-figures", "--out", str(tmp_path / "out")])
    assert run.exit_code == 3, run.output
    assert "equilibrium" in run.output
    assert json.loads((tmp_path / "out" / "manifest.json").read_text())["status"] == "failed"


def test_curve_file_holds_the_three_stresses(outcome):
    """curve-<test>.csv's three-wave stress is the mean of its one- and two-wave stresses (σ₃ = (F1 + F2)/2A_s, σ₁ = F2/A_s, σ₂ = F1/A_s)."""
    import csv
    import io

    rows = list(csv.DictReader(io.StringIO(outcome.files["curve-ice-800.csv"])))
    s1, s2, s3 = (np.array([float(r[k]) for r in rows]) for k in ("stress_one_wave_Pa", "stress_two_wave_Pa", "stress_three_wave_Pa"))
    assert np.allclose(s3, 0.5 * (s1 + s2), rtol=1e-12, atol=1e-6 * np.max(s3))


@pytest.mark.slow  # the coupled plate run, about 5 s
def test_hail_on_the_composite_plate_inside_the_rates_is_not_extrapolated(tmp_path, law_file):
    """The 38.1-mm hailstone at its terminal velocity on the quasi-isotropic plate (V/d = 717 /s) with the two-bar law: no strain-rate
    flag (the built-in hail-plate-38mm, with the catalogue ice, is flagged: tests/test_hail_bird.py)."""
    (tmp_path / "law.json").write_text(law_file.read_text())
    (tmp_path / "hail.toml").write_text(
        'units = "SI"\n[target]\ncase = "hail-plate-qi"\n[impactor]\nthreat = { hail = "38.1 mm" }\n'
        '[contact]\nlaw = "identified"\nlaw_file = "law.json"\n[solver]\ntime_step = "1 us"\nduration = "1500 us"\n'
    )
    run = CliRunner().invoke(main, ["impact", str(tmp_path / "hail.toml"), "--no-figures", "--out", str(tmp_path / "out")])
    assert run.exit_code == 0, run.output
    assert "strain rate" not in run.output
