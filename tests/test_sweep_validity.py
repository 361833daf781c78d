"""Sweeps keep each run's validity flags (models.validity): a runs.parquet column per flag, counts in
summary.json and ONE warning line, checked against the single commands run alone at each point; the runs'
repeated warnings are shown once with their count."""

import json
import re
import shutil
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact.cli import main
from softimpact.models.validity import DEFLECTION_OVER_THICKNESS, RANGE_SLACK

from _support.constants import INCH
from _support.problems import COARSE_LONG_BEAM, IDENTIFIED_LAW, IDENTIFIED_ON_LONG_BEAM

LAW = IDENTIFIED_LAW

BEAM = COARSE_LONG_BEAM  # a beam sweep runs on the response engine in milliseconds
BEAM_VELOCITIES = (1000, 3000, 5000)  # in/s: the coarse beam's w/h passes 0.5 and its gauge strains the allowables in between
BEAM_SPEC = f"""
[sweep]
case = "beam.toml"
method = "grid"
outputs = ["peak_force_N", "validity.deflection_over_thickness"]
[[sweep.parameter]]
key = "load.history.velocity"
values = {[f"{v} in/s" for v in BEAM_VELOCITIES]}
""".replace("'", '"')

# The identified law of law.json on the long beam (coupled; four runs: the target's contact kernels).
IMPACT = IDENTIFIED_ON_LONG_BEAM.format(material="silicone rubber", velocity="2000 in/s", duration="600 us")
IMPACT_VELOCITIES = (500, 1500, 3000, 6000)  # in/s: law.json was fitted on 1000-5000 in/s (25.4-127 m/s)
IMPACT_SPEC = f"""
[sweep]
case = "impact.toml"
method = "grid"
outputs = ["peak_force_N", "validity.deflection_over_thickness", "validity.max_strain_index"]
[[sweep.parameter]]
key = "impactor.velocity"
values = {[f"{v} in/s" for v in IMPACT_VELOCITIES]}
""".replace("'", '"')

ENVELOPE_LINE = "runs outside the models' validity envelopes"


def _run(args) -> tuple:
    r = CliRunner().invoke(main, [str(a) for a in args])
    assert r.exit_code == 0, r.output
    return r, r.output


def _table(out: Path) -> dict:
    import pyarrow.parquet as pq

    return pq.read_table(out / "runs.parquet").to_pydict()


def _single_validity(tmp_path: Path, command: str, case_text: str, name: str) -> dict:
    """summary.json's ``validity`` of the command run alone on ``case_text``."""
    (tmp_path / f"{name}.toml").write_text(case_text)
    _run([command, tmp_path / f"{name}.toml", "--out", tmp_path / name, "--no-figures"])
    return json.loads((tmp_path / name / "summary.json").read_text())["validity"]


def test_beam_sweep_keeps_each_runs_validity_flags(tmp_path):
    """A beam sweep whose runs lie partly outside linear theory (w/h > 0.5) and the ply allowables flags, per run, exactly the
    runs that `softimpact beam` run alone (direct Newmark stepping) flags, counts them per flag in summary.json and says so
    in one warning line."""
    (tmp_path / "beam.toml").write_text(BEAM)
    (tmp_path / "spec.toml").write_text(BEAM_SPEC)
    _, output = _run(["sweep", tmp_path / "spec.toml", "--out", tmp_path / "out", "--workers", "0", "--no-figures"])
    single = [_single_validity(tmp_path, "beam", BEAM.replace('velocity = "2000 in/s"', f'velocity = "{v} in/s"'), f"v{v}") for v in BEAM_VELOCITIES]
    deflected = [s["deflection_over_thickness"] > DEFLECTION_OVER_THICKNESS for s in single]
    failed = [s["max_strain_index"] > 1 for s in single]
    assert any(deflected) and not all(deflected) and any(failed) and not all(failed)  # the test's premise: some runs in, some out
    t = _table(tmp_path / "out")
    assert t["validity.deflection_over_thickness"] == pytest.approx([s["deflection_over_thickness"] for s in single], rel=1e-6)
    assert t["flag.deflection_past_linear"] == deflected
    assert t["flag.strains_past_allowables"] == failed
    assert [len(f.split(", ")) if f else 0 for f in t["validity_flags"]] == [len(s["flags"]) for s in single]
    v = json.loads((tmp_path / "out" / "summary.json").read_text())["validity"]
    assert v["runs_per_flag"] == {"deflection_past_linear": sum(deflected), "strains_past_allowables": sum(failed)}
    assert v["runs_outside_envelope"] == sum(bool(s["flags"]) for s in single)
    lines = [line for line in output.splitlines() if ENVELOPE_LINE in line]
    assert len(lines) == 1
    assert f"{v['runs_outside_envelope']} of {len(BEAM_VELOCITIES)} runs" in lines[0]
    assert f"w/h > 0.5 ({sum(deflected)})" in lines[0] and f"strains past the ply allowables ({sum(failed)})" in lines[0]


def test_impact_sweep_counts_flags_and_shows_repeated_warnings_once(tmp_path):
    """A coupled-impact sweep with law.json: the law's missing projectile record is warned once with its count of runs
    (screen and manifest.json), the velocities outside the law's fitted range (from law.json's own record) are flagged
    per run, the fastest run's flags are those of `softimpact impact` alone, and the rate is not rounded to 0."""
    shutil.copy(LAW, tmp_path / "law.json")
    (tmp_path / "impact.toml").write_text(IMPACT)
    (tmp_path / "spec.toml").write_text(IMPACT_SPEC)
    _, output = _run(["sweep", tmp_path / "spec.toml", "--out", tmp_path / "out", "--workers", "0", "--no-figures"])
    n = len(IMPACT_VELOCITIES)
    unrecorded = [line for line in output.splitlines() if "does not record the projectile" in line]
    assert len(unrecorded) == 1 and unrecorded[0].endswith(f"({n} runs)")
    manifest = json.loads((tmp_path / "out" / "manifest.json").read_text())
    assert sum("does not record the projectile" in w for w in manifest["warnings"]) == 1
    assert sum(ENVELOPE_LINE in line for line in output.splitlines()) == 1
    lo, hi = json.loads(LAW.read_text())["identified_on"]["velocity_m_s"]
    outside = [not (1 - RANGE_SLACK) * lo <= v * INCH <= (1 + RANGE_SLACK) * hi for v in IMPACT_VELOCITIES]
    assert any(outside) and not all(outside)
    t = _table(tmp_path / "out")
    assert t["flag.extrapolated_velocity"] == outside
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["validity"]["runs_per_flag"]["extrapolated_velocity"] == sum(outside)
    fastest = _single_validity(tmp_path, "impact", IMPACT.replace('velocity = "2000 in/s"', f'velocity = "{IMPACT_VELOCITIES[-1]} in/s"'), "fastest")
    assert t["validity.deflection_over_thickness"][-1] == pytest.approx(fastest["deflection_over_thickness"], rel=1e-6)
    assert t["validity.max_strain_index"][-1] == pytest.approx(fastest["max_strain_index"], rel=1e-6)
    assert t["flag.deflection_past_linear"][-1] == (fastest["deflection_over_thickness"] > DEFLECTION_OVER_THICKNESS)
    assert t["flag.strains_past_allowables"][-1] == (fastest["max_strain_index"] > 1)
    assert len(t["validity_flags"][-1].split(", ")) == len(fastest["flags"]) + outside[-1]  # the range flag is a warning of the single run
    rate = float(re.search(r"([0-9.]+) runs/s", output).group(1))
    assert rate > 0 and np.isfinite(rate)


@pytest.mark.parametrize("rate, text", [(1 / 3, "0.33"), (5.64, "5.6"), (123.4, "123"), (0.0, "0")])
def test_runs_per_second_keep_two_significant_digits(rate, text):
    """The sweep's rate is printed with two significant digits (a third of a run per second is 0.33, not 0), never in exponent form."""
    from softimpact.app.sweep import _rate

    assert _rate(rate) == text
