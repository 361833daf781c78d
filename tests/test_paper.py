"""`softimpact paper`: the whole paper into one report — every figure and table present — and the physics of
the report's own sections (the paper's question, the beams as plates, the damage thresholds) read from the files
of the one run the whole test session shares (the ``paper_report`` fixture, tests/_support/paper.py)."""

import base64
import csv
import re

import numpy as np
import pytest

from softimpact.input.beam_case import load_beam_case
from softimpact.studies.references import at_free_length, first_zero_crossing
from softimpact.workflows.beam_impact import BeamModel

from _support.constants import INCH, LBF
from _support.problems import TABLE_II, TABLE_III, table_i_pulse

pytestmark = pytest.mark.slow  # the whole paper: about 100 s on a quiet machine, computed once per test run


@pytest.mark.parametrize(
    "fig",
    ["Fig 4", "Fig 5", "Fig 6", "Fig 7", "Figs 8 and 12", "Figs 9 and 13", "Figs 10 and 14", "Figs 11 and 15", "Fig 18", "Fig 20", "Figs 21-22", "Figs 23-25"],
)
def test_every_figure_is_in_the_report(paper_report, fig):
    """Each of the paper's figures is captioned in report.html."""
    assert fig in paper_report.html


# The paper's Table I (α1, α2, α3, α4; α3 of the 1/2-in ball lost); Tables II and III are _support.problems'.
TABLE_I = {"0.375 in": (4.00, 1.03, 0.25, 0.74), "0.5 in": (4.25, 0.93, None, 0.66)}


@pytest.mark.parametrize(("group", "constant"), [(g, i) for g in TABLE_I for i in range(4) if TABLE_I[g][i] is not None])
def test_table_I_in_the_report_is_the_papers(paper_report, group, constant):
    """The report's fitted Table I (the synthetic series made from Table I, 1 % noise) is the paper's: α1, α2, α4 within 3 %, α3 within 10 %."""
    html = paper_report.html
    table = html[html.index("<caption>Table I: scaling constants") :]
    table = table[: table.index("</table>")]
    fitted = {(g, a): float(v) for g, a, v in re.findall(r"<tr><td>([^<]+)</td><td>alpha(\d)</td><td>([0-9.]+)</td>", table)}
    assert fitted[(group, str(constant + 1))] == pytest.approx(TABLE_I[group][constant], rel=0.10 if constant == 2 else 0.03)


@pytest.mark.parametrize(("beam", "table"), [("long", TABLE_II), ("short", TABLE_III)])
def test_calibrated_histories_are_tables_II_and_III(paper_report, beam, table):
    """The calibrations of the report (synthetic strains made from Tables II/III, 1.5 % noise) give back the paper's F0 within 5 % and T within 5 %."""
    import csv

    rows = list(csv.DictReader((paper_report.out / f"calibration-{beam}" / "tables.csv").read_text().splitlines()))
    assert len(rows) == len(table)
    for row, (V, F0, _, T, _) in zip(rows, table):
        assert float(row["velocity_m_s"]) == pytest.approx(V * INCH, rel=1e-3)
        assert float(row["peak_force_N"]) / LBF == pytest.approx(F0, rel=0.05)
        assert float(row["duration_s"]) * 1e6 == pytest.approx(T, rel=0.05)


def test_every_image_is_embedded_and_written(paper_report):
    """Every <img> of the report is an embedded PNG (the page opens on its own when mailed), also written beside it."""
    html = paper_report.html
    images = re.findall(r"<img src='data:image/png;base64,([^']+)' alt='([^']*)'", html)
    assert len(images) >= 20 and len(images) == html.count("<img ")
    for data, _ in images:
        assert base64.b64decode(data)[:4] == b"\x89PNG"
    assert len(list(paper_report.out.rglob("*.png"))) >= len(images)


@pytest.mark.parametrize("table", ["Table I", "Table II", "Table III"])
def test_tables(paper_report, table):
    """Table I (fitted beside the paper's) and Tables II, III (the paper's beside ours) are in the report."""
    assert table in paper_report.html


def test_assumptions_and_synthetic_labels(paper_report):
    """The report lists the assumptions of docs/modelling-notes.md and labels synthetic data as such."""
    html = paper_report.html
    assert "Assumptions and errata" in html and html.count("SYNTHETIC") >= 2


def test_threshold_curves_of_the_beams_and_a_plate(paper_report):
    """Issue 13: threshold velocities of the paper's beams and of a plate are in the report (figure and
    CSV each). The delamination index depends on the force alone (the ball's law) and the laminate's P_c,
    so the plate's delamination threshold is the beams'; the heavier 1/2-in ball reaches every index
    at a lower velocity than the 3/8-in one."""
    out, html = paper_report.out, paper_report.html
    assert "Damage thresholds of the paper" in html and "beams and of a plate" in html
    rows = {}
    for name in ("thresholds", "plate-thresholds"):
        assert (out / "thresholds" / f"{name}.png").is_file()
        for r in csv.DictReader((out / "thresholds" / f"{name}.csv").read_text().splitlines()):
            rows[(r["levels"], r["index"])] = float(r["threshold_velocity_median_m_s"])
    plate = {k: v for k, v in rows.items() if k[0].startswith("8-in plate")}
    assert len(plate) == 8 and all(1000 * INCH <= v <= 8000 * INCH for v in plate.values())
    for ball in ("rubber-3/8in", "rubber-1/2in"):
        assert plate[(f"8-in plate, {ball}", "delamination")] == pytest.approx(rows[(f"long beam, {ball}", "delamination")], rel=1e-9)
    for index in ("max_strain", "tsai_wu", "hashin", "delamination"):
        assert plate[("8-in plate, rubber-1/2in", index)] < plate[("8-in plate, rubber-3/8in", index)]


# ---- the paper's question: the force on the beams from the bar tests alone (question section) --------------


def _numbers(cell: str) -> list[float]:
    """The numbers of a table cell as displayed: '35 (-20%)' → [35.0, -20.0]."""
    return [float(x) for x in re.findall(r"[-+]?\d+(?:\.\d+)?", cell)]


def _question_rows(paper_report, table: str) -> list[list[str]]:
    (rows,) = [rows for caption, (_, rows) in paper_report.tables().items() if caption.startswith(f"Table {table} (")]
    return rows


@pytest.mark.parametrize("table, paper", [("II", TABLE_II), ("III", TABLE_III)], ids=["Table II", "Table III"])
def test_question_tables_show_the_paper_rows_and_the_bar_law(paper_report, table, paper):
    """The report's predicted Tables II and III: the paper's rows as printed in the paper (V, F0, tF0, T, r0),
    the carried-over bar law at eqs (4)-(6) with Table I (1/2-in ball, 1.1 g: α1 = 4.25, α2 = 0.93,
    α3 = 0.25) computed here, and each prediction's error written against the paper's value."""
    rows = _question_rows(paper_report, table)
    assert len(rows) == 4
    for row, (V, F0, tF0, T, r0) in zip(rows, paper):
        assert [_numbers(row[k])[0] for k in (0, 1, 4, 7, 10)] == [V, F0, tF0, T, r0]
        bar_F0, bar_tF0, bar_T, _ = table_i_pulse(0.5 * INCH, V * INCH)
        for cell, ours, ref in ((row[3], bar_F0 / LBF, F0), (row[6], bar_tF0 * 1e6, tF0), (row[9], bar_T * 1e6, T)):
            shown, err = _numbers(cell)
            assert shown == pytest.approx(ours, abs=0.5 + 1e-9)  # displayed to the unit
            assert err == pytest.approx(100 * (ours / ref - 1), abs=1.5)  # to the percent, from the rounded value
        for k, ref in ((2, F0), (5, tF0), (8, T)):
            shown, err = _numbers(row[k])
            # the error is of the unrounded value: half a unit of the shown one, and half a percent of its own rounding
            assert err == pytest.approx(100 * (shown / ref - 1), abs=100 * 0.5 / ref + 0.5 + 1e-9)


@pytest.mark.parametrize("table", ["II", "III"])
def test_question_coupled_prediction_keeps_the_bar_law(paper_report, table):
    """The coupled ball-beam prediction with the law identified from the bar tests: the compliant beam gives way,
    so its peak is below the bar law's (eq 4, Table I) but within 10 % of it (measured 5-8 %); and the force keeps the
    bar tests' skew, tF0/T between Table I's α3 = 0.25 and 0.33 (measured 0.26-0.32), never the paper's
    Tables' early peak (tF0/T of 0.06-0.09: at least three times less)."""
    paper = {"II": TABLE_II, "III": TABLE_III}[table]
    for row, (V, _, tF0p, Tp, _) in zip(_question_rows(paper_report, table), paper):
        F0, tF0, T = (_numbers(row[k])[0] for k in (2, 5, 8))
        bar_F0 = table_i_pulse(0.5 * INCH, V * INCH)[0] / LBF
        assert 0.90 * bar_F0 < F0 < bar_F0
        assert 0.25 - 0.01 <= tF0 / T <= 0.33  # displayed to the microsecond: 0.01 of rounding at 32/113
        assert tF0 / T > 3 * tF0p / Tp


def test_question_closure_recovers_the_law_that_made_the_bar_series(paper_report):
    """The report's law, identified from the synthetic rubber-ball series and run on the coupled bar
    (question/closure.csv), reproduces eqs (4)-(7) with Table I, the law the series was made with:
    I within 1.5 %, T within 4 %, tF0 within 3 %, F0 within 8 % (measured 0.8, 2.9, 1.8, 6.6 %; see
    test_cli_identify for why the peak sits above Table I's)."""
    rows = list(csv.DictReader((paper_report.out / "question" / "closure.csv").read_text().splitlines()))
    assert len(rows) == 13
    for row in rows:
        F0, tF0, T, I = table_i_pulse(float(row["diameter_m"]), float(row["velocity_m_s"]))
        assert float(row["simulated_impulse_N_s"]) == pytest.approx(I, rel=0.015)
        assert float(row["simulated_duration_s"]) == pytest.approx(T, rel=0.04)
        assert float(row["simulated_time_of_peak_s"]) == pytest.approx(tF0, rel=0.03)
        assert float(row["simulated_peak_force_N"]) == pytest.approx(F0, rel=0.08)
    assert (paper_report.out / "question" / "law.json").is_file()


# ---- the plane-strain assumption: the beams as 1-inch-wide plates (beam-as-plate section) -------------------


def test_beam_as_plate_layered_beam_agrees_with_the_plate(paper_report):
    """The report's beam-as-plate table: 2 beams × 4 histories × 2 gauges. The plane-strain beam with the real
    stacking (layered 2-D elasticity, an independent model) and the FSDT strip agree on the peak gauge strains
    within 7 % (measured ≤ 6.1 %) and within 1 % for history 1, while the smeared beam, 15 % too stiff in
    bending, is off by more than 7 % somewhere. (The table shows the differences to 0.1 %, far from these bounds.)"""
    (rows,) = [rows for caption, (_, rows) in paper_report.tables().items() if caption.startswith("Peak gauge strain of the plate")]
    assert len(rows) == 16
    smeared = np.array([_numbers(r[3])[0] for r in rows])
    layered = np.array([_numbers(r[4])[0] for r in rows])
    first = np.array(["history 1" in r[0] for r in rows])
    assert first.sum() == 4
    assert np.all(np.abs(layered) < 7) and np.all(np.abs(layered[first]) < 1)
    assert np.max(np.abs(smeared)) > 7


def test_question_text_states_what_its_synthetic_bar_series_cannot_decide(paper_report):
    """The report no longer argues in a circle: the bar series is Table I made into records (α3 = 0.25 put in),
    so it neither supports nor refutes α3; the coupled t_F0 is stated as conditional on it; the tables' own
    inconsistencies are given (F0 ∝ V^1.64 / V^1.45, floors 18.2 % and 10.3 %, computed in the code from the tables)."""
    html = paper_report.html
    assert "no law faithful" not in html
    assert "neither support nor refute α3" in html and "conditional on it" in html
    assert "V^1.64" in html and "V^1.45" in html and "18.2%" in html and "10.3%" in html


# The threshold maps (issue 21) and the references sections (issue 22) of the shared report: in this file so that one
# worker holds every test of the session's paper run (another file would block a second worker while it is computed).


def test_the_report_shows_threshold_maps_that_differ_between_the_structures(paper_report):
    """The paper report's maps: three structures × two indices × four diameters, every band containing its median and wider
    than twice the mesh's GCI; first-ply thresholds of the 1/2-in ball differ between long beam, short beam and plate by more
    than their bands' discretisation parts (the structures' bending differs), while delamination, set by the ball's peak force, differs by under 5 %."""
    import csv

    out = paper_report.out
    assert (out / "thresholds" / "threshold-maps.png").is_file()
    rows = list(csv.DictReader((out / "thresholds" / "threshold-maps.csv").read_text().splitlines()))
    assert len(rows) == 24 and {r["structure"] for r in rows} == {"long beam", "short beam", "8-in plate"}
    for r in rows:
        med, lo, hi, gci = (
            float(r[k]) for k in ("threshold_velocity_median_m_s", "threshold_velocity_p05_m_s", "threshold_velocity_p95_m_s", "discretisation_error_m_s")
        )
        assert lo < med < hi and hi - lo >= 2 * gci
    half = {(r["structure"], r["index"]): r for r in rows if abs(float(r["diameter_m"]) - 0.5 * INCH) < 1e-9}
    tw = sorted(float(half[(s, "tsai_wu")]["threshold_velocity_median_m_s"]) for s in ("long beam", "short beam", "8-in plate"))
    gci = max(float(half[(s, "tsai_wu")]["discretisation_error_m_s"]) for s in ("long beam", "short beam", "8-in plate"))
    assert min(np.diff(tw)) > gci
    de = [float(half[(s, "delamination")]["threshold_velocity_median_m_s"]) for s in ("long beam", "short beam", "8-in plate")]
    assert max(de) / min(de) - 1 < 0.05


def _table(paper_report, start: str):
    (table,) = [t for caption, t in paper_report.tables().items() if caption.startswith(start)]
    return table


def test_what_if_table_scores_against_the_papers_rows(paper_report):
    """The what-if table lists the 8 rows of Tables II and III as printed in the paper (V, t_F0, F0, T), each prediction's
    error against them, and a mean |error| row that is the mean of the row errors (to their rounding)."""
    header, rows = _table(paper_report, "What-if:")
    assert len(rows) == 9 and rows[-1][0] == "mean |error|"
    errors = []
    for row, (V, F0, tF0, T, _) in zip(rows, TABLE_II + TABLE_III):
        assert [_numbers(row[k])[0] for k in (1, 2, 5, 8)] == [V, tF0, F0, T]
        for k, ref in ((3, tF0), (4, tF0), (6, F0), (7, F0), (9, T), (10, T)):
            shown, err = _numbers(row[k])
            assert err == pytest.approx(100 * (shown / ref - 1), abs=100 * 0.5 / ref + 0.5 + 1e-9)
        errors.append([abs(_numbers(row[k])[1]) for k in (3, 4, 6, 7, 9, 10)])
    means = np.mean(errors, axis=0)
    shown = [_numbers(rows[-1][k])[0] for k in (3, 4, 6, 7, 9, 10)]
    assert shown == pytest.approx(means, abs=1.0)


def test_what_if_moves_t_F0_toward_the_tables(paper_report):
    """Bar data with the tables' skew (α3 ≈ 0.085 instead of 0.25, a third of it) give coupled peaks at least twice as
    close to the tables' t_F0 on average: the coupled t_F0 follows the bar data's α3."""
    _, rows = _table(paper_report, "What-if:")
    base, alt = _numbers(rows[-1][3])[0], _numbers(rows[-1][4])[0]
    assert alt < base / 2
    assert "what-if, not a validation" in paper_report.html


def test_crossing_table_free_length_matches_450_us(paper_report):
    """The free length the report gives for the long beam, re-run here through BeamModel (impact at mid-length, gauge 1
    1 in from it), crosses at 450 µs within 3 µs (the length is shown to 0.01 in: about 2 µs of crossing)."""
    _, rows = _table(paper_report, "First zero crossing of gauge 1")
    (long_row,) = [r for r in rows if r[0].startswith("long")]
    assert not long_row[4].startswith("none"), long_row[4]
    length = _numbers(long_row[4])[0] * INCH
    problem = at_free_length(load_beam_case("paper-long-beam", 1)[0], length)
    r = BeamModel(problem).direct(energy=False, displacement=False)
    assert first_zero_crossing(r.time, r.bending[0]) == pytest.approx(450e-6, abs=3e-6)
    assert "approximately 450 µs in fig. 21" in paper_report.html


def test_calibrations_outside_linear_theory_are_warned_and_noted(paper_report):
    """The long beam's calibrated histories deflect it past linear theory's w/h = 0.5 where the `beam` command
    flags the paper's own Table II histories (2-4: the same tests, their histories made the synthetic strains):
    the paper's manifest lists one warning per such test, within 5 % of the command's w/h, and the report says so."""
    import json

    from click.testing import CliRunner

    from softimpact.cli import main

    manifest = json.loads((paper_report.out / "manifest.json").read_text())
    flagged = {}
    for w in manifest["warnings"]:
        m = re.search(r"calibration of the long beam, test (\S+): the deflection reaches ([\d.]+) times", w)
        if m:
            flagged[m.group(1)] = float(m.group(2))
    command = []
    for history in (1, 2, 3, 4):
        result = CliRunner().invoke(
            main, ["beam", "paper-long-beam", "--history", str(history), "--out", str(paper_report.out.parent / f"h{history}"), "--no-figures"]
        )
        m = re.search(r"the deflection reaches ([\d.]+) times", result.output)
        command.append(float(m.group(1)) if m else None)
    assert [c is not None for c in command] == [False, True, True, True]
    assert sorted(flagged) == ["long-V1932", "long-V3058", "long-V4026"]
    for ratio, name in zip(command[1:], ("long-V1932", "long-V3058", "long-V4026")):
        assert flagged[name] == pytest.approx(ratio, rel=0.05)
    assert "Outside linear theory" in paper_report.html


def test_the_report_opens_with_contents_summary_and_has_alt_text(paper_report):
    """report.html has a summary of results (Table I, the calibrations' F0, the thresholds, the discretisation error, the
    warning count: as many as the manifest lists) and a contents list before the first section, each linking to an
    existing anchor, and every <img> has a non-empty alt."""
    import json
    from html.parser import HTMLParser

    class Page(HTMLParser):
        def __init__(self):
            super().__init__()
            self.ids, self.hrefs, self.alts = [], [], []

        def handle_starttag(self, tag, attrs):
            a = dict(attrs)
            self.ids += [a["id"]] if "id" in a else []
            self.hrefs += [a["href"]] if tag == "a" and a.get("href", "").startswith("#") else []
            self.alts += [a.get("alt")] if tag == "img" else []

    page = Page()
    page.feed(paper_report.html)
    head = paper_report.html[: paper_report.html.index("<h2 id='contents'>")]
    assert "Summary of results" in head
    for what in ("Table I, 0.375 in", "F0 of the long beam", "F0 of the short beam", "Threshold maps", "Discretisation error"):
        assert what in head, what
    n = len(json.loads((paper_report.out / "manifest.json").read_text())["warnings"])
    assert f"{n} warning{'' if n == 1 else 's'} raised by the run" in head
    assert page.ids.index("summary") < page.ids.index("contents") < page.ids.index("warnings-of-the-run")
    assert page.hrefs and all(h.removeprefix("#") in page.ids for h in page.hrefs)
    assert page.alts and all(alt and alt.strip() for alt in page.alts)


def test_warnings_section_counts_every_flagged_row_of_the_maps(paper_report):
    """The report's warnings section lists as many rows outside validity as the run's map CSVs flag (threshold maps,
    onset map, the plate's map on both kinematics, the hail map on both), each once per map."""
    import html

    names = ["thresholds/threshold-maps.csv", "thresholds/onset-map.csv", "hail/hail-map.csv", "hail/hail-map-von-karman.csv"]
    flagged = 0
    for name in names:
        with open(paper_report.out / name, newline="") as fh:
            flagged += sum(1 for r in csv.DictReader(fh) if r["validity_flags"] not in ("", "[]"))
    with open(paper_report.out / "thresholds/plate-kinematics-map.csv", newline="") as fh:  # both kinematics' rows in one file
        flagged += sum(1 for r in csv.DictReader(fh) if r["validity_flags"] not in ("", "[]"))
    listed = set(re.findall(r"data-row='([^']*)'", paper_report.html))
    assert len(listed) == flagged > 0
    assert f"{flagged} rows of 6 maps outside the models' validity" in html.unescape(paper_report.html)
