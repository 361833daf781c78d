"""``softimpact reduce`` and ``fit``: bar records → force histories → scaling constants α1–α4."""

from __future__ import annotations

from dataclasses import dataclass

from ..errors import InputError
from ..gates import Gate, at_most, quality
from ..input.records import read_record
from ..input.series import Series, SeriesTest, load_series
from ..output.files import json_text
from ..output.scaling_json import scaling_summary
from ..output.series import reduction_files, scaling_files
from ..workflows.reduction import Record, Reduction, reduce_record
from ..workflows.scaling import TestPoint, fit_gates, fit_groups
from . import Outcome, Progress, no_progress

__all__ = ["ReducedTest", "reduce_series", "fit_series", "reduction_gates", "reduce", "fit"]

MAX_PULSE_MISFIT = 0.2  # RMS residual of the eq-15 fit / F0: above, T and tF0 do not describe the pulse
MAX_SKEW = 0.95  # tF0/T: a peak at the very end of the pulse is a degenerate fit (tF0 ≈ T)


@dataclass(frozen=True)
class ReducedTest:
    """A test of a series with its reduction, or the reason it could not be reduced."""

    test: SeriesTest
    reduction: Reduction | None
    error: str = ""


def reduce_series(series: Series, progress: Progress = no_progress) -> list[ReducedTest]:
    """Reduce every record; a bad record is reported and the others still reduce."""
    out = []
    for i, test in enumerate(series.tests):
        try:
            t, signal, kind = read_record(test.record)
            if kind == "voltage":
                if series.bridge is None:
                    raise InputError(f"{test.record}: a voltage record needs gauge_factor, bridge and excitation in [gauge]")
                signal = series.bridge.strain(signal)
            reduction = reduce_record(Record(test.record.name, t, signal), series.bar, series.gauge_position)
            out.append(ReducedTest(test, reduction))
        except InputError as exc:
            msg = str(exc)
            out.append(ReducedTest(test, None, msg if test.record.name in msg else f"{test.record}: {msg}"))
        progress(i + 1, len(series.tests), "reducing")
    return out


def fit_series(reduced: list[ReducedTest]):
    """α1–α4 per diameter and pooled (:func:`softimpact.workflows.scaling.fit_groups`)."""
    points = [
        TestPoint(
            r.test.name,
            r.test.velocity,
            r.test.mass,
            r.test.diameter,
            r.reduction.peak_force,
            r.reduction.time_of_peak,
            r.reduction.duration,
            r.reduction.impulse,
        )
        for r in reduced
        if r.reduction is not None
    ]
    if not points:
        raise InputError("fit: no test of the series could be reduced")
    return fit_groups(points)


def reduction_gates(reduced: list[ReducedTest]) -> tuple[Gate, ...]:
    """Quality gates of each reduced test (:mod:`softimpact.gates`): the eq-15 pulse must fit
    the force (RMS residual within MAX_PULSE_MISFIT of F0) and must not be degenerate
    (tF0/T below MAX_SKEW)."""
    gates = []
    for r in reduced:
        d = r.reduction
        if d is None:
            continue
        name = r.test.name
        misfit = d.fit_rms / d.peak_force if d.peak_force > 0 else float("nan")
        gates.append(
            at_most(
                f"pulse-fit[{name}]", misfit, MAX_PULSE_MISFIT, f"{name}: the eq-15 pulse misses the force by {{value:.0%}} of F0 RMS (limit {{limit:.0%}})"
            )
        )
        skew = d.time_of_peak / d.duration if d.duration > 0 else float("nan")
        gates.append(at_most(f"pulse-skew[{name}]", skew, MAX_SKEW, f"{name}: degenerate pulse, tF0/T = {{value:.2f}} (limit {{limit:.2f}})"))
    return tuple(gates)


def _reduce(name: str, progress: Progress):
    series = load_series(name)
    reduced = reduce_series(series, progress)
    warnings = tuple(r.error for r in reduced if r.reduction is None)
    if len(warnings) == len(reduced):
        raise InputError(f"no record of the series could be reduced (first: {warnings[0]})")
    return series, reduced, warnings


def reduce(series_name: str, figures: bool = True, progress: Progress = no_progress) -> Outcome:
    """Reduce the records of a series (file or built-in name)."""
    series, reduced, warnings = _reduce(series_name, progress)
    files = reduction_files(series, reduced, figures)
    done = sum(r.reduction is not None for r in reduced)
    gates = reduction_gates(reduced)
    files["summary.json"] = json_text(
        {
            "series": str(series.path),
            "synthetic": series.synthetic,
            "reduced": done,
            "failed": {r.test.name: r.error for r in reduced if r.reduction is None},
            "quality": quality(gates),
        }
    )
    inputs = (series.path, *(t.record for t in series.tests))
    return Outcome(files, f"{done} of {len(reduced)} records reduced; tests.csv", inputs, warnings, gates)


def fit(series_name: str, figures: bool = True, progress: Progress = no_progress) -> Outcome:
    """Reduce a series, then fit the scaling constants α1–α4 of eqs (4)–(7)."""
    series, reduced, warnings = _reduce(series_name, progress)
    fits = fit_series(reduced)
    gates = reduction_gates(reduced) + fit_gates(fits)
    files = reduction_files(series, reduced, figures)
    files.update(scaling_files(fits, series.units, figures))
    files["scaling.json"] = json_text({**scaling_summary(fits), "quality": quality(gates)})
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
    inputs = (series.path, *(t.record for t in series.tests))
    return Outcome(files, "\n".join(lines + ["scaling.json"]), inputs, warnings, gates)
