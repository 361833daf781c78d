"""Conditioning of raw bar records: baseline, clipping, first arrival, reflections, double hits."""

import math
import re

import numpy as np
import pytest

from softimpact.errors import InputError
from softimpact.models.pulses import SkewedPulse
from softimpact.workflows import conditioning as cond

from _support.constants import INCH

L, X, C = 2.0, 18 * INCH, 5051.0  # bar length [m], gauge position [m], wave speed [m/s]
PRE = 50e-6  # s of pre-trigger: first contact at t = 0, record from −PRE
PULSE = SkewedPulse(1.0, 10e-6, 60e-6)
EPS0 = 500e-6  # peak strain
NOISE = 1e-3 * EPS0


def gauge_strain(t, hits=((0.0, 1.0),)):
    """Free–free bar by d'Alembert (independent of the package): −ε0 Σ ±F(t − t_hit − path/c) over the paths x, 2L−x, 2L+x, …"""
    y = np.zeros_like(t)
    for t_hit, scale in hits:
        for k in range(4):
            y -= scale * EPS0 * PULSE(t - t_hit - (2 * k * L + X) / C)  # incident sign
            y += scale * EPS0 * PULSE(t - t_hit - (2 * (k + 1) * L - X) / C)  # reflected at the far end
    return y


def record(dt, hits=((0.0, 1.0),), duration=1.5e-3, seed=1, noise=NOISE):
    t = np.arange(-PRE, duration, dt)
    rng = np.random.default_rng(seed)
    return t, gauge_strain(t, hits) + 0.2e-6 + noise * rng.standard_normal(t.size)


@pytest.mark.parametrize("dt", [0.01e-6, 0.1e-6, 1e-6])
def test_clean_record_has_no_flags(dt):
    """A noisy single-impact record with its reflections raises no flag, and every later onset is a predicted reflection."""
    t, y = record(dt)
    c = cond.condition_record(t, y, X, L, C)
    assert c.flags == ()
    assert not c.clipped and not c.double_hit
    assert c.onsets and all(explained for _, _, explained in c.onsets)
    assert c.incident_sign == -1
    assert c.baseline == pytest.approx(0.2e-6, abs=4 * NOISE / math.sqrt(c.pretrigger_samples))
    assert c.noise == pytest.approx(NOISE, rel=0.2)


@pytest.mark.parametrize("dt", [0.01e-6, 0.02e-6, 0.1e-6, 0.5e-6, 1e-6])
def test_first_arrival_within_a_sample(dt):
    """The foot of the incident pulse is found within one sample (or 20 ns) of X/c at every sampling interval."""
    t, y = record(dt, duration=0.3e-3)
    c = cond.condition_record(t, y, X, L, C)
    assert abs(c.arrival_time - X / C) <= max(dt, 20e-9)


def test_reflections_are_predicted_and_recognised():
    """The tensile onset at X/c + 2(L−X)/c and the compressive one at X/c + 2L/c are found and explained."""
    t, y = record(0.1e-6)
    c = cond.condition_record(t, y, X, L, C)
    tensile = [on for on, s, _ in c.onsets if s < 0]
    compressive = [on for on, s, _ in c.onsets if s > 0]
    assert tensile[0] == pytest.approx(X / C + 2 * (L - X) / C, abs=0.5e-6)
    assert compressive[0] == pytest.approx(X / C + 2 * L / C, abs=0.5e-6)
    assert c.tensile_arrivals[0] == pytest.approx((2 * L - X) / C, abs=0.2e-6)


def test_incident_window_covers_the_pulse():
    """The incident window starts at the arrival and ends within a few µs after the 60-µs pulse."""
    t, y = record(0.1e-6)
    c = cond.condition_record(t, y, X, L, C)
    start, end = c.incident_window
    assert start == pytest.approx(X / C, abs=0.2e-6)
    assert X / C + 55e-6 < end < X / C + 62e-6


def test_clipped_peak_is_flagged():
    """A record saturated at 70 % of its peak is flagged as clipped, with the reason."""
    t, y = record(0.1e-6)
    y = np.maximum(y, -0.7 * EPS0)
    c = cond.condition_record(t, y, X, L, C)
    assert c.clipped
    assert any("clipped" in f and "minimum" in f for f in c.flags)


def test_adc_range_clipping_is_flagged():
    """Samples at the end of a stated ADC range are flagged even when the run is short."""
    t, y = record(0.1e-6)
    c = cond.condition_record(t, y, X, L, C, adc_range=(-0.9 * EPS0, 1.0))
    assert c.clipped and any("ADC range" in f for f in c.flags)


def test_quantised_smooth_peak_is_not_clipping():
    """A finely sampled record quantised to 1/400 of its peak has flat runs at the peak but is not flagged."""
    t, y = record(0.01e-6, duration=0.3e-3)
    lsb = EPS0 / 400
    c = cond.condition_record(t, np.round(y / lsb) * lsb, X, L, C)
    assert not c.clipped


def test_second_impact_is_a_double_hit():
    """A second impact 250 µs after the first (not a reflection delay) is flagged as a double hit."""
    t, y = record(0.1e-6, hits=((0.0, 1.0), (250e-6, 0.4)))
    c = cond.condition_record(t, y, X, L, C)
    assert c.double_hit
    (flag,) = [f for f in c.flags if f.startswith("double hit")]
    after = float(re.search(r"arrival ([\d.]+) µs after the first", flag).group(1))
    assert after == pytest.approx(250.0, abs=0.5)


def test_overlapping_second_impact_is_a_double_hit():
    """A second impact 45 µs after the first, while the first pulse is still falling, is flagged."""
    t, y = record(0.1e-6, hits=((0.0, 1.0), (45e-6, 0.6)))
    c = cond.condition_record(t, y, X, L, C)
    assert c.double_hit


def test_no_pulse_is_flagged_not_raised():
    """Noise alone gives a 'no pulse' flag and a NaN arrival."""
    t = np.arange(-PRE, 0.5e-3, 0.1e-6)
    y = NOISE * np.random.default_rng(3).standard_normal(t.size)
    c = cond.condition_record(t, y, X, L, C, settings=cond.ConditioningSettings(detection_fraction=0.0, detection_sigmas=8.0))
    assert math.isnan(c.arrival_time)
    assert any("no pulse" in f for f in c.flags)


def test_short_pretrigger_is_flagged():
    """A record that starts 1 µs before the pulse flags its short pre-trigger."""
    t, y = record(0.1e-6)
    keep = t >= X / C - 1e-6
    c = cond.condition_record(t[keep], y[keep], X, L, C)
    assert any("pre-trigger" in f for f in c.flags)


def test_noise_estimate_ignores_spikes():
    """Five large spikes in the pre-trigger do not move the MAD noise estimate by more than 10 %."""
    rng = np.random.default_rng(5)
    v = rng.standard_normal(2000)
    v[::400] = 50.0
    base, sigma = cond.baseline_and_noise(v)
    assert sigma == pytest.approx(1.0, rel=0.1)
    assert abs(base) < 0.1


def test_expected_arrivals_closed_form():
    """Predicted arrivals: same sign every 2L/c, opposite sign 2(L−x)/c later."""
    same, opposite = cond.expected_arrivals(1e-4, 0.5, 2.0, 5000.0, count=2)
    assert same == pytest.approx((1e-4 + 8e-4, 1e-4 + 16e-4))
    assert opposite == pytest.approx((1e-4 + 6e-4, 1e-4 + 14e-4))


@pytest.mark.parametrize(
    "args",
    [
        (np.arange(10.0), np.zeros(9), X, L, C),
        (np.zeros(10), np.zeros(10), X, L, C),
        (np.arange(10.0), np.zeros(10), 3.0, L, C),
        (np.arange(10.0), np.zeros(10), X, L, -1.0),
    ],
)
def test_malformed_arguments_raise(args):
    """Unequal lengths, non-increasing time and impossible bar geometry raise InputError."""
    with pytest.raises(InputError):
        cond.condition_record(*args)


def test_imports_no_other_workflow():
    """conditioning.py imports nothing from the other workflow modules (the layering rule)."""
    import ast
    import inspect

    tree = ast.parse(inspect.getsource(cond))
    modules = [n.module or "" for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)]
    modules += [a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names]
    assert not [m for m in modules if "workflows" in m or (m.startswith(".") is False and m in ("bar_impact", "reduction"))]
    assert all(n.level <= 2 for n in ast.walk(tree) if isinstance(n, ast.ImportFrom))
    assert {n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom) and n.level == 1} == set()
