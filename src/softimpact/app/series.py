"""``softimpact reduce`` and ``fit``: bar records → force histories → scaling constants α1–α4.

Every record of the series is read first: a file that cannot be read (missing,
truncated, no such channel, no time base, text among the numbers, a unit
other than volts or strain) is bad input — one line, exit 2, nothing written.
Records in volts go through the series' bridge. Each record is then
conditioned (baseline, first arrival, clipping, double hits: workflows/
conditioning.py) and reduced. A *flagged* test (clipped, double hit, or no
pulse found) is still reduced, its reason written in ``tests.csv``, but
``fit`` leaves it out with a warning unless its ``[[test]]`` says
``accept_flagged = true``. A record that cannot be reduced is reported and the
others still reduce.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..errors import InputError
from ..fem.bar import Rod
from ..gates import Gate, at_most, quality
from ..input.series import Series, SeriesTest, TestRecord, load_series, read_test_record
from ..output.files import json_text
from ..output.scaling_json import scaling_summary
from ..output.series import reduction_files, scaling_files
from ..workflows.conditioning import Conditioned, condition_record
from ..workflows.reduction import Record, Reduction, reduce_record
from ..workflows.scaling import TestPoint, fit_gates, fit_groups
from . import Outcome, Progress, no_progress

__all__ = ["ReducedTest", "read_records", "reduce_series", "fit_series", "reduction_gates", "reduce", "fit"]

MAX_PULSE_MISFIT = 0.2  # RMS residual of the eq-15 fit / F0: above, T and tF0 do not describe the pulse
MAX_SKEW = 0.95  # tF0/T: a peak at the very end of the pulse is a degenerate fit (tF0 ≈ T)


@dataclass(frozen=True)
class ReducedTest:
    """A test of a series with its reduction, or the reason it could not be reduced.

    ``rejected``: the conditioning's reasons not to fit it (empty: fit it).
    ``uncorrected``: with dispersion correction, the reduction without it.
    """

    test: SeriesTest
    reduction: Reduction | None
    error: str = ""
    conditioning: Conditioned | None = None
    rejected: tuple[str, ...] = ()
    metadata: dict = field(default_factory=dict)
    uncorrected: Reduction | None = None

    @property
    def fitted(self) -> bool:
        """Reduced, and either not flagged or accepted by the user."""
        return self.reduction is not None and (not self.rejected or self.test.accept_flagged)

    @property
    def status(self) -> str:
        if self.reduction is None:
            return "error"
        if self.rejected:
            return "flagged: accepted" if self.test.accept_flagged else "flagged: not fitted"
        return "ok"


def read_records(series: Series, second: bool = False) -> list[TestRecord]:
    """Every record of the series (or of its second gauge), as strain where the bridge turns volts into strain (InputError on a bad file)."""
    out = []
    for test in series.tests:
        rec = read_test_record(test, second)
        if rec.kind == "voltage":
            if series.bridge is None:
                if rec.metadata.get("unit_stated", True):
                    raise InputError(f"{test.record}: a record in volts needs the bridge in [gauge] (gauge_factor, bridge, excitation)")
                raise InputError(
                    f"{test.record}: channel {rec.metadata.get('channel')!r} states no unit (read as volts) and [gauge] has no bridge: "
                    "name the unit in the file (time_s, microstrain, ... or 'CH1 (mV)') or give record = { file = ..., unit = ... }"
                )
            rec = TestRecord(rec.time, series.bridge.strain(rec.signal), "strain", {**rec.metadata, "bridge": series.bridge.configuration})
        out.append(rec)
    return out


def _condition(series: Series, rec: TestRecord) -> tuple[Conditioned | None, tuple[str, ...]]:
    """Conditioning of a strain record and the reasons (if any) it must not be fitted."""
    rod = Rod.of(series.bar)
    cap = 0.0 if series.bar.end_cap is None else series.bar.end_cap.mass
    try:
        c = condition_record(rec.time, rec.signal, series.gauge_position, series.bar.length, rod.wave_speed, end_delay=2 * cap / rod.impedance)
    except InputError:
        return None, ()  # the reduction says what is wrong with the record
    rejected = [f for f in c.flags if f.startswith(("clipped", "double hit", "no pulse"))]
    return c, tuple(rejected)


def reduce_series(series: Series, progress: Progress = no_progress) -> list[ReducedTest]:
    """Read every record (a bad file raises), condition and reduce each; a record that cannot be reduced is reported."""
    records = read_records(series)
    seconds = read_records(series, second=True) if series.second_position is not None else [None] * len(records)
    corrected = series.dispersion == "pochhammer-chree"
    out = []
    for i, (test, rec, rec2) in enumerate(zip(series.tests, records, seconds)):
        conditioned, rejected = _condition(series, rec)
        meta = {**rec.metadata, "dispersion": series.dispersion}
        record = Record(test.record.name, rec.time, rec.signal)
        second = None
        if rec2 is not None:
            meta["second_gauge"] = rec2.metadata
            second = Record(test.second[0].name, rec2.time, rec2.signal)
        try:
            reduction = reduce_record(record, series.bar, series.gauge_position, dispersion=corrected, second=second, second_position=series.second_position)
            plain = reduce_record(record, series.bar, series.gauge_position) if corrected else None
            out.append(ReducedTest(test, reduction, "", conditioned, rejected, meta, plain))
        except InputError as exc:
            msg = str(exc)
            error = msg if test.record.name in msg else f"{test.record}: {msg}"
            out.append(ReducedTest(test, None, error, conditioned, rejected, meta))
        progress(i + 1, len(series.tests), "reducing")
    return out


def fit_series(reduced: list[ReducedTest]):
    """α1–α4 per diameter and pooled (:func:`softimpact.workflows.scaling.fit_groups`), flagged tests left out."""
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
        if r.fitted
    ]
    if not points:
        raise InputError("fit: no test of the series could be reduced unflagged (accept_flagged = true in a [[test]] fits a flagged one)")
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
    warnings = [r.error for r in reduced if r.reduction is None]
    if len(warnings) == len(reduced):
        raise InputError(f"no record of the series could be reduced (first: {warnings[0]})")
    return series, reduced, warnings


def reduce(series_name: str, figures: bool = True, progress: Progress = no_progress) -> Outcome:
    """Reduce the records of a series (file or built-in name)."""
    series, reduced, warnings = _reduce(series_name, progress)
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
    inputs = (series.path, *(t.record for t in series.tests))
    return Outcome(files, f"{done} of {len(reduced)} records reduced; tests.csv", inputs, tuple(warnings), gates)


def fit(series_name: str, figures: bool = True, progress: Progress = no_progress) -> Outcome:
    """Reduce a series, then fit the scaling constants α1–α4 of eqs (4)–(7) to its unflagged (or accepted) tests."""
    series, reduced, warnings = _reduce(series_name, progress)
    fits = fit_series(reduced)
    warnings += [
        f"{r.test.name}: not fitted (flagged: {r.rejected[0]}; accept_flagged = true fits it)" for r in reduced if r.reduction is not None and not r.fitted
    ]
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
    return Outcome(files, "\n".join(lines + ["scaling.json"]), inputs, tuple(warnings), gates)
