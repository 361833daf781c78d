"""reduce, fit and predict from the command line: contract files, bad records, Table I."""

import csv
import json
import shutil

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact.cli import main
from softimpact.input.series import load_series
from softimpact.input.toml import builtin_cases

from _support.constants import LBF


def _mini_series(tmp_path, extra_record=None):
    """Two built-in synthetic records (and optionally a third, given as text) in a series file."""
    src = load_series("paper-rubber-series")
    lines = [
        "[bar]",
        'material = "Al 6061-T6"',
        'length = "36 in"',
        'diameter = "0.5 in"',
        "[bar.end_cap]",
        'material = "Al 6061-T6"',
        'diameter = "1.0 in"',
        'length = "0.25 in"',
        "[gauge]",
        'position = "18 in"',
    ]
    tests = [t for t in src.tests if t.name in ("1_2in-2000", "1_2in-4000")]
    for t in tests:
        shutil.copy(t.record, tmp_path / t.record.name)
        lines += ["[[test]]", f'record = "{t.record.name}"', f'velocity = "{t.velocity} m/s"', f'diameter = "{t.diameter} m"', f'mass = "{t.mass} kg"']
    if extra_record is not None:
        (tmp_path / "bad.csv").write_text(extra_record)
        lines += ["[[test]]", 'record = "bad.csv"', 'velocity = "3000 in/s"', 'diameter = "0.5 in"', 'mass = "1.1 g"']
    path = tmp_path / "series.toml"
    path.write_text("\n".join(lines) + "\n")
    return path


def test_one_bad_record_is_reported_and_the_others_reduce(tmp_path):
    """A NaN record is named on stderr and in tests.csv; the two good ones get their histories."""
    bad = "time_us,microstrain\n" + "\n".join(f"{i},{'nan' if i == 50 else 0.0}" for i in range(200))
    series = _mini_series(tmp_path, bad)
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["reduce", str(series), "--out", str(out), "--no-figures"])
    assert result.exit_code == 0, result.output
    assert "bad.csv" in result.output and "NaN" in result.output
    rows = (out / "tests.csv").read_text().splitlines()
    assert len(rows) == 4 and "error" in rows[3] and "bad.csv" in rows[3]
    assert (out / "history-1_2in-2000.csv").exists() and (out / "history-1_2in-4000.csv").exists()


def test_wrong_unit_header_names_the_file(tmp_path):
    """A record whose header states no unit (and no bridge to read volts) is bad input: file named, exit 2, nothing written."""
    series = _mini_series(tmp_path, "time,strain_gauge\n0,0\n1,0\n")
    result = CliRunner().invoke(main, ["reduce", str(series), "--out", str(tmp_path / "o"), "--no-figures"])
    assert result.exit_code == 2
    assert "bad.csv" in result.output and "unit" in result.output
    assert not (tmp_path / "o").exists()


def test_all_records_bad_exits_2_and_writes_nothing(tmp_path):
    """When no record can be reduced: exit 2, a message, and nothing in the output folder."""
    (tmp_path / "bad.csv").write_text("time_us,strain\n1,0\n0,0\n")
    series = tmp_path / "s.toml"
    series.write_text(
        '[bar]\nmaterial = "steel"\nlength = "1 m"\ndiameter = "1 cm"\n[gauge]\nposition = "0.5 m"\n'
        '[[test]]\nrecord = "bad.csv"\nvelocity = "10 m/s"\ndiameter = "1 cm"\nmass = "1 g"\n'
    )
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["reduce", str(series), "--out", str(out)])
    assert result.exit_code == 2
    assert not out.exists() or not any(out.iterdir())


@pytest.mark.slow  # seconds: the slow tier (make test-slow)
def test_fit_recovers_table_one_from_the_builtin_series(tmp_path):
    """The built-in synthetic series was made from Table I: fit returns α1, α2, α4 within 3 %, α3 within 10 %."""
    out = tmp_path / "fit"
    result = CliRunner().invoke(main, ["fit", "paper-rubber-series", "--out", str(out), "--no-figures"])
    assert result.exit_code == 0, result.output
    data = json.loads((out / "scaling.json").read_text())
    table = {"0.375 in": (4.00, 1.03, 0.25, 0.74), "0.5 in": (4.25, 0.93, 0.25, 0.66)}
    for label, alphas in table.items():
        for i, (expected, tol) in enumerate(zip(alphas, (0.03, 0.03, 0.10, 0.03))):
            got = data["groups"][label][f"alpha{i + 1}"]
            assert got["value"] == pytest.approx(expected, rel=tol)
            assert got["ci95"][0] <= got["value"] <= got["ci95"][1]
    assert "pooled" in data and "softimpact_version" in data


FAMILIES = ("knee", "ramp-under", "linear", "power-law", "free-ramp", "early-ramp")  # the reduction's tail families (issues 22, 32)


@pytest.mark.slow  # seconds: the slow tier (make test-slow)
def test_fit_writes_the_tail_shape_term(tmp_path):
    """fit's scaling.json carries, per group, a separate tail_shape term (five families ranked by AIC, those within
    ΔAIC < 4 listed) whose widened α2, α3 intervals contain Table I's values that made the built-in series
    (α2 0.93 and 1.03, α3 0.25 assumed for both), names the α's the records do not bound better than the tail's
    shape (those whose tail-shape half-width exceeds the Student one), and tests.csv names each test's best tail family."""
    out = tmp_path / "fit"
    result = CliRunner().invoke(main, ["fit", "paper-rubber-series", "--out", str(out), "--no-figures"])
    assert result.exit_code == 0, result.output
    data = json.loads((out / "scaling.json").read_text())
    for label, (a2, a3) in {"0.375 in": (1.03, 0.25), "0.5 in": (0.93, 0.25)}.items():
        term = data["groups"][label]["tail_shape"]
        assert set(term["aic"]) == set(FAMILIES) and term["best"] in term["not_rejected"]
        assert term["delta_aic_threshold"] == 4
        for name, truth in (("alpha2", a2), ("alpha3", a3)):
            lo, hi = term["ci95_with_tail_shape"][name]
            ci = data["groups"][label][name]["ci95"]
            assert lo <= ci[0] and ci[1] <= hi and term["half_width"][name] >= 0
            assert lo <= truth <= hi, (label, name, lo, hi)
        student = {n: 0.5 * (data["groups"][label][n]["ci95"][1] - data["groups"][label][n]["ci95"][0]) for n in term["half_width"]}
        assert set(term["not_bounded_by_data"]) == {n for n, h in term["half_width"].items() if h > student[n]}
    with open(out / "tests.csv") as fh:
        assert all(row["tail_best_family"] in FAMILIES for row in csv.DictReader(fh))


def test_predict_empirical_and_bar(tmp_path):
    """predict: F0 of eq (4) at 1166 in/s (36 lbf), and the bar driven by it reads F = EA·ε at the gauge."""
    out = tmp_path / "p"
    result = CliRunner().invoke(main, ["predict", "--projectile", "rubber-1/2in", "--velocity", "1166 in/s", "--bar", "paper-calibration", "--out", str(out)])
    assert result.exit_code == 0, result.output
    summary = json.loads((out / "summary.json").read_text())
    assert summary["peak_force_N"] / LBF == pytest.approx(36.0, abs=0.5)
    data = np.genfromtxt(out / "history.csv", delimiter=",", names=True)
    EA = 68.947572931683e9 * np.pi * (0.0127 / 2) ** 2
    # Until the reflection returns (271 µs at the mid gauge), −EA·ε is the force delayed by x/c (and the cap's lag).
    early = data["time_s"] < 260e-6
    assert -EA * data["strain_midpoint"][early].min() == pytest.approx(summary["peak_force_N"], rel=0.03)
    assert (out / "force-history.png").exists()


@pytest.mark.parametrize(
    "args, key",
    [
        (["--velocity", "1166 in/s"], "--projectile"),
        (["--projectile", "golf-ball", "--velocity", "30 m/s"], "--projectile"),
        (["--projectile", "rubber-1/2in", "--velocity", "30"], "--velocity"),
        (["--mass", "1 g", "--diameter", "1 cm", "--velocity", "30 m/s"], "--constants"),
    ],
)
def test_predict_bad_input(tmp_path, args, key):
    """Bad predict arguments: exit 2 and a one-line message naming the option."""
    result = CliRunner().invoke(main, ["predict", *args, "--out", str(tmp_path / "o")])
    assert result.exit_code == 2 and key in result.output
    assert not (tmp_path / "o").exists()


def test_builtin_series_listed():
    """`softimpact cases` knows the demonstration series by name."""
    assert "paper-rubber-series" in builtin_cases()
