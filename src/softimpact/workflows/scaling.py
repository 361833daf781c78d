"""Scaling laws of the pulse parameters against impact velocity, eqs (4)–(7), Table I.

Each law is a straight line y = α·x through the origin, as the paper fits it:

    α1: F0 against mV²/(2d)     α2: T against d/V
    α3: t_F0 against T          α4: I against 2mV

fitted by least squares, with a 95 % confidence interval from Student's t on
n − 1 degrees of freedom, R² (centred: 1 − SS_res/SS_tot about the mean of y)
and the residuals; the affine alternative y = a + b·x is fitted beside it (n − 2
degrees of freedom). Fits are made per projectile diameter and pooled.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import InputError
from ..gates import Gate, at_least, at_most
from ..models.empirical import REGRESSORS, ScalingLaw
from ..models.pulse_fit import TAIL_DELTA_AIC
from ..units import INCH

__all__ = [
    "TestPoint",
    "LineFit",
    "ScalingFit",
    "fit_line",
    "fit_scaling",
    "fit_groups",
    "fit_gates",
    "REGRESSORS",
    "MIN_VELOCITY_SPREAD",
    "MAX_RELATIVE_RESIDUAL",
    "TAIL_DELTA_AIC",
    "TailShapeTerm",
    "tail_shape_term",
    "TAIL_SE_FACTOR",
    "TAIL_BEYOND_FAMILIES",
    "TAIL_UNDER_PEAK",
    "UNDER_PEAK_FAMILY",
]

MIN_VELOCITY_SPREAD = 0.1  # (V_max − V_min)/mean V of a group: below, a law in V is not determined by its tests
MAX_RELATIVE_RESIDUAL = 0.3  # RMS residual / RMS response of a law: above, the straight line does not describe the tests


@dataclass(frozen=True)
class TestPoint:
    """One reduced test: V [m/s], m [kg], d [m], F0 [N], t_F0 [s], T [s], I [N·s]."""

    __test__ = False  # not a pytest test class, despite its name

    name: str
    velocity: float
    mass: float
    diameter: float
    peak_force: float
    time_of_peak: float
    duration: float
    impulse: float


@dataclass(frozen=True)
class LineFit:
    """y = slope·x (+ intercept for the affine fit), with 95 % intervals."""

    slope: float
    slope_ci: tuple[float, float]
    intercept: float
    intercept_ci: tuple[float, float]
    r2: float
    residuals: np.ndarray
    through_origin: bool


def _t95(dof: int) -> float:
    from scipy.stats import t

    return float(t.ppf(0.975, dof)) if dof > 0 else math.inf


def fit_line(x, y, through_origin: bool = True) -> LineFit:
    """Least-squares line, through the origin or affine, with 95 % intervals."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    n = x.size
    need = 1 if through_origin else 2
    if n < need:
        raise InputError(f"scaling fit: need at least {need} tests, got {n}")
    ss_tot = float(np.sum((y - y.mean()) ** 2))
    if through_origin:
        sxx = float(x @ x)
        slope = float(x @ y) / sxx
        res = y - slope * x
        dof = n - 1
        s2 = float(res @ res) / dof if dof else math.nan
        half = _t95(dof) * math.sqrt(s2 / sxx) if dof else math.inf
        icpt, icpt_ci = 0.0, (0.0, 0.0)
    elif np.ptp(x) <= 1e-12 * np.max(np.abs(x)):
        # Every test at one regressor value (repeat shots at one velocity): the
        # intercept and the slope cannot be told apart.
        nan = math.nan
        return LineFit(nan, (nan, nan), nan, (nan, nan), nan, y - y.mean(), through_origin)
    else:
        A = np.column_stack((np.ones(n), x))
        coef, *_ = np.linalg.lstsq(A, y, rcond=None)
        icpt, slope = float(coef[0]), float(coef[1])
        res = y - A @ coef
        dof = n - 2
        s2 = float(res @ res) / dof if dof else math.nan
        cov = s2 * np.linalg.inv(A.T @ A) if dof else np.full((2, 2), math.inf)
        half = _t95(dof) * math.sqrt(max(cov[1, 1], 0.0))
        ih = _t95(dof) * math.sqrt(max(cov[0, 0], 0.0))
        icpt_ci = (icpt - ih, icpt + ih)
    r2 = 1.0 - float(res @ res) / ss_tot if ss_tot > 0 else math.nan
    return LineFit(slope, (slope - half, slope + half), icpt, icpt_ci, r2, res, through_origin)


@dataclass(frozen=True)
class TailShapeTerm:
    """What the tail's shape leaves undecided in α1–α4 of a group of tests.

    Each tail family (``aic``: family → AIC summed over the group's tests) gives its own main
    pulses and so its own α's (``alphas``: family → {α name → value}); ``errors`` (family → {α name
    → half-width}) is how far that family's α's move when each test's F0, t_F0, T move by 1.96 of
    their standard errors in that family's fit (its tail's parameters free), the moves added
    linearly over the three and over the tests (one tail shape for the series: the errors of the
    tests go together). ``accepted``: the families within TAIL_DELTA_AIC of the best (``best``),
    for information only: the true tail is in none of the families, and a ΔAIC between wrong
    tails does not reject the main pulse one of them implies. The ``half_widths`` (α name →
    half-width) are therefore the largest, over every family, of its α's distance from the
    reported one plus its error, plus TAIL_BEYOND_FAMILIES of the range of the families' α's (the
    true shape lies outside the families and may move the α's past the farthest of them), added to
    each side of the 95 % interval (a systematic range, not a random error: added linearly, not in
    quadrature). The family UNDER_PEAK_FAMILY (a tail ramping in from first contact, so part of the
    recorded peak) is left out of that largest distance and that range: the records reject it, yet a
    tail they cannot tell apart may already lie under the peak, and a tail only adds force, so the
    reported F0 can only be too high by it. ``lower_extra`` (α name → extension of the interval's lower
    bound only) is TAIL_UNDER_PEAK of how far below the reported α1 that family's α1 lies.
    ``unbounded``: the α's whose tail-shape half-width (plus half of ``lower_extra``) exceeds their
    statistical (Student) half-width: the records do not bound them better than the tail's unknown shape does."""

    aic: dict
    best: str
    accepted: tuple[str, ...]
    alphas: dict
    half_widths: dict
    errors: dict = field(default_factory=dict)
    unbounded: tuple[str, ...] = ()
    lower_extra: dict = field(default_factory=dict)

    def interval(self, name: str, line: LineFit) -> tuple[float, float]:
        """The 95 % interval of α ``name`` widened by the tail-shape term (its lower bound by ``lower_extra`` too)."""
        hw = self.half_widths.get(name, 0.0)
        return (line.slope_ci[0] - hw - self.lower_extra.get(name, 0.0), line.slope_ci[1] + hw)


@dataclass(frozen=True)
class ScalingFit:
    """α1–α4 of one group of tests, through the origin and affine; ``tail_shape``: the tail-shape
    ambiguity of its α's (:class:`TailShapeTerm`), when the records were fitted with several tails."""

    label: str
    points: tuple[TestPoint, ...]
    origin: dict  # name → LineFit
    affine: dict  # name → LineFit (absent where fewer than 3 tests)
    tail_shape: TailShapeTerm | None = None

    def law(self) -> ScalingLaw:
        """The fitted constants as an empirical model (eqs 4–7)."""
        v, d = [p.velocity for p in self.points], [p.diameter for p in self.points]
        a = {k: f.slope for k, f in self.origin.items()}
        return ScalingLaw(a["alpha1"], a["alpha2"], a["alpha3"], a["alpha4"], self.label, "fitted", (min(v), max(v)), (min(d), max(d)))


def fit_scaling(points, label: str = "pooled") -> ScalingFit:
    """Fit eqs (4)–(7) to a group of tests."""
    points = tuple(points)
    origin, affine = {}, {}
    for name, (_, fx, fy) in REGRESSORS.items():
        x = np.array([fx(p) for p in points])
        y = np.array([fy(p) for p in points])
        origin[name] = fit_line(x, y, True)
        if len(points) >= 3:
            affine[name] = fit_line(x, y, False)
    return ScalingFit(label, points, origin, affine)


def diameter_label(d: float) -> str:
    """'0.5 in' style label of a diameter [m] (the paper's groups)."""
    return f"{d / INCH:.4g} in"


def fit_groups(points) -> dict[str, ScalingFit]:
    """One fit per projectile diameter, and 'pooled' over all (when there are several diameters)."""
    points = tuple(points)
    groups: dict[float, list] = {}
    for p in points:
        groups.setdefault(round(p.diameter, 7), []).append(p)
    fits = {diameter_label(d): fit_scaling(g, diameter_label(d)) for d, g in sorted(groups.items())}
    if len(groups) > 1:
        fits["pooled"] = fit_scaling(points, "pooled")
    return fits


TAIL_SE_FACTOR = 1.96  # the tail fits' standard errors taken at 95 % (two-sided normal)
# A true tail in none of the families moves the main pulse past the farthest family by a part of the families' own
# spread: half of it is added (chosen on 40 hidden series of four shapes outside the families, seed 11, then checked
# on 60 others, seed 3208: benchmarks/tail_coverage.py, BENCHMARKS.md "Tail-shape coverage"; without it α2 held
# the truth in 75 % of the series, every miss on a logistic step under the pulse).
TAIL_BEYOND_FAMILIES = 0.5
# A tail ramping in from first contact (the reduction's family "early-ramp") puts part of itself under the peak; the
# records reject that family's shape, yet on a logistic step under the pulse (rising from 0.3-0.6 T) the reported α1
# lay above the truth and outside the other families' widening (3 of 40 hidden series of seed 11, 8 of 60 of seed
# 3208). A tail only adds force, so α1's lower bound alone is moved, by this part of the distance of that family's α1
# below the reported one: 0.17 was the least that held the truth in all 40 series of seed 11, half is taken (as for
# TAIL_BEYOND_FAMILIES), then checked on the 60 series of seed 3208 (benchmarks/tail_coverage.py, BENCHMARKS.md).
UNDER_PEAK_FAMILY = "early-ramp"
TAIL_UNDER_PEAK = 0.5
_TAIL_SE = (("peak_force", 0), ("time_of_peak", 1), ("duration", 2))  # TestPoint field, index in a (se_F0, se_tF0, se_T) row


def _alphas(points, label):
    return {n: line.slope for n, line in fit_scaling(points, label).origin.items()}


def _family_error(points, errors, label, alphas) -> dict:
    """How far the α's of ``points`` (α values ``alphas``) move when every test's F0, t_F0, T move by
    TAIL_SE_FACTOR of its standard errors ``errors`` (one (se_F0, se_tF0, se_T) row per point), the three
    moves added linearly (:class:`TailShapeTerm`); a non-finite error counts as none (the fit gave none)."""
    out = dict.fromkeys(alphas, 0.0)
    for key, k in _TAIL_SE:
        shifted = [replace(p, **{key: getattr(p, key) + TAIL_SE_FACTOR * (e[k] if math.isfinite(e[k]) else 0.0)}) for p, e in zip(points, errors)]
        for n, v in _alphas(shifted, label).items():
            out[n] += abs(v - alphas[n])
    return out


def tail_shape_term(fit: ScalingFit, family_points: dict, aic: dict, family_errors: dict | None = None) -> TailShapeTerm:
    """The tail-shape term of ``fit``'s α's (:class:`TailShapeTerm`): ``family_points`` family →
    the group's TestPoints with that family's F0, t_F0, T (I is the whole record's in all);
    ``aic`` family → total AIC; ``family_errors`` family → one (se_F0, se_tF0, se_T) per point (none:
    no error term). The α's of each family are fitted as ``fit``'s (through the origin)."""
    best = min(aic, key=aic.get)
    accepted = tuple(f for f in aic if aic[f] - aic[best] < TAIL_DELTA_AIC)
    alphas = {f: _alphas(pts, fit.label) for f, pts in family_points.items()}
    errors = {f: _family_error(family_points[f], e, fit.label, alphas[f]) for f, e in (family_errors or {}).items()}
    spread = [f for f in family_points if f != UNDER_PEAK_FAMILY] or list(family_points)
    half = {}
    for n in fit.origin:
        values = [alphas[f][n] for f in spread]
        farthest = max(abs(alphas[f][n] - fit.origin[n].slope) + errors.get(f, {}).get(n, 0.0) for f in spread)
        half[n] = farthest + TAIL_BEYOND_FAMILIES * (max(values) - min(values))
    lower = {}
    if UNDER_PEAK_FAMILY in alphas and "alpha1" in fit.origin:
        lower["alpha1"] = TAIL_UNDER_PEAK * max(0.0, fit.origin["alpha1"].slope - alphas[UNDER_PEAK_FAMILY]["alpha1"])
    unbounded = tuple(n for n, h in half.items() if h + 0.5 * lower.get(n, 0.0) > 0.5 * (fit.origin[n].slope_ci[1] - fit.origin[n].slope_ci[0]))
    return TailShapeTerm(dict(aic), best, accepted, alphas, half, errors, unbounded, lower)


def fit_gates(fits: dict[str, ScalingFit]) -> tuple[Gate, ...]:
    """Quality gates of the fits of :func:`fit_groups` (:mod:`softimpact.gates`).

    Per group of two tests or more: the tests' velocities must spread by
    MIN_VELOCITY_SPREAD of their mean (repeat shots at one velocity, or copies
    of one record, leave a law in V undetermined and its interval falsely
    narrow), and each law's RMS residual must stay within MAX_RELATIVE_RESIDUAL
    of the RMS response. Every constant must be finite and positive. A group of
    one test has no gate on spread or residual (it has no intervals either: the
    app warns).
    """
    gates = []
    for label, g in fits.items():
        v = np.array([p.velocity for p in g.points])
        if len(v) >= 2:
            spread = float(np.ptp(v) / np.mean(v))
            gates.append(
                at_least(
                    f"velocity-spread[{label}]",
                    spread,
                    MIN_VELOCITY_SPREAD,
                    f"{label}: the {len(v)} tests span {{value:.1%}} of their mean velocity (need {{limit:.0%}}): the law's dependence on velocity is not determined",
                )
            )
        for name, (_, _, fy) in REGRESSORS.items():
            f = g.origin[name]
            gates.append(
                at_least(
                    f"{name}-finite[{label}]",
                    1.0 if math.isfinite(f.slope) and f.slope > 0 else 0.0,
                    1.0,
                    f"{label}: {name} = {f.slope!r} is not a positive number",
                )
            )
            if len(v) >= 2:
                y = np.array([fy(p) for p in g.points])
                rel = float(np.sqrt(np.mean(f.residuals**2)) / np.sqrt(np.mean(y**2))) if np.any(y) else math.nan
                gates.append(
                    at_most(
                        f"{name}-residual[{label}]",
                        rel,
                        MAX_RELATIVE_RESIDUAL,
                        f"{label}: the {name} line misses its tests by {{value:.0%}} RMS (limit {{limit:.0%}})",
                    )
                )
    return tuple(gates)
