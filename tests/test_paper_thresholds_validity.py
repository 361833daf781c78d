"""The threshold maps' validity columns in the report's files: the CSV cells of the flags and of inside_validity, and
the figures' open markers for the rows outside validity."""

import csv
import math

import matplotlib
import pytest

from softimpact.output.sweep import kinematics_map_figure, threshold_csv, threshold_map_figure

matplotlib.use("Agg")


def _row(kinematics, index, d, v, inside, flags=()):
    """A map row as MapRow.as_dict writes it (the fields the files read)."""
    return {
        "structure": "plate",
        "index": index,
        "diameter_m": d,
        "threshold_velocity_nominal_m_s": v,
        "threshold_velocity_median_m_s": v,
        "threshold_velocity_p05_m_s": 0.9 * v,
        "threshold_velocity_p95_m_s": 1.1 * v,
        "discretisation_error_m_s": 0.01 * v,
        "kinematics": kinematics,
        "band_from": "own draws" if kinematics == "linear" else "linear map",
        "deflection_over_thickness": 0.3 if inside else 0.7,
        "validity_flags": list(flags),
        "inside_validity": inside,
    }


ROWS = [
    _row("linear", "tsai_wu", 0.01, 100.0, True),
    _row("linear", "tsai_wu", 0.02, 80.0, False, ("deflection_past_linear", "contact_past_projectile_radius")),
    _row("von-karman", "tsai_wu", 0.01, 99.0, True),
    _row("von-karman", "tsai_wu", 0.02, 81.0, False, ("contact_past_projectile_radius",)),
    _row("linear", "delamination", 0.01, math.nan, None),
]


def test_the_csv_writes_the_flags_by_name_and_inside_validity_as_true_false_or_empty():
    """validity_flags reads back as the names joined by ", " and inside_validity as true, false or empty (no threshold)."""
    back = list(csv.DictReader(threshold_csv(ROWS).splitlines()))
    assert [r["validity_flags"] for r in back] == ["", "deflection_past_linear, contact_past_projectile_radius", "", "contact_past_projectile_radius", ""]
    assert [r["inside_validity"] for r in back] == ["true", "false", "true", "false", ""]
    assert [r["kinematics"] for r in back] == ["linear", "linear", "von-karman", "von-karman", "linear"]
    assert float(back[1]["deflection_over_thickness"]) == pytest.approx(0.7)


@pytest.mark.parametrize("draw", ["map", "kinematics"])
def test_the_figures_mark_every_row_outside_validity_with_an_open_marker(draw):
    """Each figure draws one open marker per threshold outside validity and a filled one per threshold inside."""
    rows = ROWS[:4]
    fig = threshold_map_figure(rows, [], "SI", "t") if draw == "map" else kinematics_map_figure(rows, "SI", "t")
    markers = [ln for ax in fig.axes for ln in ax.get_lines() if ln.get_linestyle() in ("None", "none", "") and ln.get_marker() not in (None, "None", "")]
    open_points = sum(len(ln.get_xdata()) for ln in markers if ln.get_markerfacecolor() == "none")
    filled_points = sum(len(ln.get_xdata()) for ln in markers if ln.get_markerfacecolor() != "none")
    assert open_points == sum(r["inside_validity"] is False for r in rows)
    assert filled_points == sum(r["inside_validity"] is True for r in rows)
