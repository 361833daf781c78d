"""Tail-shape ambiguity: several tail families fitted to a whole force record, ranked by AIC.

Private part of :mod:`softimpact.workflows.reduction` (whose names these are:
import them from there).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..models.pulse_fit import fit_main_pulse

__all__ = ["TAIL_FAMILIES", "TailShapeFit", "fit_tail_shapes"]

TAIL_FAMILIES = ("knee", "ramp-under", "linear", "power-law", "free-ramp", "early-ramp")


def _eq15(x, F0, tp, T):
    """Eq (15) from x = 0 (time since its start): quarter sine to tp, quarter cosine to T."""
    rise = F0 * np.sin(np.pi * np.clip(x, 0, None) / (2 * tp))
    fall = F0 * np.cos(np.pi * (x - tp) / (2 * (T - tp)))
    return np.where(x <= 0, 0.0, np.where(x < tp, rise, np.where(x < T, fall, 0.0)))


def _tail_model(family: str, x, F0, tp, T, q):
    """The whole record of one tail family (x: time since the pulse's start; q: the tail's parameters).

    - knee: eq 15 until its fall reaches level·F0, then level·F0·exp(−(x − x_k)/τ) (q = level, τ/T);
    - ramp-under: eq 15 plus a tail rising linearly from s·T to L·F0 at T (under the falling main
      pulse), then decaying as exp(−(x − T)/τ) (q = L, s, τ/T);
    - linear: the same rise, then a linear fall to 0 at T + τ (q = L, s, τ/T);
    - power-law: the same rise, then (1 + (x − T)/τ)^(−n) (q = L, s, τ/T, n);
    - free-ramp: a rise L·F0·r^p, r from 0 at s·T to 1 at e·T = (s + w)·T (its end free, before or
      after T; p < 1 concave, p > 1 convex), then a stretched exponential exp(−((x − e·T)/τ)^β)
      (q = L, s, w, p, τ/T, β): the least constrained tail, whose main pulse the data bound least;
    - early-ramp: the free ramp started at first contact (s = 0: q = L, e, p, τ/T, β), a tail already
      under the peak, so part of the recorded peak; its F0 counts in the widening only where the
      record cannot exclude it (:func:`softimpact.workflows.scaling.tail_shape_term`).
    """
    if family == "knee":
        level, tau = q[0], q[1] * T
        xk = tp + 2 * (T - tp) / np.pi * math.acos(min(max(level, 0.0), 1.0))
        return np.where(x < xk, _eq15(x, F0, tp, T), level * F0 * np.exp(-np.maximum(x - xk, 0.0) / tau))
    if family in ("free-ramp", "early-ramp"):
        if family == "early-ramp":
            q = (q[0], 0.0, *q[1:])
        L, s, e, p, tau, beta = q[0], q[1] * T, (q[1] + q[2]) * T, q[3], q[4] * T, q[5]
        r = np.clip((x - s) / max(e - s, 1e-12 * T), 0.0, 1.0)
        return _eq15(x, F0, tp, T) + np.where(x < e, L * F0 * r**p, L * F0 * np.exp(-((np.maximum(x - e, 0.0) / tau) ** beta)))
    L, s, tau = q[0], q[1], q[2] * T
    rise = L * F0 * np.clip((x - s * T) / max(T - s * T, 1e-12 * T), 0.0, 1.0)
    after = np.maximum(x - T, 0.0)
    if family == "ramp-under":
        decay = np.exp(-after / tau)
    elif family == "linear":
        decay = np.clip(1.0 - after / tau, 0.0, 1.0)
    else:
        decay = (1.0 + after / tau) ** (-q[3])
    return _eq15(x, F0, tp, T) + np.where(x < T, rise, L * F0 * decay)


@dataclass(frozen=True)
class TailShapeFit:
    """One tail family fitted to a whole force record: the main pulse's F0 [N], t_F0, T [s] and its
    start [s], the residual sum of squares [N²] over n samples, k parameters, and
    AIC = n·ln(RSS/n) + 2k (Akaike; Gaussian residuals of unknown variance); ``se_*``: the standard
    errors of F0 [N], t_F0 and T [s] from the fit's Jacobian, s²(JᵀJ)⁻¹ (with the tail's own
    parameters free: what the record leaves of them once this family's tail may take any of its shapes);
    ``correlation_length``: the residual's correlation length [samples] (the first lag where its
    autocorrelation falls below 1/e, at least 1): n/correlation_length is about how many independent
    samples the record holds against this family, the scale of a likelihood ratio between two tails."""

    family: str
    peak_force: float
    time_of_peak: float
    duration: float
    start: float
    rss: float
    samples: int
    parameters: int
    se_peak_force: float = math.nan
    se_time_of_peak: float = math.nan
    se_duration: float = math.nan
    correlation_length: int = 1

    @property
    def aic(self) -> float:
        return self.samples * math.log(max(self.rss, 1e-300) / self.samples) + 2 * self.parameters


def fit_tail_shapes(t, F, families=TAIL_FAMILIES) -> tuple[TailShapeFit, ...]:
    """Each tail family (:func:`_tail_model`) fitted by least squares to the whole record (``t`` [s] from
    about first contact, ``F`` [N]), started from the reduction's main-pulse fit. The main pulse's
    parameters differ between families when the tail ramps in under the falling main pulse: the
    record alone may not tell the shapes apart (their AICs then differ by little)."""
    from scipy.optimize import least_squares

    t, F = np.asarray(t, float), np.asarray(F, float)
    main = fit_main_pulse(t, F).fit
    m = main.pulse
    F0s, T0 = m.peak_force, m.duration
    after = t > main.start + T0
    level0 = float(np.clip(np.mean(F[after]) / F0s * 2.0 if after.any() else 0.1, 0.02, 0.5))
    tau0 = max(float(t[-1] - main.start - T0) / 3.0, 0.1 * T0) / T0
    out = []
    for family in families:
        if family == "knee":
            q0, qlo, qhi = [level0, tau0], [0.005, 0.01], [0.7, 50.0]
        elif family == "free-ramp":
            q0, qlo, qhi = [level0, 0.5, 0.5, 1.0, tau0, 1.0], [0.0, 0.0, 0.05, 0.1, 0.01, 0.3], [0.7, 0.999, 2.0, 6.0, 50.0, 3.0]
        elif family == "early-ramp":
            q0, qlo, qhi = [level0, 1.0, 2.0, tau0, 1.0], [0.0, 0.1, 0.1, 0.01, 0.3], [0.7, 3.0, 8.0, 50.0, 3.0]
        else:
            q0, qlo, qhi = [level0, 0.5, tau0], [0.0, 0.0, 0.01], [0.7, 0.999, 50.0]
            if family == "linear":
                q0[2], qlo[2] = max(2 * tau0, 0.05), 0.05
            if family == "power-law":
                q0, qlo, qhi = q0 + [2.0], qlo + [0.2], qhi + [10.0]
        p0 = np.array([main.start / T0, 1.0, m.time_of_peak / T0, 1.0, *q0])
        lo = np.array([-0.2, 0.3, 1e-3, 0.2, *qlo])
        hi = np.array([0.2, 3.0, 0.95, 5.0, *qhi])
        p0 = np.clip(p0, lo + 1e-9, hi - 1e-9)

        def residual(p, family=family):
            t0, f0, tp, T = p[0] * T0, p[1] * F0s, p[2] * T0, p[3] * T0
            return (_tail_model(family, t - t0, f0, min(tp, 0.999 * T), T, p[4:]) - F) / F0s

        sol = least_squares(residual, p0, bounds=(lo, hi), x_scale=np.array([0.02, 1.0, 0.1, 1.0] + [0.1] * len(q0)))
        t0, f0, tp, T = sol.x[0] * T0, sol.x[1] * F0s, sol.x[2] * T0, sol.x[3] * T0
        rss = float(sol.fun @ sol.fun) * F0s**2
        *se, B = _standard_errors(sol, np.array([F0s, T0, T0]))
        out.append(TailShapeFit(family, float(f0), float(min(tp, 0.999 * T)), float(T), float(t0), rss, int(t.size), len(p0), *se, B))
    return tuple(out)


def _standard_errors(sol, scales) -> tuple[float, float, float, int]:
    """Standard errors of (F0, t_F0, T) [N, s, s] of a tail fit and the residual's correlation length B [samples], robust to a residual that is not white
    (the misfit of a tail shape that is not the true one is structured under the pulse): the
    Newey–West (1987) covariance (JᵀJ)⁻¹·Σ_l w_l·Gᵀ_l G·(JᵀJ)⁻¹ of the scaled parameters, G_i = J_i·r_i,
    Bartlett weights w_l = 1 − l/(B + 1) to the residual's correlation length B (the first lag where
    its autocorrelation falls below 1/e, at least 1, at most n/4). Pseudo-inverse: a tail parameter at
    a bound or without effect leaves JᵀJ singular."""
    J, r = sol.jac, sol.fun
    n = r.size
    c = np.correlate(r, r, "full")[n - 1 :] if n <= 4096 else np.array([r[: n - k] @ r[k:] for k in range(n // 4 + 1)])
    below = np.flatnonzero(c[: n // 4 + 1] < c[0] / math.e)
    B = int(min(max(below[0] if below.size else n // 4, 1), n // 4))
    G = J * r[:, None]
    meat = G.T @ G
    for lag in range(1, B + 1):
        S = G[lag:].T @ G[:-lag]
        meat += (1.0 - lag / (B + 1)) * (S + S.T)
    bread = np.linalg.pinv(J.T @ J)
    cov = bread @ meat @ bread
    se = np.sqrt(np.maximum(np.diag(cov)[1:4], 0.0)) * scales
    return float(se[0]), float(se[1]), float(se[2]), B
