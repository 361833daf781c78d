"""Calibrate the transverse force history against measured gauge strains (paper
"Impact force history", steps 1–3; Tables II, III; Figs 21–25).

All three methods run the beam through its response engine, so one evaluation
of a force history costs milliseconds.

- ``paper``: the paper's procedure, automated. Start from the bar-model history
  for the velocity (eqs 4–6 with eq 15); scale F0 by the ratio of the measured to
  the computed peak strain of the first gauge's first main lobe; scale T, keeping t_F0/T, by the
  ratio of the measured to the computed first zero crossing of that gauge's
  strain (after its first excursion beyond a quarter of its peak); re-align the
  clocks (the shift that best matches the early strains); repeat until both
  ratios are within ``tol`` of one. It keeps the
  starting t_F0/T, so it can only be as right as that ratio.
- ``least-squares`` (default): fit F0, t_F0, T (and optionally r0 and the time
  origin) of eq (15), with a baseline correction per gauge, to the whole records
  of all gauges (pre-impact part included), each weighted by its noise; standard
  errors from the Jacobian, s²·(JᵀJ)⁻¹ with s² the residual variance (they cover
  the noise, not a mismatch of the model).
- ``deconvolve``: a non-parametric force history. With the patch frozen at r0
  the strains are linear in F: y_g = h_g * F. F is sought as hat functions on a
  coarse grid, with Tikhonov regularisation of its second difference,
  non-negative, and zero before first contact. λ by the discrepancy principle
  (default: the largest λ whose residual is within the measured noise, raised by
  the model's estimated error), the L-curve, or generalised cross-validation
  (:mod:`softimpact.models.regularisation`).

Measured strains arrive with an offset per gauge and on their own clock: the
offsets are the means of the pre-impact part; the instant of first contact is
given or estimated by matching the time at which the first gauge leaves the
noise with the same instant in the model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import InputError
from ..models.features import first_lobe_peak, first_zero_crossing
from ..models.noise import white_noise_sigma
from ..models.pulse_fit import fit_pulse as fit_eq15
from ..models.pulses import SkewedPulse, TabulatedPulse

__all__ = ["Measured", "Prepared", "Calibration", "ModelCheck", "prepare", "calibrate", "calibrate_checked", "on_bounds", "METHODS", "BOUND_TOLERANCE"]

METHODS = ("least-squares", "paper", "deconvolve")
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


def calibrate(
    model,
    measured: Measured,
    start: SkewedPulse,
    method: str = "least-squares",
    *,
    contact_time=None,
    radius: float | None = None,
    fit_radius: bool = False,
    fit_origin: bool = True,
    tol: float = 1e-4,
    max_iterations: int = 200,
    defect=None,
    rule: str = "discrepancy",
    error_to_noise=None,
) -> Calibration:
    """Calibrate the force history by ``method`` (module docstring); ``radius``: r0 of the test
    (default the case's), at most the model's patch radius. ``defect`` (n_gauges, n_steps + 1)
    on the model's grid: the model's discretisation error (its strains minus a better model's),
    subtracted from every computed strain (defect correction; least-squares only). ``rule``:
    the deconvolution's choice of λ; ``error_to_noise``: the model's estimated error per gauge
    (in noise σ), which the discrepancy principle adds to the noise."""
    r0 = model.problem.load.contact_radius if radius is None else radius
    if not 0 < r0 <= model.patch.radius * (1 + 1e-12):
        raise InputError(f"contact_radius: {r0!r} m must be positive and within the model's patch ({model.patch.radius!r} m)")
    if method not in METHODS:
        raise InputError(f"method: {method!r} is not one of {', '.join(METHODS)}", "method")
    prep = prepare(model, measured, start, contact_time, r0)
    record_after = prep.time[-1]
    if record_after < start.duration:
        raise InputError(
            f"{measured.name}: the record runs {record_after * 1e6:.0f} µs after first contact, shorter than the pulse ({start.duration * 1e6:.0f} us)"
        )
    if method == "paper":
        return _paper(model, prep, start, r0, tol, max_iterations, contact_time is not None)
    if method == "least-squares":
        return _least_squares(model, prep, start, r0, fit_radius, fit_origin, defect)
    return _deconvolve(model, prep, start, r0, rule=rule, error_to_noise=error_to_noise)


def _strains(model, pulse, radius=None):
    return model.respond(pulse, radius).strain


ALIGN_RANGE = 30e-6  # s: the clock correction searched for on each realignment


def _realign(model, prep, computed, given: bool):
    """Re-estimate first contact: the shift s that best matches the measured strains to
    the computed ones (each scaled freely) over the early part of the record."""
    if given:
        return prep
    from scipy.optimize import minimize_scalar

    tm = model.problem.solver.times()
    early = (prep.time > -ALIGN_RANGE) & (prep.time < 0.4 * tm[-1])
    ts, ys = prep.time[early], prep.strains[:, early]

    def misfit(shift):
        total = 0.0
        for y, c in zip(ys, computed):
            m = np.interp(ts - shift, tm, c, left=0.0)
            a = (m @ y) / max(m @ m, 1e-300)
            total += float(np.sum((y - a * m) ** 2))
        return total

    shift = minimize_scalar(misfit, bounds=(-ALIGN_RANGE, ALIGN_RANGE), method="bounded", options={"xatol": 1e-9}).x
    rel = prep.time - shift
    return Prepared(prep.name, rel, prep.strains, prep.noise, prep.offsets, prep.contact_time + shift, (rel >= 0) & (rel <= tm[-1]))


PAPER_SMOOTHING = 20e-6  # s: the measured trace is smoothed over this before its peak and zero crossing are read


def _paper(model, prep, start, r0, tol, max_iterations, given_contact=False):
    from scipy.signal import savgol_filter

    tm = model.problem.solver.times()
    dt_meas = float(np.median(np.diff(prep.time)))
    window = max(5, int(round(PAPER_SMOOTHING / dt_meas)) | 1)
    # Peaks and zero crossings of a noisy trace are biased (the largest noise sample,
    # the first noise-induced crossing): read them off a smoothed trace, as off a scope.
    meas = savgol_filter(prep.strains[0], window, 3) if window < prep.strains[0].size else prep.strains[0]
    F0, T, skew = start.peak_force, start.duration, start.time_of_peak / start.duration
    history = []
    converged, it = False, 0
    f_ratio = t_ratio = math.nan
    for it in range(1, max_iterations + 1):  # noqa: B007 (the count is reported after the loop)
        pulse = SkewedPulse(F0, skew * T, T)
        c = _strains(model, pulse, r0)
        prep = _realign(model, prep, c, given_contact)
        w = prep.window
        peak_m = first_lobe_peak(prep.time[w], meas[w])
        zero_m = first_zero_crossing(prep.time[w], meas[w])
        zero_c = first_zero_crossing(tm, c[0])
        if not (math.isfinite(zero_m) and math.isfinite(zero_c)):
            raise InputError(f"{prep.name}: the first gauge's strain has no zero crossing in the record or the model: the paper method needs one")
        f_ratio, t_ratio = peak_m / first_lobe_peak(tm, c[0]), zero_m / zero_c
        history.append((F0, skew * T, T))
        F0, T = F0 * f_ratio, T * t_ratio
        if abs(f_ratio - 1) < tol and abs(t_ratio - 1) < tol:
            converged = True
            break
    pulse = SkewedPulse(F0, skew * T, T)
    computed = model.respond(pulse, r0).strain
    msg = f"converged in {it} iterations" if converged else f"not converged after {it} iterations (ratios {f_ratio:.4f}, {t_ratio:.4f})"
    return Calibration("paper", pulse, r0, {}, it, converged, msg, _residual_rms(model, prep, computed), computed, prep, start, history, time=tm)


def _least_squares(model, prep, start, r0, fit_radius, fit_origin, defect=None):
    """Eq (15) fitted to every sample up to the end of the model's run, pre-impact part
    included, with a baseline correction per gauge fitted alongside: the offsets' own
    uncertainty then reaches the standard errors instead of biasing F0 unseen."""
    from scipy.optimize import least_squares

    tm = model.problem.solver.times()
    n_g = len(prep.noise)
    use = prep.time <= tm[-1]
    ts, ys = prep.time[use], prep.strains[:, use]
    weights = 1.0 / prep.noise[:, None]
    names = ["peak_force", "time_of_peak", "duration"] + (["contact_radius"] if fit_radius else []) + (["time_origin"] if fit_origin else [])
    names += [f"offset_{g.name}" for g in model.problem.gauges]
    scale = np.array([start.peak_force, start.time_of_peak, start.duration] + ([r0] if fit_radius else []) + ([10e-6] if fit_origin else []) + list(prep.noise))
    n_main = len(names) - n_g

    def unpack(p):
        v = p * scale
        F0, tp, T = v[0], v[1], v[2]
        r = v[3] if fit_radius else r0
        shift = v[n_main - 1] if fit_origin else 0.0
        return F0, tp, T, r, shift, v[n_main:]

    def residual(p):
        F0, tp, T, r, shift, offs = unpack(p)
        if not (0 < tp < T) or F0 <= 0 or r <= 0:
            return np.full(ys.size, 1e6)
        c = _strains(model, SkewedPulse(F0, tp, T), r)
        if defect is not None:
            c = c - defect
        comp = np.array([np.interp(ts - shift, tm, ci, left=0.0) for ci in c]) + offs[:, None]
        return ((comp - ys) * weights).ravel()

    lo = [1e-3, 1e-3, 1e-3] + ([0.2] if fit_radius else []) + ([-10.0] if fit_origin else []) + [-np.inf] * n_g
    hi = [100.0, 50.0, 50.0] + ([model.patch.radius / r0] if fit_radius else []) + ([10.0] if fit_origin else []) + [np.inf] * n_g
    p0 = np.ones(len(names))
    if fit_origin:
        p0[n_main - 1] = 0.0
    p0[n_main:] = 0.0
    sol = least_squares(residual, p0, bounds=(lo, hi), x_scale="jac", diff_step=1e-6, ftol=1e-12, xtol=1e-10, gtol=1e-12)
    dof = max(sol.fun.size - len(names), 1)
    s2 = float(sol.fun @ sol.fun) / dof
    correlations = {}
    try:
        cov = np.linalg.inv(sol.jac.T @ sol.jac) * s2
        se = {n: float(math.sqrt(max(cov[i, i], 0.0)) * scale[i]) for i, n in enumerate(names)}
        d = np.sqrt(np.maximum(np.diag(cov), 1e-300))
        corr = cov / np.outer(d, d)
        for i in range(n_main):
            for j in range(i + 1, n_main):
                if abs(corr[i, j]) >= 0.5:
                    correlations[f"{names[i]}~{names[j]}"] = float(corr[i, j])
    except np.linalg.LinAlgError:
        se = {}
    at_bounds = on_bounds(names[:n_main], sol.x[:n_main], lo[:n_main], hi[:n_main], sol.active_mask[:n_main])
    F0, tp, T, r, shift, offs = unpack(sol.x)
    pulse = SkewedPulse(F0, tp, T)
    comp = _strains(model, pulse, r) - (0.0 if defect is None else defect)
    rel = prep.time - shift
    prep = Prepared(prep.name, rel, prep.strains - offs[:, None], prep.noise, prep.offsets + offs, prep.contact_time + shift, (rel >= 0) & (rel <= tm[-1]))
    return Calibration(
        "least-squares",
        pulse,
        r,
        se,
        int(sol.nfev),
        bool(sol.success),
        fit_outcome(sol.status, sol.nfev),
        _residual_rms(model, prep, comp),
        comp,
        prep,
        start,
        time=tm,
        correlations=correlations,
        at_bounds=at_bounds,
    )


RULES = ("discrepancy", "l-curve", "gcv", "gcv-floored")  # choices of the deconvolution's λ


def _deconvolve(model, prep, start, r0, knots: int = 160, rule: str = "discrepancy", error_to_noise=None):
    """Tikhonov-regularised, non-negative deconvolution through the impulse responses (module docstring).
    ``rule`` chooses λ (:mod:`softimpact.models.regularisation`); ``error_to_noise`` (per gauge) raises
    the discrepancy level by the model's estimated error."""
    from ..models.regularisation import choose_discrepancy, choose_gcv, choose_l_curve

    tm = model.problem.solver.times()
    N = tm.size
    # Patch frozen at r0: the load pattern of unit total force.
    shape = model.nodal_loads(np.array([0.0, 1.0]), r0)[:, 1]
    eng = model.engine()
    n_g = len(model.problem.gauges)
    h = np.tensordot(eng.kernel[model.gauge_rows()], shape, axes=([1], [0]))  # (n_g, N-1): strain per unit force at step 1
    # Basis: hat functions on a coarse grid over the window where the force may act.
    span = min(tm[-1], 2.5 * start.duration)
    grid = np.linspace(0.0, span, knots + 1)
    Phi = np.clip(1.0 - np.abs(tm[:, None] - grid[None, 1:]) / (grid[1] - grid[0]), 0.0, None)  # (N, knots); F(0) = 0
    # Columns: the gauge response to each hat, y = conv(h, φ).
    # Convolutions by real FFT along time (numpy's: scipy.signal costs a second to import).
    nfft = 1 << (2 * N - 1).bit_length()
    Hg = np.fft.rfft(h, nfft, axis=-1)  # (n_g, nfft/2 + 1)
    Pk = np.fft.rfft(Phi[1:], nfft, axis=0)  # (nfft/2 + 1, knots)

    cols = []
    for g in range(n_g):
        resp = np.fft.irfft(Hg[g][:, None] * Pk, nfft, axis=0)[: N - 1]
        cols.append(np.vstack((np.zeros((1, knots)), resp)))
    A_full = np.stack(cols)  # (n_g, N, knots)
    w = prep.window
    ts = prep.time[w]
    # Linear interpolation from the model grid to the measured samples, as one sparse-free matrix.
    k = np.clip(np.searchsorted(tm, ts) - 1, 0, N - 2)
    frac = ((ts - tm[k]) / (tm[k + 1] - tm[k]))[:, None]
    rows, rhs = [], []
    for g in range(n_g):
        rows.append(((1 - frac) * A_full[g, k] + frac * A_full[g, k + 1]) / prep.noise[g])
        rhs.append(prep.strains[g, w] / prep.noise[g])
    A = np.vstack(rows)
    y = np.concatenate(rhs)
    L = np.diff(np.eye(knots), 2, axis=0)
    # The data are in units of each gauge's noise; with a model error estimate the
    # expected misfit per sample is √(1 + (e/σ)²) (the discrepancy principle's level).
    level = 1.0 if error_to_noise is None else float(np.sqrt(1.0 + np.mean(np.square(error_to_noise))))
    scale = math.sqrt(np.trace(A.T @ A) / np.trace(L.T @ L))
    lambdas = scale * np.logspace(-4, 2, 31)
    if rule == "discrepancy":
        choice = choose_discrepancy(A, y, L, lambdas, level)
    elif rule == "l-curve":
        choice = choose_l_curve(A, y, L, lambdas)
    elif rule == "gcv":
        choice = choose_gcv(A, y, L, lambdas, floor=False)
    elif rule == "gcv-floored":
        choice = choose_gcv(A, y, L, lambdas, level)
    else:
        raise InputError(f"rule: {rule!r} is not one of {', '.join(RULES)}", "rule")
    lam = choice.lam

    class _Solution:  # the chosen non-negative solution, as lsq_linear reported it before
        x, nit, success, message = choice.solution, 0, True, choice.reason

    sol = _Solution
    F = Phi @ sol.x
    pulse = TabulatedPulse(tm, F)
    computed = np.array([np.convolve(h[g], F[1:])[: N - 1] for g in range(n_g)])
    computed = np.hstack((np.zeros((n_g, 1)), computed))
    # Beside it, the eq-15 fit to the deconvolved force.
    k = int(np.argmax(F))
    fit_pulse = None
    try:
        fit_pulse = fit_eq15(tm, F, guess=(F[k], max(tm[k], tm[1]), start.duration)).pulse
    except Exception:  # a degenerate deconvolution has no eq-15 shape; the history stands alone
        fit_pulse = None
    return Calibration(
        "deconvolve",
        pulse,
        r0,
        {},
        int(sol.nit),
        bool(sol.success),
        f"λ = {lam:.3g} by {choice.method}: {choice.reason}",
        _residual_rms(model, prep, computed),
        computed,
        prep,
        start,
        fit_pulse=fit_pulse,
        time=tm,
        regularisation=choice,
    )


MAIN = ("peak_force", "time_of_peak", "duration")  # the parameters the check judges
# Roache's factor of safety when the order is assumed, not observed (two levels): the
# model-error shift Δ becomes a 95 % bound 3|Δ|, i.e. a standard uncertainty 3|Δ|/1.96.
ASSUMED_ORDER_SAFETY = 3.0


# Skews t_F0/T of the extra starting pulses on the case's mesh: the misfit is multimodal in t_F0 (a start
# from Table I's 0.25 can settle on a late, low peak that misses the record by several noise σ while
# Tables II/III's histories peak at 0.06-0.09), so the fit is also started from short rises.
START_SKEWS = (0.05, 0.12)


def _misfits(fits: list[Calibration]) -> list[float]:
    """Each fit's least-squares objective Σ_g Σ_j ((computed − measured)/σ_g)² on one common set of record
    samples: every sample the fits share up to the end of the model's run after the earliest fitted first
    contact (pre-impact part included, as the fits see it), with each fit's own clock and offsets; so
    that fits whose first contacts differ are compared on the same data."""
    first = min(c.prepared.contact_time for c in fits)
    out = []
    for c in fits:
        prep = c.prepared
        record_time = prep.time + prep.contact_time
        use = record_time <= first + c.time[-1]
        computed = np.array([np.interp(prep.time[use], c.time, y, left=0.0) for y in c.computed])
        out.append(float(np.sum(np.square((computed - prep.strains[:, use]) / prep.noise[:, None]))))
    return out


def _best_start(model, measured, start, contact_time=None, **kw) -> Calibration:
    """The least-squares fit on ``model`` from ``start`` and from starts with the same F0 and T and
    the skews :data:`START_SKEWS`, the one of lowest misfit on common samples (:func:`_misfits`;
    ties: the given start's). Each start locates first contact from its own shape unless
    ``contact_time`` is given (a start unlike the record misplaces it); a start that cannot be
    prepared is passed over."""
    fits = []
    for skew in (None, *START_SKEWS):
        if skew is not None and abs(start.time_of_peak / start.duration - skew) < 0.02:
            continue
        s = start if skew is None else SkewedPulse(start.peak_force, skew * start.duration, start.duration)
        try:
            fits.append(calibrate(model, measured, s, "least-squares", contact_time=contact_time, **kw))
        except InputError:
            if skew is None:
                raise
    misfit = _misfits(fits)
    best = 0
    for k in range(1, len(fits)):
        if misfit[k] < misfit[best] * (1 - 1e-6):
            best = k
    return replace(fits[best], start=start)


def _observed_order(ys: dict, low: int, mid: int, high: int, ratio: float, formal: float) -> float | None:
    """The order p of the model's discretisation error, observed from three levels' strain
    histories (``ys``: level → (time, strains)) on the coarsest grid: p = ln(‖ε_low‖/‖ε_high‖)/ln r
    for monotone convergence (⟨ε_low, ε_high⟩ > 0, ‖ε_high‖ < ‖ε_low‖), at most the formal
    order (a higher one would shrink the estimate below what the scheme promises); None
    when it cannot be observed."""
    if not all(k in ys for k in (low, mid, high)):
        return None
    t = ys[low][0]
    a = _on_grid(t, *ys[mid]) - ys[low][1]
    b = _on_grid(t, *ys[high]) - _on_grid(t, *ys[mid])
    na, nb = float(np.linalg.norm(a)), float(np.linalg.norm(b))
    if not (nb > 0 and nb < na and float(np.sum(a * b)) > 0):
        return None
    return min(math.log(na / nb) / math.log(ratio), formal)


def _on_grid(t_to, t_from, y):
    """Histories y (n_g, n) on grid t_from, linearly interpolated onto t_to."""
    return np.array([np.interp(t_to, t_from, yi) for yi in y])


def calibrate_checked(
    level_model,
    measured: Measured,
    start: SkewedPulse,
    method: str = "least-squares",
    *,
    ratio: int = 2,
    order: float = 2.0,
    tolerance: float = 0.5,
    max_level: int = 1,
    contact_time=None,
    radius: float | None = None,
    fit_radius: bool = False,
    progress=None,
) -> Calibration:
    """Calibrate with a model whose discretisation error is known and bounded.

    ``level_model(k)`` gives the model refined by ratio^k (k = 0: the case's own);
    models of coarser levels stay in use (they are built once by the caller).
    At level L the model error e_L = y_L − y_∞ is estimated by Richardson from two levels at the
    current fit p̂: e_L = (y_L − y_{L+1})·r^p/(r^p − 1) for the case's own level,
    e_L = (y_{L−1} − y_L)/(r^p − 1) above it (y_k = y_∞ + C·(h/r^k)^p), with the order p observed from three
    levels (one below the case's mesh included: cheap) and at most the formal
    ``order``; where it cannot be observed, the formal order. The fit is repeated with e_L subtracted from the
    model (defect correction); the parameter shifts Δ it causes are the model's
    bias. If any |Δ| exceeds ``tolerance`` × its noise standard error, the next
    level is used, up to ``max_level`` (the caller's time budget). The reported
    standard errors are √(SE_noise² + (Fs·Δ/1.96)²), Fs = 3 (Roache's factor for an
    order not observed for the parameter itself): noise and discretisation together.
    The least-squares fits made on the way are kept (``check.level_fits``).
    Least squares carries the check; another ``method`` is then run on the chosen level.
    """

    def note(label):
        if progress is not None:
            progress(label)

    level, model = 0, level_model(0)
    note("fitting on the case's mesh")
    cal = _best_start(model, measured, start, contact_time=contact_time, radius=radius, fit_radius=fit_radius)
    if contact_time is None:  # every later fit (other levels, defect correction) starts from this fit's first contact
        contact_time = cal.prepared.contact_time
    level_fits = {}
    while True:
        level_fits[level] = tuple(getattr(cal, n) for n in MAIN)
        tm = model.problem.solver.times()
        y = model.respond(cal.pulse, cal.contact_radius).strain
        # Three levels (the two around this one and one below) give the observed order p.
        low, mid, high = (-1, 0, 1) if level <= 1 else (level - 2, level - 1, level)
        note("estimating the model's error (refined and coarsened meshes)")
        ys = {level: (tm, y)}
        for k in (low, mid, high):
            if k in ys:
                continue
            try:
                m = level_model(k)
            except InputError:  # a mesh that cannot be coarsened: the order stays assumed
                continue
            if k == level + 1 and max_level < 1:  # one direct run is cheaper than an engine used once
                yk = m.direct(cal.pulse, energy=False, displacement=False, radius=cal.contact_radius).strain
            else:  # an engine that a refined fit will reuse, or a coarse one that costs little
                yk = m.respond(cal.pulse, cal.contact_radius).strain
            ys[k] = (m.problem.solver.times(), yk)
        p_obs = _observed_order(ys, low, mid, high, float(ratio), order)
        # The order observed is the strain histories'; a parameter's shift keeps the assumed-order
        # safety (its own order is not observed here: the app's parameter_convergence does that).
        p_used, safety = (p_obs if p_obs is not None else order), ASSUMED_ORDER_SAFETY
        r_p = float(ratio) ** p_used
        # e_L = y_L − y_∞ (the model's strains minus the converged ones), the defect subtracted below
        if level == 0:
            error = (y - _on_grid(tm, *ys[1])) * r_p / (r_p - 1.0)
        else:
            error = (_on_grid(tm, *ys[level - 1]) - y) / (r_p - 1.0)
        prep = cal.prepared
        w = (prep.time >= 0) & (prep.time <= tm[-1])
        err_w = _on_grid(prep.time[w], tm, error)
        error_to_noise = np.sqrt(np.mean(err_w**2, axis=1)) / prep.noise
        note("correcting the model's error (defect correction)")
        corrected = calibrate(model, measured, cal.pulse, "least-squares", contact_time=contact_time, radius=radius, fit_radius=fit_radius, defect=error)
        names = [n for n in cal.standard_errors if n in corrected.standard_errors]
        values = lambda c: {"peak_force": c.peak_force, "time_of_peak": c.time_of_peak, "duration": c.duration, "contact_radius": c.contact_radius}  # noqa: E731
        v0, v1 = values(cal), values(corrected)
        shifts = {n: v1[n] - v0[n] for n in v0 if n in names}
        noise = dict(cal.standard_errors)
        meets = all(abs(shifts[n]) <= tolerance * noise[n] for n in MAIN if n in shifts and noise.get(n))
        if meets or level >= max_level:
            break
        level += 1
        note(f"refining the model (×{ratio**level})")
        model = level_model(level)
        cal = calibrate(model, measured, cal.pulse, "least-squares", contact_time=contact_time, radius=radius, fit_radius=fit_radius)
    total = {n: math.hypot(se, safety / 1.96 * shifts.get(n, 0.0)) for n, se in noise.items()}
    worst = max((abs(shifts[n]) / noise[n] for n in MAIN if n in shifts and noise.get(n)), default=0.0)
    message = (
        f"model ×{ratio**level}: its estimated discretisation error (order {p_used:.2f}, {'observed' if p_obs is not None else 'assumed'}) "
        f"is {np.max(error_to_noise):.2g} × the noise (RMS), "
        f"and moves the fit by up to {worst:.2g} noise standard errors"
        + ("" if meets else f" (above {tolerance:g}: the time budget stopped the refinement; the standard errors include it)")
    )
    check = ModelCheck(
        level, ratio**level, error_to_noise, shifts, noise, tolerance, meets, message, p_used, p_obs is not None, safety, level_fits, contact_time
    )
    if method == "least-squares":
        return replace(cal, standard_errors=total, check=check)
    other = calibrate(model, measured, start, method, contact_time=cal.prepared.contact_time, radius=cal.contact_radius, error_to_noise=error_to_noise)
    return replace(other, check=check)


# scipy.optimize.least_squares's status → (how the fit ended, why), plain phrases of ours.
_LSQ_OUTCOMES = {
    1: ("converged", "the misfit's gradient vanished"),
    2: ("converged", "the misfit no longer decreasing"),
    3: ("converged", "the parameters no longer changing"),
    4: ("converged", "the misfit and the parameters no longer changing"),
    0: ("not converged", "stopped at the limit of evaluations"),
    -1: ("not converged", "the fit could not start"),
}


def fit_outcome(status: int, evaluations: int) -> str:
    """How a least-squares fit ended, in our words (``status``: scipy's least_squares status;
    ``evaluations``: model runs), e.g. "converged after 6 model runs, the misfit no longer decreasing"."""
    head, why = _LSQ_OUTCOMES.get(int(status), ("ended", f"status {int(status)}"))
    return f"{head} after {int(evaluations)} model runs, {why}"
