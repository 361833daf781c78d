"""Figures legible (issue 23 item 6): distinct styles for many curves, axis labels, display units everywhere."""

import matplotlib

matplotlib.use("Agg")

import pytest

from softimpact.output.plots import _figure, curve_colors
from softimpact.units import INCH, POUND_FORCE, display


def test_thirteen_curves_on_one_axes_are_pairwise_distinct():
    """13 curves drawn without a style (the identification's case) get 13 distinct colour–line-style pairs,
    the first ten solid as before."""
    fig, ax = _figure()
    lines = [ax.plot([0, 1], [i, i])[0] for i in range(13)]
    styles = {(matplotlib.colors.to_hex(ln.get_color()), ln.get_linestyle()) for ln in lines}
    assert len(styles) == 13
    assert all(ln.get_linestyle() == "-" for ln in lines[:10])


@pytest.mark.parametrize("n", [3, 13, 25])
def test_curve_colors_are_distinct(n):
    """Colours for curves whose line style means something (measured solid, model dashed) are all distinct."""
    assert len({matplotlib.colors.to_hex(c) for c in curve_colors(n)}) == n


def test_in_lbf_s_shows_energies_and_moments_in_its_own_units():
    """in-lbf-s shows energy in in·lbf and a bending stiffness per width in lbf·in (1 N·m = 1/(lbf·in) of them)."""
    for kind in ("energy", "moment"):
        u = display("in-lbf-s", kind)
        assert u.factor == pytest.approx(1 / (POUND_FORCE * INCH), rel=1e-9)
        assert "lbf" in u.label and "J" not in u.label and "N" not in u.label


def test_thresholds_figure_has_both_axis_labels():
    """thresholds.png labels its x axis (the levels) as well as its y axis (velocity with its unit)."""
    from softimpact.output.sweep import threshold_figure

    th = [
        {
            "levels": "",
            "index": "damage.tsai_wu",
            "threshold_velocity_median_m_s": 100.0,
            "threshold_velocity_p05_m_s": 90.0,
            "threshold_velocity_p95_m_s": 110.0,
        }
    ]
    ax = threshold_figure(th, "in-lbf-s").axes[0]
    assert ax.get_xlabel() and "in/s" in ax.get_ylabel()


def test_beam_gauge_table_puts_still_growing_on_the_peak_at_the_window_end():
    """The long beam run for 60 µs: gauge g2's TENSILE peak sits on the last sample (summary.json says so) and the
    report's gauge table attaches "still growing?" to that peak, not to the compressive one."""
    import dataclasses

    from softimpact.cases.run import execute
    from softimpact.input.beam_case import load_beam_case
    from softimpact.output.beam import beam_section

    p, _ = load_beam_case("paper-long-beam")
    p = dataclasses.replace(p, solver=dataclasses.replace(p.solver, duration=60e-6))
    run = execute(p, energy=False)
    at_end = {g: d["peak_at_window_end"] for g, d in run.summary["gauges"].items()}
    assert at_end["g2"] == ["tensile"]
    rows = {row[0]: row for row in beam_section(run.model, run.result, "", run.summary).tables[1][2]}
    assert "still growing" in rows["g2"][2] and "still growing" not in rows["g2"][3]
    assert not any("still growing" in c for c in rows["g1"])


@pytest.mark.parametrize("fmt, magic", [("svg", b"<?xml"), ("pdf", b"%PDF")])
def test_figure_format_writes_vector_figures_under_their_own_names(tmp_path, fmt, magic):
    """`--figure-format svg|pdf` writes every figure in that format, named for it (no .png left); the default
    run after it in the same process draws PNG again (the format does not leak between commands)."""
    from click.testing import CliRunner

    from softimpact.cli import main

    r = CliRunner().invoke(main, ["bar", "paper-calibration", "--figure-format", fmt, "--out", str(tmp_path / "v")])
    assert r.exit_code == 0, r.output
    figs = sorted((tmp_path / "v").glob(f"*.{fmt}"))
    assert len(figs) == 4 and not list((tmp_path / "v").glob("*.png"))
    assert all(f.read_bytes().startswith(magic) for f in figs)
    r = CliRunner().invoke(main, ["bar", "paper-calibration", "--out", str(tmp_path / "p")])
    assert r.exit_code == 0 and all(f.read_bytes()[:4] == b"\x89PNG" for f in (tmp_path / "p").glob("*.png"))
    assert len(list((tmp_path / "p").glob("*.png"))) == 4


def test_with_figure_format_renames_figures_and_their_links_in_reports():
    """Renaming for svg: figures "x.png" become "x.svg" and an HTML report's links to them follow; text files keep their names."""
    from softimpact.output.files import with_figure_format

    files = {"a.png": b"<?xml ...", "summary.json": "{}", "report.html": "<img src='a.png'>"}
    out = with_figure_format(files, "svg")
    assert set(out) == {"a.svg", "summary.json", "report.html"} and out["report.html"] == "<img src='a.svg'>"
    assert with_figure_format(files, "png") is files
