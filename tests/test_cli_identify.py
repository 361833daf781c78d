"""`softimpact identify` and law.json: recovery of a known law, the file contract, the closure on the rubber series."""

import csv
import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact.cli import main
from softimpact.fem.bar import Rod, assemble_rod
from softimpact.fem.contact import rod_contact_structure
from softimpact.formats.law_json import law_json, read_law
from softimpact.input.series import load_series
from softimpact.models.contact_laws import SoftProjectileLaw, ViscoelasticSoftLaw
from softimpact.workflows.identification import BarTest, IdentifiedLaw, closure, identify

from _support.constants import INCH
from _support.problems import table_i_pulse

TRUE = {"k_ref": 3.0, "p": 0.9, "c_ref": 2.0, "q_k": -0.5, "q_c": 1.5}  # a law chosen here
# with a Maxwell arm (and no rate term: the identification keeps c = 0 beside the arm)
TRUE_ARM = {"k_ref": 2.0, "p": 1.1, "c_ref": 0.0, "q_k": -0.5, "q_c": 0.0, "q_p": 0.0, "kappa_ref": 6.0, "theta_ref": 0.25, "q_kappa": 0.8, "q_theta": -0.3}
D_REF = 0.5 * INCH


@pytest.fixture(scope="module")
def rod() -> Rod:
    """The rubber series' bar (36-in Al 6061-T6, end cap) as the rod FE the identification runs on."""
    return Rod.of(load_series("paper-rubber-series").bar)


def _synthetic_test(rod, name, mass, d, V, true):
    """A bar test made by the coupled impactor-rod integration with the chosen law (noise-free)."""
    from softimpact.fem.impact import integrate_impact

    chosen = IdentifiedLaw(tuple(true), np.array(list(true.values())), np.zeros(len(true)), D_REF, np.zeros(1), 0.0)
    T = 1.0 * d / V  # Table I: T ≈ α2·d/V with α2 ≈ 1
    h = integrate_impact(rod_contact_structure(assemble_rod(rod)), chosen.law(mass, d, V), mass, V, T / 400, 1200, energy=False, stop_after=0.3 * T)
    return BarTest(name, h.time, h.force, mass, d, V)


CASES = [
    ("a", 1.1e-3, 0.5 * INCH, 1000 * INCH),
    ("b", 1.1e-3, 0.5 * INCH, 3000 * INCH),
    ("c", 0.46e-3, 0.375 * INCH, 2000 * INCH),
    ("d", 0.46e-3, 0.375 * INCH, 4500 * INCH),
]


@pytest.fixture(scope="module")
def synthetic(rod):
    """The four bar tests of CASES made with the law TRUE."""
    return [_synthetic_test(rod, *c, TRUE) for c in CASES]


@pytest.mark.parametrize("true", [TRUE, TRUE_ARM], ids=["memoryless", "maxwell-arm"])
def test_identify_recovers_a_known_law(rod, true):
    """Force histories made with a chosen law on the same rod give back its parameters (to 0.5 %),
    through the reconstructed approach (impactor by momentum, bar end by the rod FE); the memoryless
    family when asked for it, the Maxwell arm's κ and θ with it."""
    tests = [_synthetic_test(rod, *c, true) for c in CASES]
    law, _ = identify(tests, rod, d_ref=D_REF, memory="kappa_ref" in true)
    got = dict(zip(law.names, law.values))
    for k, v in true.items():
        assert got[k] == pytest.approx(v, rel=5e-3, abs=5e-3)
    assert np.all(law.rms_per_test < 1e-3)


def test_closure_of_the_true_law_is_exact(rod, synthetic):
    """The closure of the law that made the histories reproduces their F0, T and I (to 0.2 %)."""
    law = IdentifiedLaw(tuple(TRUE), np.array(list(TRUE.values())), np.zeros(5), D_REF, np.zeros(4), 0.0)
    assert np.max(np.abs(closure(law, synthetic, rod).errors)) < 2e-3


def test_law_json_round_trip(tmp_path):
    """law.json written and read back gives the same law (family, parameters, d_ref, SI)."""
    law = IdentifiedLaw(tuple(TRUE), np.array(list(TRUE.values())), np.full(5, 0.1), D_REF, np.array([0.01, 0.02]), 1.5)
    (tmp_path / "law.json").write_text(law_json(law, ["t1", "t2"]))
    data = json.loads((tmp_path / "law.json").read_text())
    assert data["family"] == "soft-projectile" and data["units"] == "SI" and data["d_ref_m"] == D_REF
    assert data["parameters"]["k_ref"] == {"value": 3.0, "ci95_half_width": 0.1}
    back = read_law(tmp_path / "law.json")
    assert np.allclose(back.values[:5], law.values) and back.values[5] == 0.0 and back.d_ref == D_REF
    a, b = law.law(0.46e-3, 0.375 * INCH, 50.0), back.law(0.46e-3, 0.375 * INCH, 50.0)
    assert isinstance(b, SoftProjectileLaw)  # a file without the arm is the memoryless law it was written for
    assert a.force(1e-3, 10.0) == pytest.approx(b.force(1e-3, 10.0), rel=1e-15)


def test_law_json_with_the_arm_round_trip(tmp_path):
    """A law with its Maxwell arm written and read back is the same viscoelastic law (κ, θ scaled by size)."""
    vals = np.array(list(TRUE_ARM.values()))
    law = IdentifiedLaw(tuple(TRUE_ARM), vals, np.full(vals.size, 0.1), D_REF, np.array([0.01]), 1.0)
    (tmp_path / "law.json").write_text(law_json(law, ["t1"]))
    back = read_law(tmp_path / "law.json")
    assert np.allclose(back.values, vals, rtol=1e-15)
    got = back.law(0.46e-3, 0.375 * INCH, 50.0)
    assert isinstance(got, ViscoelasticSoftLaw)
    assert got.kappa == pytest.approx(6.0 * 0.75**0.8, rel=1e-14) and got.theta == pytest.approx(0.25 * 0.75**-0.3, rel=1e-14)


def test_law_json_with_an_arm_but_no_relaxation_time_is_refused(tmp_path):
    """kappa_ref > 0 with theta_ref = 0 is not a law: one-line InputError naming the file."""
    from softimpact.errors import InputError

    law = IdentifiedLaw(tuple(TRUE_ARM)[:8], np.array([2.0, 1.1, 0.5, 0, 0, 0, 6.0, 0.0]), np.zeros(8), D_REF, np.zeros(1), 0.0)
    (tmp_path / "law.json").write_text(law_json(law, ["t1"]))
    with pytest.raises(InputError, match="theta_ref > 0"):
        read_law(tmp_path / "law.json")


@pytest.fixture(scope="module")
def identified(tmp_path_factory):
    """`softimpact identify paper-rubber-series --no-figures`, run once: (CLI result, output folder)."""
    out = tmp_path_factory.mktemp("identify") / "out"
    return CliRunner().invoke(main, ["identify", "paper-rubber-series", "--out", str(out), "--no-figures"]), out


@pytest.mark.slow
def test_identify_command_on_the_rubber_series(identified):
    """`softimpact identify paper-rubber-series`: law.json with intervals and fit quality per test, a law
    with its Maxwell arm, and a closure whose coupled bar runs reproduce every test's reduced F0, T and I
    within 5 % (issue 10; the memoryless law reached 7 % on the 3/8-in tests) and the law that made the
    synthetic series (eqs 4-7 with Table I, independent of the reduction): I within 1.5 %, T within 4 %,
    tF0 within 3 %, F0 within 8 % (measured 0.8, 3.3, 1.7, 6.8 %; the reduced records peak 2-10 % above
    Table I's F0 — noise on the peak and the bar's dispersion — and the law follows the records)."""
    r, out = identified
    assert r.exit_code == 0, r.output
    law = json.loads((out / "law.json").read_text())
    assert law["parameters"]["kappa_ref"]["value"] > 0 and law["parameters"]["theta_ref"]["value"] > 0
    assert set(law["parameters"]) >= set(TRUE) and all(math.isfinite(v["ci95_half_width"]) for v in law["parameters"].values())
    assert len(law["fit"]["rms_over_F0"]) == 13
    with open(out / "closure.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == 13
    for row in rows:
        err = max(abs(float(row[f"error_{k}"])) for k in ("peak_force", "duration", "impulse"))
        assert err < 0.05
        assert abs(float(row["error_time_of_peak"])) < 0.05  # the pulse's skew too (eq-15 fits)
        F0, tF0, T, I = table_i_pulse(float(row["diameter_m"]), float(row["velocity_m_s"]))
        assert float(row["simulated_impulse_N_s"]) == pytest.approx(I, rel=0.015)
        assert float(row["simulated_duration_s"]) == pytest.approx(T, rel=0.04)
        assert float(row["simulated_time_of_peak_s"]) == pytest.approx(tF0, rel=0.03)
        assert float(row["simulated_peak_force_N"]) == pytest.approx(F0, rel=0.08)
    assert (out / "approach-1_2in-1000.csv").exists()


@pytest.mark.slow
def test_identify_predictive_intervals_cover_the_measured_pulses(identified):
    """law.json gives F0, t_F0, T and I with 95 % intervals at every tested impact: they contain the pulse
    figures of the reduced records themselves (the data, independent of the law) for at least 90 % of
    the 13 × 4 figures, with an RMS z between 0.5 and 1.5 (neither too narrow nor several times too wide);
    the parameters and their covariance stay in the file."""
    from softimpact.input.series_records import read_series_records
    from softimpact.studies.series import reduce_series
    from softimpact.workflows.identification import FIGURES, bar_tests, pulse_shape

    r, out = identified
    law = json.loads((out / "law.json").read_text())
    assert "covariance" in law and len(law["covariance"]["matrix"]) == len(law["parameters"])
    series = load_series("paper-rubber-series")
    tests = {(round(t.diameter, 6), round(t.velocity, 4)): t for t in bar_tests(reduce_series(series, *read_series_records(series)))}
    preds = [p for p in law["predictions"] if p["tested"]]
    assert len(preds) == 13
    z = []
    for p in preds:
        t = tests[(round(p["diameter_m"], 6), round(p["velocity_m_s"], 4))]
        measured = pulse_shape(t.time, t.force)
        for f, m in zip(FIGURES, measured):
            z.append((m - p[f]["value"]) / (p[f]["ci95_half_width"] / 1.96))
    z = np.array(z)
    assert np.mean(np.abs(z) <= 1.96) >= 0.9, z
    assert 0.5 < math.sqrt(np.mean(z**2)) < 1.5, z


def test_predictions_at_requested_impacts_follow_the_laws_scaling(rod, synthetic):
    """A requested impact (the 1/2-in ball at 2000 in/s, between the tested 1000 and 3000) is predicted with an
    interval; on a near-rigid bar its pulse obeys the law's similarity (F0·d/(mV²) and T·V/d as at the tested
    3000 in/s, within 1 %: the rod's compliance breaks it by less), and its interval is as wide, relatively."""
    from softimpact.workflows.identification import predict_pulses

    law, _ = identify(synthetic, rod)
    cl = closure(law, synthetic, rod, 200)
    m, d, V = CASES[1][1], CASES[1][2], 2000 * INCH
    preds = predict_pulses(law, synthetic, rod, cl, points=[(m, d, V)])
    assert len(preds) == len(synthetic) + 1 and preds[-1].tested is False
    new, tested = preds[-1], preds[1]
    assert tested.velocity == pytest.approx(CASES[1][3])
    assert new.values[0] * d / (m * V**2) == pytest.approx(tested.values[0] * d / (m * tested.velocity**2), rel=0.01)
    assert new.values[2] * V / d == pytest.approx(tested.values[2] * tested.velocity / d, rel=0.01)
    assert np.all(new.half_widths > 0)
    assert np.allclose(new.half_widths / new.values, tested.half_widths / tested.values, rtol=0.05)
