"""studies/series.py (reduce a bar series, fit α1–α4) and the identification tests made from it,
at the workflow level: against the pulse that made a record, the paper's Table I, and closed forms."""

from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from softimpact.errors import InputError
from softimpact.gates import MAX_SKEW, pulse_skew
from softimpact.models.materials import lookup
from softimpact.models.pulses import SkewedPulse
from softimpact.models.specimens import BarSpec
from softimpact.studies.series import ReducedTest, failed_reductions, fit_series, reduce_series
from softimpact.workflows.identification import bar_tests

INCH = 0.0254  # m, by definition
GRAM = 1e-3  # kg

# Table I of the paper (α1, α2, α3, α4); α3 of the 1/2-in ball was lost, 0.25 (the 3/8-in value) made the series.
TABLE_I = {"0.375 in": (4.00, 1.03, 0.25, 0.74), "0.5 in": (4.25, 0.93, 0.25, 0.66)}


def _test(name, velocity, diameter=0.5 * INCH, mass=1.1 * GRAM, accept_flagged=False):
    return SimpleNamespace(name=name, record=Path(f"{name}.csv"), second=None, velocity=velocity, diameter=diameter, mass=mass, accept_flagged=accept_flagged)


def _reduced(test, alphas, rejected=()):
    """A ReducedTest whose pulse parameters follow eqs (4)-(7) exactly with the given α's."""
    a1, a2, a3, a4 = alphas
    m, d, V = test.mass, test.diameter, test.velocity
    T = a2 * d / V
    red = SimpleNamespace(peak_force=a1 * m * V**2 / (2 * d), time_of_peak=a3 * T, duration=T, impulse=a4 * 2 * m * V)
    return ReducedTest(test, red, rejected=rejected)


def test_reduce_series_recovers_the_pulse_that_made_a_record():
    """A gauge record computed by the bar FE from a known eq-15 pulse (no noise) reduces to that pulse's F0, tF0, T and 2F0T/π."""
    from softimpact.workflows.synthetic import gauge_model, synthetic_record

    al = lookup("Al 6061-T6")
    bar = BarSpec(al, 36 * INCH, 0.5 * INCH, 144)
    pulse = SkewedPulse(500.0, 30e-6, 150e-6)
    gauge = gauge_model(bar, 18 * INCH, 0.25e-6, 1.2e-3)
    t, eps = synthetic_record(
        gauge, pulse, pre_trigger=100e-6, length=1.0e-3, sample_interval=0.5e-6, noise=0.0, offset=0.0, clock_start=0.0, rng=np.random.default_rng(1)
    )
    series = SimpleNamespace(tests=[_test("a", 1000 * INCH)], bar=bar, gauge_position=18 * INCH, dispersion="none", second_position=None)
    (r,) = reduce_series(series, [SimpleNamespace(time=t, signal=eps, metadata={})])
    d = r.reduction
    assert r.error == "" and r.rejected == ()
    assert d.peak_force == pytest.approx(500.0, rel=0.02)
    assert d.time_of_peak == pytest.approx(30e-6, rel=0.05)
    assert d.duration == pytest.approx(150e-6, rel=0.03)
    assert d.impulse == pytest.approx(2 * 500.0 * 150e-6 / np.pi, rel=0.02)


def test_fit_series_recovers_the_alphas_of_exact_pulse_parameters():
    """Tests whose F0, T, tF0, I follow eqs (4)-(7) exactly give back those α's (closed form, through the origin)."""
    alphas = (4.1, 0.95, 0.2, 0.7)
    reduced = [_reduced(_test(f"t{v}", v * INCH), alphas) for v in (1000, 2500, 4000)]
    fits = fit_series(reduced)
    assert list(fits) == ["0.5 in"]
    got = [fits["0.5 in"].origin[f"alpha{i}"].slope for i in (1, 2, 3, 4)]
    assert got == pytest.approx(alphas, rel=1e-9)


def test_flagged_tests_stay_out_of_the_fit_unless_accepted():
    """A flagged test (here with wrong α's) leaves the fit unchanged, unless its [[test]] accepts it; none fitted is bad input."""
    good = [_reduced(_test(f"t{v}", v * INCH), (4.0, 1.0, 0.25, 0.7)) for v in (1000, 3000)]
    bad = _reduced(_test("clipped", 2000 * INCH), (8.0, 1.0, 0.25, 0.7), rejected=("clipped",))
    accepted = _reduced(_test("clipped", 2000 * INCH, accept_flagged=True), (8.0, 1.0, 0.25, 0.7), rejected=("clipped",))
    assert fit_series([*good, bad])["0.5 in"].origin["alpha1"].slope == pytest.approx(4.0, rel=1e-9)
    assert fit_series([*good, accepted])["0.5 in"].origin["alpha1"].slope > 4.5
    with pytest.raises(InputError, match="no test of the series could be reduced unflagged"):
        fit_series([bad])


def test_failed_reductions_refuse_only_a_series_where_nothing_reduced():
    """The errors of unreduced records are returned as warnings; a series of which none reduced is bad input."""
    ok = _reduced(_test("a", 1000 * INCH), (4.0, 1.0, 0.25, 0.7))
    broken = ReducedTest(_test("b", 2000 * INCH), None, "b.csv: truncated")
    assert failed_reductions([ok, broken]) == ["b.csv: truncated"]
    with pytest.raises(InputError, match="b.csv: truncated"):
        failed_reductions([broken])


@pytest.mark.parametrize(("time_of_peak", "duration", "passed"), [(25e-6, 100e-6, True), (96e-6, 100e-6, False), (1e-6, 0.0, False)])
def test_pulse_skew_gate(time_of_peak, duration, passed):
    """The one degenerate-pulse gate of reduce, fit and calibrate: tF0/T must stay below MAX_SKEW; T ≤ 0 cannot be checked and fails."""
    gate = pulse_skew("x", time_of_peak, duration)
    assert gate.passed is passed and gate.limit == MAX_SKEW and gate.name == "pulse-skew[x]"


def test_bar_tests_resample_the_force_evenly_up_to_where_the_record_holds_it():
    """identify's tests: time from 0 at the reduction's median step, ending within valid_until, the force interpolated (exact for a linear force)."""
    t = np.concatenate([np.arange(0.0, 50e-6, 1e-6), np.arange(50e-6, 200e-6, 1.5e-6)])
    red = SimpleNamespace(time=t, force=3e6 * t, valid_until=120e-6)
    dt = float(np.median(np.diff(t)))
    tests = bar_tests([ReducedTest(_test(n, 1000 * INCH), red) for n in ("a", "b")] + [ReducedTest(_test("c", 1), None, "c: no")])
    assert [b.name for b in tests] == ["a", "b"]
    b = tests[0]
    assert b.time[0] == 0.0 and np.allclose(np.diff(b.time), dt) and b.time[-1] <= 120e-6 + 0.5 * dt
    assert b.force == pytest.approx(3e6 * b.time, rel=1e-12, abs=1e-9)
    with pytest.raises(InputError, match="at least two"):
        bar_tests([ReducedTest(_test("a", 1000 * INCH), red)])


@pytest.mark.slow
def test_fit_of_the_built_in_series_recovers_table_I():
    """The built-in synthetic rubber series (made from Table I, tail, 1 % noise) fits back to Table I: α1, α2, α4 within 3 %, α3 within 10 %."""
    from softimpact.input.series import load_series
    from softimpact.input.series_records import read_series_records

    series = load_series("paper-rubber-series")
    fits = fit_series(reduce_series(series, *read_series_records(series)))
    for label, alphas in TABLE_I.items():
        for i, (expected, tol) in enumerate(zip(alphas, (0.03, 0.03, 0.10, 0.03)), 1):
            assert fits[label].origin[f"alpha{i}"].slope == pytest.approx(expected, rel=tol), (label, i)
