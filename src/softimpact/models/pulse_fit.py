"""Tail-aware fit of eq (15) to a measured force history.

A soft projectile leaves a long, low tail after the main pulse (paper Fig 7);
the paper's T is "the duration of the main pulse, ignoring the tail". Fitting
eq (15) to the whole record lets the tail pull T (and t_F0) long and F0 low.
Here the fit is done in two stages:

1. **Locate the tail** with a composite model over the whole record:
   eq (15) until its falling quarter cosine reaches a level ℓ·F0 (the knee
   t_k), then an exponential decay ℓ·F0·exp(−(t − t_k)/τ) (the
   :class:`~softimpact.models.pulses.TailedPulse`). The exponential is chosen
   because it is the simplest monotone decay with a level and a time scale, the
   two things needed to find the knee; it is *not* trusted for the tail's shape.
2. **Fit the main pulse** — eq (15) with a start time t0 — only to the samples
   before the fall reaches max(KNEE_MARGIN·ℓ, ℓ + KNEE_GAP)·F0, safely above the
   knee, so that whatever shape the tail has (linear, power law, a second low
   lobe) it cannot bias F0, t_F0 and T.

The impulse is the trapezoidal integral of the whole record (tail included),
as the paper's I. The whole-record eq-15 fit is returned beside the main-pulse
fit, and ``differs`` flags when their T, t_F0 or F0 differ by more than
``FLAG_SIGMAS`` standard errors (from the Jacobian, s²(JᵀJ)⁻¹ with s the
residual RMS) plus ``FLAG_FLOOR`` relative: the tail matters.

Every eq-15 fit of softimpact is :func:`fit_pulse` (one set of bounds, below);
:func:`fit_main_pulse` is the main-pulse procedure of ``reduce`` (seed window down
to a fixed fraction of F0, then the tail-aware fit), used as it is by ``identify``
for measured and simulated pulses alike, so both report the same T for one pulse.

Times [s] from first contact, forces [N]. Parameters are scaled to order one
for the solver.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from .pulses import SkewedPulse, TailedPulse

__all__ = ["MainPulseFit", "PulseFit", "TailAwareFit", "fit_main_pulse", "fit_pulse", "fit_tail_aware", "skewed_shape", "TAIL_DELTA_AIC"]

KNEE_MARGIN = 1.5  # the main-pulse window ends where the fall reaches 1.5·ℓ·F0 ...
KNEE_GAP = 0.05  # ... or (ℓ + 0.05)·F0 if higher: clear of the knee's misfit
FLAG_SIGMAS = 3.0  # the two fits "differ" beyond this many standard errors ...
FLAG_FLOOR = 0.01  # ... plus this relative amount (model error of eq 15 on real pulses)
MIN_WINDOW_SAMPLES = 12  # fewer samples cannot determine four parameters
# tail families within this ΔAIC of the best are not rejected (Burnham & Anderson 2002: beyond 4, "considerably less support")
TAIL_DELTA_AIC = 4.0
MAIN_PULSE_CUTOFF = 0.15  # the seed window ends where the (smoothed) force falls to 15 % of its peak

# Bounds of the eq-15 least squares, as multiples of the guess (F0, T); the one set for every fit.
ONSET_BOUND = 0.2  # |t0| ≤ 0.2·T: first contact is known from the record to within a fraction of the rise
PEAK_BOUNDS = (0.3, 3.0)  # F0 ×0.3–3 of the guess: a smoothed or sampled peak is never off by more
RISE_BOUNDS = (1e-3, 0.95)  # t_F0/T_guess: a rise within the guessed duration, never of zero length
DURATION_BOUNDS = (0.2, 5.0)  # T ×0.2–5 of the guess: the guess comes from the fall to the cutoff level
X_SCALE = (0.02, 1.0, 0.1, 1.0)  # typical steps of (t0/T, F0, t_F0/T, T): t0 and t_F0 move in small fractions of T


def skewed_shape(t, t0, F0, tp, T):
    """Eq (15) started at t0: quarter sine to t0 + t_F0, quarter cosine to t0 + T, zero elsewhere.

    The parameters may be arrays that broadcast against ``t`` (a column (k, 1) of each: k pulses
    at once, row by row the same numbers as k calls)."""
    x = np.asarray(t, float) - t0
    rise = F0 * np.sin(np.pi * x / (2 * tp))
    fall = F0 * np.cos(np.pi * (x - tp) / (2 * (T - tp)))
    return np.where(x <= 0, 0.0, np.where(x < tp, rise, np.where(x < T, fall, 0.0)))


def _tailed_shape(t, t0, F0, tp, T, level, decay):
    """Eq (15) to the knee where its fall reaches level·F0, then level·F0·exp(−(t − t_k)/decay); the
    parameters scalars, or columns (k, 1) of k pulses at once (as :func:`skewed_shape`)."""
    x = np.asarray(t, float) - t0
    knee = math.acos(level) if np.ndim(level) == 0 else np.array([[math.acos(v)] for v in np.ravel(level)])  # libm's acos either way
    tk = tp + 2 * (T - tp) / np.pi * knee
    tail = level * F0 * np.exp(-np.maximum(x - tk, 0.0) / decay)
    return np.where(x < tk, skewed_shape(x, 0.0, F0, tp, T), tail)


@dataclass(frozen=True)
class PulseFit:
    """An eq-(15) least-squares fit: the pulse (time from t0), its start t0 [s], the residual
    RMS [N] over the window t ≤ ``window_end``, and standard errors of (F0, t_F0, T)."""

    pulse: SkewedPulse
    start: float
    rms: float
    window_end: float
    samples: int
    se_peak_force: float
    se_time_of_peak: float
    se_duration: float

    def as_tuple(self) -> tuple[SkewedPulse, float, float]:
        """(pulse, t0 [s], rms [N])."""
        return self.pulse, self.start, self.rms


@dataclass(frozen=True)
class TailAwareFit:
    """Main-pulse and whole-record fits of eq (15), the tail, and the impulse (module docstring)."""

    main: PulseFit
    whole: PulseFit
    tail: TailedPulse  # composite model of stage 1 (its main part is not the reported one)
    impulse: float  # N·s, ∫F dt over the whole record
    noise: float  # N, σ of the residual of the main fit
    differs: bool
    message: str

    @property
    def peak_force(self) -> float:
        return self.main.pulse.peak_force

    @property
    def time_of_peak(self) -> float:
        return self.main.pulse.time_of_peak

    @property
    def duration(self) -> float:
        return self.main.pulse.duration

    @property
    def tail_impulse(self) -> float:
        """What the main pulse's 2F0T/π leaves out of the impulse [N·s]."""
        return self.impulse - self.main.pulse.impulse


def _validate(t, F):
    t = np.asarray(t, float)
    F = np.asarray(F, float)
    if t.ndim != 1 or t.shape != F.shape:
        raise InputError(f"pulse fit: time and force must be 1-D of equal length, got {t.shape} and {F.shape}")
    if t.size < MIN_WINDOW_SAMPLES:
        raise InputError(f"pulse fit: {t.size} samples, need at least {MIN_WINDOW_SAMPLES}")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(F))):
        raise InputError("pulse fit: time or force contains NaN or infinite values")
    if not np.all(np.diff(t) > 0):
        raise InputError("pulse fit: time must increase strictly")
    return t, F


def _guess(t, F):
    """Rough F0, t_F0, T from a lightly smoothed copy (peak, and the fall to half of it)."""
    from scipy.ndimage import uniform_filter1d

    Fs = uniform_filter1d(F, max(3, t.size // 200))
    k = int(np.argmax(Fs))
    F0, tp = float(Fs[k]), float(max(t[k], t[1]))
    half = np.flatnonzero((np.arange(t.size) > k) & (Fs < 0.5 * F0))
    t_half = float(t[half[0]]) if half.size else float(t[-1])
    # On eq 15 the fall reaches F0/2 at t_F0 + (T − t_F0)·(2/π)·acos(1/2) = t_F0 + (T − t_F0)·2/3.
    T = tp + 1.5 * max(t_half - tp, 2 * (t[1] - t[0]))
    return F0, tp, T


def _least_squares(residuals, p0, **options):
    """scipy's least_squares of ``residuals`` with its forward-difference Jacobian's points evaluated
    in one call: ``residuals(P)`` takes parameter rows P (k, n_p) and returns residual rows (k, m),
    each row the numbers a call on that row alone gives. The steps and the points are scipy's own
    (its ``workers`` hook, SciPy ≥ 1.16): the same fit as a plain call, in a fraction of the calls.
    """
    from scipy.optimize import least_squares

    def one(q):
        return residuals(q[None, :])[0]

    def points(fun, xs):  # the map least_squares runs the difference points through
        return list(residuals(np.array(list(xs))))

    try:
        return least_squares(one, p0, workers=points, **options)
    except TypeError as exc:  # SciPy < 1.16: no workers
        if "workers" not in str(exc):
            raise
        return least_squares(one, p0, **options)


def _errors(sol, scales, n):
    """Standard errors of the scaled parameters from the Jacobian: s²(JᵀJ)⁻¹."""
    J = sol.jac
    dof = max(n - J.shape[1], 1)
    s2 = float(sol.fun @ sol.fun) / dof
    try:
        cov = np.linalg.inv(J.T @ J) * s2
    except np.linalg.LinAlgError:
        return np.full(J.shape[1], math.nan)
    return np.sqrt(np.maximum(np.diag(cov), 0.0)) * scales


def fit_pulse(t, F, *, t_end: float | None = None, guess: tuple[float, float, float] | None = None, with_onset: bool = True) -> PulseFit:
    """THE least-squares fit of eq (15) to the samples t ≤ ``t_end`` (default: all); every eq-15 fit
    of softimpact (reduce, identify, calibrate, the tail-aware fit) is this one.

    ``t`` [s] increasing, ``F`` [N], same 1-D shape. With ``with_onset`` the pulse starts at a
    fitted time t0 (first contact, within ±ONSET_BOUND·T of t = 0); without, at t = 0.
    ``guess``: (F0, t_F0, T) to start from (default: from a lightly smoothed copy of the record);
    the bounds (module constants) are multiples of it.
    """
    t, F = _validate(t, F)
    t_end = float(t[-1]) if t_end is None else float(t_end)
    sel = t <= t_end
    if sel.sum() < MIN_WINDOW_SAMPLES:
        raise InputError(f"pulse fit: only {int(sel.sum())} samples up to t_end = {t_end:.6g} s")
    ts, Fs = t[sel], F[sel]
    F0, tp, T = guess if guess is not None else _guess(t, F)
    # parameters scaled to order one: (t0/T, F0/F0g, t_F0/Tg, T/Tg), t0 dropped without an onset
    lo = np.array([-ONSET_BOUND, PEAK_BOUNDS[0], RISE_BOUNDS[0], DURATION_BOUNDS[0]])
    hi = np.array([ONSET_BOUND, PEAK_BOUNDS[1], RISE_BOUNDS[1], DURATION_BOUNDS[1]])
    p0 = np.array([0.0, 1.0, tp / T, 1.0])
    scales = np.array([T, F0, T, T])
    x_scale = np.array(X_SCALE)
    free = slice(0, 4) if with_onset else slice(1, 4)

    def unpack(q):  # (n_free,) or (n_free, k)
        p = np.concatenate((np.zeros((1, *q.shape[1:])), q)) if not with_onset else q
        return p[0] * T, p[1] * F0, p[2] * T, p[3] * T

    def residuals(Q):  # rows of parameters → rows of residuals
        t0, f0, tpk, dur = (c[:, None] for c in unpack(Q.T))
        return (skewed_shape(ts, t0, f0, np.minimum(tpk, 0.999 * dur), dur) - Fs) / F0

    lo, hi, p0 = lo[free], hi[free], p0[free]
    p0 = np.clip(p0, lo + 1e-9, hi - 1e-9)
    sol = _least_squares(residuals, p0, bounds=(lo, hi), x_scale=x_scale[free])
    t0, f0, tpk, dur = unpack(sol.x)
    tpk = min(tpk, 0.999 * dur)
    se = np.concatenate(([0.0], _errors(sol, scales[free], ts.size))) if not with_onset else _errors(sol, scales, ts.size)
    rms = float(F0 * np.sqrt(np.mean(sol.fun**2)))
    return PulseFit(SkewedPulse(f0, tpk, dur), t0, rms, t_end, int(ts.size), float(se[1]), float(se[2]), float(se[3]))


def _fit_tailed(t, F, main: PulseFit) -> tuple[TailedPulse, float]:
    """Stage 1: eq (15) to the knee, then an exponential tail, over the whole record."""
    m = main.pulse
    F0, T = m.peak_force, m.duration
    after = t > main.start + T
    tail_mean = float(np.mean(F[after])) if after.any() else 0.0
    level0 = float(np.clip(tail_mean / F0 * 2.0, 0.05, 0.5))
    decay0 = max(float(t[-1] - main.start - T) / 3.0, 0.1 * T)

    def unpack(p):
        return p[0] * T, p[1] * F0, p[2] * T, p[3] * T, p[4], p[5] * T

    def residuals(P):  # rows of parameters → rows of residuals
        t0, f0, tpk, dur, lev, dec = (c[:, None] for c in unpack(P.T))
        return (_tailed_shape(t, t0, f0, np.minimum(tpk, 0.999 * dur), dur, lev, dec) - F) / F0

    p0 = np.array([main.start / T, 1.0, m.time_of_peak / T, 1.0, level0, decay0 / T])
    lo = np.array([-ONSET_BOUND, PEAK_BOUNDS[0], RISE_BOUNDS[0], DURATION_BOUNDS[0], 0.005, 0.01])  # tail level and decay/T: wide
    hi = np.array([ONSET_BOUND, PEAK_BOUNDS[1], RISE_BOUNDS[1], DURATION_BOUNDS[1], 0.7, 50.0])
    p0 = np.clip(p0, lo + 1e-9, hi - 1e-9)
    sol = _least_squares(residuals, p0, bounds=(lo, hi), x_scale=np.array([*X_SCALE, 0.05, 0.5]))
    t0, f0, tpk, dur, lev, dec = unpack(sol.x)
    return TailedPulse(SkewedPulse(f0, min(tpk, 0.999 * dur), dur), lev, dec), t0


def fit_tail_aware(t, F, *, with_onset: bool = True) -> TailAwareFit:
    """Main-pulse eq-(15) fit that ignores the tail, the whole-record fit, and the impulse (module docstring).

    ``t`` [s] increasing, from (about) first contact; ``F`` [N] the whole record, tail included.
    """
    t, F = _validate(t, F)
    whole = fit_pulse(t, F, with_onset=with_onset)
    # A first, rough main-pulse fit (down to a quarter of the peak) seeds the composite fit.
    g = whole.pulse
    seed_end = whole.start + g.time_of_peak + (g.duration - g.time_of_peak) * 2 / math.pi * math.acos(0.25)
    seed = fit_pulse(t, F, t_end=seed_end, guess=(g.peak_force, g.time_of_peak, g.duration), with_onset=with_onset)
    tailed, t0_tail = _fit_tailed(t, F, seed)
    level = min(max(KNEE_MARGIN * tailed.level, tailed.level + KNEE_GAP), 0.9)
    m = tailed.main
    t_end = t0_tail + m.time_of_peak + (m.duration - m.time_of_peak) * 2 / math.pi * math.acos(level)
    main = fit_pulse(t, F, t_end=t_end, guess=(m.peak_force, m.time_of_peak, m.duration), with_onset=with_onset)
    noise = float(main.rms)
    impulse = float(np.trapezoid(np.where(t >= main.start, F, 0.0), t))

    diffs = []
    for label, a, b, se in (
        ("T", main.pulse.duration, whole.pulse.duration, main.se_duration),
        ("t_F0", main.pulse.time_of_peak, whole.pulse.time_of_peak, main.se_time_of_peak),
        ("F0", main.pulse.peak_force, whole.pulse.peak_force, main.se_peak_force),
    ):
        allowed = FLAG_SIGMAS * (se if math.isfinite(se) else 0.0) + FLAG_FLOOR * abs(a)
        if abs(b - a) > allowed:
            diffs.append(f"{label} {(b - a) / a:+.1%}")
    differs = bool(diffs)
    if differs:
        message = f"whole-record fit differs from the main-pulse fit ({', '.join(diffs)}): the tail biases it"
    else:
        message = "whole-record and main-pulse fits agree within the noise"
    message += f"; tail from {tailed.level:.0%} of F0, main pulse fitted down to {level:.0%} of F0"
    return TailAwareFit(main, whole, tailed, impulse, noise, differs, message)


@dataclass(frozen=True)
class MainPulseFit:
    """The main pulse of a force record (:func:`fit_main_pulse`): ``fit`` is the tail-aware main-pulse
    fit where it could be made and agrees with the seed, else ``seed``, the fit to the samples before
    the fall to the cutoff level; ``aware`` the tail-aware fit (None if it could not be made)."""

    fit: PulseFit
    seed: PulseFit
    aware: TailAwareFit | None


def _smoothed(t, F):
    """Savitzky–Golay copy of F (cubic) over 0.2 of the time to the peak: the noise of a sample
    averaged away, the crown kept. The peak is first located on a copy smoothed over 0.1 of the
    rise (first contact, t = 0, to the first reach of 90 % of the largest sample)."""
    from scipy.signal import savgol_filter

    dt = float(t[1] - t[0])

    def smooth(scale):
        window = max(7, int(round(scale / dt)) | 1)
        if window >= F.size:
            window = (F.size - 1) | 1 if (F.size - 1) % 2 else F.size - 2
        return savgol_filter(F, window, 3)

    rise = max(float(t[int(np.argmax(F >= 0.9 * F.max()))]), 3 * dt)
    rough = smooth(0.1 * rise)
    return smooth(0.2 * max(float(t[int(np.argmax(rough))]), 3 * dt))


def fit_main_pulse(t, F, *, cutoff: float = MAIN_PULSE_CUTOFF, with_onset: bool = True) -> MainPulseFit:
    """The main pulse of eq (15) in a force record: F0, t_F0, T ignoring the tail (module docstring).

    ``t`` [s] uniformly sampled, zero at (about) first contact (samples before it allowed), ``F`` [N].
    A seed fit (:func:`fit_pulse`) over the samples until the smoothed force falls to ``cutoff``·F0
    after its peak starts the tail-aware fit over the record from the seed's onset on.
    """
    t, F = _validate(t, F)
    dt = float(t[1] - t[0])
    Fs = _smoothed(t, F)
    k_pk = int(np.argmax(Fs))
    F0, tp = float(Fs[k_pk]), float(t[k_pk])
    after = np.flatnonzero((np.arange(Fs.size) > k_pk) & (Fs < cutoff * F0))
    if not F0 > 0 or after.size == 0:
        raise InputError(f"pulse fit: the record ends before the force falls to {cutoff:.0%} of its peak: the main pulse is truncated")
    t_cut = float(t[after[0]])
    # On eq 15 the fall reaches cutoff·F0 at t_F0 + (T − t_F0)·(2/π)·acos(cutoff).
    T = tp + (t_cut - tp) / (2 / math.pi * math.acos(cutoff))
    seed = fit_pulse(t, F, t_end=t_cut, guess=(F0, max(tp, dt), T), with_onset=with_onset)
    aware = None
    keep = t >= seed.start - 2 * dt
    try:
        aware = fit_tail_aware(t[keep], F[keep], with_onset=with_onset)
    except InputError:  # too few samples after the onset: the seed stands
        pass
    fit = seed
    if aware is not None and aware.main.pulse.peak_force > 0 and abs(aware.main.start - seed.start) < 0.5 * seed.pulse.duration:
        fit = aware.main
    return MainPulseFit(fit, seed, aware)
