"""The report's section on the rubber-ball series: reduction and Table I's scaling constants (paper Figs 7-15)."""

from __future__ import annotations

from ...output.report import Section
from ...output.series import TABLE_I, reduction_files, scaling_files, scaling_section
from ...studies.paper.series import rubber_series, rubber_series_fits
from .comparison import comparison_section

__all__ = ["rubber_series_sections", "rubber_series", "rubber_series_fits"]


def rubber_series_sections(figures: bool, files: dict) -> list[Section]:
    """The built-in rubber series reduced and fitted (Table I), then the empirical model beside the classical ones."""
    series, reduced = rubber_series()
    fits = rubber_series_fits()
    files.update(reduction_files(series, reduced, figures, prefix="rubber-series/"))
    files.update(scaling_files(fits, series.units, figures, prefix="rubber-series/"))
    sections = [scaling_section(fits, series, reduced, "rubber-series/", figures)]
    sections[0].summary = table_i_summary(fits)
    sections.append(comparison_section(figures, files))
    return sections


def table_i_summary(fits) -> list[str]:
    """One line per ball of Table I: the fitted α1-α4 (the section's table) beside the paper's (output.series.TABLE_I, the paper's Table I)."""
    lines = []
    for label, g in fits.items():
        paper = TABLE_I.get(label)
        if paper is None:  # the pooled fit: no column of Table I to stand beside (it stays in the section's table)
            continue
        pairs = []
        for i, name in enumerate(("alpha1", "alpha2", "alpha3", "alpha4")):
            ref = "—" if paper[i] is None else f"{paper[i]:.3g}"
            pairs.append(f"α{i + 1} {g.origin[name].slope:.3f} ({ref})")
        lines.append(f"Table I, {label}: fitted (paper) " + ", ".join(pairs))
    return lines
