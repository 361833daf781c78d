"""Bar strain records → contact force histories and pulse parameters (paper Figs 7–15).

The bar is a non-dispersive, free–free rod (length L, wave speed c, gauge at x
from the struck end). With G(t) = Σ_k F(t − k·P), P = 2L/c, the strain at the
gauge is (d'Alembert, the struck end loaded by F, the far end free)

    −EA·ε(x, t + x/c) = s(t) = G(t) − G(t − τ),   τ = 2(L − x)/c,

so G(t) = s(t) + G(t − τ) and F(t) = G(t) − G(t − P): an exact, causal
recursion that separates the incident wave from every reflection, however long
the pulse. Up to τ after first contact the force is the shifted strain itself
(F = EA·ε, the paper's reading); after τ it carries reflection corrections, and
the noise of the result grows like the square root of the number of terms.

The baseline comes from the pre-trigger part, refined by the mean strain over
the whole periods P that end the record once the main pulse is over (on a plain
free–free bar that mean is the baseline when no force acts); the two are pooled
only when they agree within three standard errors, otherwise the force has not
ended (a tail) and the pre-trigger value is kept and flagged. A baseline error
δ biases the force by about δ·EA·L/(L − x) for the rest of the record, so the
impulse's uncertainty grows with the record's length: it is reported.

Two options leave the non-dispersive, free-far-end picture: ``dispersion``
replaces each pure delay by the first-mode (Pochhammer–Chree) move along the
bar and turns surface strain into force by the radial factors
(:func:`dispersive_wave_separation`); a second gauge separates the waves from
the two stations, so the far end need not be free (:func:`two_gauge_separation`).

An end cap of mass m_c (lumped at the struck end) is corrected for: the contact
force is the bar force plus m_c times the end acceleration, the end velocity
being (G(t) + G(t − P))/(ρcA).

Pulse parameters (time from first contact):
- F0: maximum of a cubic fitted to the force over the crown of the pulse (where
  the eq-15 fit is within 10 % of its peak): the largest raw sample is biased up
  by the noise, the fit averages it;
- T and t_F0: least-squares fit of the eq-(15) shape, with its start time t0,
  to the main pulse: down to a level safely above where the tail takes over,
  the tail located by a composite fit (:func:`~softimpact.models.pulse_fit.fit_tail_aware`;
  a fixed 15 % of F0 seeds it). t0 is first contact. T is thus the duration of
  the main pulse, ignoring the tail, whatever level the tail starts at; the fit
  to the whole record is kept beside it (``whole_fit``) and a flag says when the
  two differ. t_F0 uses the whole rise (the location of the
  maximum of a flat-topped, noisy peak is poorly determined; it is reported too,
  as ``time_of_max``);
- threshold duration: time until the smoothed force first falls below 5 % of F0;
- I: trapezoidal integral of the whole force history, tail included.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..fem.bar import Rod
from ..models.dispersion import RoundBar, disperse, radial_band_edge, rayleigh_speed_ratio
from ..models.noise import white_noise_sigma
from ..models.pulse_fit import MAIN_PULSE_CUTOFF, fit_main_pulse
from ..models.pulses import SkewedPulse
from ..models.sampling import series_problem
from ..models.specimens import BarSpec
from ._reduction_tails import TAIL_FAMILIES, TailShapeFit, fit_tail_shapes  # the tail-shape ambiguity, a step of its own

__all__ = [
    "Record",
    "ReductionSettings",
    "Reduction",
    "reduce_record",
    "wave_separation",
    "dispersive_wave_separation",
    "two_gauge_separation",
    "TAIL_FAMILIES",
    "TailShapeFit",
    "fit_tail_shapes",
]

MIN_SAMPLES = 64  # fewer cannot hold a pre-trigger baseline and a pulse
BASELINE_RESOLUTION = 1e-6  # of the peak strain: the finest resolution a record can claim (noise-free data)
CLIP_RUN = 4  # this many equal consecutive extreme samples mean a saturated recorder


@dataclass(frozen=True)
class Record:
    """A gauge record: time [s] on an arbitrary clock, strain [-] (tension +)."""

    name: str
    time: np.ndarray
    strain: np.ndarray


@dataclass(frozen=True)
class ReductionSettings:
    """Thresholds, as fractions of the peak (see the module docstring)."""

    fit_cutoff: float = MAIN_PULSE_CUTOFF  # the eq-15 fit uses the pulse until it falls to this fraction of F0
    duration_threshold: float = 0.05  # threshold-based duration
    detection_sigmas: float = 8.0  # arrival: the signal leaves the noise by this many σ ...
    detection_fraction: float = 0.05  # ... and by this fraction of its peak


@dataclass(frozen=True)
class Reduction:
    """A reduced record. Times from first contact [s]; forces [N]."""

    name: str
    time: np.ndarray
    force: np.ndarray
    peak_force: float
    time_of_peak: float  # eq-15 fit
    time_of_max: float  # where the smoothed force is largest
    duration: float  # eq-15 fit
    duration_threshold: float
    impulse: float
    impulse_uncertainty: float  # from the baseline's uncertainty, accumulated by the reflection corrections
    valid_until: float  # the record holds the force up to here
    direct_until: float  # up to here no reflection correction was needed
    first_contact_record_time: float  # first contact at the struck end, on the record's clock
    arrival_record_time: float  # pulse arrival at the gauge, on the record's clock
    baseline_strain: float
    noise_strain: float
    fit: SkewedPulse
    fit_rms: float  # N, residual of the eq-15 fit over its window
    flags: tuple[str, ...]
    whole_fit: SkewedPulse | None = None  # eq 15 fitted to the whole record, tail included (beside the main-pulse fit)


def _fail(name, msg):
    raise InputError(f"{name}: {msg}")


def _validate(record: Record) -> tuple[np.ndarray, np.ndarray, float]:
    """Checks and a uniform grid: returns t, y, dt."""
    t = np.asarray(record.time, dtype=float)
    y = np.asarray(record.strain, dtype=float)
    problem = series_problem(t, y, min_samples=MIN_SAMPLES, what="strain")
    if problem is not None:
        _fail(record.name, problem)
    d = np.diff(t)
    dt = float(np.median(d))
    if np.max(np.abs(d - dt)) > 0.01 * dt:  # hand-digitised records: put them on a uniform grid
        grid = np.arange(t[0], t[-1] + 0.5 * dt, dt)
        y, t = np.interp(grid, t, y), grid
    return t, y, dt


def _check_clipping(name, y):
    if np.ptp(y) == 0:  # no excursion at all: nothing was recorded, not a saturated recorder
        _fail(name, f"flat signal: all {y.size} samples equal {float(y[0]):.6g} (an empty record: gauge not connected or channel not recorded?)")
    for extreme in (y.max(), y.min()):
        at = np.isclose(y, extreme, rtol=0, atol=1e-9 * max(np.ptp(y), 1e-300))
        runs = np.diff(np.flatnonzero(np.diff(np.concatenate(([0], at.astype(int), [0])))))[::2]
        if runs.size and runs.max() >= CLIP_RUN:
            _fail(name, f"signal clipped: {runs.max()} consecutive samples at {extreme:.6g} (recorder saturated?)")


def wave_separation(s: np.ndarray, t: np.ndarray, tau: float, period: float) -> tuple[np.ndarray, np.ndarray]:
    """Solve s(t) = G(t) − G(t − τ) for G, then F(t) = G(t) − G(t − P).

    ``t`` increasing, zero at first contact; G = s before τ (no reflection has
    come back yet). Returns (F, G), both on ``t``.
    """
    G = s.copy()
    k = 1
    while k * tau <= t[-1]:
        block = (t >= k * tau) & (t < (k + 1) * tau)
        done = t < k * tau
        G[block] = s[block] + np.interp(t[block] - tau, t[done], G[done])
        k += 1
    F = G - np.interp(t - period, t, G, left=0.0)
    return F, G


def _smooth(y, dt, scale):
    from scipy.signal import savgol_filter

    window = max(7, int(round(scale / dt)) | 1)
    if window >= y.size:
        window = (y.size - 1) | 1 if (y.size - 1) % 2 else y.size - 2
    return savgol_filter(y, window, 3)


def dispersive_wave_separation(s: np.ndarray, t: np.ndarray, x: float, length: float, bar: RoundBar) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`wave_separation` with the first-mode (Pochhammer–Chree) dispersion of each path.

    ``s`` is −EA·ε_surface at the gauge on ``t`` (zero at first contact + x/c0).
    Harmonic by harmonic, s_x = D(x) G − D(2L − x) G with D(d) the move by d
    (:func:`softimpact.models.dispersion.propagate`), and the surface strain is
    turned into force by M1·M2. Moving back by x, with the bulk delays kept on
    the clock as in the non-dispersive case:

        s0 = Δ(−x)[M1 M2 s],   G(t) = s0(t) + Δ(2(L − x))[G](t − τ),   F(t) = G(t) − Δ(2L)[G](t − P),

    with Δ(d) the dispersion of a move by d without its bulk delay
    (:func:`softimpact.models.dispersion.disperse`). Δ(d > 0) is causal, so the
    recursion is solved as before, a pass per τ of record. Returns (F, G, Δ(2L)[G](t − P)).
    """
    c0 = bar.wave_speed
    tau, period = 2 * (length - x) / c0, 2 * length / c0
    s0 = disperse(t, s, -x, bar, surface_to_force=True)
    # Iterated over the whole record rather than block by block: band-limited, the
    # operators put a few µs of precursor before each front, which a block that
    # starts at k·τ would miss. Each pass makes G right for another τ.
    G = s0.copy()
    for _ in range(int((t[-1] - t[0]) // tau) + 1):
        G = s0 + np.interp(t - tau, t, disperse(t, G, 2 * (length - x), bar), left=0.0)
    back = np.interp(t - period, t, disperse(t, G, 2 * length, bar), left=0.0)
    return G - back, G, back


def two_gauge_separation(n1: np.ndarray, n2: np.ndarray, t: np.ndarray, delay: float) -> tuple[np.ndarray, np.ndarray]:
    """Waves at station 1 from the axial forces at two stations (Lundberg & Henchoz 1977).

    With N = −EA·ε = a + b at station 1 (a travelling away from the struck end,
    b toward it) and the second station ``delay`` = (x2 − x1)/c further on,
    N2(t) = a(t − Δ) + b(t + Δ), so

        b(t) = N2(t − Δ) − N1(t − 2Δ) + b(t − 2Δ),   a = N1 − b,

    a causal recursion (all quiet before the record starts) that needs nothing
    of the far end: its reflections are whatever comes back as b. A baseline
    error δ in N2 − N1 adds δ to b every 2Δ. Returns (a, b) on ``t``.
    """
    if not delay > 0:
        raise InputError(f"two gauges: the second must lie beyond the first (delay {delay!r} s)", "second_position")
    source = np.interp(t - delay, t, n2, left=0.0) - np.interp(t - 2 * delay, t, n1, left=0.0)
    b = source.copy()
    k = 1
    while t[0] + 2 * k * delay <= t[-1]:
        block = t >= t[0] + 2 * k * delay
        b[block] = source[block] + np.interp(t[block] - 2 * delay, t, b, left=0.0)
        k += 1
    return n1 - b, b


def _bar_force(y, baseline, tt, tau, period, EA, cap_mass, Z, window, dt, dispersion=None, x=0.0, length=0.0, second=None):
    """Contact force at the struck end from the gauge strain (module docstring).

    ``second``: (strain at the second gauge less its baseline, delay Δ to it, c): two-gauge separation.
    """
    if second is not None:
        y2, delay, c = second
        a, b = two_gauge_separation(-EA * (y - baseline), -EA * y2, tt, delay)
        # At the struck end: a left it x/c before it passed the gauge (tt's clock is shifted so);
        # b passed the gauge x/c before it gets there.
        b0 = np.interp(tt - 2 * x / c, tt, b, left=0.0)
        F, G, back = a + b0, a, -b0
    elif dispersion is None:
        F, G = wave_separation(-EA * (y - baseline), tt, tau, period)
        back = np.interp(tt - period, tt, G, left=0.0)
    else:
        F, G, back = dispersive_wave_separation(-EA * (y - baseline), tt, x, length, dispersion)
    if cap_mass > 0:
        from scipy.signal import savgol_filter

        v_end = (G + back) / Z
        F = F + cap_mass * savgol_filter(v_end, window, 3, deriv=1, delta=dt)
    return F


def _late_baseline(y, tt, start, period):
    """Mean strain over the whole periods P = 2L/c after ``start`` that end the record.

    Once the force is over, the strain at the gauge is a sum of waves bouncing
    with period P whose mean over a period is zero, so this mean is the baseline.
    Returns (mean, samples) or (nan, 0) when not even one period fits.
    """
    k = int((tt[-1] - start) // period)
    if k < 1:
        return math.nan, 0
    sel = tt > tt[-1] - k * period
    return float(np.mean(y[sel])), int(sel.sum())


def _records(record: Record, x: float, L: float, dispersion: bool, second: Record | None, second_position: float | None):
    """The gauge record validated and on a uniform grid, and the second gauge's on the same grid.

    Returns (t, y, dt, y2); y2 is None without a second gauge.
    """
    name = record.name
    t, y, dt = _validate(record)
    _check_clipping(name, y)
    y2 = None
    if second is not None:
        if dispersion:
            _fail(name, "two-gauge separation with dispersion correction is not implemented: use one or the other")
        if second_position is None or not x < second_position < L:
            _fail(name, f"second gauge position {second_position!r} m must lie beyond the first ({x!r} m) on the bar")
        t2, y2, _ = _validate(second)
        _check_clipping(second.name, y2)
        if t2[0] > t[0] + dt or t2[-1] < t[-1] - dt:
            _fail(name, f"the second gauge's record ({second.name}) must cover the first's time span (same clock)")
        y2 = np.interp(t, t2, y2)
    return t, y, dt, y2


def _arrival(name: str, t: np.ndarray, y: np.ndarray, dt: float, settings: ReductionSettings):
    """The pulse detected above the noise and its rough arrival at the gauge.

    The arrival extrapolates the rising edge (10 % to 40 % of the first peak)
    back to zero. Returns (inverted, peak_dev, t_arrive, rise): ``inverted`` when
    the first excursion is tensile (compression is assumed first: the caller
    inverts the signal), ``peak_dev`` the largest excursion from the head's
    median, ``rise`` the time from arrival to 90 % of the first peak (≥ 3 dt).
    """
    sigma = white_noise_sigma(y)
    head = max(8, y.size // 20)
    base0 = float(np.median(y[:head]))
    dev = y - base0
    peak_dev = dev[np.argmax(np.abs(dev))]
    threshold = max(settings.detection_sigmas * sigma, settings.detection_fraction * abs(peak_dev))
    if abs(peak_dev) < 10 * sigma or abs(peak_dev) <= threshold:
        _fail(name, f"no pulse: largest excursion {abs(peak_dev):.3g} is within the noise (σ = {sigma:.3g})")
    i_cross = int(np.argmax(np.abs(dev) > threshold))
    inverted = bool(dev[i_cross] > 0)
    if inverted:
        dev = -dev
    first = -dev
    k90 = int(np.argmax(first >= 0.9 * first.max()))  # the incident pulse's first approach to its peak
    local_peak = first[i_cross : k90 + 1].max()
    low = np.flatnonzero(first[: k90 + 1] < 0.1 * local_peak)
    i10 = int(low[-1]) + 1 if low.size else 0
    i40 = i10 + int(np.argmax(first[i10 : k90 + 1] >= 0.4 * local_peak))
    if i40 - i10 >= 2:
        slope, icpt = np.polyfit(t[i10 : i40 + 1], first[i10 : i40 + 1], 1)
        t_arrive = -icpt / slope if slope > 0 else t[i10]
    else:
        t_arrive = t[max(i10 - 1, 0)]
    rise = max(t[k90] - t_arrive, 3 * dt)
    return inverted, peak_dev, t_arrive, rise


def _pretrigger(name, t, y, y2, before, x, second_position, c):
    """Baseline and noise from the samples before ``before``; the second gauge's signal less its baseline.

    Returns (baseline, noise, n_base, two); ``two`` is None without a second
    gauge, else (its strain less its baseline, the delay Δ to it, c) for
    :func:`_bar_force`.
    """
    pre = t < before
    if pre.sum() < 10:
        _fail(name, f"no pre-trigger baseline: only {pre.sum()} samples before the pulse arrives")
    baseline = float(np.mean(y[pre]))
    noise = float(np.std(y[pre]))
    n_base = int(pre.sum())
    two = None
    if y2 is not None:  # the second gauge is further on: quiet at least as long
        delay = (second_position - x) / c
        two = (y2 - float(np.mean(y2[pre])), delay, c)
    return baseline, noise, n_base, two


def _pulse_parameters(name: str, F: np.ndarray, tt: np.ndarray, dt: float, rise: float, settings: ReductionSettings):
    """Pulse parameters of a force history on the clock ``tt`` (module docstring).

    Returns (fit, t0, rms, F0, t_pk, t_thr, aware): the main-pulse eq-15 fit, its
    start, its rms residual; F0 and its time from the cubic over the crown; the
    threshold duration (nan when the force never falls below the threshold); the
    tail-aware fit (None when none was made).
    """
    Fs = _smooth(F, dt, 0.1 * rise)
    Fs = _smooth(F, dt, 0.2 * max(tt[np.argmax(Fs)], 3 * dt))
    k_pk = int(np.argmax(Fs))
    F0_guess, t_pk_guess = float(Fs[k_pk]), float(tt[k_pk])
    after = np.flatnonzero((np.arange(Fs.size) > k_pk) & (Fs < settings.fit_cutoff * F0_guess))
    if after.size == 0:
        _fail(name, "the record ends before the force falls to 15 % of its peak: the main pulse is truncated")
    # The main pulse, wherever its tail starts (models/pulse_fit.fit_main_pulse, as identify):
    # a fit down to the fixed cutoff seeds a tail-aware fit; the whole record's fit kept beside it.
    try:
        main = fit_main_pulse(tt, F, cutoff=settings.fit_cutoff)
    except InputError as exc:
        _fail(name, str(exc).removeprefix("pulse fit: "))
    (fit, t0, rms), aware = main.fit.as_tuple(), main.aware
    # F0: the maximum of a cubic fitted to the crown, where the eq-15 fit is within
    # 10 % of its peak: it averages the noise over the whole crown (< 0.3 % model
    # error on eq-15 shapes) and follows the data where they depart from eq 15.
    crown = np.flatnonzero(fit(tt - t0) >= 0.9 * fit.peak_force)
    if crown.size >= 7:
        tc = tt[crown] - t0 - fit.time_of_peak
        coef = np.polyfit(tc, F[crown], 3)
        fine = np.linspace(tc[0], tc[-1], 2001)
        vals = np.polyval(coef, fine)
        F0, t_pk = float(vals.max()), float(t0 + fit.time_of_peak + fine[np.argmax(vals)])
    else:
        F0, t_pk = F0_guess, t_pk_guess
    below = np.flatnonzero((np.arange(Fs.size) > k_pk) & (Fs < settings.duration_threshold * F0))
    t_thr = float(tt[below[0]]) - t0 if below.size else math.nan
    return fit, t0, rms, F0, t_pk, t_thr, aware


def _pooled_baseline(y, tt, start, period, baseline, noise, n_base, peak_dev):
    """The pre-trigger baseline pooled with the late one (:func:`_late_baseline`) when they agree.

    A baseline error δ adds about δ·EA·L/(L − x) to F for the rest of the record,
    so the impulse needs the baseline well. Where the record runs on for whole
    periods P after the main pulse, their mean strain is a second estimate, pooled
    when the two agree within three standard errors. Returns (pooled, baseline,
    n_base, flag): the pooled values, or the pre-trigger ones and, when the two
    disagree, a flag saying so.
    """
    late, n_late = _late_baseline(y, tt, start, period)
    if not n_late:
        return False, baseline, n_base, None
    # The standard error of the difference, floored at the resolution a record can
    # claim, so that a noise-free record (σ = 0) does not divide by zero.
    se = max(noise * math.sqrt(1 / n_base + 1 / n_late), BASELINE_RESOLUTION * abs(peak_dev))
    if abs(late - baseline) <= 3 * se:
        return True, (n_base * baseline + n_late * late) / (n_base + n_late), n_base + n_late, None
    flag = (
        f"mean strain over the last {n_late} samples departs from the pre-trigger baseline by "
        f"{abs(late - baseline) / se:.0f} standard errors: force not over (tail) or drift; pre-trigger baseline kept"
    )
    return False, baseline, n_base, flag


def _from_contact(tt, t0, F, round_bar, x, c):
    """The force from first contact (t0 on the clock ``tt``), with a first sample interpolated at 0.

    With the dispersion correction the record's end is dropped: moving it back by
    x needs it up to x(1/c_R − 1/c0) past each instant. Returns (time, force, flags).
    """
    time = tt - t0
    keep = time >= 0
    flags = []
    if round_bar is not None:
        lost = x * (1 / (rayleigh_speed_ratio(round_bar.poisson_ratio) * c) - 1 / c)
        keep &= tt <= tt[-1] - lost
        flags.append(
            f"Pochhammer-Chree dispersion corrected (nu = {round_bar.poisson_ratio:g}; band to {radial_band_edge(round_bar) / 1e3:.0f} kHz); "
            f"last {lost * 1e6:.0f} us of the record dropped (the correction needs the record beyond it)"
        )
    time, force = time[keep], F[keep]
    force_start = float(np.interp(0.0, tt - t0, F))
    return np.concatenate(([0.0], time)), np.concatenate(([force_start], force)), flags


def _reach(valid_until, tau, period, t0, t_thr, two, EA, noise, n_base, L, x, F0, aware):
    """How far the force is direct, the impulse's uncertainty, and the flags on the result's reach.

    One gauge: direct up to the reflection's return τ; the baseline's error grows
    the impulse's by EA·σ/√n·L/(L − x) per second of record. Two gauges: the
    separation adds a term every 2Δ, and a baseline error δ grows the force by
    δ·EA per 2Δ. The noise grows like the square root of the number of wave
    terms summed. Returns (direct_until, impulse_sd, flags).
    """
    flags = []
    if two is None:
        direct_until = tau - t0 if tau - t0 < valid_until else valid_until
        if not math.isfinite(t_thr) or t_thr > direct_until:
            flags.append(f"pulse longer than the reflection return 2(L-x)/c = {tau * 1e6:.0f} µs: reflection-corrected beyond")
        terms = 1 + int(valid_until // tau) + int(valid_until // period)
        impulse_sd = EA * noise / math.sqrt(n_base) * L / (L - x) * valid_until
    else:
        spacing = 2 * two[1]
        direct_until = valid_until  # the returning waves are measured, not inferred from the far end
        terms = 2 + 2 * int(valid_until // spacing)
        impulse_sd = EA * noise / math.sqrt(n_base) * math.sqrt(2) * valid_until * (1 + valid_until / (2 * spacing))
    if not math.isfinite(t_thr):
        flags.append("the force never falls below 5 % of F0 within the record: threshold duration undefined")
    if aware is not None and aware.differs:
        flags.append(aware.message)
    end_noise = EA * noise * math.sqrt(terms)
    if end_noise > 0.05 * F0:
        flags.append(f"reflection corrections amplify the noise to {end_noise / F0:.0%} of F0 by the end")
    return direct_until, impulse_sd, flags


def reduce_record(
    record: Record,
    bar: BarSpec,
    gauge_position: float,
    settings: ReductionSettings = ReductionSettings(),
    dispersion: bool = False,
    second: Record | None = None,
    second_position: float | None = None,
) -> Reduction:
    """Force history at the struck end and its pulse parameters (module docstring).

    ``dispersion``: correct for the bar's first-mode (Pochhammer–Chree)
    dispersion, ν from the bar's material (:func:`dispersive_wave_separation`).
    ``second``, ``second_position``: the record of a second gauge further from
    the struck end (on the same clock): the waves are separated from the two
    stations (:func:`two_gauge_separation`), so the far end's condition need not
    be known (not with ``dispersion``).
    """
    name = record.name
    L, x = bar.length, gauge_position
    if not 0 <= x < L:
        _fail(name, f"gauge position {x!r} m must lie on the bar [0, {L!r}) m")
    rod = Rod.of(bar)
    c, EA, Z = rod.wave_speed, rod.axial_stiffness, rod.impedance
    tau, period = 2 * (L - x) / c, 2 * L / c
    round_bar = RoundBar(c, bar.material.poisson_ratio, bar.diameter / 2) if dispersion else None
    t, y, dt, y2 = _records(record, x, L, dispersion, second, second_position)
    flags = []
    inverted, peak_dev, t_arrive, rise = _arrival(name, t, y, dt, settings)
    if inverted:
        flags.append("first excursion tensile: signal inverted (compression assumed first)")
        y, y2 = -y, (None if y2 is None else -y2)
    baseline, noise, n_base, two = _pretrigger(name, t, y, y2, t_arrive - 0.5 * rise, x, second_position, c)
    if two is not None:
        flags.append(f"two-gauge wave separation ({x * 1e3:.0f} and {second_position * 1e3:.0f} mm): far-end condition not used")

    # Force at the struck end, on a clock from the (rough) first contact.
    tt = t - t_arrive
    cap_mass = 0.0 if bar.end_cap is None else bar.end_cap.mass
    window = max(7, int(round(0.25 * rise / dt)) | 1)
    if cap_mass > 0:
        flags.append(f"end-cap inertia corrected (m = {cap_mass * 1e3:.2f} g, lag m/ρcA = {cap_mass / Z * 1e6:.1f} µs)")
    F = _bar_force(y, baseline, tt, tau, period, EA, cap_mass, Z, window, dt, round_bar, x, L, two)
    fit, t0, rms, F0, t_pk, t_thr, aware = _pulse_parameters(name, F, tt, dt, rise, settings)
    if cap_mass == 0 and two is None:  # a mass-loaded end breaks the P-periodicity the late baseline needs
        pooled, baseline, n_base, flag = _pooled_baseline(y, tt, t0 + 3.0 * fit.duration, period, baseline, noise, n_base, peak_dev)
        if pooled:
            F = _bar_force(y, baseline, tt, tau, period, EA, cap_mass, Z, window, dt, round_bar, x, L, two)
            fit, t0, rms, F0, t_pk, t_thr, aware = _pulse_parameters(name, F, tt, dt, rise, settings)
        elif flag:
            flags.append(flag)

    time, force, dropped = _from_contact(tt, t0, F, round_bar, x, c)
    flags += dropped
    valid_until = float(time[-1])
    direct_until, impulse_sd, more = _reach(valid_until, tau, period, t0, t_thr, two, EA, noise, n_base, L, x, F0, aware)
    flags += more
    return Reduction(
        name=name,
        time=time,
        force=force,
        peak_force=F0,
        time_of_peak=fit.time_of_peak,
        time_of_max=t_pk - t0,
        duration=fit.duration,
        duration_threshold=t_thr,
        impulse=float(np.trapezoid(force, time)),
        impulse_uncertainty=impulse_sd,
        valid_until=valid_until,
        direct_until=direct_until,
        first_contact_record_time=float(t_arrive + t0 - x / c),
        arrival_record_time=float(t_arrive + t0),
        baseline_strain=baseline,
        noise_strain=noise,
        fit=fit,
        fit_rms=rms,
        flags=tuple(flags),
        whole_fit=None if aware is None else aware.whole.pulse,
    )
