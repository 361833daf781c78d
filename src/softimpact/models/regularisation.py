"""Choice of the regularisation parameter of a linear, non-negative deconvolution.

The problem is min ‖G f − d‖² + λ²‖L f‖² subject to f ≥ 0 (G: (m, n) forward
operator, e.g. the gauge impulse responses convolved with a basis; L: (k, n) a
difference operator; d: (m,) data). Three rules choose λ over a grid:

- **discrepancy principle** (Morozov): the largest λ whose residual satisfies
  ‖G f_λ − d‖² ≤ τ²·m·σ², with σ the noise level measured from the data (the
  pre-trigger part or a residual) as the normal-scaled median absolute
  deviation, robust to the odd spike; τ = ``DISCREPANCY_TAU`` slightly above 1.
  When no λ gets there (the model cannot fit the data to the noise), the
  smallest residual reached stands for the noise: the largest λ within τ of it.
- **L-curve** (Hansen 1992, *SIAM Review* 34, 561): the corner of
  (log ‖G f − d‖, log ‖L f‖), the point of largest curvature.
- **GCV** (Golub, Heath & Wahba 1979, *Technometrics* 21, 215): minimiser of
  m‖r_λ‖²/(m − tr A_λ)², A_λ = G(GᵀG + λ²LᵀL)⁻¹Gᵀ, the influence matrix of
  the unconstrained problem. GCV is known to undersmooth, most of all when the
  noise is correlated (sampled from a filtered signal): its minimum can sit at
  a λ that fits the noise. With ``floor`` (default on when σ is known) the
  search is restricted to λ whose residual is at least ``GCV_FLOOR_FRACTION``
  of the expected noise, ‖r‖² ≥ FLOOR·m·σ².

Each returns a :class:`LambdaChoice`: λ, the non-negative solution, the curve
(λ, residual norm, solution norm ‖L f‖) and the reason in words.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..models.noise import robust_sigma

__all__ = [
    "RegularisationCurve",
    "LambdaChoice",
    "noise_sigma",
    "solve_nonnegative",
    "regularisation_curve",
    "choose_discrepancy",
    "choose_l_curve",
    "choose_gcv",
]

DISCREPANCY_TAU = 1.05  # Morozov's safety factor on the noise norm (τ > 1)
GCV_FLOOR_FRACTION = 0.5  # GCV may not pick a λ whose residual is below half the noise energy


@dataclass(frozen=True)
class RegularisationCurve:
    """Over the grid of λ (increasing): residual ‖G f − d‖, seminorm ‖L f‖ of the non-negative solution, and GCV."""

    lambdas: np.ndarray
    residual_norms: np.ndarray
    solution_norms: np.ndarray
    gcv: np.ndarray


@dataclass(frozen=True)
class LambdaChoice:
    """The chosen λ, its non-negative solution f (n,), the curve and why."""

    method: str
    lam: float
    solution: np.ndarray
    curve: RegularisationCurve
    reason: str
    noise: float  # σ used (nan if none)


def noise_sigma(samples) -> float:
    """σ of the noise: normal-scaled median absolute deviation of ``samples`` (pre-trigger part or a residual)."""
    x = np.asarray(samples, float)
    if x.size < 8:
        raise InputError(f"noise: need at least 8 samples to measure the noise, got {x.size}")
    return float(robust_sigma(x))


def _check(G, d, L):
    G, d, L = np.asarray(G, float), np.asarray(d, float), np.asarray(L, float)
    if G.ndim != 2 or d.shape != (G.shape[0],) or L.ndim != 2 or L.shape[1] != G.shape[1]:
        raise InputError(f"regularisation: shapes G {G.shape}, d {d.shape}, L {L.shape} do not agree (G (m, n), d (m,), L (k, n))")
    return G, d, L


def solve_nonnegative(G, d, L, lam: float) -> np.ndarray:
    """argmin ‖G f − d‖² + λ²‖L f‖², f ≥ 0 (NNLS on the stacked system)."""
    from scipy.optimize import nnls

    G, d, L = _check(G, d, L)
    A = np.vstack((G, lam * L))
    b = np.concatenate((d, np.zeros(L.shape[0])))
    return nnls(A, b, maxiter=50 * G.shape[1])[0]


def _gcv(G, d, L, lam):
    m = G.shape[0]
    M = G.T @ G + lam**2 * (L.T @ L)
    try:
        X = np.linalg.solve(M, G.T)  # (n, m)
    except np.linalg.LinAlgError:
        return math.nan
    r = G @ (X @ d) - d
    trace = float(np.einsum("ij,ji->", G, X))
    return m * float(r @ r) / (m - trace) ** 2


def regularisation_curve(G, d, L, lambdas, gcv: bool = True) -> tuple[RegularisationCurve, np.ndarray]:
    """Non-negative solutions over the grid ``lambdas`` (sorted increasing); returns the curve and the solutions (n_λ, n).
    ``gcv``: also the GCV function (one n × n solve per λ; NaN when not asked for)."""
    G, d, L = _check(G, d, L)
    lam = np.sort(np.asarray(lambdas, float))
    if lam.size < 3 or np.any(lam <= 0):
        raise InputError("regularisation: need at least 3 positive values of λ")
    sols = np.array([solve_nonnegative(G, d, L, x) for x in lam])
    res = np.linalg.norm(sols @ G.T - d, axis=1)
    semi = np.linalg.norm(sols @ L.T, axis=1)
    values = np.array([_gcv(G, d, L, x) for x in lam]) if gcv else np.full(lam.size, np.nan)
    return RegularisationCurve(lam, res, semi, values), sols


def choose_discrepancy(G, d, L, lambdas, sigma: float, tau: float = DISCREPANCY_TAU) -> LambdaChoice:
    """Largest λ with ‖G f_λ − d‖ ≤ τ·sqrt(m)·σ (Morozov)."""
    if not (math.isfinite(sigma) and sigma > 0):
        raise InputError(f"discrepancy: the noise level σ must be positive, got {sigma!r}")
    curve, sols = regularisation_curve(G, d, L, lambdas, gcv=False)
    target = tau * math.sqrt(len(d)) * sigma
    ok = np.flatnonzero(curve.residual_norms <= target)
    if ok.size == 0:
        # The model cannot fit the data to the noise (model error): the smallest residual
        # reached is the floor, and the discrepancy is measured from it instead.
        floor = float(np.min(curve.residual_norms))
        k = int(np.flatnonzero(curve.residual_norms <= tau * floor)[-1])
        reason = (
            f"no λ on the grid brings the residual down to τ√m·σ = {target:.3g} (model error?): largest λ within τ of the "
            f"smallest residual reached, {floor:.3g}"
        )
    else:
        k = int(ok[-1])
        reason = f"largest λ with residual {curve.residual_norms[k]:.3g} ≤ τ√m·σ = {target:.3g} (σ = {sigma:.3g}, τ = {tau:g})"
        if k == curve.lambdas.size - 1:
            reason += "; at the top of the grid: widen it"
    return LambdaChoice("discrepancy", float(curve.lambdas[k]), sols[k], curve, reason, float(sigma))


def choose_l_curve(G, d, L, lambdas) -> LambdaChoice:
    """Corner of the L-curve: largest curvature of (log ‖r‖, log ‖L f‖) against log λ."""
    curve, sols = regularisation_curve(G, d, L, lambdas, gcv=False)
    x = np.log(np.maximum(curve.residual_norms, 1e-300))
    y = np.log(np.maximum(curve.solution_norms, 1e-300))
    s = np.log(curve.lambdas)
    x1, y1 = np.gradient(x, s), np.gradient(y, s)
    x2, y2 = np.gradient(x1, s), np.gradient(y1, s)
    kappa = (x1 * y2 - x2 * y1) / np.maximum((x1**2 + y1**2) ** 1.5, 1e-300)
    inner = np.arange(1, s.size - 1)
    k = int(inner[np.argmax(kappa[inner])])
    reason = f"L-curve corner (curvature {kappa[k]:.3g}) at λ = {curve.lambdas[k]:.3g}"
    return LambdaChoice("l-curve", float(curve.lambdas[k]), sols[k], curve, reason, math.nan)


def choose_gcv(G, d, L, lambdas, sigma: float | None = None, floor: bool = True) -> LambdaChoice:
    """Minimiser of GCV over the grid; with ``floor`` and σ, only among λ whose residual is at least
    sqrt(GCV_FLOOR_FRACTION·m)·σ (module docstring)."""
    curve, sols = regularisation_curve(G, d, L, lambdas)
    allowed = np.isfinite(curve.gcv)
    note = ""
    if floor:
        if sigma is None or not (math.isfinite(sigma) and sigma > 0):
            raise InputError("gcv: the floor needs the noise level σ (or floor=False)")
        level = math.sqrt(GCV_FLOOR_FRACTION * len(d)) * sigma
        above = allowed & (curve.residual_norms >= level)
        if above.any() and not above[np.nanargmin(np.where(allowed, curve.gcv, np.nan))]:
            note = f"; unfloored minimum fits the noise (residual below {level:.3g}): floored"
        if above.any():
            allowed = above
    k = int(np.flatnonzero(allowed)[np.argmin(curve.gcv[allowed])])
    reason = f"GCV minimum {curve.gcv[k]:.3g} at λ = {curve.lambdas[k]:.3g}" + note
    if k == 0 or k == curve.lambdas.size - 1:
        reason += "; at the edge of the grid"
    return LambdaChoice("gcv" if not floor else "gcv-floored", float(curve.lambdas[k]), sols[k], curve, reason, math.nan if sigma is None else float(sigma))
