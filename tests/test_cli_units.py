"""``--units`` on the commands that print numbers or draw: the display system changes the printed line and the
figures, never the numbers of the files (summary.json, CSV), which stay SI."""

import json
import re

import pytest
from click.testing import CliRunner

from softimpact.app.options import UNITS
from softimpact.cli import main

from _support.constants import LBF

# the bar case of tests/test_cli_bar.py, its display system SI
SI_BAR = """
title = "t"
units = "SI"
[bar]
material = "Al 6061-T6"
length = "36 in"
diameter = "0.5 in"
elements = 20
[projectile]
material = "steel"
diameter = "0.625 in"
velocity = "62.1 in/s"
[solver]
time_step = "1 us"
duration = "150 us"
[[gauges]]
name = "mid"
position = "18 in"
"""

SWEEP_SPEC = """
[sweep]
case = "paper-calibration"
method = "grid"
outputs = ["peak_force_N"]
[[sweep.parameter]]
key = "projectile.velocity"
values = ["40 in/s", "80 in/s"]
[[sweep.parameter]]
key = "solver.duration"
value = "120 us"
[[sweep.parameter]]
key = "output.snapshots"
value = ["60 us"]
"""


def _invoke(args, out) -> str:
    result = CliRunner().invoke(main, [*args, "--out", str(out)])
    assert result.exit_code == 0, result.output
    return result.output


def _without_display(value):
    """summary.json's content without the display systems it records (``units`` of case_SI and of its target) and the
    wall-clock times of converge's levels (``run_time_s``: they differ between any two runs)."""
    if isinstance(value, dict):
        return {k: _without_display(v) for k, v in value.items() if k not in ("units", "run_time_s")}
    if isinstance(value, list):
        return [_without_display(v) for v in value]
    return value


def _files(folder) -> dict:
    """The numbers written: every CSV's bytes and summary.json's content but its display system (no figures, no manifest)."""
    out = {}
    for path in sorted(folder.rglob("*")):
        if path.suffix == ".csv":
            out[path.name] = path.read_bytes()
        elif path.name == "summary.json":
            out[path.name] = _without_display(json.loads(path.read_text()))
    return out


def _quantity(text: str, what: str, unit: str) -> float:
    """The number printed after ``what`` with its ``unit``."""
    match = re.search(rf"{what} (-?[\d.]+) {re.escape(unit)}\b", text)
    assert match, (what, unit, text)
    return float(match.group(1))


def test_every_command_that_prints_or_draws_has_units_from_the_one_table():
    """Every command that prints numbers or draws figures has --units with the table's choices and no fixed default (the case's)."""
    for name in ("bar", "beam", "plate", "impact", "reduce", "fit", "identify", "calibrate", "converge", "sweep", "predict"):
        (option,) = [p for p in main.commands[name].params if p.name == "units"]
        assert option.opts == ["--units"] and list(option.type.choices) == list(UNITS.choices) and option.default is None, name


@pytest.mark.parametrize(("flag", "unit"), [((), "N"), (("--units", "SI"), "N"), (("--units", "in-lbf-s"), "lbf")])
def test_bar_prints_in_the_units_asked_else_the_cases_and_writes_the_same_numbers(tmp_path, flag, unit):
    """An SI bar case prints newtons by default and with --units SI, pounds-force with --units in-lbf-s (N / 4.448 within print rounding); its files are the same."""
    case = tmp_path / "case.toml"
    case.write_text(SI_BAR)
    reference = _invoke(["bar", str(case), "--no-figures"], tmp_path / "ref")
    line = _invoke(["bar", str(case), "--no-figures", *flag], tmp_path / "out")
    peak = _quantity(line, "peak force", unit)
    assert peak == pytest.approx(_quantity(reference, "peak force", "N") / (LBF if unit == "lbf" else 1.0), abs=0.1)
    assert _files(tmp_path / "out") == _files(tmp_path / "ref")
    assert json.loads((tmp_path / "out" / "summary.json").read_text())["case_SI"]["units"] == ("in-lbf-s" if unit == "lbf" else "SI")


def test_impact_prints_newtons_with_units_si_and_writes_the_same_numbers(tmp_path):
    """The built-in beam impact (in-lbf-s) prints F0 and Olsson's threshold in lbf, with --units SI in N (lbf × 4.448 within print rounding); same files."""
    default = _invoke(["impact", "paper-long-beam-impact", "--no-figures"], tmp_path / "ref")
    si = _invoke(["impact", "paper-long-beam-impact", "--no-figures", "--units", "SI"], tmp_path / "si")
    assert " lbf" not in si
    assert _quantity(si, "F0", "N") == pytest.approx(_quantity(default, "F0", "lbf") * LBF, abs=0.05 * LBF + 0.05)
    assert _quantity(si, r"F_d \(Olsson\)", "N") == pytest.approx(_quantity(default, r"F_d \(Olsson\)", "lbf") * LBF, abs=0.05 * LBF + 0.05)
    assert _files(tmp_path / "si") == _files(tmp_path / "ref")


def test_beam_records_the_display_system_asked_and_writes_the_same_numbers(tmp_path):
    """A beam run with --units SI draws in SI (summary.json's case_SI.units says so) and writes the same numbers as the case's own in-lbf-s."""
    _invoke(["beam", "paper-long-beam", "--history", "1", "--no-figures"], tmp_path / "ref")
    _invoke(["beam", "paper-long-beam", "--history", "1", "--no-figures", "--units", "SI"], tmp_path / "si")
    assert json.loads((tmp_path / "si" / "summary.json").read_text())["case_SI"]["units"] == "SI"
    assert json.loads((tmp_path / "ref" / "summary.json").read_text())["case_SI"]["units"] == "in-lbf-s"
    assert _files(tmp_path / "si") == _files(tmp_path / "ref")


@pytest.mark.parametrize(("flag", "unit"), [((), "lbf"), (("--units", "SI"), "N")])
def test_predict_prints_in_the_units_asked(tmp_path, flag, unit):
    """predict prints F0 in lbf by default (no case) and in N with --units SI, the same force (lbf × 4.448 within print rounding); same files."""
    args = ["predict", "--projectile", "rubber-1/2in", "--velocity", "2000 in/s", "--no-figures"]
    reference = _invoke([*args, "--units", "SI"], tmp_path / "ref")
    line = _invoke([*args, *flag], tmp_path / "out")
    newtons = _quantity(reference, "F0", "N")
    assert _quantity(line, "F0", unit) == pytest.approx(newtons / (LBF if unit == "lbf" else 1.0), rel=1e-3)
    assert _files(tmp_path / "out") == _files(tmp_path / "ref")


def test_predict_driving_a_bar_shows_the_bar_cases_units(tmp_path):
    """predict --bar on an SI case prints newtons without --units (the case's display system), pounds-force with --units in-lbf-s."""
    case = tmp_path / "case.toml"
    case.write_text(SI_BAR)
    args = ["predict", "--projectile", "rubber-1/2in", "--velocity", "200 in/s", "--bar", str(case), "--no-figures"]
    assert " N at " in _invoke(args, tmp_path / "own")
    assert " lbf at " in _invoke([*args, "--units", "in-lbf-s"], tmp_path / "asked")


@pytest.mark.slow  # seconds: the slow tier (make test-slow)
def test_reduce_draws_in_the_units_asked_and_writes_the_same_numbers(tmp_path, monkeypatch):
    """reduce --units SI draws each force history in SI (the series says in-lbf-s) and writes the same tests.csv and histories."""
    from test_cli_series import _mini_series

    from softimpact.output import plots

    drawn = []
    original = plots.force_history
    monkeypatch.setattr(plots, "force_history", lambda r, system: drawn.append(system) or original(r, system))
    series = _mini_series(tmp_path)
    _invoke(["reduce", str(series)], tmp_path / "ref")
    _invoke(["reduce", str(series), "--units", "SI"], tmp_path / "si")
    assert drawn == ["in-lbf-s", "in-lbf-s", "SI", "SI"]
    assert _files(tmp_path / "si") == _files(tmp_path / "ref")


def test_converge_records_the_display_system_asked_and_writes_the_same_numbers(tmp_path):
    """converge --units SI on an in-lbf-s case: summary.json's case_SI.units is SI, convergence.csv and the other numbers unchanged."""
    args = ["converge", "paper-calibration", "--levels", "2", "--no-figures"]
    _invoke(args, tmp_path / "ref")
    _invoke([*args, "--units", "SI"], tmp_path / "si")
    assert json.loads((tmp_path / "si" / "summary.json").read_text())["case_SI"]["units"] == "SI"
    assert _files(tmp_path / "si") == _files(tmp_path / "ref")


def test_sweep_draws_in_the_units_asked(tmp_path, monkeypatch):
    """sweep --units SI hands SI to the writer of its lines and figures (the case says in-lbf-s); runs.parquet's numbers are the plain loop's either way."""
    import io

    import pyarrow.parquet as pq

    import softimpact.app.sweep as app

    systems = []
    original = app.sweep_files
    monkeypatch.setattr(app, "sweep_files", lambda cols, summary, th, figures, system: systems.append(system) or original(cols, summary, th, figures, system))
    spec = tmp_path / "spec.toml"
    spec.write_text(SWEEP_SPEC)
    _invoke(["sweep", str(spec), "--workers", "0", "--no-figures"], tmp_path / "ref")
    _invoke(["sweep", str(spec), "--workers", "0", "--no-figures", "--units", "SI"], tmp_path / "si")
    assert systems == ["in-lbf-s", "SI"]
    peaks = [pq.read_table(io.BytesIO((tmp_path / d / "runs.parquet").read_bytes())).column("peak_force_N").to_pylist() for d in ("ref", "si")]
    assert peaks[0] == peaks[1]
