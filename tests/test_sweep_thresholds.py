"""Thresholds of a sweep against any level (energy, diameter, velocity) and against a user's limit, onsets of sizes,
and the validity of the runs each row rests on: sweep_stats against closed forms, the spec's keys and refusals, and
the engine end to end."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact.cli import main
from softimpact.errors import InputError
from softimpact.workflows import sweep_stats

from _support.problems import COARSE_LONG_BEAM, LONG_BEAM_IMPACT

# A size linear in the impact energy above an onset: s(E) = K·(E − E0) for E > E0, 0 below (a dent's depth, m).
ENERGIES = np.array([10.0, 20.0, 30.0, 40.0, 50.0])  # J, the swept levels
K = 2e-6  # m/J
E0 = 23.0  # J, between the levels 20 and 30


def _size(E, e0=E0):
    return np.clip(K * (np.asarray(E) - e0), 0.0, None)


def _grid(e0s):
    """Runs of a level grid crossed with draws: one draw per onset in ``e0s``; (level, draw, size) per run."""
    level = np.repeat(ENERGIES, len(e0s))
    draws = np.tile(np.arange(len(e0s)), ENERGIES.size)
    return level, draws, np.array([_size(E, e0s[d]) for E, d in zip(level, draws)])


def test_onset_of_a_size_linear_above_its_onset_is_exact():
    """s = K·(E − 23 J)⁺ on levels 10..50 J: the onset is 23 J exactly (the line through the first two positive levels,
    30 and 40 J, reaches zero there), inside the bracket (20 J zero, 30 J positive), named after the energy in J."""
    level, draws, s = _grid([E0])
    (row,) = sweep_stats.onsets(level, [""] * level.size, draws, {"damage.dent_depth_m": s}, quantity="energy", unit="J")
    assert row["onset_energy_median_J"] == pytest.approx(E0, rel=1e-12)
    assert (row["onset_energy_last_zero_J"], row["onset_energy_first_positive_J"]) == (20.0, 30.0)
    assert row["index"] == "dent_depth_m" and row["onset_energy_median_bound"] == ""


def test_threshold_of_a_size_against_a_limit_is_exact_where_the_size_is_linear():
    """The level where s = K·(E − E0) first reaches a limit L is E0 + L/K (35.5 J for L = 25 µm): linear between the
    levels 30 and 40 J that bracket it, so the interpolation is exact."""
    level, draws, s = _grid([E0])
    limit = 25e-6
    (row,) = sweep_stats.thresholds(level, [""] * level.size, draws, {"damage.dent_depth_m": s / limit}, quantity="energy", unit="J")
    assert row["threshold_energy_median_J"] == pytest.approx(E0 + limit / K, rel=1e-12)
    assert row["lowest_level_J"] == 10.0 and row["highest_level_J"] == 50.0 and row["draws_reaching_1"] == 1


def test_onsets_over_draws_give_the_percentiles_of_the_draws_onsets():
    """Five draws with onsets 21, 23, 25, 27, 29 J (all inside 20-30 J): the median and 5/95 % are numpy's percentiles
    of those five onsets; the bracket is the last level where every draw is zero (20) and the first where all are
    positive (30)."""
    e0s = [21.0, 23.0, 25.0, 27.0, 29.0]
    level, draws, s = _grid(e0s)
    (row,) = sweep_stats.onsets(level, [""] * level.size, draws, {"damage.dent_depth_m": s}, quantity="energy", unit="J")
    for q, p in (("median", 50), ("p05", 5), ("p95", 95)):
        assert row[f"onset_energy_{q}_J"] == pytest.approx(np.percentile(e0s, p), rel=1e-12)
    assert (row["onset_energy_last_zero_J"], row["onset_energy_first_positive_J"]) == (20.0, 30.0)
    assert row["draws"] == 5 and row["draws_positive"] == 5


@pytest.mark.parametrize(
    "e0, limit, bound",
    [
        (5.0, 1e-6, sweep_stats.BELOW),  # past the limit (and positive) at the lowest level: an upper bound only
        (23.0, 1.0, sweep_stats.ABOVE),  # 1 m is never reached: a lower bound only
    ],
)
def test_censored_thresholds_and_onsets_are_bounds(e0, limit, bound):
    """A size positive already at the lowest level has its onset (and a small limit's threshold) below the swept
    range; a limit never reached has its threshold above it: NaN with the bound in words, never the end level."""
    level, draws, s = _grid([e0])
    (th,) = sweep_stats.thresholds(level, [""] * level.size, draws, {"damage.dent_depth_m": s / limit}, quantity="energy", unit="J")
    assert math.isnan(th["threshold_energy_median_J"]) and th["threshold_energy_median_bound"] == bound
    if bound == sweep_stats.BELOW:
        (on,) = sweep_stats.onsets(level, [""] * level.size, draws, {"damage.dent_depth_m": s}, quantity="energy", unit="J")
        assert math.isnan(on["onset_energy_median_J"]) and on["onset_energy_median_bound"] == bound
        assert math.isnan(on["onset_energy_last_zero_J"]) and on["onset_energy_first_positive_J"] == ENERGIES[0]


def test_a_size_never_positive_has_its_onset_above_the_range_and_round_off_is_zero():
    """A size zero at every level but for round-off (1e-17 m, as a relaxed elastic plate's dent) beside a real dent at
    the highest level only: its onset is bracketed by the last two levels and falls back to the first positive level
    (no second one to extrapolate from); a size that stays at round-off everywhere is above the range."""
    level = ENERGIES
    dent = np.array([1e-17, -2e-17, 3e-17, 1e-17, 4e-4])
    flat = np.full(5, 1e-17)
    rows = sweep_stats.onsets(level, [""] * 5, np.zeros(5), {"a_m": dent, "b_m": flat}, quantity="energy", unit="J")
    assert rows[0]["onset_energy_median_J"] == 50.0 and rows[0]["onset_energy_last_zero_J"] == 40.0
    assert rows[1]["onset_energy_median_bound"] == sweep_stats.ABOVE


def test_each_row_counts_the_runs_it_rests_on_outside_validity():
    """A threshold rests on the two runs bracketing its crossing (30 and 40 J), an onset on those and the next one
    used to extrapolate (20, 30 and 40 J): a flag on the 40-J run counts in both, one on the 50-J run in neither."""
    level, draws, s = _grid([E0])
    flags = [[], [], [], ["contact_past_run_end"], ["law_extrapolated_velocity"]]
    (th,) = sweep_stats.thresholds(level, [""] * 5, draws, {"d_m": s / 25e-6}, quantity="energy", unit="J", flags=flags)
    (on,) = sweep_stats.onsets(level, [""] * 5, draws, {"d_m": s}, quantity="energy", unit="J", flags=flags)
    assert (th["runs_used"], th["runs_outside_validity"], th["validity_flags"]) == (2, 1, ["contact_past_run_end"])
    assert (on["runs_used"], on["runs_outside_validity"], on["validity_flags"]) == (3, 1, ["contact_past_run_end"])


def test_velocity_rows_keep_their_column_names():
    """Against a velocity (the default) the columns are today's: threshold_velocity_<q>_m_s, lowest_level_m_s, ..."""
    (row,) = sweep_stats.thresholds(np.array([1.0, 2.0]), ["", ""], np.zeros(2), {"damage.tsai_wu": np.array([0.5, 1.5])})
    assert row["threshold_velocity_median_m_s"] == 1.5
    assert {"lowest_level_m_s", "highest_level_m_s", "threshold_velocity_p05_bound", "draws_reaching_1"} <= set(row)


# --- the spec's keys -----------------------------------------------------------------------------------------------

SPEC = {
    "sweep": {
        "case": "paper-long-beam-impact",
        "method": "grid",
        "outputs": ["peak_force_N", "damage.max_strain", "max_approach_m"],
        "parameter": [{"key": "impactor.diameter", "values": ["0.25 in", "0.5 in"]}, {"key": "impactor.velocity", "values": ["1000 in/s", "2000 in/s"]}],
    }
}


def _read(**sweep):
    import copy
    from pathlib import Path

    from softimpact.input.sweep_spec import read_sweep_spec

    data = copy.deepcopy(SPEC)
    data["sweep"].update(sweep)
    return read_sweep_spec(data, Path("."))


@pytest.mark.parametrize(
    "output, given, si",
    [
        ("max_approach_m", "0.25 mm", 2.5e-4),
        ("max_approach_m", "0.01 in", 2.54e-4),
        ("peak_force_N", "2 kN", 2000.0),
        ("peak_force_N", "100 lbf", 100 * 4.4482216152605),
        ("damage.max_strain", 0.8, 0.8),
    ],
)
def test_a_limit_is_read_in_the_outputs_own_unit(output, given, si):
    """A limit is converted to the SI unit of its output's suffix (_m: 0.25 mm → 2.5e-4 m; _N: lbf → N); an output
    without a unit (an index) takes a plain number."""
    (lim,) = _read(limits={output: given}).limits
    assert (lim.output, lim.given) == (output, given) and lim.value == pytest.approx(si, rel=1e-12)


def test_an_area_limit_and_bare_dotted_keys():
    """ "100 mm^2" on an _m2 output is 1e-4 m²; a limit written as a bare dotted TOML key (nested tables) is the same key."""
    from softimpact.input.sweep_spec import _limit

    assert _limit("damage.projected_delamination_area_m2", "100 mm^2", "k").value == pytest.approx(1e-4, rel=1e-12)
    (lim,) = _read(limits={"damage": {"max_strain": 2}}).limits
    assert lim.output == "damage.max_strain" and lim.value == 2.0


@pytest.mark.parametrize(
    "sweep, words",
    [
        ({"limits": {"max_approach_m": "0.25 J"}}, ["sweep.limits.max_approach_m", "'0.25 J'", "m"]),
        ({"limits": {"max_approach_m": "0.25"}}, ["sweep.limits.max_approach_m", "'0.25'"]),
        ({"limits": {"max_approach_m": "-1 mm"}}, ["sweep.limits.max_approach_m", "positive", "'-1 mm'"]),
        ({"limits": {"damage.max_strian": 1.2}}, ["sweep.limits.damage.max_strian", "did you mean 'damage.max_strain'"]),
        ({"limits": {"damage.max_strain": "1 mm"}}, ["sweep.limits.damage.max_strain", "plain number", "'1 mm'"]),
        ({"threshold_against": "impactor.diametre"}, ["sweep.threshold_against", "did you mean 'impactor.diameter'"]),
        ({"onset": ["damage.dent_m"]}, ["sweep.onset", "'damage.dent_m'", "not one of sweep.outputs"]),
    ],
)
def test_bad_threshold_keys_are_refused_naming_the_key(sweep, words):
    """A limit in the wrong unit, without one, not positive, or on an output not swept; a threshold_against that is not
    a level; an onset of an output not swept: refused before any run, naming the user's key and echoing the value."""
    with pytest.raises(InputError) as exc:
        _read(**sweep)
    for w in words:
        assert w in str(exc.value)


def test_the_axis_is_named_from_its_key():
    """threshold_against names the columns' quantity and unit: impactor.diameter → diameter in m; a hail threat's size
    (impactor.threat.hail) → diameter; no threshold_against → the velocity level in m/s."""
    import dataclasses

    from softimpact.cases.sweep import threshold_axis
    from softimpact.input.sweep_spec import Level

    spec = _read(threshold_against="impactor.diameter")
    assert (threshold_axis(spec).quantity, threshold_axis(spec).suffix) == ("diameter", "m")
    assert (threshold_axis(_read()).quantity, threshold_axis(_read()).suffix) == ("velocity", "m_s")
    hail = dataclasses.replace(spec, threshold_against="impactor.threat.hail", parameters=(Level("impactor.threat.hail", ("1 in",), (0.0254,), "m"),))
    assert (threshold_axis(hail).quantity, threshold_axis(hail).suffix) == ("diameter", "m")
    energy = dataclasses.replace(spec, threshold_against="impactor.energy", parameters=(Level("impactor.energy", ("30 J",), (30.0,), "J"),))
    assert (threshold_axis(energy).quantity, threshold_axis(energy).suffix) == ("energy", "J")


# --- end to end ----------------------------------------------------------------------------------------------------

E2E = """
[sweep]
case = "impact.toml"
method = "grid"
outputs = ["peak_force_N", "damage.max_strain"]
threshold_against = "impactor.diameter"
[sweep.limits]
peak_force_N = "{limit}"
[[sweep.parameter]]
key = "impactor.diameter"
values = ["0.2 in", "0.35 in", "0.5 in"]
"""


def test_a_sweep_gives_the_diameter_where_the_peak_force_reaches_a_limit(tmp_path):
    """si.sweep of a diameter grid of a steel ball on the coarse long beam with a 1000-lbf limit on the peak force: the
    result's thresholds.csv and summary give the diameter where the straight line between the two bracketing runs' peak
    forces (from the run table) reaches 1000 lbf, under threshold_diameter_median_m, with the limit as written; its line
    (the command's) shows it in the case's display units (in) with the limit; the row counts the two runs it rests on
    that are outside validity."""
    import io

    import pyarrow.parquet as pq

    import softimpact as si

    (tmp_path / "beam.toml").write_text(COARSE_LONG_BEAM)
    case = LONG_BEAM_IMPACT.format(velocity="2000 in/s").replace('"paper-long-beam"', '"beam.toml"').replace('"300 us"', '"150 us"')
    (tmp_path / "impact.toml").write_text(case)
    (tmp_path / "spec.toml").write_text(E2E.format(limit="1000 lbf"))
    res = si.sweep(tmp_path / "spec.toml", out=tmp_path / "out", workers=0, figures=False)
    table = pq.read_table(io.BytesIO(res.outcome.files["runs.parquet"])).to_pydict()
    d, f = np.array(table["impactor.diameter"]), np.array(table["peak_force_N"]) / (1000 * 4.4482216152605)
    j = int(np.flatnonzero(f >= 1.0)[0])
    assert j > 0  # the premise: the limit is bracketed by the swept diameters
    expected = d[j - 1] + (1.0 - f[j - 1]) * (d[j] - d[j - 1]) / (f[j] - f[j - 1])
    row = next(t for t in res.summary()["thresholds"] if t["index"] == "peak_force_N")
    assert row["threshold_diameter_median_m"] == pytest.approx(expected, rel=1e-12)
    assert (row["against"], row["quantity"], row["unit"], row["limit"]) == ("impactor.diameter", "diameter", "m", "1000 lbf")
    flagged = [table["validity_flags"][k] for k in (j - 1, j)]  # the runs it rests on, and their flags
    assert row["runs_used"] == 2 and row["runs_outside_validity"] == sum(bool(x) for x in flagged)
    assert set(row["validity_flags"]) == {n for x in flagged for n in x.split(", ") if n}
    csv_row = res.table("thresholds.csv").set_index("index").loc["peak_force_N"]
    assert csv_row["threshold_diameter_median_m"] == pytest.approx(expected, rel=1e-9) and csv_row["limit"] == "1000 lbf"
    assert f"threshold diameter peak_force_N reaching 1000 lbf: median {expected / 0.0254:.4g} in" in res.line


METAL_PLATE = """
title = "Quarter of a clamped 250 x 250 mm Al 2024-T3 panel, 2 mm, coarse"
units = "SI"
[plate]
length = "125 mm"
width = "125 mm"
elements = [4, 4]
support = { x0 = "symmetry", x1 = "clamped", y0 = "symmetry", y1 = "clamped" }
kinematics = "von-karman"
material = "Al 2024-T3"
thickness = "2 mm"
[load]
position = ["0 mm", "0 mm"]
contact_radius = "10 mm"
history = { shape = "skewed", peak_force = "2 kN", time_of_peak = "50 us", duration = "300 us" }
[solver]
time_step = "2 us"
duration = "600 us"
"""
METAL_IMPACT = """
[target]
case = "plate.toml"
[impactor]
material = "steel"
diameter = "20 mm"
velocity = "20 m/s"
[contact]
law = "hertz"
[solver]
time_step = "2 us"
duration = "600 us"
"""
DENT_SPEC = """
[sweep]
case = "impact.toml"
method = "grid"
outputs = ["damage.dent_depth_m", "damage.plastic_zone_area_m2"]
threshold_against = "impactor.diameter"
[sweep.limits]
"damage.dent_depth_m" = "0.05 mm"
[[sweep.parameter]]
key = "impactor.diameter"
values = ["10 mm", "15 mm", "20 mm"]
"""


@pytest.mark.slow  # three elastic-plastic von Karman runs: about 4 s of CPU, more on a busy machine
def test_a_metal_skin_sweep_gives_the_diameter_of_a_visible_dent_and_the_dents_onset(tmp_path):
    """Steel balls of 10, 15 and 20 mm at 20 m/s on a plastic Al skin: the 10-mm ball leaves no dent (round-off), the
    others do. The diameter where the dent reaches the user's 0.05 mm is the straight line between the bracketing runs'
    dents (from the run table); the dent's onset lies between 10 and 15 mm, where the line through the 15- and 20-mm
    dents reaches zero (clipped into that bracket); the plastic zone's area has its onset too (every damage size does)."""
    import pyarrow.parquet as pq

    (tmp_path / "plate.toml").write_text(METAL_PLATE)
    (tmp_path / "impact.toml").write_text(METAL_IMPACT)
    (tmp_path / "spec.toml").write_text(DENT_SPEC)
    out = tmp_path / "out"
    r = CliRunner().invoke(main, ["sweep", str(tmp_path / "spec.toml"), "--out", str(out), "--no-figures", "--workers", "0"])
    assert r.exit_code == 0, r.output
    table = pq.read_table(out / "runs.parquet").to_pydict()
    d, dent = np.array(table["impactor.diameter"]), np.array(table["damage.dent_depth_m"])
    assert abs(dent[0]) < 1e-12 < 5e-5 < dent[2] and dent[1] > 1e-9  # the premise: no dent, then dents across the limit
    summary = json.loads((out / "summary.json").read_text())
    (th,) = [t for t in summary["thresholds"] if t["index"] == "dent_depth_m"]
    j = 1 if dent[1] >= 5e-5 else 2
    f = dent / 5e-5
    assert th["threshold_diameter_median_m"] == pytest.approx(d[j - 1] + (1 - f[j - 1]) * (d[j] - d[j - 1]) / (f[j] - f[j - 1]), rel=1e-9)
    onset = {t["index"]: t for t in summary["onsets"]}
    x0 = d[1] - dent[1] * (d[2] - d[1]) / (dent[2] - dent[1])
    assert onset["dent_depth_m"]["onset_diameter_median_m"] == pytest.approx(min(max(x0, d[0]), d[1]), rel=1e-9)
    assert (onset["dent_depth_m"]["onset_diameter_last_zero_m"], onset["dent_depth_m"]["onset_diameter_first_positive_m"]) == (d[0], d[1])
    assert "plastic_zone_area_m2" in onset and (out / "onsets.csv").is_file()
    assert "threshold diameter dent_depth_m reaching 0.05 mm" in r.output and "onset diameter dent_depth_m" in r.output


@pytest.mark.parametrize(
    "outputs, refused",
    [
        (["damage.dent_depth_m", "damage.plastic_zone_area_m2", "damage.plastic_work_J"], None),
        (["damage.tsai_wu"], "need a laminate"),
    ],
)
def test_a_metal_skin_sweep_takes_its_dent_and_refuses_a_ply_index(tmp_path, outputs, refused):
    """An impact on a plastic metal plate sweeps its damage outputs (the dent, the plastic zone and work its runs write);
    a ply's failure index is refused before any run (a metal has no ply strengths)."""
    from softimpact.cases.sweep import plan_sweep
    from softimpact.input.sweep_spec import load_sweep_spec

    (tmp_path / "plate.toml").write_text(METAL_PLATE)
    (tmp_path / "impact.toml").write_text(METAL_IMPACT)
    (tmp_path / "spec.toml").write_text(
        DENT_SPEC.replace('["damage.dent_depth_m", "damage.plastic_zone_area_m2"]', json.dumps(outputs)).replace('"damage.dent_depth_m" = "0.05 mm"', "")
    )
    spec = load_sweep_spec(str(tmp_path / "spec.toml"))
    if refused is None:
        assert len(plan_sweep(spec).runs) == 3
    else:
        with pytest.raises(InputError, match=refused):
            plan_sweep(spec)


def test_the_threshold_figure_and_lines_name_the_level_in_display_units():
    """Rows against an energy are drawn and printed as energies in the display system's unit (SI: mJ, 35.5 J →
    35500 mJ), a limit as written and the runs outside validity counted."""
    from softimpact.app.sweep import threshold_lines
    from softimpact.output.sweep import threshold_figure

    level, draws, s = _grid([E0])
    flags = [[], [], [], ["contact_past_run_end"], []]
    th = sweep_stats.thresholds(level, [""] * 5, draws, {"damage.dent_depth_m": s / 25e-6}, quantity="energy", unit="J", flags=flags)
    th = [{**t, "against": "impactor.energy", "quantity": "energy", "unit": "J", "limit": "25 um"} for t in th]
    ax = threshold_figure(th, "SI").axes[0]
    assert ax.get_ylabel() == "threshold energy [mJ]" and ax.lines[0].get_ydata()[0] == pytest.approx(35500.0)
    line = threshold_lines(th, "SI")
    assert line.startswith("threshold energy dent_depth_m reaching 25 um: median 3.55e+04 mJ")
    assert "1 of its 2 runs outside validity (contact_past_run_end)" in line


@pytest.mark.parametrize(
    "sweep, words",
    [
        ({"threshold_against": "impactor.diameter", "outputs": ["peak_force_N"]}, "no output has a threshold"),
        ({"limits": {"peak_force_N": "1 kN"}, "parameter": [{"key": "impactor.diameter", "values": ["0.25 in", "0.5 in"]}]}, "sweep.limits: a threshold"),
    ],
)
def test_threshold_keys_that_would_give_nothing_are_refused(sweep, words):
    """threshold_against with no output to find a threshold or onset of, and a limit with no level to find it against
    (no velocity level, no threshold_against), are refused before any run rather than silently giving no rows."""
    from softimpact.cases.sweep import plan_sweep

    with pytest.raises(InputError, match=words):
        plan_sweep(_read(**sweep))
