"""Statistics of a sweep's runs: summaries, rank correlations, first-order Sobol indices, thresholds.

Plain arrays in, plain dicts out (the rows of summary.json and thresholds.csv): the
sweep's plan and spec stay above, in :mod:`softimpact.cases.sweep`.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["statistics", "sensitivity", "sobol_first_order", "thresholds"]


def statistics(values: np.ndarray) -> dict:
    """Mean, standard deviation, extremes and percentiles (2.5, 5, 50, 95, 97.5) of the finite values."""
    v = np.asarray(values, float)
    v = v[np.isfinite(v)]
    if v.size == 0:
        return {"count": 0}
    p = np.percentile(v, [2.5, 5, 50, 95, 97.5])
    return {
        "count": int(v.size),
        "mean": float(v.mean()),
        "std": float(v.std(ddof=1)) if v.size > 1 else 0.0,
        "min": float(v.min()),
        "p05": float(p[1]),
        "median": float(p[2]),
        "p95": float(p[3]),
        "max": float(v.max()),
        "interval95": [float(p[0]), float(p[4])],
    }


def sensitivity(columns: dict[str, np.ndarray], y: np.ndarray) -> list[dict]:
    """Varied inputs ranked by |Spearman rank correlation| with output ``y`` (finite runs only)."""
    from scipy.stats import spearmanr

    out = []
    ok = np.isfinite(y)
    for name, x in columns.items():
        x = np.asarray(x)
        if x.dtype.kind not in "fiu" or ok.sum() < 3:
            continue
        xs, ys = x[ok].astype(float), y[ok]
        if np.ptp(xs) == 0 or np.ptp(ys) == 0:
            continue
        rho = float(spearmanr(xs, ys).statistic)
        out.append({"parameter": name, "spearman": rho})
    return sorted(out, key=lambda d: -abs(d["spearman"]))


def sobol_first_order(columns: dict[str, np.ndarray], y: np.ndarray) -> list[dict]:
    """First-order Sobol indices S_i = Var(E[Y | X_i]) / Var(Y) of the varied inputs, from the runs
    already made (a given-data estimate: no extra design), ranked largest first.

    E[Y | X_i] is estimated by the mean of Y over bins of X_i: its distinct values when
    there are few (levels), else ⌈√n⌉ bins of equal count by rank. The between-bin share of
    the variance, S_raw, is biased up by (M − 1)/(n − 1) for M bins when Y does not depend
    on X_i; that bias is removed, S = (S_raw − b)/(1 − b), and S clipped at 0. Assumes the
    inputs independent (the α's of a scaling.json are not: their indices share the
    variance their correlation carries). Finite runs only; needs 10 or more.
    """
    y = np.asarray(y, float)
    ok = np.isfinite(y)
    n = int(ok.sum())
    if n < 10 or np.ptp(y[ok]) == 0:
        return []
    yk = y[ok]
    total = float(np.sum((yk - yk.mean()) ** 2))
    out = []
    for name, x in columns.items():
        x = np.asarray(x)
        if x.dtype.kind not in "fiu":
            continue
        xk = x[ok].astype(float)
        if np.ptp(xk) == 0:
            continue
        levels = np.unique(xk)
        M = math.ceil(math.sqrt(n))
        if levels.size <= M:
            labels = np.searchsorted(levels, xk)
            M = levels.size
        else:
            labels = np.minimum((np.argsort(np.argsort(xk, kind="stable"), kind="stable") * M) // n, M - 1)
        counts = np.bincount(labels, minlength=M)
        means = np.bincount(labels, weights=yk, minlength=M) / np.maximum(counts, 1)
        raw = float(np.sum(counts * (means - yk.mean()) ** 2)) / total
        bias = (M - 1) / (n - 1)
        out.append({"parameter": name, "S1": max(0.0, (raw - bias) / (1 - bias)), "bins": int(M)})
    return sorted(out, key=lambda d: -d["S1"])


BELOW = "below the lowest level"  # a threshold quantile at or under the lowest swept velocity: an upper bound only
ABOVE = "above the highest level"  # a threshold quantile over the highest swept velocity (index never reached 1): a lower bound only
QUANTILES = (("p05", 5.0), ("median", 50.0), ("p95", 95.0))


def _quantile(f: np.ndarray, q: float) -> tuple[float, str]:
    """The ``q`` % quantile (numpy's linear interpolation) of draws ``f`` whose thresholds outside the swept
    levels are -inf (below the lowest) or +inf (above the highest): (value, "") when both draws it interpolates
    between are bracketed, else (NaN, :data:`BELOW` or :data:`ABOVE`): a bound, never a bare value."""
    s = np.sort(f)
    pos = q / 100.0 * (s.size - 1)
    window = s[int(np.floor(pos)) : int(np.ceil(pos)) + 1]
    if np.all(np.isfinite(window)):
        return float(np.percentile(f, q)), ""
    if np.any(window == np.inf) and np.any(window == -np.inf):
        return math.nan, f"{BELOW} for some draws, {ABOVE} for others"
    return math.nan, BELOW if np.any(window == -np.inf) else ABOVE


def thresholds(velocity: np.ndarray, labels: list[str], draws: np.ndarray, indices: dict[str, np.ndarray]) -> list[dict]:
    """Threshold velocities: per combination of the other levels (``labels``, one text per run)
    and per damage index (``indices``: output name → values, shape (n_runs,)), the velocity
    [m/s] where the index first reaches 1 (linear between velocity levels), over the draws
    (``draws``: each run's draw number): median and 5–95 % band, and how many draws reach 1
    within the swept range. ``velocity``: each run's velocity level [m/s].

    A draw whose index is 1 or more already at the lowest level has its threshold below that level, one that
    never reaches 1 above the highest: both are censored (ordered as -inf and +inf among the draws), and a
    quantile that falls on one is NaN with ``threshold_velocity_<q>_bound`` saying :data:`BELOW` or :data:`ABOVE`
    (beside ``lowest_level_m_s`` and ``highest_level_m_s``); a bracketed quantile has an empty bound."""
    velocity = np.asarray(velocity, float)
    draws = np.asarray(draws)
    out = []
    for label in dict.fromkeys(labels):
        sel = np.array([lab == label for lab in labels])
        for o, values in indices.items():
            found = []
            for d in np.unique(draws[sel]):
                m = sel & (draws == d)
                order = np.argsort(velocity[m])
                v, idx = velocity[m][order], np.asarray(values, float)[m][order]
                k = np.flatnonzero(np.nan_to_num(idx, nan=-np.inf) >= 1.0)
                if k.size == 0:
                    found.append(np.inf)
                elif k[0] == 0:
                    found.append(-np.inf)
                else:
                    j = k[0]
                    found.append(float(v[j - 1] + (1.0 - idx[j - 1]) * (v[j] - v[j - 1]) / (idx[j] - idx[j - 1])))
            f = np.array(found)
            row = {"levels": label, "index": o.removeprefix("damage.")}
            quantiles = {name: _quantile(f, q) for name, q in QUANTILES}
            row.update({f"threshold_velocity_{name}_m_s": quantiles[name][0] for name in ("median", "p05", "p95")})
            row.update(
                {
                    "draws": int(f.size),
                    "draws_reaching_1": int(np.sum(f < np.inf)),
                    "draws_below_lowest_level": int(np.sum(f == -np.inf)),
                    "lowest_level_m_s": float(velocity[sel].min()),
                    "highest_level_m_s": float(velocity[sel].max()),
                }
            )
            row.update({f"threshold_velocity_{name}_bound": quantiles[name][1] for name in ("median", "p05", "p95")})
            out.append(row)
    return out
