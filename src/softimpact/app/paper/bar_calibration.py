"""The report's section on the bar calibration case (paper Figs 4-6)."""

from __future__ import annotations

from ...input.bar_case import load_bar_case
from ...output.bar import bar_files, bar_section
from ...output.report import Section
from ..bar import gauge_lag, run_bar

__all__ = ["bar_calibration_sections"]


def bar_calibration_sections(figures: bool, files: dict) -> list[Section]:
    """The 5/8-in steel ball on the instrumented bar (paper-calibration): contact force, gauge strain, strain along the bar."""
    problem, _ = load_bar_case("paper-calibration")
    result, plain, inferred = run_bar(problem)
    files.update(bar_files(result, plain, inferred, figures, prefix="bar-calibration/"))
    return [bar_section(result, plain, gauge_lag(result, inferred), "bar-calibration/")]
