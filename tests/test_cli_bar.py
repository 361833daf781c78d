"""The bar command's contract: outputs, and bad input refused with exit 2 and nothing written."""

import json

import pytest
from click.testing import CliRunner

from softimpact.cli import main

GOOD = """
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


def _run(tmp_path, text, *extra):
    case = tmp_path / "case.toml"
    case.write_text(text)
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["bar", str(case), "--out", str(out), *extra])
    return result, out


def test_bar_writes_the_contract_files(tmp_path):
    """history.csv columns and summary.json keys are those the contract names; impulse matches the CSV."""
    import numpy as np

    result, out = _run(tmp_path, GOOD, "--no-figures")
    assert result.exit_code == 0, result.output
    header = (out / "history.csv").read_text().splitlines()[0].split(",")
    assert header[:3] == ["time_s", "contact_force_N", "impactor_velocity_m_s"] and "strain_mid" in header
    summary = json.loads((out / "summary.json").read_text())
    for key in ("peak_force_N", "time_of_peak_s", "contact_duration_s", "impulse_N_s", "rebound_velocity_m_s", "softimpact_version", "case_SI"):
        assert key in summary
    data = np.loadtxt(out / "history.csv", delimiter=",", skiprows=1)
    assert summary["impulse_N_s"] == pytest.approx(np.trapezoid(data[:, 1], data[:, 0]), rel=1e-9)
    assert not list(out.glob("*.png"))


@pytest.mark.parametrize(
    "old, new, key",
    [
        ('length = "36 in"', "length = 36", "bar.length"),
        ('material = "steel"', 'material = "unobtainium"', "projectile.material"),
        ('length = "36 in"', 'length = "-36 in"', "bar.length"),
        ('position = "18 in"', 'position = "40 in"', "gauges[0].position"),
        ('time_step = "1 us"', 'time_step = "0 us"', "solver.time_step"),
        ("elements = 20", 'elements = 20\ncolour = "red"', "bar.colour"),
        ('velocity = "62.1 in/s"', 'velocity = "62.1 in"', "projectile.velocity"),
    ],
)
def test_bad_input_exits_2_with_one_line_and_writes_nothing(tmp_path, old, new, key):
    """Each bad value gives exit 2, a single line naming the key, and no output folder content."""
    assert old in GOOD
    result, out = _run(tmp_path, GOOD.replace(old, new, 1))
    assert result.exit_code == 2
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert len(lines) == 1 and key in lines[0]
    assert not out.exists() or not any(out.iterdir())


def test_unknown_case_name(tmp_path):
    """A case that is neither a file nor a built-in is refused with exit 2."""
    result = CliRunner().invoke(main, ["bar", "no-such-case", "--out", str(tmp_path / "o")])
    assert result.exit_code == 2 and "no-such-case" in result.output


def test_builtin_case_by_name_with_figures(tmp_path):
    """The built-in paper-calibration case runs by name and draws Figs 4-6 as PNG."""
    out = tmp_path / "o"
    result = CliRunner().invoke(main, ["bar", "paper-calibration", "--out", str(out)])
    assert result.exit_code == 0, result.output
    for name in ("fig04-gauge-strain.png", "fig05-contact-force.png", "fig06-strain-along-bar.png"):
        assert (out / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert not [p for p in out.iterdir() if p.name.startswith(".")]  # no staging left behind


def test_a_contact_iteration_that_does_not_converge_is_a_named_failure(tmp_path, monkeypatch):
    """A contact Newton iteration cut to one iteration fails to converge: exit 3 and one line saying when (time,
    step) and how far (residual, bracket), not an internal error (exit 70); the folder holds that reason alone
    (summary.json marked failed, no results: there are none)."""
    import softimpact.fem.impact as impact

    monkeypatch.setattr(impact, "NEWTON_MAXITER", 1)
    result, out = _run(tmp_path, GOOD, "--no-figures")
    assert result.exit_code == 3, result.output
    lines = [ln for ln in result.output.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("softimpact: solver failed: the contact Newton iteration did not converge at t = ")
    assert "(step 1)" in lines[0] and "residual" in lines[0] and "bracket" in lines[0]
    summary = json.loads((out / "summary.json").read_text())
    assert summary["status"] == "failed" and summary["reason"] in lines[0]
    assert sorted(p.name for p in out.iterdir()) == ["manifest.json", "summary.json"]
