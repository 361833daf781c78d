"""A bar test series: every record conditioned and reduced to a force history, then the
scaling constants α1–α4 of eqs (4)–(7) fitted to the unflagged tests (paper Figs 7–15, Table I).

A study (one level above the workflows): it composes :mod:`softimpact.workflows.conditioning`,
:mod:`softimpact.workflows.reduction` and :mod:`softimpact.workflows.scaling`.

The records arrive read (strain against time, one per test, SI; the input layer reads
the files and applies the bridge): this module conditions each (baseline, first arrival,
clipping, double hits: :mod:`softimpact.workflows.conditioning`) and reduces it
(:func:`softimpact.workflows.reduction.reduce_record`). A *flagged* test (clipped, double
hit, or no pulse found) is still reduced, its reasons kept, but :func:`fit_series` leaves
it out unless its ``[[test]]`` says ``accept_flagged = true``. A record that cannot be
reduced is kept with its error and the others still reduce.

The series and its tests are read duck-typed (``tests``, ``bar``, ``gauge_position``,
``dispersion``, ``second_position``; per test ``name``, ``record``, ``second``,
``velocity``, ``mass``, ``diameter``, ``accept_flagged``), as
:class:`softimpact.input.series.Series` has them.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from functools import cached_property

from ..errors import InputError
from ..fem.bar import Rod
from ..gates import Gate, at_most, pulse_skew
from ..workflows.conditioning import Conditioned, condition_record
from ..workflows.reduction import Record, Reduction, fit_tail_shapes, reduce_record
from ..workflows.scaling import ScalingFit, TestPoint, fit_groups, tail_shape_term

__all__ = [
    "ReducedTest",
    "MAX_PULSE_MISFIT",
    "REJECTING_FLAGS",
    "condition",
    "reduce_series",
    "failed_reductions",
    "fit_series",
    "with_tail_shapes",
    "reduction_gates",
]

MAX_PULSE_MISFIT = 0.2  # RMS residual of the eq-15 fit / F0: above, T and tF0 do not describe the pulse
REJECTING_FLAGS = ("clipped", "double hit", "no pulse")  # conditioning flags that keep a test out of the fit


def _silent(done: int, total: int, label: str) -> None:
    """The default progress callback: silent."""


@dataclass(frozen=True)
class ReducedTest:
    """A test of a series with its reduction, or the reason it could not be reduced.

    ``rejected``: the conditioning's reasons not to fit it (empty: fit it).
    ``uncorrected``: with dispersion correction, the reduction without it.
    """

    test: object  # softimpact.input.series.SeriesTest
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

    @cached_property
    def tail_shapes(self) -> tuple:
        """The tail families fitted to the reduced force up to where the record holds it
        (:func:`softimpact.workflows.reduction.fit_tail_shapes`); () when not reduced."""
        r = self.reduction
        if r is None or getattr(r, "time", None) is None:  # no history to fit (a reduction read back without one)
            return ()
        keep = r.time <= r.valid_until
        try:
            return fit_tail_shapes(r.time[keep], r.force[keep])
        except (InputError, ValueError):
            return ()

    @property
    def status(self) -> str:
        if self.reduction is None:
            return "error"
        if self.rejected:
            return "flagged: accepted" if self.test.accept_flagged else "flagged: not fitted"
        return "ok"


def condition(series, time, strain) -> tuple[Conditioned | None, tuple[str, ...]]:
    """Conditioning of a strain record (``time`` [s], ``strain`` [-], shape (n,)) and the reasons
    (if any) it must not be fitted; (None, ()) when the record cannot be conditioned (the
    reduction then says what is wrong with it). The end cap delays the reflected wave by
    2·m_cap/Z (its mass over the bar's impedance)."""
    rod = Rod.of(series.bar)
    cap = 0.0 if series.bar.end_cap is None else series.bar.end_cap.mass
    try:
        c = condition_record(time, strain, series.gauge_position, series.bar.length, rod.wave_speed, end_delay=2 * cap / rod.impedance)
    except InputError:
        return None, ()
    return c, tuple(f for f in c.flags if f.startswith(REJECTING_FLAGS))


def reduce_series(series, records: Sequence, seconds: Sequence | None = None, *, progress: Callable[[int, int, str], None] = _silent) -> list[ReducedTest]:
    """Condition and reduce each test's record; a record that cannot be reduced is kept with its error.

    ``records``: one per test of ``series``, each with ``time`` [s], ``signal`` (strain) and
    ``metadata`` (:class:`softimpact.input.series.TestRecord`); ``seconds``: the second gauge's
    records (``series.second_position``), or None. With ``series.dispersion ==
    "pochhammer-chree"`` each test is reduced with and without the dispersion correction.
    """
    seconds = [None] * len(records) if seconds is None else seconds
    corrected = series.dispersion == "pochhammer-chree"
    out = []
    for i, (test, rec, rec2) in enumerate(zip(series.tests, records, seconds)):
        conditioned, rejected = condition(series, rec.time, rec.signal)
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


def failed_reductions(reduced: Sequence[ReducedTest]) -> list[str]:
    """The errors of the tests that could not be reduced; InputError when none could."""
    errors = [r.error for r in reduced if r.reduction is None]
    if reduced and len(errors) == len(reduced):
        raise InputError(f"no record of the series could be reduced (first: {errors[0]})")
    return errors


def fit_series(reduced: Sequence[ReducedTest]) -> dict[str, ScalingFit]:
    """α1–α4 of eqs (4)–(7) per diameter and pooled (:func:`softimpact.workflows.scaling.fit_groups`)
    from each fitted test's V [m/s], m [kg], d [m] and reduced F0 [N], tF0, T [s], I [N·s];
    flagged tests left out (InputError when none is left)."""
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
    shapes = {r.test.name: r.tail_shapes for r in reduced if r.fitted}
    return with_tail_shapes(fit_groups(points), shapes)


def with_tail_shapes(fits: dict[str, ScalingFit], shapes: dict) -> dict[str, ScalingFit]:
    """Each group's fit with its tail-shape term (:func:`softimpact.workflows.scaling.tail_shape_term`):
    ``shapes`` test name → its TailShapeFits (one per family); the group's points refitted with each
    family's F0, t_F0, T, with their standard errors, and the families' AICs summed over the group. Unchanged when a test of the
    group has no tail fits."""
    out = {}
    for label, g in fits.items():
        per_test = [shapes.get(p.name, ()) for p in g.points]
        if not all(per_test):
            out[label] = g
            continue
        families = [f.family for f in per_test[0]]
        family_points = {
            fam: [replace(p, peak_force=s[k].peak_force, time_of_peak=s[k].time_of_peak, duration=s[k].duration) for p, s in zip(g.points, per_test)]
            for k, fam in enumerate(families)
        }
        aic = {fam: float(sum(s[k].aic for s in per_test)) for k, fam in enumerate(families)}
        errors = {fam: [(s[k].se_peak_force, s[k].se_time_of_peak, s[k].se_duration) for s in per_test] for k, fam in enumerate(families)}
        out[label] = replace(g, tail_shape=tail_shape_term(g, family_points, aic, errors))
    return out


def reduction_gates(reduced: Sequence[ReducedTest]) -> tuple[Gate, ...]:
    """Quality gates of each reduced test (:mod:`softimpact.gates`): the eq-15 pulse must fit
    the force (RMS residual within MAX_PULSE_MISFIT of F0) and must not be degenerate
    (tF0/T below :data:`softimpact.gates.MAX_SKEW`)."""
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
        gates.append(pulse_skew(name, d.time_of_peak, d.duration))
    return tuple(gates)
