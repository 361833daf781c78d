"""Glue at the edge: read a series' files, run the workflows, shared by the CLI and ``paper``."""

from __future__ import annotations

from dataclasses import dataclass

from .errors import InputError
from .io import read_record
from .workflows.reduction import Record, Reduction, reduce_record
from .workflows.scaling import TestPoint, fit_groups

__all__ = ["ReducedTest", "reduce_series", "test_points", "fit_series", "CalibratedTest", "start_pulse", "calibration_model", "calibrate_tests"]


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


@dataclass(frozen=True)
class CalibratedTest:
    """A calibration test with its result (and the deconvolved history beside it), or its error."""

    test: object  # cases.CalibrationTest
    calibration: object | None
    deconvolved: object | None = None
    error: str = ""


def start_pulse(projectile: str, constants: str | None, velocity: float):
    """The bar-model history at ``velocity``: eqs (4)–(6) with eq (15); refuses velocities out of the constants' range."""
    from .models.empirical import PROJECTILES
    from .predict import scaling_law

    P = PROJECTILES[projectile]
    law = scaling_law(constants, "pooled", P)
    if not law.in_range(velocity):
        lo, hi = law.velocity_range
        raise InputError(
            f"velocity: {velocity / 0.0254:.0f} in/s is outside the range of the bar model {law.name} "
            f"({lo / 0.0254:.0f}-{hi / 0.0254:.0f} in/s)"
        )
    return law.pulse(P.mass, P.diameter, velocity)


def calibration_model(problem, radii, fit_radius: bool):
    """A beam model whose contact patch covers every r0 to be used (and 1.5 r0 when r0 is fitted)."""
    from .workflows.beam_impact import BeamModel

    reach = max(radii) * (1.5 if fit_radius else 1.0)
    x, L = problem.load.position, problem.beam.length
    return BeamModel(problem, patch_radius=min(reach, x, L - x))


def calibrate_tests(model, tests, projectile, constants, method, fit_radius=False, deconvolve=True, progress=None):
    """Calibrate each test; a bad test is reported and the others go on."""
    from .io import read_strains
    from .workflows.calibration import Measured, calibrate

    out = []
    for test in tests:
        try:
            start = start_pulse(projectile, constants, test.velocity)
            t, strains = read_strains(test.measured)
            measured = Measured(test.measured.name, t, strains)
            r0 = test.contact_radius or model.problem.load.contact_radius
            cal = calibrate(model, measured, start, method, contact_time=test.contact_time, radius=r0, fit_radius=fit_radius)
            dec = None
            if deconvolve and method != "deconvolve":
                dec = calibrate(model, measured, start, "deconvolve", contact_time=cal.prepared.contact_time, radius=r0)
            out.append(CalibratedTest(test, cal, dec))
        except InputError as exc:
            out.append(CalibratedTest(test, None, None, str(exc)))
        if progress is not None:
            progress(test.name)
    return out
