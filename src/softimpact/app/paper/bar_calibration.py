"""The report's section on the bar calibration case (paper Figs 4-6)."""

from __future__ import annotations

from ...cases.run import execute
from ...input.bar_case import load_bar_case
from ...output.bar import bar_files, bar_section
from ...output.report import Section
from ...units import display
from ..bar import gauge_lag
from .notes import SYSTEM

__all__ = ["bar_calibration_sections"]


def bar_calibration_sections(figures: bool, files: dict) -> list[Section]:
    """The 5/8-in steel ball on the instrumented bar (paper-calibration): contact force, gauge strain, strain along the bar."""
    problem, _ = load_bar_case("paper-calibration")
    run = execute(problem)
    files.update(bar_files(run.result, run.plain, run.inferred, figures, prefix="bar-calibration/", summary=run.summary))
    lag = gauge_lag(run.result, run.inferred)
    section = bar_section(run.result, run.plain, lag, "bar-calibration/")
    section.summary = [bar_summary(run.result, lag)]
    return [section]


def bar_summary(result, lag) -> str:
    """The bar calibration's headline, in the case's units as its table: peak contact force and contact duration, and how
    far the gauge-derived force's peak falls from it (``lag``: :func:`~softimpact.app.bar.gauge_lag`, None without a gauge)."""
    fu, tu = display(SYSTEM, "force"), display(SYSTEM, "time")
    line = (
        f"Bar calibration: peak contact force {result.peak_force * fu.factor:.1f} {fu.label}, "
        f"contact duration {result.contact_duration * tu.factor:.1f} {tu.label}"
    )
    if lag is not None:
        line += f"; the gauge-derived force peaks {abs(1 - lag[0]):.1%} {'below' if lag[0] < 1 else 'above'} it"
    return line
