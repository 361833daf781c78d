"""Glue at the edge: read a series' files, run the workflows, shared by the CLI and ``paper``."""

from __future__ import annotations

from dataclasses import dataclass

from .errors import InputError
from .io import read_record
from .workflows.reduction import Record, Reduction, reduce_record
from .workflows.scaling import TestPoint, fit_groups

__all__ = ["ReducedTest", "reduce_series", "test_points", "fit_series"]


@dataclass(frozen=True)
class ReducedTest:
    """A test of a series with its reduction, or the reason it could not be reduced."""

    test: object  # cases.SeriesTest
    reduction: Reduction | None
    error: str = ""


def reduce_series(series, progress=None) -> list[ReducedTest]:
    """Reduce every record; a bad record is reported and the others still reduce."""
    out = []
    for test in series.tests:
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
        if progress is not None:
            progress(test.name)
    return out


def test_points(reduced: list[ReducedTest]) -> list[TestPoint]:
    return [
        TestPoint(r.test.name, r.test.velocity, r.test.mass, r.test.diameter, r.reduction.peak_force, r.reduction.time_of_peak, r.reduction.duration, r.reduction.impulse)
        for r in reduced
        if r.reduction is not None
    ]


def fit_series(reduced: list[ReducedTest]):
    points = test_points(reduced)
    if not points:
        raise InputError("fit: no test of the series could be reduced")
    return fit_groups(points)
