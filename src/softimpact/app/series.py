"""``softimpact reduce`` and ``fit``: bar records → force histories → scaling constants α1–α4.

Every record of the series is read first: a file that cannot be read (missing,
truncated, no such channel, no time base, text among the numbers, a unit
other than volts or strain) is bad input — one line, exit 2, nothing written.
Records in volts go through the series' bridge. Each record is then
conditioned and reduced (:mod:`softimpact.studies.series`). A *flagged* test
(clipped, double hit, or no pulse found) is still reduced, its reason written
in ``tests.csv``, but ``fit`` leaves it out with a warning unless its
``[[test]]`` says ``accept_flagged = true``. A record that cannot be reduced is
reported and the others still reduce.
"""

from __future__ import annotations

from dataclasses import replace

from ..gates import quality
from ..input.series import load_series
from ..input.series_records import read_series_records
from ..output.files import json_text
from ..output.series import reduction_files, scaling_data, scaling_files
from ..studies.series import failed_reductions, fit_series, reduce_series, reduction_gates
from ..workflows.scaling import fit_gates
from . import Outcome, Progress, no_progress
from .options import display_system

__all__ = ["reduce", "fit", "require_readers"]


def require_readers(series) -> None:
    """Before any record is read: the optional reader of every lab record of ``series`` (its format detected from the
    file's first bytes, :func:`softimpact.input.records.registry.detect`) installed, or exit 2 with the extra's install line."""
    from ..extras import FORMAT_EXTRAS, require
    from ..input.records.registry import detect

    for test in series.tests:
        for path in (test.record, *(test.second[:1] if test.second else ())):
            fmt = detect(path) if path.is_file() else None  # (a missing file: the reader names it, as before)
            if fmt in FORMAT_EXTRAS:
                extra, modules = FORMAT_EXTRAS[fmt]
                require(extra, f"{path} ({fmt} record)", modules)


def _reduce(name: str, units: str | None, progress: Progress):
    """The series (file or built-in name) read, shown in display ``units`` (None: the series' own), and reduced,
    and the errors of the records that could not be reduced."""
    series = load_series(name)
    series = replace(series, units=display_system(units, series.units))
    require_readers(series)
    reduced = reduce_series(series, *read_series_records(series), progress=progress)
    return series, reduced, failed_reductions(reduced)


def reduce(*, series_name: str, units: str | None = None, figures: bool = True, progress: Progress = no_progress) -> Outcome:
    """Reduce the records of a series (file or built-in name); ``units``: the display system of the figures (None: the series')."""
    series, reduced, warnings = _reduce(series_name, units, progress)
    warnings += [f"{r.test.name}: flagged ({r.rejected[0]})" for r in reduced if r.reduction is not None and r.rejected]
    files = reduction_files(series, reduced, figures)
    done = sum(r.reduction is not None for r in reduced)
    gates = reduction_gates(reduced)
    files["summary.json"] = json_text(
        {
            "series": str(series.path),
            "synthetic": series.synthetic,
            "reduced": done,
            "failed": {r.test.name: r.error for r in reduced if r.reduction is None},
            "flagged": {r.test.name: list(r.rejected) for r in reduced if r.rejected},
            "dispersion": series.dispersion,
            "records": {r.test.name: r.metadata for r in reduced},
            "quality": quality(gates),
        }
    )
    inputs = (series.path, *(t.record for t in series.tests), *((series.bar_file,) if series.bar_file else ()))
    return Outcome(files, f"{done} of {len(reduced)} records reduced; tests.csv", inputs, tuple(warnings), gates)


def fit(*, series_name: str, units: str | None = None, figures: bool = True, progress: Progress = no_progress) -> Outcome:
    """Reduce a series, then fit the scaling constants α1–α4 of eqs (4)–(7) to its unflagged (or accepted) tests;
    ``units``: the display system of the figures (None: the series')."""
    series, reduced, warnings = _reduce(series_name, units, progress)
    fits = fit_series(reduced)
    warnings += [
        f"{r.test.name}: not fitted (flagged: {r.rejected[0]}; accept_flagged = true fits it)" for r in reduced if r.reduction is not None and not r.fitted
    ]
    gates = reduction_gates(reduced) + fit_gates(fits)
    files = reduction_files(series, reduced, figures)
    files.update(scaling_files(fits, series.units, figures))
    files["scaling.json"] = json_text({**scaling_data(fits), "quality": quality(gates)})
    lonely = [label for label, g in fits.items() if len(g.points) == 1]
    if lonely:
        warnings = (
            *warnings,
            f"{', '.join(lonely)}: one test only: the constants have no confidence interval and the law is not checked against other velocities",
        )
    lines = []
    for label, g in fits.items():
        a = {k: f.slope for k, f in g.origin.items()}
        lines.append(
            f"{label:>10s}: alpha1 {a['alpha1']:.3f}  alpha2 {a['alpha2']:.3f}  alpha3 {a['alpha3']:.3f}  alpha4 {a['alpha4']:.3f}  ({len(g.points)} tests)"
        )
    inputs = (series.path, *(t.record for t in series.tests), *((series.bar_file,) if series.bar_file else ()))
    return Outcome(files, "\n".join(lines + ["scaling.json"]), inputs, tuple(warnings), gates)
