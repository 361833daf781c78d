"""Never silently wrong (issue 32): a sweep's fingerprint covers every file its runs read; bounds are labelled as bounds."""

import json

import pyarrow.parquet as pq
from click.testing import CliRunner

from softimpact.cli import main

from _support.problems import COARSE_LONG_BEAM, LONG_BEAM_IMPACT

SPEC = """
[sweep]
case = "impact.toml"
method = "grid"
outputs = ["peak_force_N"]
[[sweep.parameter]]
key = "impactor.velocity"
values = ["1000 in/s", "3000 in/s"]
"""


def _impact_on_local_beam(folder, layup="[90/0]5s"):
    """An impact case whose target is the beam case beam.toml beside it, and a velocity grid on it."""
    (folder / "beam.toml").write_text(COARSE_LONG_BEAM.replace("[90/0]5s", layup))
    case = LONG_BEAM_IMPACT.format(velocity="2000 in/s").replace('"paper-long-beam"', '"beam.toml"').replace('"300 us"', '"150 us"')
    (folder / "impact.toml").write_text(case)
    (folder / "spec.toml").write_text(SPEC)
    return folder / "spec.toml"


def _sweep(spec, out):
    r = CliRunner().invoke(main, ["sweep", str(spec), "--out", str(out), "--no-figures", "--workers", "0"])
    assert r.exit_code == 0, r.output
    return r.output, pq.read_table(out / "runs.parquet").to_pydict()["peak_force_N"], json.loads((out / "summary.json").read_text())


def test_a_sweep_resumed_after_its_target_case_was_edited_follows_the_edit_and_names_the_file(tmp_path):
    """Editing the impact case's target case between two sweeps into one --out: the second sweep's peak forces are those
    of a fresh sweep of the edited cases (computed independently into another --out), not the old checkpoints', and its
    warning names the edited file."""
    first = tmp_path / "a"
    first.mkdir()
    spec = _impact_on_local_beam(first)
    out = tmp_path / "out"
    _, before, _ = _sweep(spec, out)
    (first / "beam.toml").write_text(COARSE_LONG_BEAM.replace("[90/0]5s", "[90/0]10s"))  # twice as thick: stiffer, higher peak force
    text, after, summary = _sweep(spec, out)
    fresh = tmp_path / "b"
    fresh.mkdir()
    _, expected, _ = _sweep(_impact_on_local_beam(fresh, "[90/0]10s"), tmp_path / "fresh")
    assert after == expected
    assert all(a > b for a, b in zip(after, before))
    assert summary["from_checkpoints"] == 0
    assert "beam.toml (edited)" in text and "inputs changed" in text
    # unchanged inputs resume from the new checkpoints without a word about changes
    text, again, summary = _sweep(spec, out)
    assert again == after and summary["from_checkpoints"] == 2 and "inputs changed" not in text


def test_the_fingerprint_covers_the_law_json_of_an_identified_contact_law(tmp_path):
    """The law.json an impact case's identified contact law reads (``contact.law_file``) enters the spec's inputs:
    editing one of its numbers changes the fingerprint, so its checkpoints are not reused."""
    from softimpact.input.sweep_spec import load_sweep_spec

    from _support.problems import IDENTIFIED_LAW, IDENTIFIED_ON_LONG_BEAM

    (tmp_path / "law.json").write_text(IDENTIFIED_LAW.read_text())
    (tmp_path / "impact.toml").write_text(IDENTIFIED_ON_LONG_BEAM.format(material="steel", velocity="2000 in/s", duration="100 us"))
    (tmp_path / "spec.toml").write_text(SPEC)
    one = load_sweep_spec(str(tmp_path / "spec.toml"))
    assert str((tmp_path / "law.json").resolve()) in dict(one.inputs)
    law = json.loads(IDENTIFIED_LAW.read_text())
    law["edited"] = True
    (tmp_path / "law.json").write_text(json.dumps(law))
    assert load_sweep_spec(str(tmp_path / "spec.toml")).fingerprint != one.fingerprint


BEAM_SPEC = """
[sweep]
case = "beam.toml"
method = "grid"
outputs = ["damage.max_strain"]
[[sweep.parameter]]
key = "load.history.velocity"
values = [{values}]
"""


def _beam_thresholds(tmp_path, values):
    """A velocity grid on the coarse long beam: (printed output, thresholds.csv rows, summary.json's thresholds, the run table)."""
    import csv

    (tmp_path / "beam.toml").write_text(COARSE_LONG_BEAM)
    (tmp_path / "spec.toml").write_text(BEAM_SPEC.format(values=", ".join(f'"{v} in/s"' for v in values)))
    out = tmp_path / "out"
    r = CliRunner().invoke(main, ["sweep", str(tmp_path / "spec.toml"), "--out", str(out), "--no-figures", "--workers", "0"])
    assert r.exit_code == 0, r.output
    with open(out / "thresholds.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    return r.output, rows, json.loads((out / "summary.json").read_text())["thresholds"], pq.read_table(out / "runs.parquet").to_pydict()


def test_a_threshold_below_the_swept_range_is_reported_as_a_bound(tmp_path):
    """A grid whose lowest velocity already takes the strain index past 1 reports the threshold as below the lowest level
    (a text cell, no number) in thresholds.csv, summary.json and the printed line, never as the lowest velocity itself."""
    text, rows, summary, table = _beam_thresholds(tmp_path, [5000, 8000])
    assert min(table["damage.max_strain"]) >= 1.0  # the premise: every run is past onset
    assert rows[0]["threshold_velocity_median_bound"] == "below the lowest level"
    assert rows[0]["threshold_velocity_median_m_s"] == ""  # an empty cell: no number
    assert float(rows[0]["lowest_level_m_s"]) == 5000 * 0.0254
    assert summary[0]["threshold_velocity_median_bound"] == "below the lowest level" and summary[0]["threshold_velocity_median_m_s"] is None
    assert "median below the lowest level (5000 in/s)" in text


def test_a_threshold_above_the_swept_range_is_reported_as_a_bound(tmp_path):
    """A grid whose highest velocity stays short of onset reports the threshold as above the highest level."""
    text, rows, summary, table = _beam_thresholds(tmp_path, [1000, 2000])
    assert max(table["damage.max_strain"]) < 1.0
    assert rows[0]["threshold_velocity_median_bound"] == "above the highest level"
    assert "median above the highest level (2000 in/s)" in text


def test_a_bracketed_threshold_is_the_linear_crossing_and_has_no_bound(tmp_path):
    """A grid that brackets onset gives the velocity where the straight line between the two bracketing runs' indices
    crosses 1 (computed here from the run table), with an empty bound."""
    text, rows, summary, table = _beam_thresholds(tmp_path, [3000, 5000])
    (v1, v2), (i1, i2) = table["load.history.velocity"], table["damage.max_strain"]
    assert i1 < 1.0 <= i2
    assert summary[0]["threshold_velocity_median_m_s"] == v1 + (1.0 - i1) * (v2 - v1) / (i2 - i1)
    assert summary[0]["threshold_velocity_median_bound"] == ""


def test_censored_quantiles_are_bounds_where_they_fall_on_censored_draws():
    """Over the draws (below, 1, 2, 3, above) the median is 2 (the middle draw) while the 5 % and 95 % quantiles,
    interpolated between a censored draw and a bracketed one, are the bounds below the lowest / above the highest level."""
    import math

    import numpy as np

    from softimpact.workflows.sweep_stats import ABOVE, BELOW, _quantile

    f = np.array([-np.inf, 1.0, 2.0, 3.0, np.inf])
    assert _quantile(f, 50.0) == (2.0, "")
    lo, hi = _quantile(f, 5.0), _quantile(f, 95.0)
    assert math.isnan(lo[0]) and lo[1] == BELOW and math.isnan(hi[0]) and hi[1] == ABOVE


def test_power_law_rise_is_the_time_to_peak_of_the_rigid_wall_ode():
    """Hertz's closed-form rise (α_m/V·√π·Γ(7/5)/Γ(9/10) ≈ 1.4716·α_m/V) equals the time of maximum approach of
    m·α̈ = −K·α^1.5, α(0) = 0, α̇(0) = V, integrated here with scipy (an independent computation)."""
    import pytest
    from scipy.integrate import solve_ivp

    from softimpact.guards import power_law_rise

    m, K, V = 8.4e-3, 8.4e8, 2.54  # a 1/2-in steel ball on a laminate (Sun's form, E2 7.9 GPa), 100 in/s
    peak = lambda t, y: y[1]  # noqa: E731
    peak.terminal = True
    sol = solve_ivp(lambda t, y: [y[1], -K * max(y[0], 0.0) ** 1.5 / m], (0.0, 1e-3), [0.0, V], events=peak, rtol=1e-11, atol=1e-15)
    assert power_law_rise(K, 1.5, m, V) == pytest.approx(sol.t_events[0][0], rel=1e-6)


def test_a_coupled_impact_with_too_coarse_a_step_exits_2_with_a_finer_advised_step(tmp_path):
    """The built-in long-beam impact stepped at 100 us (10 steps over its 1 ms) exits 2 from `softimpact impact` and
    from a sweep of it, naming a time step below 100 us; stepped at that advised value it passes the check."""
    import dataclasses
    import re

    import softimpact as si
    from softimpact.cases import KINDS

    text = (si.load("paper-long-beam-impact").files[0]).read_text().replace('time_step = "0.5 us"', 'time_step = "100 us"')
    (tmp_path / "coarse.toml").write_text(text)
    r = CliRunner().invoke(main, ["impact", str(tmp_path / "coarse.toml"), "--out", str(tmp_path / "o"), "--no-figures"])
    assert r.exit_code == 2, r.output
    advised = float(re.search(r"solver.time_step = ([0-9.]+) us or less", r.output).group(1))
    assert advised < 100.0
    (tmp_path / "spec.toml").write_text(SPEC.replace("impact.toml", "coarse.toml"))
    r = CliRunner().invoke(main, ["sweep", str(tmp_path / "spec.toml"), "--out", str(tmp_path / "s"), "--no-figures", "--workers", "0"])
    assert r.exit_code == 2 and "cannot resolve the contact force's rise" in r.output, r.output
    problem = si.load("paper-long-beam-impact").problem
    solver = dataclasses.replace(problem.solver, time_step=advised * 1e-6)
    KINDS["impact"].check(problem.with_solver(solver))  # the advised step passes


def test_a_contact_still_on_at_the_end_says_why_its_duration_is_null(tmp_path):
    """A coupled run ending while the ball still presses on the beam reports contact_duration_s null with a
    contact_duration_note saying the contact had not ended and what to lengthen."""
    case = LONG_BEAM_IMPACT.format(velocity="100 in/s").replace('"300 us"', '"20 us"')
    (tmp_path / "short.toml").write_text(case)
    r = CliRunner().invoke(main, ["impact", str(tmp_path / "short.toml"), "--out", str(tmp_path / "o"), "--no-figures"])
    assert r.exit_code == 0, r.output
    summary = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert summary["contact_duration_s"] is None
    assert "had not ended" in summary["contact_duration_note"] and "solver.duration" in summary["contact_duration_note"]
