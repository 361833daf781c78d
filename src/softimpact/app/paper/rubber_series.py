"""The report's section on the rubber-ball series: reduction and Table I's scaling constants (paper Figs 7-15)."""

from __future__ import annotations

from ...input.series import load_series
from ...input.series_records import read_series_records
from ...output.report import Section
from ...output.series import reduction_files, scaling_files, scaling_section
from ...studies.series import fit_series, reduce_series
from .comparison import comparison_section

__all__ = ["rubber_series_sections"]


def rubber_series_sections(figures: bool, files: dict) -> list[Section]:
    """The built-in rubber series reduced and fitted (Table I), then the empirical model beside the classical ones."""
    series = load_series("paper-rubber-series")
    reduced = reduce_series(series, *read_series_records(series))
    fits = fit_series(reduced)
    files.update(reduction_files(series, reduced, figures, prefix="rubber-series/"))
    files.update(scaling_files(fits, series.units, figures, prefix="rubber-series/"))
    sections = [scaling_section(fits, series, reduced, "rubber-series/", figures)]
    sections.append(comparison_section(figures, files))
    return sections
