"""Models past their range are flagged where a number is reported (issue 42): a von Kármán plate stretched past small
strain, a plate thicker than a tenth of its span, a quasi-static delamination criterion on a wave-controlled impact (runs,
sweep rows), an identified law past the approach its tests reached (and not judged by Hertz's small-contact check)."""

import json
import math

import pyarrow.parquet as pq
import pytest
from click.testing import CliRunner

from softimpact.cli import main
from softimpact.input.toml import locate

from _support.problems import COARSE_LONG_BEAM, IDENTIFIED_LAW, IDENTIFIED_ON_LONG_BEAM, PLATE

INCH = 0.0254


def invoke(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def _summary(tmp_path, command, text, name="case"):
    (tmp_path / f"{name}.toml").write_text(text)
    r = invoke(command, tmp_path / f"{name}.toml", "--out", tmp_path / name, "--no-figures")
    assert r.exit_code == 0, r.output
    return json.loads((tmp_path / name / "summary.json").read_text()), r.output


@pytest.mark.parametrize("pressure, flagged", [("20 psi", False), ("5000 psi", True)])
def test_a_von_karman_plate_stretched_past_small_strain_is_flagged(tmp_path, pressure, flagged):
    """The built-in immovable-edge plate (a = 10 in) pressed to w0: its centre strip's mean strain is the mean of w,x²/2
    (u = 0 at both edges), at least 2(w0/a)² for any profile from 0 to w0 and back (the triangle's, by Cauchy–Schwarz),
    so the reported largest mid-surface strain is at least that; at 5000 psi (w/h ≈ 10) the bound alone passes 2 % and
    the run is flagged; at 20 psi (w/h 1.6) it stays under 2 % and is not."""
    text = locate("plate-ss-pressure-vk").read_text().replace('pressure = "20 psi"', f'pressure = "{pressure}"')
    s, out = _summary(tmp_path, "plate", text)
    w0, a = s["max_deflection_m"], 10 * INCH
    strain = s["validity"]["max_membrane_strain"]
    assert strain >= 2 * (w0 / a) ** 2
    assert (2 * (w0 / a) ** 2 > 0.02) is flagged and (strain > 0.02) is flagged
    assert any("von Karman's strains" in f for f in s["validity"]["flags"]) is flagged
    assert ("past the 2%" in out) is flagged


@pytest.mark.parametrize("support, span", [("simply-supported", 4.0), ("quarter", 8.0)])
def test_a_plate_thicker_than_a_tenth_of_its_span_is_flagged(tmp_path, support, span):
    """An inline ply of 0.5 in as the whole laminate: a 4 × 4 in plate is 0.125 of its span thick, flagged with the ratio
    h/a (by hand); the same plate as a quarter model (symmetry edges at x0 and y0) spans 8 in, 0.0625: not flagged."""
    ply = (
        '[plate.laminate.ply]\nname = "thick"\nE1 = "100 GPa"\nE2 = "10 GPa"\nE3 = "10 GPa"\nG12 = "5 GPa"\nG13 = "5 GPa"\nG23 = "3 GPa"\n'
        'nu12 = 0.3\nnu13 = 0.3\nnu23 = 0.4\ndensity = "1600 kg/m^3"\nthickness = "0.5 in"\n\n[plate.laminate]\nlayup = "[0]"\n'
    )
    text = PLATE.format(layup="[0]", force="10 lbf").replace('[plate.laminate]\nply = "T300/934"\nlayup = "[0]"\n', ply)
    if support == "quarter":
        text = text.replace('x0 = "simply-supported"', 'x0 = "symmetry"').replace('y0 = "simply-supported"', 'y0 = "symmetry"')
        text = text.replace('position = ["2 in", "2 in"]', 'position = ["0 in", "0 in"]', 1)  # the load at the centre; the gauge stays
    s, _ = _summary(tmp_path, "plate", text)
    ratio = 0.5 / span
    assert s["validity"]["thickness_over_span"] == pytest.approx(ratio, rel=1e-12)
    assert any("of the plate's shorter span" in f for f in s["validity"]["flags"]) is (ratio > 0.1)


def _steel_on_plate(tmp_path, grams: float) -> str:
    """A solid steel ball of ``grams`` (its diameter from the catalogue's density) at 100 in/s on the 4 × 4 in plate."""
    d = (6 * grams * 1e-3 / (math.pi * 7833.413032987483)) ** (1 / 3)
    (tmp_path / "plate.toml").write_text(PLATE.format(layup="[90/0]5s", force="10 lbf"))
    return (
        f'units = "in-lbf-s"\n[target]\ncase = "plate.toml"\n[impactor]\nmaterial = "steel"\ndiameter = "{d!r} m"\nvelocity = "100 in/s"\n'
        '[contact]\nlaw = "hertz"\n[solver]\ntime_step = "2 us"\nduration = "100 us"\n'
    )


@pytest.mark.parametrize("grams, flagged", [(5.0, True), (300.0, False)])
def test_a_quasi_static_criterion_on_a_wave_controlled_impact_is_flagged(tmp_path, grams, flagged):
    """The run's damage block reports Olsson's and Davies–Zhang's quasi-static thresholds: on a 5 g ball (M_i/M_p 0.11 of
    the 45.6 g plate, by hand: wave-controlled) the run carries criterion_outside_regime; on a 300 g ball (6.6:
    quasi-static) it does not."""
    s, _ = _summary(tmp_path, "impact", _steel_on_plate(tmp_path, grams))
    plate = 1580.0 * 20 * 0.0055 * INCH * (4 * INCH) ** 2
    assert s["damage"]["regime"] == ("wave-controlled" if grams * 1e-3 / plate < 0.25 else "quasi-static")
    assert any("quasi-static thresholds applied" in f for f in s["validity"]["flags"]) is flagged


def test_sweep_rows_carry_the_criterion_flag(tmp_path):
    """A sweep of the 5 g ball asking a damage output: every row carries flag.criterion_outside_regime (runs.parquet), as the run does."""
    (tmp_path / "case.toml").write_text(_steel_on_plate(tmp_path, 5.0))
    (tmp_path / "spec.toml").write_text(
        '[sweep]\ncase = "case.toml"\nmethod = "grid"\noutputs = ["damage.peak_over_olsson"]\n'
        '[[sweep.parameter]]\nkey = "impactor.velocity"\nvalues = ["80 in/s", "100 in/s"]\n'
    )
    r = invoke("sweep", tmp_path / "spec.toml", "--out", tmp_path / "s", "--no-figures", "--workers", "0")
    assert r.exit_code == 0, r.output
    t = pq.read_table(tmp_path / "s" / "runs.parquet").to_pydict()
    assert t["flag.criterion_outside_regime"] == [True, True]


def _law_with_record(tmp_path, reached: float):
    """The built-in rubber law.json, with the approach its tests reached recorded as [reached/2, reached] (as identify writes it)."""
    law = json.loads(IDENTIFIED_LAW.read_text())
    law.setdefault("identified_on", {})["approach_over_diameter"] = [reached / 2, reached]
    law["identified_on"]["contact_radius_over_bar_radius"] = [0.1, 0.5]
    (tmp_path / "law.json").write_text(json.dumps(law))


@pytest.mark.parametrize("reached, flagged", [(0.05, True), (5.0, False)])
def test_an_identified_law_is_judged_by_the_approach_its_tests_reached(tmp_path, reached, flagged):
    """The rubber ball on the long beam under its identified law: its contact radius passes the ball's (a = √(dα), a
    small-contact relation the ball's own flattening on the bar was fitted to) without a Hertz flag; the approach is
    flagged exactly when it passes 1.1 times the largest α/d the law.json records (summary.json's approach_over_diameter
    against the record)."""
    _law_with_record(tmp_path, reached)
    (tmp_path / "beam.toml").write_text(COARSE_LONG_BEAM)
    case = IDENTIFIED_ON_LONG_BEAM.format(material="silicone rubber", velocity="4000 in/s", duration="60 us").replace('"paper-long-beam"', '"beam.toml"')
    s, _ = _summary(tmp_path, "impact", case.replace('time_step = "0.5 us"', 'time_step = "1 us"'))
    v = s["validity"]
    assert v["contact_radius_over_projectile_radius"] > 1 and not any("no sphere touches" in f for f in v["flags"])
    assert v["approach_over_identified_max"] == pytest.approx(v["approach_over_diameter"] / reached, rel=1e-12)
    assert (v["approach_over_diameter"] > 1.1 * reached) is flagged
    assert any("its bar tests reached" in f for f in v["flags"]) is flagged


def test_identify_records_the_approach_and_contact_its_tests_reached():
    """approach_record: each test's largest approach over its diameter and the law's contact radius there over the bar's
    radius (a = √(dα) for the soft law, computed here), their ranges over the tests; read back from law.json."""
    from types import SimpleNamespace

    import numpy as np

    from softimpact.formats.law_json import read_law
    from softimpact.output.identify import approach_record

    law = read_law(IDENTIFIED_LAW)
    d, bar_radius = 0.5 * INCH, 0.25 * INCH
    tests = [SimpleNamespace(diameter=d, mass=1.1e-3, velocity=v, time=np.arange(4) * 1e-6) for v in (25.0, 50.0)]
    approaches = [SimpleNamespace(approach=np.array([0.0, a, a / 2]), main_pulse=np.array([True, True, True])) for a in (1e-3, 2e-3)]
    rec = approach_record(tests, approaches, law, bar_radius)
    assert rec["approach_over_diameter"] == pytest.approx([1e-3 / d, 2e-3 / d], rel=1e-12)
    assert rec["contact_radius_over_bar_radius"] == pytest.approx([math.sqrt(d * 1e-3) / bar_radius, math.sqrt(d * 2e-3) / bar_radius], rel=1e-12)
