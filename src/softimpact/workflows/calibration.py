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
from dataclasses import replace

import numpy as np

from ..errors import InputError
from ..models.features import first_lobe_peak, first_zero_crossing
from ..models.pulse_fit import fit_pulse as fit_eq15
from ..models.pulses import SkewedPulse, TabulatedPulse
from ._calibration_data import BOUND_TOLERANCE, Calibration, Measured, ModelCheck, Prepared, _residual_rms, on_bounds, prepare

__all__ = ["Measured", "Prepared", "Calibration", "ModelCheck", "prepare", "calibrate", "calibrate_checked", "on_bounds", "METHODS", "BOUND_TOLERANCE"]

METHODS = ("least-squares", "paper", "deconvolve")


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


def _hat_responses(model, r0, start, knots):
    """The gauges' responses to hat functions of force on a coarse grid, the patch frozen at r0.

    The hats span the window where the force may act (2.5 T of the start, at
    most the run); F(0) = 0. Returns (h, Phi, A_full): the strain per unit force
    at step 1 (n_g, N − 1), the basis on the model's grid (N, knots), and each
    gauge's response to each hat, y = conv(h, φ) (n_g, N, knots).
    """
    tm = model.problem.solver.times()
    N = tm.size
    # Patch frozen at r0: the load pattern of unit total force.
    shape = model.nodal_loads(np.array([0.0, 1.0]), r0)[:, 1]
    eng = model.engine()
    n_g = len(model.problem.gauges)
    h = np.tensordot(eng.kernel[model.gauge_rows()], shape, axes=([1], [0]))  # (n_g, N-1): strain per unit force at step 1
    span = min(tm[-1], 2.5 * start.duration)
    grid = np.linspace(0.0, span, knots + 1)
    Phi = np.clip(1.0 - np.abs(tm[:, None] - grid[None, 1:]) / (grid[1] - grid[0]), 0.0, None)  # (N, knots); F(0) = 0
    # Convolutions by real FFT along time (numpy's: scipy.signal costs a second to import).
    nfft = 1 << (2 * N - 1).bit_length()
    Hg = np.fft.rfft(h, nfft, axis=-1)  # (n_g, nfft/2 + 1)
    Pk = np.fft.rfft(Phi[1:], nfft, axis=0)  # (nfft/2 + 1, knots)
    cols = []
    for g in range(n_g):
        resp = np.fft.irfft(Hg[g][:, None] * Pk, nfft, axis=0)[: N - 1]
        cols.append(np.vstack((np.zeros((1, knots)), resp)))
    return h, Phi, np.stack(cols)


def _noise_weighted(prep, tm, A_full):
    """The hats' responses at the measured samples of the window and the measured strains, each gauge in units of its noise.

    Linear interpolation from the model grid to the measured samples, as one
    sparse-free matrix. Returns (A, y).
    """
    N = tm.size
    w = prep.window
    ts = prep.time[w]
    k = np.clip(np.searchsorted(tm, ts) - 1, 0, N - 2)
    frac = ((ts - tm[k]) / (tm[k + 1] - tm[k]))[:, None]
    rows, rhs = [], []
    for g in range(A_full.shape[0]):
        rows.append(((1 - frac) * A_full[g, k] + frac * A_full[g, k + 1]) / prep.noise[g])
        rhs.append(prep.strains[g, w] / prep.noise[g])
    return np.vstack(rows), np.concatenate(rhs)


def _choose_lambda(A, y, knots, rule, error_to_noise):
    """λ of the Tikhonov regularisation of the second difference, by ``rule``, and its non-negative solution.

    The data are in units of each gauge's noise; with a model error estimate the
    expected misfit per sample is √(1 + (e/σ)²) (the discrepancy principle's level).
    """
    from ..models.regularisation import choose_discrepancy, choose_gcv, choose_l_curve

    L = np.diff(np.eye(knots), 2, axis=0)
    level = 1.0 if error_to_noise is None else float(np.sqrt(1.0 + np.mean(np.square(error_to_noise))))
    scale = math.sqrt(np.trace(A.T @ A) / np.trace(L.T @ L))
    lambdas = scale * np.logspace(-4, 2, 31)
    if rule == "discrepancy":
        return choose_discrepancy(A, y, L, lambdas, level)
    if rule == "l-curve":
        return choose_l_curve(A, y, L, lambdas)
    if rule == "gcv":
        return choose_gcv(A, y, L, lambdas, floor=False)
    if rule == "gcv-floored":
        return choose_gcv(A, y, L, lambdas, level)
    raise InputError(f"rule: {rule!r} is not one of {', '.join(RULES)}", "rule")


def _deconvolve(model, prep, start, r0, knots: int = 160, rule: str = "discrepancy", error_to_noise=None):
    """Tikhonov-regularised, non-negative deconvolution through the impulse responses (module docstring).
    ``rule`` chooses λ (:mod:`softimpact.models.regularisation`); ``error_to_noise`` (per gauge) raises
    the discrepancy level by the model's estimated error."""
    tm = model.problem.solver.times()
    N = tm.size
    n_g = len(model.problem.gauges)
    h, Phi, A_full = _hat_responses(model, r0, start, knots)
    A, y = _noise_weighted(prep, tm, A_full)
    choice = _choose_lambda(A, y, knots, rule, error_to_noise)
    F = Phi @ choice.solution
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
        0,  # the chosen non-negative solution: no iterations reported
        True,
        f"λ = {choice.lam:.3g} by {choice.method}: {choice.reason}",
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


def _model_error(level_model, model, level, cal, ratio, order, max_level):
    """The model's discretisation error e_L = y_L − y_∞ at the current fit, by Richardson (:func:`calibrate_checked`).

    Three levels (the two around this one and one below) give the observed order
    p, at most the formal ``order``; where it cannot be observed, the formal one.
    Returns (error on the model's grid (n_g, n), p observed or None, p used).
    """
    tm = model.problem.solver.times()
    y = model.respond(cal.pulse, cal.contact_radius).strain
    low, mid, high = (-1, 0, 1) if level <= 1 else (level - 2, level - 1, level)
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
    p_used = p_obs if p_obs is not None else order
    r_p = float(ratio) ** p_used
    # e_L = y_L − y_∞ (the model's strains minus the converged ones), the defect subtracted by the caller
    if level == 0:
        error = (y - _on_grid(tm, *ys[1])) * r_p / (r_p - 1.0)
    else:
        error = (_on_grid(tm, *ys[level - 1]) - y) / (r_p - 1.0)
    return error, p_obs, p_used


def _error_to_noise(tm, prep: Prepared, error) -> np.ndarray:
    """Per gauge, the RMS of the model's error ``error`` (on the model's grid ``tm``) over the record's window, in units of the gauge's noise σ."""
    w = (prep.time >= 0) & (prep.time <= tm[-1])
    err_w = _on_grid(prep.time[w], tm, error)
    return np.sqrt(np.mean(err_w**2, axis=1)) / prep.noise


def _shifts(cal: Calibration, corrected: Calibration) -> dict:
    """How far the defect correction moves each parameter both fits estimated."""
    names = [n for n in cal.standard_errors if n in corrected.standard_errors]
    values = lambda c: {"peak_force": c.peak_force, "time_of_peak": c.time_of_peak, "duration": c.duration, "contact_radius": c.contact_radius}  # noqa: E731
    v0, v1 = values(cal), values(corrected)
    return {n: v1[n] - v0[n] for n in v0 if n in names}


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
    # The order observed is the strain histories'; a parameter's shift keeps the assumed-order
    # safety (its own order is not observed here: the app's parameter_convergence does that).
    safety = ASSUMED_ORDER_SAFETY
    while True:
        level_fits[level] = tuple(getattr(cal, n) for n in MAIN)
        note("estimating the model's error (refined and coarsened meshes)")
        error, p_obs, p_used = _model_error(level_model, model, level, cal, ratio, order, max_level)
        error_to_noise = _error_to_noise(model.problem.solver.times(), cal.prepared, error)
        note("correcting the model's error (defect correction)")
        corrected = calibrate(model, measured, cal.pulse, "least-squares", contact_time=contact_time, radius=radius, fit_radius=fit_radius, defect=error)
        shifts = _shifts(cal, corrected)
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
