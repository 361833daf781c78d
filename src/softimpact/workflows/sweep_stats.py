"""Statistics of a sweep's runs: summaries, rank correlations, first-order Sobol indices, thresholds and onsets.

Plain arrays in, plain dicts out (the rows of summary.json and thresholds.csv): the
sweep's plan and spec stay above, in :mod:`softimpact.cases.sweep`.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["statistics", "sensitivity", "sobol_first_order", "thresholds", "onsets", "ONSET_FLOOR", "ONSET_FLOOR_SI"]


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


BELOW = "below the lowest level"  # a quantile at or under the lowest swept level: an upper bound only
ABOVE = "above the highest level"  # a quantile over the highest swept level (never reached): a lower bound only
QUANTILES = (("p05", 5.0), ("median", 50.0), ("p95", 95.0))
# A size is positive above the larger of ONSET_FLOOR_SI (in its SI unit: a picometre, a square micrometre, a picojoule:
# far above a zero's round-off, a relaxed elastic plate's dent is ~1e-17 m, and far below any damage a test can see)
# and ONSET_FLOOR times its largest magnitude in the sweep (round-off scales with the values the runs reach).
ONSET_FLOOR_SI = 1e-12
ONSET_FLOOR = 1e-6


def _quantile(f: np.ndarray, q: float) -> tuple[float, str]:
    """The ``q`` % quantile (numpy's linear interpolation) of draws ``f`` whose values outside the swept
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


def _suffix(unit: str) -> str:
    return f"_{unit}" if unit else ""


def _first_reaching(x: np.ndarray, y: np.ndarray, runs: np.ndarray) -> tuple[float, np.ndarray, float, float]:
    """Where index ``y`` (against levels ``x``, increasing) first reaches 1, linear between the two levels that
    bracket it: (value, the runs it rests on, bracket low, bracket high); -inf at or past 1 at the lowest level
    (resting on that run), +inf never reaching 1 (resting on the highest level's run). A failed run (NaN) does not reach."""
    k = np.flatnonzero(np.nan_to_num(y, nan=-np.inf) >= 1.0)
    if k.size == 0:
        return np.inf, runs[-1:], x[-1], math.nan
    if k[0] == 0:
        return -np.inf, runs[:1], math.nan, x[0]
    j = k[0]
    return float(x[j - 1] + (1.0 - y[j - 1]) * (x[j] - x[j - 1]) / (y[j] - y[j - 1])), runs[j - 1 : j + 1], x[j - 1], x[j]


def _first_positive(floor: float):
    """The onset of a size (zero, then positive, against increasing levels): the bracket (last level where it is
    zero, first where it is positive) and, inside it, the straight line through the first two positive levels
    extrapolated to zero, clipped into the bracket (the first positive level when there is no second one, or
    the size does not grow from the first to the second). "Positive" is above ``floor``; a failed run (NaN) is not."""

    def find(x: np.ndarray, y: np.ndarray, runs: np.ndarray) -> tuple[float, np.ndarray, float, float]:
        k = np.flatnonzero(np.nan_to_num(y, nan=-np.inf) > floor)
        if k.size == 0:
            return np.inf, runs[-1:], x[-1], math.nan
        if k[0] == 0:
            return -np.inf, runs[:1], math.nan, x[0]
        j = k[0]
        lo, hi = x[j - 1], x[j]
        if j + 1 < x.size and np.isfinite(y[j + 1]) and y[j + 1] > y[j]:
            x0 = x[j] - y[j] * (x[j + 1] - x[j]) / (y[j + 1] - y[j])
            return float(np.clip(x0, lo, hi)), runs[j - 1 : j + 2], lo, hi
        return float(hi), runs[j - 1 : j + 1], lo, hi

    return find


def _per_row(level, labels, draws, series, finder, flags):
    """For each combination of the other levels (``labels``) and each series: the draws' (value, runs, bracket) from
    ``finder(name)`` over the levels, the combination's selection, and the validity of the runs the draws rest on."""
    level = np.asarray(level, float)
    draws = np.asarray(draws)
    flags = [()] * level.size if flags is None else [tuple(f) for f in flags]
    for label in dict.fromkeys(labels):
        sel = np.array([lab == label for lab in labels])
        for name, values in series.items():
            values = np.asarray(values, float)
            found = []
            for d in np.unique(draws[sel]):
                m = np.flatnonzero(sel & (draws == d))
                m = m[np.argsort(level[m], kind="stable")]
                found.append(finder(name)(level[m], values[m], m))
            used = sorted({int(r) for f in found for r in f[1]})
            validity = {
                "runs_used": len(used),
                "runs_outside_validity": sum(bool(flags[r]) for r in used),
                "validity_flags": list(dict.fromkeys(n for r in used for n in flags[r])),
            }
            yield label, name, found, sel, validity


def _quantile_columns(f: np.ndarray, prefix: str, unit: str) -> tuple[dict, dict]:
    """The median, p05 and p95 of draws ``f`` (:func:`_quantile`) as ``<prefix>_<q>_<unit>`` and their bounds as ``<prefix>_<q>_bound``."""
    quantiles = {name: _quantile(f, q) for name, q in QUANTILES}
    row = {f"{prefix}_{name}{_suffix(unit)}": quantiles[name][0] for name in ("median", "p05", "p95")}
    return row, {f"{prefix}_{name}_bound": quantiles[name][1] for name in ("median", "p05", "p95")}


def thresholds(
    level: np.ndarray,
    labels: list[str],
    draws: np.ndarray,
    indices: dict[str, np.ndarray],
    *,
    quantity: str = "velocity",
    unit: str = "m_s",
    flags: list | None = None,
) -> list[dict]:
    """Thresholds: per combination of the other levels (``labels``, one text per run) and per index (``indices``:
    output name → values, shape (n_runs,), 1 at the threshold: a damage index, or an output over a limit), the level
    ``x`` of the swept ``quantity`` [``unit``, SI] where the index first reaches 1, linear between levels,
    x* = x_{j-1} + (1 − I_{j-1})·(x_j − x_{j-1})/(I_j − I_{j-1}), over the draws (``draws``: each run's draw number):
    median and 5–95 % band, and how many draws reach 1 within the swept range. ``level``: each run's level [SI].
    Columns ``threshold_<quantity>_<q>_<unit>`` (``threshold_velocity_median_m_s``, ``threshold_energy_median_J``).

    A draw whose index is 1 or more already at the lowest level has its threshold below that level, one that
    never reaches 1 above the highest: both are censored (ordered as -inf and +inf among the draws), and a
    quantile that falls on one is NaN with ``threshold_<quantity>_<q>_bound`` saying :data:`BELOW` or :data:`ABOVE`
    (beside ``lowest_level_<unit>`` and ``highest_level_<unit>``); a bracketed quantile has an empty bound.

    Validity (``flags``: each run's validity flag names): the runs a row rests on are, per draw, the two runs
    bracketing its crossing (the lowest level's run for a draw below, the highest's for one above);
    ``runs_used`` counts them, ``runs_outside_validity`` those that raised a flag, ``validity_flags`` names the flags."""
    out = []
    level = np.asarray(level, float)
    for label, o, found, sel, validity in _per_row(level, labels, draws, indices, lambda name: _first_reaching, flags):
        f = np.array([v for v, *_ in found])
        values, bounds = _quantile_columns(f, f"threshold_{quantity}", unit)
        row = {"levels": label, "index": o.removeprefix("damage."), **values}
        row.update(
            {
                "draws": int(f.size),
                "draws_reaching_1": int(np.sum(f < np.inf)),
                "draws_below_lowest_level": int(np.sum(f == -np.inf)),
                f"lowest_level{_suffix(unit)}": float(level[sel].min()),
                f"highest_level{_suffix(unit)}": float(level[sel].max()),
            }
        )
        row.update(bounds)
        row.update(validity)
        out.append(row)
    return out


def onsets(
    level: np.ndarray,
    labels: list[str],
    draws: np.ndarray,
    sizes: dict[str, np.ndarray],
    *,
    quantity: str = "velocity",
    unit: str = "m_s",
    flags: list | None = None,
) -> list[dict]:
    """Onsets of sizes (``sizes``: output name → values, shape (n_runs,); zero below some level, positive above, as a
    dent's depth or a delaminated area): per combination of the other levels and per size, the level of the swept
    ``quantity`` where the size first becomes positive, from each draw's bracket x_{j-1} < x0 ≤ x_j (the last level
    where it is zero, the first where it is positive) and the straight line through the first two positive levels
    extrapolated to zero, x0 = x_j − s_j·(x_{j+1} − x_j)/(s_{j+1} − s_j), clipped into the bracket (x_j when there is
    no second positive level or the size does not grow between them). Exact for a size linear in the level above its
    onset. Over the draws: ``onset_<quantity>_<q>_<unit>`` (median, p05, p95), censored as in :func:`thresholds`
    (``onset_<quantity>_<q>_bound``), and the row's bracket: ``onset_<quantity>_last_zero_<unit>`` the last level where
    every draw is still zero and ``onset_<quantity>_first_positive_<unit>`` the first where every draw is positive
    (NaN when no such level was swept). Positive: above :data:`ONSET_FLOOR_SI` (in the size's SI unit) and
    :data:`ONSET_FLOOR` times its largest magnitude over all runs (a relaxed elastic plate's dent is round-off, not zero). Validity as in :func:`thresholds` (the runs of
    each draw's bracket and the one beyond it used by the extrapolation)."""
    out = []
    level = np.asarray(level, float)
    sizes = {o: np.asarray(v, float) for o, v in sizes.items()}
    floors = {}
    for o, values in sizes.items():
        finite = np.abs(values[np.isfinite(values)])
        floors[o] = _first_positive(max(ONSET_FLOOR_SI, ONSET_FLOOR * (float(finite.max()) if finite.size else 0.0)))
    prefix = f"onset_{quantity}"
    for label, o, found, sel, validity in _per_row(level, labels, draws, sizes, floors.__getitem__, flags):
        f = np.array([v for v, *_ in found])
        lows, highs = np.array([b[2] for b in found]), np.array([b[3] for b in found])
        quantiles, bounds = _quantile_columns(f, prefix, unit)
        row = {"levels": label, "index": o.removeprefix("damage."), **quantiles}
        row.update(
            {
                f"{prefix}_last_zero{_suffix(unit)}": float(lows.min()) if np.all(np.isfinite(lows)) else math.nan,
                f"{prefix}_first_positive{_suffix(unit)}": float(highs.max()) if np.all(np.isfinite(highs)) else math.nan,
                "draws": int(f.size),
                "draws_positive": int(np.sum(f < np.inf)),
                "draws_positive_at_lowest_level": int(np.sum(f == -np.inf)),
                f"lowest_level{_suffix(unit)}": float(level[sel].min()),
                f"highest_level{_suffix(unit)}": float(level[sel].max()),
            }
        )
        row.update(bounds)
        row.update(validity)
        out.append(row)
    return out
