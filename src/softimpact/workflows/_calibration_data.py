"""What a calibration works on and returns: the measured strains prepared (offsets, noise,
first contact, the model's rate), the result types, and the bound check of a fit.

Private part of :mod:`softimpact.workflows.calibration` (import the names from there).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from ..models.noise import white_noise_sigma
from ..models.pulses import SkewedPulse, TabulatedPulse

WEAK_CORRELATION = 0.9  # |correlation| of two estimates beyond which they are called weakly identifiable
NOISE_FLOOR = 1e-4  # of a gauge's peak |strain|: the least noise assumed (a 14-bit digitiser's step)
DEPARTURE_SIGMAS = 6.0  # a gauge "leaves the noise" at this many σ of its pre-impact part
BOUND_TOLERANCE = 0.01  # a parameter within 1 % of a bound (of the bound's size, or of the range for a bound at 0) sits on it


def on_bounds(names, x, lower, upper, active=None) -> tuple[str, ...]:
    """The names of the parameters ``x`` that sit on a bound: flagged active by the optimiser
    (``active``, scipy's ``active_mask``), or within BOUND_TOLERANCE of the bound (relative to
    |bound|, or to the range when the bound is 0). An estimate on its bound is not a minimum
    of the misfit but the edge of the search: its standard error means nothing."""
    out = []
    for i, n in enumerate(names):
        lo, hi, v = float(lower[i]), float(upper[i]), float(x[i])
        span = hi - lo if math.isfinite(hi - lo) else math.inf
        hit = active is not None and active[i] != 0
        for b in (lo, hi):
            if math.isfinite(b):
                scale = abs(b) if b != 0 else (span if math.isfinite(span) else 1.0)
                hit = hit or abs(v - b) <= BOUND_TOLERANCE * scale
        if hit:
            out.append(n)
    return tuple(out)


@dataclass(frozen=True)
class Measured:
    """Measured strains: time [s] on the record's clock, strain per gauge name."""

    name: str
    time: np.ndarray
    strains: dict


@dataclass(frozen=True)
class Prepared:
    """Measured strains, offsets removed, on a clock from first contact."""

    name: str
    time: np.ndarray  # (n,) s from first contact (negative before)
    strains: np.ndarray  # (n_gauges, n), model's gauge order
    noise: np.ndarray  # (n_gauges,) σ of the pre-impact part
    offsets: np.ndarray  # (n_gauges,) removed
    contact_time: float  # first contact on the record's clock
    window: np.ndarray  # (n,) bool: samples used (0 ≤ t ≤ end of the model's run)


@dataclass(frozen=True)
class ModelCheck:
    """How good the calibration model is (:func:`calibrate_checked`).

    ``level``: the refinement level used (0 = the case's own mesh, k = refined by
    ratio^k); ``error_to_noise``: per gauge, the RMS of the model's estimated
    discretisation error over the record's window divided by the gauge's noise σ;
    ``shifts``: per parameter, how far the fit moves when the estimated model
    error is corrected (defect correction toward the Richardson-extrapolated model);
    ``noise_errors``: the standard errors from the noise alone; ``meets``:
    whether every shift is within ``tolerance`` × its noise standard error.
    """

    level: int
    factor: int
    error_to_noise: np.ndarray
    shifts: dict
    noise_errors: dict
    tolerance: float
    meets: bool
    message: str
    order: float = math.nan  # of the discretisation error used in the estimate
    order_observed: bool = False  # from three levels (else the formal order, assumed)
    safety: float = math.nan  # Roache's factor applied to the shifts in the standard errors
    level_fits: dict = field(default_factory=dict)  # level → (F0, t_F0, T) of its least-squares fit in the check
    contact_time: float = math.nan  # first contact on the record's clock every later fit of the check started from (given, or the case-mesh fit's)
    parameter_orders: dict = field(default_factory=dict)  # observed order of each parameter's convergence (app)
    parameter_uncertainty_95: dict = field(default_factory=dict)  # 1.96 × its discretisation standard uncertainty (studies)
    parameter_gci: dict = field(default_factory=dict)  # its GCI: Fs × the Richardson error estimate, the conservative bound (studies)
    parameter_levels: dict = field(default_factory=dict)  # its values on the three levels, coarse → fine (studies)
    parameter_status: dict = field(default_factory=dict)  # asymptotic, monotone, oscillatory, ... (app)
    parameter_safety: dict = field(default_factory=dict)  # Roache's factor behind each parameter's uncertainty (1.25 or 3)


@dataclass(frozen=True)
class Calibration:
    """A calibrated force history and how it was found."""

    method: str
    pulse: object  # SkewedPulse (paper, least-squares) or TabulatedPulse (deconvolve)
    contact_radius: float
    standard_errors: dict  # name → SE (SI); empty where not estimated
    iterations: int
    converged: bool
    message: str
    residual_rms: np.ndarray  # (n_gauges,) strain
    computed: np.ndarray  # (n_gauges, n_model_steps + 1) on the model grid
    prepared: Prepared
    start: SkewedPulse
    history: list = field(default_factory=list)  # per iteration (paper method): (F0, tF0, T)
    fit_pulse: object = None  # deconvolve: the eq-15 least-squares pulse beside it
    time: np.ndarray | None = None  # the model's grid of ``computed`` [s]
    check: ModelCheck | None = None  # the discretisation check, when the model was checked
    regularisation: object = None  # deconvolve: the LambdaChoice (λ, rule, curve, reason)
    correlations: dict = field(default_factory=dict)  # least squares: "a~b" → correlation of the estimates, for |r| ≥ 0.5
    at_bounds: tuple = ()  # least squares: the parameters that ended on (or within BOUND_TOLERANCE of) a bound of the fit

    @property
    def weakly_identified(self) -> list[str]:
        """Parameters whose estimate trades against another (|correlation| ≥ WEAK_CORRELATION)."""
        return [f"{pair.replace('~', ' trades against ')} (correlation {r:+.2f})" for pair, r in self.correlations.items() if abs(r) >= WEAK_CORRELATION]

    @property
    def peak_force(self) -> float:
        """F0; for a deconvolved history, its maximum."""
        if isinstance(self.pulse, TabulatedPulse):
            return float(np.max(self.pulse.force))
        return float(self.pulse.peak_force)

    @property
    def time_of_peak(self) -> float:
        """t_F0; for a deconvolved history, that of its eq-15 fit (the regularised peak is rounded)."""
        p = self.fit_pulse if isinstance(self.pulse, TabulatedPulse) else self.pulse
        return math.nan if p is None else float(p.time_of_peak)

    @property
    def duration(self) -> float:
        """T; for a deconvolved history, that of its eq-15 fit."""
        p = self.fit_pulse if isinstance(self.pulse, TabulatedPulse) else self.pulse
        return math.nan if p is None else float(p.duration)


def _departure(t, y, sigma, level=None):
    """First time |y| exceeds ``level`` (default DEPARTURE_SIGMAS·σ), linearly interpolated."""
    level = DEPARTURE_SIGMAS * sigma if level is None else level
    k = np.flatnonzero(np.abs(y) > level)
    if k.size == 0:
        return math.nan
    k = k[0]
    if k == 0:
        return float(t[0])
    a, b = abs(y[k - 1]), abs(y[k])
    return float(t[k - 1] + (t[k] - t[k - 1]) * (level - a) / (b - a)) if b != a else float(t[k])


def _to_model_rate(t: np.ndarray, Y: np.ndarray, dt_model: float):
    """A record sampled much finer than the model, averaged over blocks of q samples
    (q = ⌊dt_model/dt⌋ ≥ 2): the model cannot use the finer detail, and the block
    mean is an anti-aliasing filter that leaves the noise white at the model's rate,
    so the noise level and the first departure from it mean the same at any
    sampling rate (an interpolated, oversampled record has correlated noise)."""
    q = int(dt_model / float(np.median(np.diff(t))) + 1e-9)
    if q < 2:
        return t, Y
    n = t.size // q
    if n < 32:
        return t, Y
    return t[: n * q].reshape(n, q).mean(axis=1), Y[:, : n * q].reshape(Y.shape[0], n, q).mean(axis=2)


def prepare(model, measured: Measured, start: SkewedPulse, contact_time: float | None = None, radius: float | None = None) -> Prepared:
    """Offsets removed, gauges in the model's order, first contact located (module docstring)."""
    names = [g.name for g in model.problem.gauges]
    missing = [n for n in names if n not in measured.strains]
    unknown = [n for n in measured.strains if n not in names]
    if unknown:
        raise InputError(f"{measured.name}: gauge(s) {', '.join(unknown)} are not in the case (its gauges: {', '.join(names)})")
    if missing:
        raise InputError(f"{measured.name}: no column strain_<name> for gauge(s) {', '.join(missing)}")
    t = np.asarray(measured.time, float)
    Y = np.array([np.asarray(measured.strains[n], float) for n in names])
    if t.ndim != 1 or t.size < 32:
        raise InputError(f"{measured.name}: too short ({t.size} samples)")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(Y))):
        raise InputError(f"{measured.name}: contains NaN or infinite values")
    if np.any(np.diff(t) <= 0):
        raise InputError(f"{measured.name}: time is not strictly increasing")
    t, Y = _to_model_rate(t, Y, model.problem.solver.time_step)
    # Pre-impact part: before any gauge leaves a robust noise band around its first samples.
    head = max(16, t.size // 20)
    sig0 = white_noise_sigma(Y, axis=1)
    sig0 = np.maximum(sig0, 1e-15)
    starts = [_departure(t, y - np.median(y[:head]), s) for y, s in zip(Y, sig0)]
    t_dep = np.nanmin(starts) if np.any(np.isfinite(starts)) else math.nan
    if not math.isfinite(t_dep):
        raise InputError(f"{measured.name}: no gauge leaves the noise: no impact in the record")
    pre = t < t_dep - 0.1 * (t_dep - t[0])
    if pre.sum() >= 10:
        offsets = Y[:, pre].mean(axis=1)
        noise = np.maximum(Y[:, pre].std(axis=1), 1e-15)
    else:
        offsets = np.median(Y[:, :head], axis=1)
        noise = sig0
    # A noise-free record (a model's own output) is weighted as if read by a fine digitiser.
    noise = np.maximum(noise, NOISE_FLOOR * np.max(np.abs(Y - offsets[:, None]), axis=1))
    Y = Y - offsets[:, None]
    if contact_time is None:
        # The model, driven by the starting history, leaves the same noise level at t_m after contact.
        model_y = model.respond(start, radius).strain
        tm = model.problem.solver.times()
        lags = []
        for y_meas, y_mod, s in zip(Y, model_y, noise):
            level = max(DEPARTURE_SIGMAS * s, 0.05 * np.max(np.abs(y_mod)))
            a, b = _departure(t, y_meas, s, level), _departure(tm, y_mod, s, level)
            if math.isfinite(a) and math.isfinite(b):
                lags.append(a - b)
        if not lags:
            raise InputError(f"{measured.name}: cannot locate first contact; give the contact time", "contact_time")
        contact_time = float(lags[0])
    rel = t - contact_time
    end = model.problem.solver.duration
    window = (rel >= 0) & (rel <= end)
    return Prepared(measured.name, rel, Y, noise, offsets, contact_time, window)


def _residual_rms(model, prep, computed):
    tm = model.problem.solver.times()
    w = prep.window
    return np.array([np.sqrt(np.mean((np.interp(prep.time[w], tm, c) - y[w]) ** 2)) for c, y in zip(computed, prep.strains)])
