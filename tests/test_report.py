"""The HTML report's structure (output/report.py render_report): the table of contents, the summary of results
gathered from the sections' own ``summary`` lines, alt text on every figure and the run's warnings — on small
fake sections, without running the paper."""

import html
import warnings
from html.parser import HTMLParser

from softimpact.errors import SoftimpactWarning
from softimpact.output.report import Section, render_report

PNG = b"\x89PNG\r\n\x1a\n" + b"\0" * 16  # bytes that render_report embeds as a PNG


class _Page(HTMLParser):
    """The ids, the links (in order, with the list they sit in), the <img> alts and the <h2> ids of a page."""

    def __init__(self, text: str):
        super().__init__()
        self.ids, self.links, self.alts, self.h2, self.order = [], [], [], [], []
        self._ul = None
        self.feed(text)

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids.append(a["id"])
            self.order.append(a["id"])
        if tag == "h2":
            self.h2.append(a.get("id"))
        if tag == "ul" and a.get("class") == "summary":
            self._ul = "summary"
        if tag == "a" and "href" in a:
            self.links.append((self._ul, a["href"]))
        if tag == "img":
            self.alts.append(a.get("alt"))

    def handle_endtag(self, tag):
        if tag == "ul":
            self._ul = None


def _sections():
    """Two small sections, one with a summary of two results and a captioned figure, one with an uncaptioned figure."""
    a = Section("Table I: scaling constants", ["text"], [("t", ["a"], [["1"]])], [("a/fig.png", "Fig 8: F0 against V²")], ["α1 = 4.1 (paper 4.00)", "R² 0.99"])
    b = Section("Table I: scaling constants", ["more"], [], [("b/fig.png", "")])  # the same title: its anchor must still be unique
    return a, b


def test_contents_link_every_section_and_summary_links_its_own():
    """Every section's <h2> has a unique id, the contents link each of them, and each summary line links to the section it came from."""
    a, b = _sections()
    page = _Page(render_report("T", [a, b], ["a note"], {"a/fig.png": PNG}, warnings=["w one", "w two"]))
    assert len(page.ids) == len(set(page.ids))
    section_ids = [i for i in page.h2 if i not in ("summary", "contents")]
    assert len(section_ids) == 4  # two sections, the warnings, the notes
    toc = [h.removeprefix("#") for ul, h in page.links if ul is None]
    assert toc == section_ids
    summary = [h.removeprefix("#") for ul, h in page.links if ul == "summary"]
    assert summary == [section_ids[0], section_ids[0], section_ids[2]]  # a's two lines, then the warnings' count


def test_summary_comes_first_and_repeats_the_sections_lines():
    """The summary and contents precede the first section, and the summary carries each line of the sections' summaries and the warning count."""
    a, b = _sections()
    text = render_report("T", [a, b], [], {}, warnings=["w one", "w two"])
    page = _Page(text)
    assert page.order.index("summary") < page.order.index("contents") < page.order.index(page.h2[2])
    head = text[: text.index("id='contents'")]
    for line in a.summary:
        assert line in head
    assert "2 warnings raised by the run" in head


def test_every_figure_has_alt_text():
    """Each <img>, embedded or linked, captioned or not, has a non-empty alt."""
    a, b = _sections()
    page = _Page(render_report("T", [a, b], [], {"a/fig.png": PNG}))
    assert len(page.alts) == 2
    assert all(alt and alt.strip() for alt in page.alts)
    assert page.alts[0] == "Fig 8: F0 against V²"


def test_warnings_are_listed_escaped_and_none_is_said():
    """Each warning is an item of the warnings section (escaped); an empty list says so; None (not collected) gives no section."""
    a, _ = _sections()
    text = render_report("T", [a], [], {}, warnings=["deflection <0.5> & more"])
    assert "<li>deflection &lt;0.5&gt; &amp; more</li>" in text
    assert "1 warning raised by the run" in text
    assert "The run raised no warning." in render_report("T", [a], [], {}, warnings=[])
    assert "Warnings of the run" not in render_report("T", [a], [], {})


def test_paper_collects_the_steps_warnings(monkeypatch):
    """softimpact paper holds the SoftimpactWarnings its steps raise and hands them to the report and to the outcome (the manifest)."""
    import softimpact.app.paper as paper_app

    def step(figures, files):
        warnings.warn("the deflection reaches 0.7 times the thickness", SoftimpactWarning, stacklevel=1)
        return [Section("A step", ["text"], summary=["x = 1"])]

    monkeypatch.setattr(paper_app, "STEPS", (("one", step), ("two", step)))
    with warnings.catch_warnings():
        warnings.simplefilter("error", SoftimpactWarning)  # a warning not held would fail the test
        outcome = paper_app.paper(figures=False)
    assert outcome.warnings == ("the deflection reaches 0.7 times the thickness",) * 2
    assert outcome.files["report.html"].count("<li>the deflection reaches 0.7 times the thickness</li>") == 2
    assert "2 warnings raised by the run" in outcome.files["report.html"]


def test_calibration_summary_converts_and_compares_f0():
    """The calibrations' summary line gives each calibrated F0 beside the paper's in lbf (1 lbf = 4.4482216152605 N, exact by
    definition) and their largest relative difference; an uncalibrated test is left out, a test without a paper row shows '—'."""
    from types import SimpleNamespace as NS

    from softimpact.app.paper.calibrations import f0_summary

    lbf = 4.4482216152605
    items = [
        NS(test=NS(velocity=10.0), calibration=NS(peak_force=20 * lbf)),
        NS(test=NS(velocity=20.0), calibration=None),
        NS(test=NS(velocity=30.0), calibration=NS(peak_force=33 * lbf)),
    ]
    line = f0_summary(items, NS(reference=[(10.0, 25 * lbf, 0, 0, 0), (20.0, 1.0, 0, 0, 0)]), "long")
    assert "20.0 (25.0), 33.0 (—)" in line
    assert "at most 20.0% apart" in line  # |20/25 - 1|
    assert "Table II" in line


def test_threshold_headline_picks_each_structures_lowest_index_at_half_inch():
    """The threshold maps' headline gives, for the 1/2-in ball, each structure's lowest median threshold (in/s: m/s / 0.0254) and says
    'above' the searched range when no draw reaches 1."""
    from softimpact.app.paper.thresholds import MAP_RANGE_IN_S, _map_headline
    from softimpact.units import display

    inch = 0.0254
    rows = [
        ("long beam", 0.5, "tsai_wu", 5, 30 * inch),
        ("long beam", 0.5, "delamination", 5, 20 * inch),
        ("long beam", 0.375, "tsai_wu", 5, 1 * inch),  # another diameter: not the headline's
        ("plate", 0.5, "tsai_wu", 0, 1 * inch),
    ]
    maps = [dict(structure=s, diameter_m=d * inch, index=i, draws_reaching_1=n, threshold_velocity_median_m_s=v) for s, d, i, n, v in rows]
    line = _map_headline(maps, display("in-lbf-s", "velocity"))
    assert "long beam 20 (delamination)" in line
    assert f"plate above {MAP_RANGE_IN_S[1]:.0f}" in line


def test_table_i_summary_stands_each_fit_beside_the_papers_table_i():
    """Each ball's summary line gives its fitted α1-α4 beside the paper's Table I (3/8 in: 4.00, 1.03, 0.25, 0.74; 1/2 in:
    4.25, 0.93, α3 lost, 0.66: /work/shared/paper/soft-projectile-impact.txt, Table I), and a pooled fit, absent from
    Table I, is left to the section."""
    from types import SimpleNamespace as NS

    from softimpact.app.paper.rubber_series import table_i_summary

    def fit(*slopes):
        return NS(origin={f"alpha{i + 1}": NS(slope=s) for i, s in enumerate(slopes)})

    lines = table_i_summary({"0.375 in": fit(4.1, 1.0, 0.3, 0.7), "0.5 in": fit(4.2, 0.9, 0.25, 0.6), "pooled": fit(1, 1, 1, 1)})
    assert lines == [
        "Table I, 0.375 in: fitted (paper) α1 4.100 (4), α2 1.000 (1.03), α3 0.300 (0.25), α4 0.700 (0.74)",
        "Table I, 0.5 in: fitted (paper) α1 4.200 (4.25), α2 0.900 (0.93), α3 0.250 (—), α4 0.600 (0.66)",
    ]


def test_paper_command_lists_each_warning_once_in_manifest_and_report(monkeypatch, tmp_path):
    """`softimpact paper` (on two fake steps) writes each warning its steps raise once into manifest.json, once into
    report.html's warnings section, and once onto stderr."""
    import json

    from click.testing import CliRunner

    import softimpact.app.paper as paper_app
    from softimpact.cli import main

    def step(k):
        def run(figures, files):
            warnings.warn(f"step warning {k}", SoftimpactWarning, stacklevel=1)
            files[f"x{k}.txt"] = "x"
            return [Section(f"Step {k}", ["text"])]

        return run

    monkeypatch.setattr(paper_app, "STEPS", (("one", step(0)), ("two", step(1))))
    result = CliRunner().invoke(main, ["paper", "--out", str(tmp_path / "out"), "--no-figures"])
    assert result.exit_code == 0, result.output
    manifest = json.loads((tmp_path / "out" / "manifest.json").read_text())
    assert manifest["warnings"] == ["step warning 0", "step warning 1"]
    html = (tmp_path / "out" / "report.html").read_text(encoding="utf-8")
    assert html.count("<li>step warning 0</li>") == 1 and html.count("<li>step warning 1</li>") == 1
    assert result.output.count("softimpact: warning: step warning 0") == 1


def test_calibration_summary_matches_the_built_in_series_to_tables_ii_and_iii():
    """On the built-in calibration series the summary finds each test's row of the paper's table by velocity: the paper's
    column reads Table II's and Table III's F0 in lbf (the paper's tables, tests/_support/problems.py)."""
    from types import SimpleNamespace as NS

    from softimpact.app.paper.calibrations import f0_summary
    from softimpact.input.series import load_calibration_series

    from _support.problems import TABLE_II, TABLE_III

    for beam, table in (("long", TABLE_II), ("short", TABLE_III)):
        series = load_calibration_series(f"paper-{beam}-calibration")
        items = [NS(test=t, calibration=NS(peak_force=1.0)) for t in series.tests]
        line = f0_summary(items, series, beam)
        assert ", ".join(f"0.2 ({row[1]:.1f})" for row in table) in line  # 1 N = 0.2248 lbf beside each paper F0


def _map_row(structure, index, d_in, flags):
    """A threshold-map row (MapRow.as_dict's keys that the report reads) with its validity flags."""
    return {"structure": structure, "index": index, "diameter_m": d_in * 0.0254, "validity_flags": list(flags)}


def test_warnings_section_lists_every_flagged_row_of_every_map():
    """The report's warnings section and summary count as many rows outside validity as the maps have flagged rows
    (counted here from the rows themselves), each listed under each of its flags, grouped by map."""
    import html
    import re

    from softimpact.app.paper.hail import hail_flags
    from softimpact.app.paper.thresholds import map_flags
    from softimpact.output.report import Section, render_report
    from softimpact.studies.hail import HailRow

    maps = [
        _map_row("long beam", "tsai_wu", 0.375, ["deflection_past_linear", "contact_past_projectile_radius"]),
        _map_row("long beam", "tsai_wu", 0.5, []),
        _map_row("8-in plate", "delamination", 0.75, ["extrapolated_diameter"]),
    ]
    onset = [_map_row("short beam", "olsson", d, ["deflection_past_linear"]) for d in (0.375, 0.5, 0.625)]
    hail = [
        HailRow(1.59e-3, d, 1.0, "olsson", 10.0, 10.0, 0.1, 1e3, 1e3, {"flags": ["the crushing strength (Jones 1997): strain rate 400 1/s"] * k}, 0.1, "x")
        for k, d in enumerate((0.0381, 0.0508))
    ]
    section = Section("Thresholds", ["text"])
    section.flagged = map_flags("Threshold maps", maps) + map_flags("Onset map", onset) + hail_flags("Hail map", hail)
    page = render_report("t", [section], [], {}, warnings=["one warning"])
    expected = sum(1 for r in maps + onset if r["validity_flags"]) + sum(1 for r in hail if r.validity["flags"])
    listed = set(re.findall(r"data-row='([^']*)'", page))
    assert len(listed) == expected == 6
    assert f"1 warning raised by the run; {expected} rows of 3 maps outside the models' validity" in html.unescape(page)
    assert page.count("<h3>") == 3  # one group per map
    assert "w/h &gt; 0.5 (3)" in page and "w/h &gt; 0.5 (1)" in page  # per map: the onset map's three rows under one flag
    assert page.count("data-row='Threshold maps | long beam, tsai_wu, d = 0.375 in'") == 2


def test_paper_marks_qualified_results_and_states_each_sections_units(monkeypatch):
    """A step that raised a warning has its summary line marked qualified, a clean one not; every section states its
    unit system at its head (the paper's by default, the step's own where it has one)."""
    import softimpact.app.paper as paper_app

    def warned(figures, files):
        warnings.warn("the deflection reaches 0.7 times the thickness", SoftimpactWarning, stacklevel=1)
        return [Section("Warned", ["text"], summary=["peak 1 lbf"])]

    def clean(figures, files):
        return [Section("Clean", ["text"], summary=["peak 2 lbf"])]

    monkeypatch.setattr(paper_app, "STEPS", (("warned", warned), ("clean", clean)))
    monkeypatch.setitem(paper_app.SECTION_UNITS, "clean", paper_app.UNITS["SI"])
    page = paper_app.paper(figures=False, workers=1).files["report.html"]
    assert "<li class='qualified'>peak 1 lbf [qualified: 1 warning of its runs, see Warnings of the run]" in page
    assert "<li>peak 2 lbf (" in page
    assert f"Units in this section: {paper_app.UNITS['in-lbf-s']}." in html.unescape(page)
    assert f"Units in this section: {paper_app.UNITS['SI']}." in html.unescape(page)
