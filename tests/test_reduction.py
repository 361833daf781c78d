"""Bar records → force histories (paper Figs 7-15), against records made by the bar FE."""

import numpy as np
import pytest

from softimpact.errors import InputError
from softimpact.models.bridge import Bridge
from softimpact.models.materials import lookup
from softimpact.models.pulses import SkewedPulse, TailedPulse
from softimpact.models.specimens import BarSpec, EndCap
from softimpact.workflows.reduction import Record, reduce_record, wave_separation
from softimpact.workflows.synthetic import gauge_model, synthetic_record

from _support.constants import INCH

AL = lookup("Al 6061-T6")
PLAIN = BarSpec(AL, 36 * INCH, 0.5 * INCH, 96)
CAPPED = BarSpec(AL, 36 * INCH, 0.5 * INCH, 96, EndCap(AL, 1.0 * INCH, 0.25 * INCH))
GAUGE = 18 * INCH
LONG = SkewedPulse(120.0, 115e-6, 465e-6)  # 1/2-in ball at 1000 in/s: 2.6 reflection return times long
SHORT = SkewedPulse(2900.0, 23e-6, 93e-6)  # 1/2-in ball at 5000 in/s


@pytest.fixture(scope="module")
def gauges():
    return {bar.end_cap is None: gauge_model(bar, GAUGE, 0.5e-6, 2.6e-3) for bar in (PLAIN, CAPPED)}


def _record(gauge, pulse, seed):
    """A record as an experimenter would take it: 250 µs pre-trigger, time base ≈ 5 main-pulse durations or the tail."""
    main = getattr(pulse, "main", pulse)
    length = min(2.4e-3, 250e-6 + max(5 * main.duration, pulse.duration))
    rng = np.random.default_rng(seed)
    t, y = synthetic_record(
        gauge,
        pulse,
        pre_trigger=250e-6,
        length=length,
        sample_interval=1e-6,
        noise=0.01,
        offset=rng.normal(0, 2e-5),
        clock_start=rng.uniform(-1, 1),
        rng=rng,
    )
    return Record(f"seed{seed}", t, y)


CASES = [
    ("long pulse", LONG, PLAIN),
    ("short pulse", SHORT, PLAIN),
    ("long pulse, tail", TailedPulse.with_impulse(LONG, 0.04, 1.05 * LONG.impulse), PLAIN),
    ("short pulse, end cap", SHORT, CAPPED),
    ("long pulse, tail, end cap", TailedPulse.with_impulse(LONG, 0.04, 1.05 * LONG.impulse), CAPPED),
]


@pytest.mark.parametrize("seed", [1, 2, 3])
@pytest.mark.parametrize("label, pulse, bar", CASES, ids=[c[0] for c in CASES])
def test_parameters_recovered_from_fe_records(gauges, label, pulse, bar, seed):
    """1 % noise, offset, arbitrary clock: F0 within 2 %, T 4 %, t_F0 10 %, I 2 % (I of the whole history)."""
    main = getattr(pulse, "main", pulse)
    r = reduce_record(_record(gauges[bar.end_cap is None], pulse, seed), bar, GAUGE)
    assert r.peak_force == pytest.approx(main.peak_force, rel=0.02)
    assert r.duration == pytest.approx(main.duration, rel=0.04)
    assert r.time_of_peak == pytest.approx(main.time_of_peak, rel=0.10)
    assert r.impulse == pytest.approx(pulse.impulse, rel=0.02)


def test_first_contact_on_the_record_clock(gauges):
    """First contact is located on the record's own clock to within 2 µs."""
    rng = np.random.default_rng(7)
    t, y = synthetic_record(gauges[True], LONG, pre_trigger=250e-6, length=2e-3, sample_interval=1e-6, noise=0.01, offset=0.0, clock_start=5.0, rng=rng)
    r = reduce_record(Record("x", t, y), PLAIN, GAUGE)
    assert abs(r.first_contact_record_time - (5.0 + 250e-6)) < 2e-6


def test_long_pulse_is_flagged_and_window_reported(gauges):
    """A pulse longer than 2(L−x)/c is flagged as reflection-corrected; the valid window is reported."""
    r = reduce_record(_record(gauges[True], LONG, 4), PLAIN, GAUGE)
    tau = 2 * (PLAIN.length - GAUGE) / AL.wave_speed
    assert any("reflection" in f for f in r.flags)
    assert r.direct_until == pytest.approx(tau, abs=3e-6)
    assert r.valid_until > LONG.duration


def test_wave_separation_inverts_dalembert():
    """Strain built from F by d'Alembert's sum of reflections (written here) is inverted exactly."""
    c, L, x = 5000.0, 1.0, 0.3
    tau, P = 2 * (L - x) / c, 2 * L / c
    t = np.arange(0, 3e-3, 1e-7)
    F = SkewedPulse(100.0, 2e-4, 9e-4)
    s = sum(F(t - k * P) - F(t - tau - k * P) for k in range(8))  # −EA·ε(x, t + x/c)
    Fr, _ = wave_separation(s, t, tau, P)
    assert np.max(np.abs(Fr - F(t))) < 1e-6 * 100.0


def test_quarter_bridge_against_exact_wheatstone():
    """ε from V_out inverts the exact quarter-bridge output V·(ΔR/R)/(4 + 2ΔR/R) (tension reading positive: polarity −1)."""
    GF, Vexc, gain, eps = 2.1, 5.0, 100.0, -250e-6
    dr = GF * eps
    vout = gain * Vexc * dr / (4 + 2 * dr)
    assert Bridge("quarter", GF, Vexc, gain, polarity=-1).strain(vout) == pytest.approx(eps, rel=1e-12)


def _clean(n=800):
    t = np.arange(n) * 1e-6
    y = -1e-4 * SkewedPulse(1.0, 50e-6, 200e-6)(t - 200e-6) + 1e-7 * np.random.default_rng(0).standard_normal(n)
    return t, y


@pytest.mark.parametrize(
    "mutate, message",
    [
        (lambda t, y: (t[::-1], y), "not strictly increasing"),
        (lambda t, y: (np.concatenate((t[:10], t[9:-1])), y), "not strictly increasing"),
        (lambda t, y: (t, np.where(np.arange(t.size) == 300, np.nan, y)), "NaN"),
        (lambda t, y: (t[:20], y[:20]), "too short"),
        (lambda t, y: (t, 1e-7 * np.random.default_rng(1).standard_normal(t.size)), "no pulse"),
        (lambda t, y: (t, np.maximum(y, -0.6e-4)), "clipped"),
    ],
    ids=["unsorted", "repeated time", "NaN", "too short", "no pulse", "clipped"],
)
def test_bad_records_are_refused_naming_the_record(mutate, message):
    """Each defect gives an InputError that names the record and says what is wrong."""
    t, y = mutate(*_clean())
    with pytest.raises(InputError, match=f"rec-7.*{message}"):
        reduce_record(Record("rec-7", t, y), PLAIN, GAUGE)


def test_clean_record_reduces():
    """The unmutated record of the bad-record tests reduces (so the failures above are the defects)."""
    t, y = _clean()
    r = reduce_record(Record("rec-7", t, y), PLAIN, GAUGE)
    assert r.peak_force == pytest.approx(1e-4 * AL.youngs_modulus * PLAIN.area, rel=0.02)


def test_noise_free_record_reduces():
    """A record without noise (zero standard errors) reduces to its pulse instead of dividing by zero."""
    al = lookup("Al 6061-T6")
    bar = BarSpec(al, 36 * INCH, 0.5 * INCH, 144)
    gauge = gauge_model(bar, 18 * INCH, 0.25e-6, 1.0e-3)
    pulse = SkewedPulse(200.0, 10e-6, 60e-6)
    t, y = synthetic_record(
        gauge, pulse, pre_trigger=50e-6, length=0.9e-3, sample_interval=0.5e-6, noise=0.0, offset=0.0, clock_start=0.0, rng=np.random.default_rng(1)
    )
    r = reduce_record(Record("clean", t, y), bar, 18 * INCH)
    assert r.peak_force == pytest.approx(pulse.peak_force, rel=0.01)
    assert r.impulse == pytest.approx(pulse.impulse, rel=0.01)
