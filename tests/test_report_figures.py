"""The report's figures: Figs 23–25 readable (open markers for the paper's points above ours, no offset notation,
text of at least 8 pt once shrunk to the report's width) and figures stored as small PNGs that look the same."""

import io

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest

from softimpact.output.files import _small_png, figure_bytes
from softimpact.output.plots import beam_force_scaling

INCH, LBF = 0.0254, 4.4482216152605
REPORT_WIDTH_PX = 1000 - 2 * 16  # output/report.py: body max-width 1000px, padding 1em (16 px) each side
DPI = 120  # output/files.py figure_bytes


def _groups():
    """Table II and III's rows (V [in/s], F0 [lbf], tF0 [µs], T [µs]) in SI, with 'our' points 2 % off them."""
    table = {
        "long": [(1166, 44, 30, 355), (1932, 90, 21, 250), (3058, 215, 13, 158), (4026, 325, 10, 120)],
        "short": [(1166, 42, 35, 415), (1981, 84, 20, 310), (2994, 170, 13, 205), (4049, 245, 10, 155)],
    }
    groups = {}
    for beam, rows in table.items():
        si = [(v * INCH, f * LBF, tp * 1e-6, T * 1e-6) for v, f, tp, T in rows]
        groups[f"{beam} beam, calibrated"] = [(v, 1.02 * f, tp, 0.98 * T) for v, f, tp, T in si]
        groups[f"{beam} beam, Table (paper)"] = si
    return groups


@pytest.fixture(scope="module")
def figure():
    fig = beam_force_scaling(_groups(), "in-lbf-s")
    fig.canvas.draw()
    yield fig
    import matplotlib.pyplot as plt

    plt.close(fig)


def test_figs_23_25_have_no_offset_or_multiplier(figure):
    """No axis of Figs 23–25 carries matplotlib's offset or ×10ⁿ text: V² (up to 1.7e7 (in/s)²) is in scaled units."""
    for ax in figure.axes:
        for axis in (ax.xaxis, ax.yaxis):
            assert axis.get_offset_text().get_text() == "", (ax.get_title(), axis.get_offset_text().get_text())
    assert "10⁶" in figure.axes[0].get_xlabel()
    ticks = [float(t.get_text().replace("−", "-")) for t in figure.axes[0].get_xticklabels() if t.get_text()]
    assert max(ticks) < 100  # (4049 in/s)² = 16.4 × 10⁶


def test_figs_23_25_text_is_8_pt_at_the_reports_width(figure):
    """Every text of the figure (legend, ticks, labels) is at least 8 pt once the 120-dpi PNG is shrunk to the report's width."""
    shrink = min(1.0, REPORT_WIDTH_PX / (figure.get_figwidth() * DPI))
    sizes = [t.get_fontsize() for t in figure.findobj(matplotlib.text.Text) if t.get_text()]
    assert sizes and min(sizes) * shrink >= 8.0, (min(sizes), shrink)


def test_the_papers_points_are_open_and_drawn_above_ours(figure):
    """The paper's points are open markers, larger than ours and above them, so a filled point inside shows through."""
    ax = figure.axes[0]
    lines = {ln.get_label(): ln for ln in ax.get_lines() if not ln.get_label().startswith("_")}
    paper, ours = lines["long beam, Table (paper)"], lines["long beam, calibrated"]
    assert paper.get_markerfacecolor() == "none" and ours.get_markerfacecolor() != "none"
    assert paper.get_markersize() > ours.get_markersize() and paper.get_zorder() > ours.get_zorder()


@pytest.mark.slow  # seconds: the slow tier (make test-slow)
def test_small_png_looks_the_same_and_is_smaller():
    """A figure's PNG as a palette decodes to within half a level (of 255) of matplotlib's on average, and is at least half as large."""
    from PIL import Image

    fig = beam_force_scaling(_groups(), "in-lbf-s")
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=DPI, bbox_inches="tight")
    raw = buf.getvalue()
    small = _small_png(raw)
    a = np.asarray(Image.open(io.BytesIO(raw)).convert("RGB"), dtype=float)
    b = np.asarray(Image.open(io.BytesIO(small)).convert("RGB"), dtype=float)
    assert a.shape == b.shape and np.abs(a - b).mean() <= 0.5
    assert len(small) <= 0.5 * len(raw)
    assert figure_bytes(fig)[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_transparent_png_is_kept_as_it_is():
    """A PNG with transparent pixels is returned unchanged (a palette would lose its alpha)."""
    from PIL import Image

    image = Image.new("RGBA", (8, 8), (255, 0, 0, 0))
    buf = io.BytesIO()
    image.save(buf, format="PNG")
    assert _small_png(buf.getvalue()) == buf.getvalue()


def _map_rows(kinematics="linear", scale=1.0):
    """Threshold-map rows (MapRow.as_dict's keys the figures read) of three structures, two indices, four diameters."""
    rows = []
    for s in ("long beam", "short beam", "8-in plate"):
        for index in ("tsai_wu", "delamination"):
            for k, d in enumerate((0.375, 0.5, 0.625, 0.75)):
                v = scale * 120.0 / (1 + k)
                rows.append(
                    {
                        "structure": s,
                        "index": index,
                        "diameter_m": d * INCH,
                        "kinematics": kinematics,
                        "inside_validity": k % 2 == 0,
                        **{f"threshold_velocity_{q}_m_s": v * f for q, f in (("median", 1), ("nominal", 1), ("coarse_mesh", 1.02), ("p05", 0.9), ("p95", 1.1))},
                    }
                )
    return rows


def _hail_figure():
    import dataclasses

    from softimpact.app.paper.hail import _figure_fte
    from softimpact.studies.hail import RHYMER_DIAMETERS, RHYMER_THICKNESSES, HailRow

    rows = tuple(
        HailRow(h, d, 0.03 * (d / 0.0381) ** 3, index, 10.0 + 1e4 * h, 10.5, 0.05, 1e3, 1e3, {"flags": []}, 0.1, "intermediate")
        for index in ("olsson", "delamination")
        for h in RHYMER_THICKNESSES
        for d in RHYMER_DIAMETERS
    )
    return _figure_fte(rows, tuple(dataclasses.replace(r, velocity=0.8 * r.velocity, kinematics="von-karman") for r in rows if r.index == "olsson"))


def _figures():
    from softimpact.output.sweep import kinematics_map_figure, threshold_map_figure

    plate = [r for r in _map_rows() if r["structure"] == "8-in plate"]
    return {
        "threshold maps": lambda: threshold_map_figure(_map_rows(), [], "in-lbf-s", "Damage-onset velocity against the ball's diameter " * 3),
        "onset map": lambda: threshold_map_figure([r for r in _map_rows() if r["index"] == "delamination"], [], "SI", "Onset map"),
        "two kinematics": lambda: kinematics_map_figure(plate + [dict(r, kinematics="von-karman") for r in plate], "in-lbf-s", "Two kinematics"),
        "hail": _hail_figure,
    }


@pytest.mark.parametrize("name", list(_figures()))
def test_map_figures_text_is_9_pt_at_the_reports_width(name):
    """Every text of the maps' figures (threshold, onset, two kinematics, hail) is at least 9 pt once the 120-dpi PNG
    is shrunk to the report's width (its drawn size: width and font sizes read from the laid-out figure)."""
    import matplotlib.pyplot as plt

    fig = _figures()[name]()
    fig.canvas.draw()
    width_px = fig.get_tightbbox().width * DPI  # the saved PNG's width (bbox_inches="tight"), in pixels
    shrink = min(1.0, REPORT_WIDTH_PX / width_px)
    sizes = [t.get_fontsize() for t in fig.findobj(matplotlib.text.Text) if t.get_text() and t.get_visible()]
    plt.close(fig)
    assert sizes and min(sizes) * shrink >= 9.0, (min(sizes), shrink)
