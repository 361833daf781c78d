"""Conditioning of a raw bar-gauge record before reduction: baseline, noise,
clipping, first arrival, the incident window, expected reflections, double hits.

Nothing here raises on a doubtful record: each check adds a *flag*, a sentence
saying what was seen and why it matters, and the caller decides. Only malformed
arguments (unequal lengths, non-increasing time) raise InputError.

The bar is free–free, length L, gauge at x from the struck end, wave speed c.
On the record's clock, with t_a the first arrival at the gauge (Grady's Fig 3
geometry; d'Alembert):

- waves of the incident sign (compressive) arrive at t_a + k·2L/c, k = 0, 1, …
  (reflected once at each free end),
- waves of the opposite sign (tensile) at t_a + 2(L − x)/c + k·2L/c
  (reflected once more, at the far end).

The incident window runs from t_a until the signal has come back to the
baseline (within 3σ, for 2 µs or 3 samples), and never past the first
reflection at t_a + 2(L − x)/c. A *double hit* is an onset of the incident
sign that matches none of the predicted arrival times (of either sign: a
reflection off a mass-loaded end starts with a lobe of the other sign) within
a tolerance of max(5 samples, 2 µs, 2 % of the elapsed time — the uncertainty
of c): a second impact of the projectile (a rebound, or a bounce off the
support). An end cap of mass m delays each struck-end reflection by 2m/(ρcA)
(``end_delay``). When the incident pulse is still going as its first
reflection returns, later onsets are mixtures of waves and are not classified
by their times; only a second rise inside the incident window counts then.

Baseline: median of the pre-trigger (samples before t = 0, or before the
arrival less a margin, whichever holds more); noise σ: median absolute
deviation scaled to a normal σ (scipy.stats.median_abs_deviation,
scale='normal'), insensitive to a few spikes.

First arrival: the first sample where |y − baseline| exceeds ``sigmas``·σ
(and 2 % of the record's largest excursion), refined backwards to the foot:
the run above 1σ that leads to it is followed back to its start, and a
straight line fitted to the rising edge from there to 4 times the detection
level is extended back to the baseline. Works at any sampling interval (tested
from 0.01 µs to 1 µs).

Clipping: a flat run of at least ``clip_run`` samples at the record's maximum
or minimum, entered with a slope that would have carried the signal on by more
than 3σ over the run (a quantised smooth peak is entered with zero slope and is
not flagged), or any sample at the ends of the ADC range when it is given.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..models.noise import robust_sigma
from ..models.sampling import series_problem

__all__ = [
    "ConditioningSettings",
    "Conditioned",
    "condition_record",
    "baseline_and_noise",
    "detect_clipping",
    "first_arrival",
    "expected_arrivals",
]

MIN_PRETRIGGER = 20  # fewer samples make the median and MAD unreliable: flagged
QUIET_TIME = 2e-6  # s: the signal must stay near the baseline this long for a pulse to have ended


@dataclass(frozen=True)
class ConditioningSettings:
    """Thresholds; see the module docstring."""

    detection_sigmas: float = 8.0  # arrival: excursion beyond this many σ ...
    detection_fraction: float = 0.02  # ... and beyond this fraction of the largest excursion
    event_fraction: float = 0.10  # a later onset counts when it exceeds this fraction of the incident peak
    clip_run: int = 4  # equal samples at an extreme that may be clipping
    reflections: int = 6  # predicted arrivals listed


@dataclass(frozen=True)
class Conditioned:
    """A conditioned record. Times on the record's clock [s].

    ``signal`` is the record less its baseline. ``arrival_time`` is NaN when no
    pulse was found. ``incident_window`` is (start, end). ``compressive_arrivals``
    and ``tensile_arrivals`` are the predicted times (incident sign and opposite
    sign). ``onsets`` lists the detected onsets as (time, sign relative to the
    incident: +1 or −1, explained: True if a predicted arrival).
    """

    time: np.ndarray
    signal: np.ndarray
    baseline: float
    noise: float
    pretrigger_samples: int
    arrival_time: float
    arrival_index: int
    incident_sign: int
    incident_peak: float
    incident_window: tuple[float, float]
    compressive_arrivals: tuple[float, ...]
    tensile_arrivals: tuple[float, ...]
    onsets: tuple[tuple[float, int, bool], ...]
    clipped: bool
    double_hit: bool
    flags: tuple[str, ...]


def _arrays(t, y):
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    problem = series_problem(t, y, min_samples=8)
    if problem is not None:
        raise InputError(f"conditioning: {problem}")
    return t, y


def baseline_and_noise(values) -> tuple[float, float]:
    """(median, MAD-based σ) of pre-trigger samples."""
    v = np.asarray(values, dtype=float)
    return float(np.median(v)), float(robust_sigma(v))


def detect_clipping(y, noise: float, clip_run: int = 4, adc_range: tuple[float, float] | None = None) -> list[str]:
    """Reasons (possibly none) to think the record is clipped (module docstring)."""
    y = np.asarray(y, dtype=float)
    reasons = []
    span = float(np.ptp(y)) or 1.0
    for label, extreme in (("maximum", y.max()), ("minimum", y.min())):
        at = np.abs(y - extreme) <= 1e-9 * span
        edges = np.diff(np.concatenate(([0], at.astype(np.int8), [0])))
        starts, ends = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
        for s, e in zip(starts, ends):
            run = e - s
            if run < clip_run:
                continue
            before = y[max(s - 3, 0) : s + 1]
            slope = float(np.max(np.abs(np.diff(before)))) if before.size > 1 else math.inf
            if slope * run / 2 > 3 * noise:
                reasons.append(
                    f"clipped: {run} consecutive samples at the record's {label} {extreme:.6g}, entered steeply "
                    "(recorder or amplifier saturated): the peak is not in the record"
                )
                break
    if adc_range is not None:
        lo, hi = adc_range
        tol = 1e-9 * (hi - lo)
        n_hi, n_lo = int(np.sum(y >= hi - tol)), int(np.sum(y <= lo + tol))
        if n_hi or n_lo:
            reasons.append(f"clipped: {n_hi + n_lo} samples at the ends of the ADC range [{lo:.6g}, {hi:.6g}]")
    return reasons


def _foot(t, dev, i_det, level, noise):
    """Refine a detection at i_det back to the foot of the edge (module docstring). dev > 0 on the edge."""
    i = i_det
    while i > 0 and dev[i - 1] > 3 * noise:  # 1σ is crossed by noise alone one sample in six
        i -= 1
    hi = i_det
    while hi + 1 < dev.size and dev[hi] < 4 * level:
        hi += 1
    hi = min(max(hi, i + 1), dev.size - 1)
    if hi <= i:
        return float(t[i])
    slope, icpt = np.polyfit(t[i : hi + 1] - t[i], dev[i : hi + 1], 1)
    if slope <= 0:
        return float(t[i])
    below = np.flatnonzero(dev[:i] <= 0)  # the edge cannot start before the last sample at the baseline
    earliest = t[below[-1]] if below.size else t[0]
    return float(np.clip(t[i] - icpt / slope, earliest, t[i_det]))


def first_arrival(t, y, baseline: float, noise: float, settings: ConditioningSettings = ConditioningSettings()):
    """(time of the foot, index of detection, sign) of the first excursion; (nan, -1, 0) if none."""
    t, y = _arrays(t, y)
    dev = y - baseline
    level = max(settings.detection_sigmas * noise, settings.detection_fraction * float(np.max(np.abs(dev))))
    above = np.flatnonzero(np.abs(dev) > level)
    if above.size == 0 or noise <= 0 and level == 0:
        return math.nan, -1, 0
    i_det = int(above[0])
    sign = 1 if dev[i_det] > 0 else -1
    return _foot(t, sign * dev, i_det, level, noise), i_det, sign


def expected_arrivals(arrival: float, gauge_position: float, bar_length: float, wave_speed: float, count: int = 6, end_delay: float = 0.0):
    """(incident-sign times, opposite-sign times) after ``arrival`` on a free–free bar (module docstring).

    ``end_delay`` [s]: the delay of each reflection at the struck end (2m/(ρcA)
    for an end cap of mass m: the low-frequency group delay of a mass-loaded
    free end, whose reflection coefficient is −(Z − iωm)/(Z + iωm)).
    """
    period = 2 * bar_length / wave_speed
    tau = 2 * (bar_length - gauge_position) / wave_speed
    same = tuple(arrival + k * (period + end_delay) for k in range(1, count + 1))
    opposite = tuple(arrival + tau + k * (period + end_delay) for k in range(count))
    return same, opposite


def _onsets(t, dev, level, quiet_samples):
    """Start indices of excursions of dev above level that follow a quiet stretch (|dev| < level/2)."""
    out = []
    quiet = 0
    armed = False
    for i, v in enumerate(dev):
        if abs(v) < 0.5 * level:
            quiet += 1
            if quiet >= quiet_samples:
                armed = True
        else:
            quiet = 0
        if armed and abs(v) > level:
            out.append(i)
            armed = False
    return out


def _pretrigger(t, y, pretrigger_end, dt, settings):
    """Baseline, noise and first arrival, in two passes (module docstring).

    Pass 1: a provisional pre-trigger; pass 2: everything before the arrival less
    a margin. Returns (base, noise, arrival, i_det, sign, n_pre).
    """
    end = pretrigger_end if pretrigger_end is not None else (0.0 if t[0] < 0 else None)
    first = np.arange(t.size) < MIN_PRETRIGGER  # provisional only: pass 2 takes all that precedes the arrival
    pre = t < end if end is not None else first
    if pre.sum() < MIN_PRETRIGGER:
        pre = first
    base, noise = baseline_and_noise(y[pre])
    arrival, i_det, sign = first_arrival(t, y, base, noise, settings)
    n_pre = int(pre.sum())
    if math.isfinite(arrival):
        margin = max(10 * dt, 1e-6)
        pre2 = t < arrival - margin
        if pretrigger_end is not None:
            pre2 &= t < pretrigger_end
        n_pre = int(pre2.sum())
        if n_pre >= 3 and (n_pre >= pre.sum() or (pre & ~pre2).any()):
            base, noise = baseline_and_noise(y[pre2])
            arrival, i_det, sign = first_arrival(t, y, base, noise, settings)
    return base, noise, arrival, i_det, sign, n_pre


def _window_end(t, dev, i_det, arrival, tau, noise, quiet_samples) -> float:
    """End of the incident window: back within 3σ for QUIET_TIME, at most until the first reflection."""
    k_end = None
    calm = np.abs(dev) < max(3 * noise, 0.01 * np.max(np.abs(dev)))
    run = 0
    for i in range(i_det, t.size):
        run = run + 1 if calm[i] else 0
        if run >= quiet_samples:
            k_end = i - run + 1
            break
        if t[i] >= arrival + tau:
            break
    return float(t[k_end]) if k_end is not None else min(float(t[-1]), arrival + tau)


def _later_onsets(t, dev, sign, arrival, window_end, level, noise, quiet_samples, geometry, settings, flags):
    """Onsets after the incident window, each classified against the predicted arrivals of every impact so far.

    ``geometry``: (gauge_position, bar_length, wave_speed, end_delay). A flag is
    added to ``flags`` for each double hit. Returns (onsets, double).
    """
    dt = float(np.median(np.diff(t)))
    onsets = []
    double = False
    start = int(np.searchsorted(t, window_end))
    sources = [arrival]  # impacts so far: each one's reflections are expected
    for i in _onsets(t[start:], dev[start:], level, quiet_samples):
        i += start
        s = 1 if dev[i] * sign > 0 else -1
        t_on = _foot(t, s * sign * dev, i, level, noise)
        predicted = []
        for t_hit in sources:
            p_same, p_opp = expected_arrivals(t_hit, geometry[0], geometry[1], geometry[2], settings.reflections, geometry[3])
            # Either sign: a reflection off a mass-loaded or imperfect end starts with a lobe
            # of the other sign, so an onset at a predicted time of either sign is explained.
            predicted += [(p, max(5 * dt, 2e-6, 0.02 * (p - t_hit))) for p in p_same + p_opp]
        explained = any(abs(t_on - p) <= tol for p, tol in predicted)
        onsets.append((float(t_on), s, bool(explained)))
        if s > 0 and not explained:
            double = True
            nearest = min((p for p, _ in predicted), key=lambda p: abs(p - t_on)) if predicted else math.nan
            flags.append(
                f"double hit: a second compressive arrival {(t_on - arrival) * 1e6:.1f} µs after the first is not a "
                f"reflection (nearest predicted {(nearest - arrival) * 1e6:.1f} µs): a second impact; force after it is not the first impact's"
            )
            sources.append(t_on)
    return onsets, double


def _second_rise(t, s_dev, in_window, peak, noise, arrival, settings) -> str | None:
    """A second rise inside the incident window (impacts overlapping): a dip, then a rise again by > event_fraction.

    Returns the double-hit flag, or None.
    """
    if in_window.sum() <= 3:
        return None
    seg = s_dev[in_window]
    running_max = np.maximum.accumulate(seg)
    k_pk = int(np.argmax(seg))
    after_min = np.minimum.accumulate(seg[k_pk:])
    rebound = seg[k_pk:] - after_min
    if rebound.size and rebound.max() > settings.event_fraction * peak + 3 * noise and after_min[int(np.argmax(rebound))] < 0.5 * running_max[-1]:
        k = k_pk + int(np.argmax(rebound))
        return (
            f"double hit: the incident pulse falls to {after_min[int(np.argmax(rebound))] / peak:.0%} of its peak and rises "
            f"again by {rebound.max() / peak:.0%} at {(t[in_window][k] - arrival) * 1e6:.1f} µs, before any reflection"
        )
    return None


def condition_record(
    t,
    y,
    gauge_position: float,
    bar_length: float,
    wave_speed: float,
    pretrigger_end: float | None = None,
    adc_range: tuple[float, float] | None = None,
    settings: ConditioningSettings = ConditioningSettings(),
    end_delay: float = 0.0,
) -> Conditioned:
    """Baseline, noise, clipping, first arrival, incident window, reflections, double hits (module docstring).

    ``pretrigger_end``: the record time before which the signal is pre-trigger
    (default: t = 0 if the record starts before it, else found from the arrival).
    ``end_delay``: delay of each struck-end reflection (:func:`expected_arrivals`).
    """
    t, y = _arrays(t, y)
    for name, v in (("gauge_position", gauge_position), ("bar_length", bar_length), ("wave_speed", wave_speed)):
        if not (math.isfinite(v) and v >= 0 and (v > 0 or name == "gauge_position")):
            raise InputError(f"conditioning: {name} must be a positive number, got {v!r}")
    if gauge_position >= bar_length:
        raise InputError(f"conditioning: gauge_position {gauge_position!r} m must be less than bar_length {bar_length!r} m")
    flags: list[str] = []
    dt = float(np.median(np.diff(t)))
    base, noise, arrival, i_det, sign, n_pre = _pretrigger(t, y, pretrigger_end, dt, settings)
    if n_pre < MIN_PRETRIGGER:
        flags.append(f"only {n_pre} pre-trigger samples before the pulse: baseline and noise uncertain (record more pre-trigger)")
    if noise == 0:
        flags.append("no noise in the pre-trigger (σ = 0): synthetic or digitally zeroed record; thresholds from the pulse size only")
    dev = y - base

    clip_reasons = detect_clipping(y, noise, settings.clip_run, adc_range)
    flags.extend(clip_reasons)

    same, opposite = expected_arrivals(arrival if math.isfinite(arrival) else 0.0, gauge_position, bar_length, wave_speed, settings.reflections, end_delay)
    if not math.isfinite(arrival):
        flags.append(f"no pulse: nothing leaves the noise (σ = {noise:.3g}) by {settings.detection_sigmas:g}σ")
        return Conditioned(t, dev, base, noise, n_pre, math.nan, -1, 0, 0.0, (math.nan, math.nan), same, opposite, (), bool(clip_reasons), False, tuple(flags))

    tau = 2 * (bar_length - gauge_position) / wave_speed
    quiet_samples = max(3, int(math.ceil(QUIET_TIME / dt)))
    s_dev = sign * dev
    window_end = _window_end(t, dev, i_det, arrival, tau, noise, quiet_samples)
    in_window = (t >= arrival) & (t <= window_end)
    peak = float(np.max(s_dev[in_window])) if in_window.any() else float(s_dev[i_det])
    overlapping = window_end >= arrival + tau - dt
    if overlapping:
        flags.append(
            f"incident pulse still going when the first reflection returns at {tau * 1e6:.0f} µs after arrival: "
            "the incident window is cut there (reflections overlap the pulse; later onsets not classified)"
        )
    # While the incident pulse overlaps its reflections, an onset is a mixture of
    # waves and cannot be told from a new impact by its time: none is classified.
    onsets, double = [], False
    if not overlapping:
        level = max(settings.detection_sigmas * noise, settings.event_fraction * peak)
        geometry = (gauge_position, bar_length, wave_speed, end_delay)
        onsets, double = _later_onsets(t, dev, sign, arrival, window_end, level, noise, quiet_samples, geometry, settings, flags)
    if (rise := _second_rise(t, s_dev, in_window, peak, noise, arrival, settings)) is not None:
        double = True
        flags.append(rise)
    return Conditioned(
        time=t,
        signal=dev,
        baseline=base,
        noise=noise,
        pretrigger_samples=n_pre,
        arrival_time=float(arrival),
        arrival_index=int(i_det),
        incident_sign=int(sign),
        incident_peak=float(sign * peak),
        incident_window=(float(arrival), window_end),
        compressive_arrivals=same,
        tensile_arrivals=opposite,
        onsets=tuple(onsets),
        clipped=bool(clip_reasons),
        double_hit=double,
        flags=tuple(flags),
    )
