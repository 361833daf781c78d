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
