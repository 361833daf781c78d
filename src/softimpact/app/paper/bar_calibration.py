"""The report's section on the bar calibration case (paper Figs 4-6)."""

from __future__ import annotations

from ...cases.run import execute
from ...input.bar_case import load_bar_case
from ...output.bar import bar_files, bar_section
from ...output.report import Section
from ..bar import gauge_lag

__all__ = ["bar_calibration_sections"]


def bar_calibration_sections(figures: bool, files: dict) -> list[Section]:
    """The 5/8-in steel ball on the instrumented bar (paper-calibration): contact force, gauge strain, strain along the bar."""
    problem, _ = load_bar_case("paper-calibration")
    run = execute(problem)
    files.update(bar_files(run.result, run.plain, run.inferred, figures, prefix="bar-calibration/", summary=run.summary))
    return [bar_section(run.result, run.plain, gauge_lag(run.result, run.inferred), "bar-calibration/")]
