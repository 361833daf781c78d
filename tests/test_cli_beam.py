"""The beam command: contract files, --history, bad input refused with exit 2 and nothing written."""

import json

import pytest
from click.testing import CliRunner

from softimpact.cli import main
from softimpact.input.toml import locate

BASE = locate("paper-short-beam").read_text()


def _run(tmp_path, text, *extra):
    case = tmp_path / "beam.toml"
    case.write_text(text)
    out = tmp_path / "out"
    return CliRunner().invoke(main, ["beam", str(case), "--out", str(out), *extra]), out


def test_history_selects_table_row(tmp_path):
    """--history 3 runs Table III row 3 (F0 = 170 lbf); history.csv and summary.json follow the contract."""
    text = BASE.replace('duration = "1000 us"', 'duration = "300 us"')
    result, out = _run(tmp_path, text, "--history", "3", "--no-figures")
    assert result.exit_code == 0, result.output
    summary = json.loads((out / "summary.json").read_text())
    assert summary["peak_force_N"] == pytest.approx(170 * 4.4482216152605, rel=1e-3)
    assert set(summary["gauges"]) == {"g1", "g2"} and "effective_moduli_Pa" in summary and "softimpact_version" in summary
    header = (out / "history.csv").read_text().splitlines()[0].split(",")
    assert header[:4] == ["time_s", "force_N", "strain_g1", "strain_g2"]


@pytest.mark.parametrize(
    "old, new, key",
    [
        ('layup = "[90/0]5s"', 'layup = "[90/0"', "layup"),
        ('layup = "[90/0]5s"', 'fractions = { 0 = 0.5, 90 = 0.4 }\nthickness = "0.11 in"', "fractions"),
        ('position = "1.0 in"\nsurface', 'position = "4.2 in"\nsurface', "gauges"),
        ('contact_radius = "0.25 in"\nhistory', 'contact_radius = "2.5 in"\nhistory', "contact patch"),
        ('time_step = "1 us"', 'time_step = "20 us"', "solver.time_step"),
        ('support = "clamped-free"', 'support = "glued"', "beam.support"),
    ],
    ids=["layup syntax", "fractions", "gauge off beam", "patch too wide", "time step", "support"],
)
def test_bad_input(tmp_path, old, new, key):
    """Each bad value: exit 2, one line naming it, nothing written."""
    assert old in BASE
    result, out = _run(tmp_path, BASE.replace(old, new, 1))
    assert result.exit_code == 2, result.output
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert len(lines) == 1 and key in lines[0]
    assert not out.exists() or not any(out.iterdir())


def test_run_shorter_than_the_pulse_draws_its_figures(tmp_path):
    """A run that ends before the prescribed pulse does (100 µs of a 415 µs pulse) still writes Fig 20, at the
    instants inside the run, and its force history is the pulse's own first 100 µs (the skewed pulse peaks at 35 µs)."""
    text = BASE.replace('duration = "1000 us"', 'duration = "100 us"')
    result, out = _run(tmp_path, text)
    assert result.exit_code == 0, result.output
    assert (out / "fig20-load-distribution.png").stat().st_size > 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["peak_force_N"] == pytest.approx(42 * 4.4482216152605, rel=1e-3)  # the case's history (42 lbf)
