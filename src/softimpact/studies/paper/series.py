"""The paper report's rubber-ball series: the built-in series read, reduced and fitted (Table I) once per run; the
series section, the thresholds' α covariance and the identification share them."""

from __future__ import annotations

from ..series import fit_series, reduce_series
from ..tasks import once

__all__ = ["rubber_series", "rubber_series_fits"]


@once
def rubber_series():
    """The built-in rubber series and its reduced tests, read and reduced once per run (this section,
    the thresholds' α covariance and the identification share them; not to be changed): (series, reduced)."""
    from ...input.series import load_series
    from ...input.series_records import read_series_records

    series = load_series("paper-rubber-series")
    return series, reduce_series(series, *read_series_records(series))


@once
def rubber_series_fits():
    """The scaling fits (Table I) of :func:`rubber_series`, once per run (not to be changed)."""
    return fit_series(rubber_series()[1])
