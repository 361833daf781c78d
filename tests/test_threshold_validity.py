"""Threshold maps inside the physics: each row's validity at its threshold equals what the single impact command
reports there, and a map on a von Kármán plate finds the threshold a bisection over single nonlinear runs finds."""

import json
import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact.app.paper.thresholds import PAPER_PLATE, paper_plate_case
from softimpact.cases.impact import ImpactKind
from softimpact.cli import main
from softimpact.formats.law_json import read_law
from softimpact.input.plate_case import plate_problem
from softimpact.input.toml import locate
from softimpact.models.materials import lookup
from softimpact.studies import thresholds as T

INCH = 0.0254
LAW = Path(__file__).parent / "data" / "law-v-main.json"
RHO = lookup("silicone rubber").density  # the balls' material: the map's density and the impact case's


def _toml(value) -> str:
    """A TOML value (strings, numbers, booleans, lists, inline tables): the plate case written back for the command."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, list):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    return "{ " + ", ".join(f"{k} = {_toml(v)}" for k, v in value.items()) + " }"


def _write_case(folder: Path, data: dict) -> Path:
    """``data`` (a case dict) as a TOML file in ``folder``: top-level keys, then each table's keys (nested tables inline)."""
    lines = [f"{k} = {_toml(v)}" for k, v in data.items() if not isinstance(v, dict)]
    for name, table in data.items():
        if isinstance(table, dict):
            lines += [f"[{name}]"] + [f"{k} = {_toml(v)}" for k, v in table.items()]
    path = folder / "target.toml"
    path.write_text("\n".join(lines) + "\n")
    return path


def _impact_case(folder: Path, diameter: float, velocity: float, time_step: str, duration: str) -> Path:
    """An impact case on ``folder``/target.toml: a silicone-rubber ball under the identified law of ``LAW``."""
    case = folder / "impact.toml"
    case.write_text(
        f"""title = "threshold-map row checked by the impact command"
units = "SI"
[target]
case = "target.toml"
[impactor]
material = "silicone rubber"
diameter = "{diameter!r} m"
velocity = "{velocity!r} m/s"
[contact]
law = "identified"
law_file = "{LAW}"
[solver]
time_step = "{time_step}"
duration = "{duration}"
"""
    )
    return case


def _plate(elements: int, kinematics: str, duration: str) -> dict:
    """The report's quarter of the 8-in plate (MITC4, symmetry edges, struck at the centre) on ``elements`` a side."""
    data = paper_plate_case(elements, duration)
    data["plate"]["kinematics"] = kinematics
    return data


@pytest.fixture(scope="module")
def linear_row(tmp_path_factory):
    """A Tsai–Wu row of the linear quarter plate (8 × 8 MITC4, 2 µs, 400 µs) for the 3/4-in ball (past w/h = 0.5 at its threshold)."""
    data = _plate(8, "linear", "400 us")
    law = read_law(LAW)
    s = T.structure("plate", plate_problem(data, locate(PAPER_PLATE).parent), 0.75 * INCH, RHO, 2e-6, 400e-6, law)
    (row,) = T.threshold_map(s, law, [0.75 * INCH], 200 * INCH, 20000 * INCH, draws=0, strength_quantiles=3, indices=("tsai_wu",))
    folder = tmp_path_factory.mktemp("row")
    _write_case(folder, data)
    return row, folder, (s, law)


def test_a_rows_validity_columns_equal_the_impact_commands_summary_at_its_threshold(linear_row):
    """Every validity ratio of a map row (kernel runs) equals summary.json's of `softimpact impact` run at the row's V* (direct stepping),
    to 1e-9, and the row raises as many flags as the command (its validity's and its warnings on the law's range)."""
    row, folder, _ = linear_row
    case = _impact_case(folder, row.diameter, row.nominal, "2 us", "400 us")
    out = folder / "out"
    result = CliRunner().invoke(main, ["impact", str(case), "--out", str(out), "--no-figures"])
    assert result.exit_code == 0, result.output
    validity = json.loads((out / "summary.json").read_text())["validity"]
    columns = row.as_dict()
    assert set(row.ratios) == set(validity) - {"flags"}
    for name in row.ratios:
        assert columns[name] == pytest.approx(validity[name], rel=1e-9, abs=1e-12), name
    fitted = result.output.count("it was fitted on")  # the command's warnings on the law's range (read with the law)
    # the command's run also reports the delamination criteria (its damage block), outside their regime here; a Tsai–Wu row does not
    criteria = sum("quasi-static threshold" in f for f in validity["flags"])
    assert len(row.flags) == len(validity["flags"]) - criteria + fitted
    assert columns["inside_validity"] is (not row.flags)


def test_a_row_past_the_linear_deflection_limit_says_so(linear_row):
    """The 3/4-in ball's Tsai–Wu threshold on the linear quarter plate deflects it past w/h = 0.5: the row is flagged and outside."""
    row, _, _ = linear_row
    d = row.as_dict()
    assert d["deflection_over_thickness"] > 0.5
    assert "deflection_past_linear" in d["validity_flags"]
    assert d["inside_validity"] is False
    assert d["kinematics"] == "linear" and d["band_from"] == "own draws"


def test_a_threshold_below_the_searched_range_is_flagged_not_reported_as_found(linear_row):
    """Searched from 1.2 times its threshold, the row's index is past 1 at the range's floor: V* is the floor and the row
    says so (threshold_at_range_floor), where it used to look found."""
    row, _, (s, law) = linear_row
    lo = 1.2 * row.nominal
    (floored,) = T.threshold_map(s, law, [row.diameter], lo, 20000 * INCH, draws=0, strength_quantiles=3, indices=("tsai_wu",))
    assert floored.nominal == lo
    assert "threshold_at_range_floor" in floored.flags and "threshold_at_range_floor" not in row.flags
    assert floored.as_dict()["inside_validity"] is False


@pytest.mark.slow
def test_a_nonlinear_threshold_equals_a_bisection_over_single_nonlinear_runs(tmp_path):
    """On a von Kármán quarter plate (4 × 4 MITC4, 4 µs, 240 µs) the map's delamination threshold of the 1/2-in ball equals a
    bisection over single impact runs of the case (the command's path, delamination index from its summary) to 1e-4."""
    data = _plate(4, "von-karman", "240 us")
    law = read_law(LAW)
    s = T.structure("plate", plate_problem(data, locate(PAPER_PLATE).parent), 0.5 * INCH, RHO, 4e-6, 240e-6, law)
    assert s.kernels is None and s.stepping == "von-karman"
    (row,) = T.threshold_map(s, law, [0.5 * INCH], 1000 * INCH, 20000 * INCH, draws=0, strength_quantiles=3, indices=("delamination",))
    assert row.kinematics == "von-karman" and math.isfinite(row.nominal)
    _write_case(tmp_path, data)
    kind = ImpactKind()

    def index(v):
        case = _impact_case(tmp_path, 0.5 * INCH, v, "4 us", "240 us")
        from softimpact.input.toml import load_toml

        run = kind.execute(kind.problem(load_toml(case), tmp_path), energy=False)
        return run.summary["damage"]["delamination"]

    lo, hi = 1000 * INCH, 20000 * INCH
    assert index(lo) < 1.0 <= index(hi)
    while hi / lo - 1.0 > 2e-5:
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if index(mid) < 1.0 else (lo, mid)
    assert row.nominal == pytest.approx(math.sqrt(lo * hi), rel=1e-4)


@pytest.mark.parametrize("velocity", [2.0])
def test_a_law_with_memory_on_the_von_karman_plate_recovers_the_linear_run_at_small_deflection(velocity):
    """The identified law (its Maxwell arm: a law with memory) on the von Kármán quarter plate at w/h ~ 1e-4 gives the linear
    plate's direct run (the generic loop's memory bookkeeping): the force history within 1e-9 of the peak force (the membrane term ~ (w/h)² ~ 4e-9)."""
    law = read_law(LAW)
    assert law.has_memory
    runs = {}
    for kinematics in ("linear", "von-karman"):
        data = _plate(4, kinematics, "240 us")
        s = T.structure("plate", plate_problem(data, locate(PAPER_PLATE).parent), 0.5 * INCH, RHO, 4e-6, 240e-6, law)
        problem, result = T.structure_run(s, law, 0.5 * INCH, velocity, "direct")
        runs[kinematics] = result
        assert T.run_validity(problem, result).values["deflection_over_thickness"] < 1e-4
    lin, vk = runs["linear"], runs["von-karman"]
    assert vk.peak_force == pytest.approx(lin.peak_force, rel=1e-9)
    assert np.max(np.abs(vk.force - lin.force)) < 1e-9 * lin.peak_force
