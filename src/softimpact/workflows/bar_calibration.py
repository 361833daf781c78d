"""Calibration of a lab's own instrumented bar from its records: wave speed, dispersion, gauge position and
gauge sensitivity, each with its 95 % interval and its fit's residual, and a gate when the records disagree.

Records of a free–free bar of length L, diameter d = 2a and density ρ, one gauge at x from the struck end,
each shot a short impact on the struck end (a steel ball), the strain read through the bridge with its
nominal gauge factor GF_nom. From each record:

1. **Wave speed, dispersion, gauge position** — the echoes: every later arrival at the gauge is the incident
   wave moved further along the bar, by 2kL (back from the struck end) or 2(L − x) + 2kL (from the far
   end), through the first longitudinal mode (:mod:`softimpact.workflows._bar_echoes`, its eq. (E)). The fit
   gives the bar wave speed c0 (the long-wavelength limit, c0² = E/ρ), Poisson's ratio ν from the dispersion
   of the wave's front (or the effective radius, ν given), and x.
2. **Gauge sensitivity** — a known impact: a ball of mass m striking at V and leaving at V_r (measured, or
   only bounded: 0 ≤ V_r ≤ V_r,max, taken as uniform) gives the bar the momentum m(V + V_r), which the
   incident wave carries:

       m(V + V_r) = ∫F dt = ρ c0² A ∫(−ε) dt = ρ c0² A · S · ∫(−ε_rec) dt,                        (M)

   over the incident wave's window (before the first echo), dispersion leaving the integral unchanged (the
   zero-frequency harmonic is not dispersed). S = ε/ε_rec is the record's sensitivity; every bridge's strain
   is ∝ 1/GF (:mod:`softimpact.models.bridge`), so the true gauge factor is GF = GF_nom / S.

Shots are pooled by their inverse variances; their spread is tested against their intervals (χ², the
``records-agree[...]`` gates: p < :data:`AGREEMENT_P` fails, the records disagree) and a pooled interval is
widened by the Birge ratio √(χ²/(n − 1)) when it exceeds 1. What every shot shares (the bar's length for c0
and x, its radius for ν, its density and diameter and the ball's mass for S) is added after pooling: no
number of shots averages it away. Uncertainties given with the inputs are standard uncertainties (one σ);
the intervals reported are 95 % (normal).

Units SI; records 1-D, time on the axis, strain tension positive (the incident wave compressive, negative).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from ..gates import Gate, at_least, at_most
from ..models.noise import robust_sigma
from ..models.sampling import series_problem
from ._bar_echoes import Z95, EchoFit, fit_echoes

__all__ = [
    "BarGeometry",
    "KnownImpact",
    "Shot",
    "Constant",
    "ShotCalibration",
    "BarCalibration",
    "calibrate_bar",
    "pool",
    "AGREEMENT_P",
    "ECHO_CHI2_LIMIT",
]

AGREEMENT_P = 0.01  # the shots disagree when their χ² about the pooled value is this improbable
ECHO_CHI2_LIMIT = 4.0  # the echo fit's residual power over the noise's: above, the records are not echoes of one wave in a uniform bar
NOMINAL_SPEED_SLACK = 0.05  # a wave speed this far from the nominal material's is flagged (another material, a wrong length)
END_CLEARANCE = 0.1  # of the length: a gauge nearer an end has its two ends' echoes arriving together (refused)
LOSS_FLAG = 0.8  # an echo amplitude below this: the ends are not free, or the bar damps (flagged)
DETECTION_SIGMAS = 8.0  # the incident wave's arrival: the record leaves its noise by this many σ ...
DETECTION_FRACTION = 0.05  # ... and by this fraction of its largest excursion
PRETRIGGER_MIN = 20  # samples before the arrival needed for a baseline and a noise
BASELINE_MARGIN = 20e-6  # s: the baseline ends this long before the arrival, clear of a band-limited record's ringing before its front
# the incident wave's impulse is summed from this fraction of the gap to the first echo before its arrival to this
# fraction after it: clear of the band-limited ringing about each front (a record's filters; the dispersion model's band),
# which moved the sum by 0.25 % (2 us before the front) and 1 % (6 us before the echo) on synthetic records
IMPULSE_WINDOW = (0.05, 0.9)


@dataclass(frozen=True)
class BarGeometry:
    """What is known of the bar before its calibration (SI), with standard uncertainties (σ, 0: exact).

    ``wave_speed``: a first guess [m/s] (the nominal material's; the fit searches ±30 %), also what the
    result is compared with; ``poisson_ratio``: the nominal ν (the fit's start; the given value when the
    unknown is the radius); ``gauge_position``: the nominal x [m] from the struck end; ``unknown``: what the
    dispersion gives, ``"poisson_ratio"`` (radius measured), ``"radius"`` (ν given) or ``"none"``."""

    length: float
    diameter: float
    density: float
    gauge_position: float
    poisson_ratio: float
    wave_speed: float
    length_sd: float = 0.0
    diameter_sd: float = 0.0
    density_sd: float = 0.0
    unknown: str = "poisson_ratio"

    def __post_init__(self):
        for name in ("length", "diameter", "density", "wave_speed"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise InputError(f"{name} must be positive, got {v!r}", name)
        for name in ("length_sd", "diameter_sd", "density_sd"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v >= 0):
                raise InputError(f"{name} must be zero or positive, got {v!r}", name)
        if not 0.0 < self.gauge_position < self.length:
            raise InputError(f"gauge_position {self.gauge_position!r} m must lie inside the bar (0 to {self.length!r} m)", "gauge_position")
        if not 0.0 <= self.poisson_ratio < 0.5:
            raise InputError(f"poisson_ratio must lie in [0, 0.5), got {self.poisson_ratio!r}", "poisson_ratio")
        if self.unknown not in ("poisson_ratio", "radius", "none"):
            raise InputError(f"unknown must be poisson_ratio, radius or none, got {self.unknown!r}", "unknown")

    @property
    def area(self) -> float:
        return math.pi * self.diameter**2 / 4.0


@dataclass(frozen=True)
class KnownImpact:
    """A ball of ``mass`` [kg] striking the struck end at ``velocity`` [m/s] and leaving at ``rebound`` [m/s]
    (its speed away from the bar, σ ``rebound_sd``), or with only a bound ``rebound_max`` on it (uniform on
    [0, rebound_max]); standard uncertainties ``mass_sd``, ``velocity_sd``. Neither: V_r ∈ [0, V] (a ball
    cannot leave faster than it came)."""

    mass: float
    velocity: float
    mass_sd: float = 0.0
    velocity_sd: float = 0.0
    rebound: float | None = None
    rebound_sd: float = 0.0
    rebound_max: float | None = None

    def __post_init__(self):
        for name in ("mass", "velocity"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise InputError(f"{name} must be positive, got {v!r}", name)
        if self.rebound is not None and self.rebound_max is not None:
            raise InputError("give the rebound measured or bounded, not both", "rebound_max")
        if self.rebound is not None and not (0.0 <= self.rebound <= self.velocity):
            raise InputError(f"rebound {self.rebound!r} m/s must lie in [0, the impact velocity {self.velocity!r} m/s]", "rebound")
        if self.rebound_max is not None and not (0.0 < self.rebound_max <= self.velocity):
            raise InputError(f"rebound_max {self.rebound_max!r} m/s must lie in (0, the impact velocity {self.velocity!r} m/s]", "rebound_max")

    def momentum(self) -> tuple[float, float, float]:
        """(m(V + V_r) [N·s], the standard uncertainty of V + V_r [m/s], that of m [kg])."""
        if self.rebound is not None:
            vr, vr_sd = self.rebound, self.rebound_sd
        else:
            top = self.velocity if self.rebound_max is None else self.rebound_max
            vr, vr_sd = 0.5 * top, top / math.sqrt(12.0)
        return self.mass * (self.velocity + vr), math.hypot(self.velocity_sd, vr_sd), self.mass_sd


@dataclass(frozen=True)
class Shot:
    """One record: ``time`` [s] (any clock), ``strain`` as recorded (through the bridge with its nominal
    gauge factor), and the ``impact`` that made it when it is known (None: its echoes only)."""

    name: str
    time: np.ndarray
    strain: np.ndarray
    impact: KnownImpact | None = None


@dataclass(frozen=True)
class Constant:
    """A calibrated constant: ``value`` and the half-width of its 95 % interval (SI), its fit's ``residual``
    (what ``residual_meaning`` says), and each shot's (value, half-width) it was pooled from."""

    value: float
    half_width: float
    residual: float
    residual_meaning: str
    shots: tuple[tuple[float, float], ...] = ()


@dataclass(frozen=True)
class ShotCalibration:
    """One record's calibration: its echo fit (None when it could not be fitted, ``error`` says why), the
    incident arrival on the record's clock, its noise, and its sensitivity S = ε/ε_rec with its standard
    uncertainty from this shot alone (NaN without a known impact)."""

    name: str
    echo: EchoFit | None
    arrival_time: float
    noise: float
    impulse: float  # ∫(−ε_rec) dt over the incident window [s]
    sensitivity: float
    sensitivity_sd: float  # this shot's own: its noise, its velocity and rebound
    flags: tuple[str, ...] = ()
    error: str = ""


@dataclass(frozen=True)
class BarCalibration:
    """The calibrated bar: ``wave_speed`` c0 [m/s], ``youngs_modulus`` ρc0² [Pa], ``poisson_ratio`` or ``radius``
    [m] (what the dispersion gave; None when not fitted), ``gauge_position`` [m] (None when the records hold no
    far-end echo), ``sensitivity`` S (None without a known impact), the ``shots``, the quality ``gates`` and
    ``flags`` (sentences)."""

    geometry: BarGeometry
    wave_speed: Constant
    youngs_modulus: Constant
    poisson_ratio: Constant | None
    radius: Constant | None
    gauge_position: Constant | None
    sensitivity: Constant | None
    shots: tuple[ShotCalibration, ...]
    gates: tuple[Gate, ...] = ()
    flags: tuple[str, ...] = field(default_factory=tuple)


def _arrival(t, y):
    """(arrival time, baseline, noise, sign, samples in the baseline) of the first wave: the first sample leaving the
    pre-trigger noise by DETECTION_SIGMAS·σ (and DETECTION_FRACTION of the largest excursion), followed back to where it
    left 2σ; the baseline and noise from the samples BASELINE_MARGIN before it (a median, a robust σ)."""
    head = max(PRETRIGGER_MIN, y.size // 50)
    base0, sig0 = float(np.median(y[:head])), float(robust_sigma(y[:head]))
    dev = y - base0
    level = max(DETECTION_SIGMAS * sig0, DETECTION_FRACTION * float(np.max(np.abs(dev))))
    above = np.flatnonzero(np.abs(dev) > level)
    if above.size == 0:
        raise InputError("no wave: the record never leaves its noise")
    i = int(above[0])
    sign = 1 if dev[i] > 0 else -1
    j = i
    while j > 0 and sign * dev[j - 1] > 2 * sig0:
        j -= 1
    pre = t < t[j] - BASELINE_MARGIN
    if pre.sum() < PRETRIGGER_MIN:
        raise InputError(f"only {int(pre.sum())} samples before the wave arrives: record more pre-trigger (at least {PRETRIGGER_MIN})")
    return float(t[j]), float(np.median(y[pre])), float(robust_sigma(y[pre])), sign, int(pre.sum())


def _uniform(name, t, y):
    t = np.asarray(t, float)
    y = np.asarray(y, float)
    problem = series_problem(t, y, min_samples=64, what="strain")
    if problem is not None:
        raise InputError(f"{name}: {problem}")
    dt = float(np.median(np.diff(t)))
    if np.max(np.abs(np.diff(t) - dt)) > 0.01 * dt:
        grid = np.arange(t[0], t[-1] + 0.5 * dt, dt)
        y, t = np.interp(grid, t, y), grid
    return t, y


def _coarse_speed(t, y, arrival, bar: BarGeometry) -> float:
    """c0 from the cross-correlation of the incident wave with the first echo off the struck end (at 2L/c0),
    searched within ±30 % of the nominal speed: a start the fit can refine."""
    gap = 2.0 * min(bar.gauge_position, bar.length - bar.gauge_position) / bar.wave_speed
    w = (t >= arrival - 0.25 * gap) & (t < arrival + 0.75 * gap)
    template = y[w]
    dt = float(t[1] - t[0])
    best, lag_best = -np.inf, None
    lo, hi = 2 * bar.length / (1.3 * bar.wave_speed), 2 * bar.length / (0.7 * bar.wave_speed)
    start = int(np.searchsorted(t, arrival - 0.25 * gap))
    for lag in range(int(lo / dt), int(hi / dt) + 1):
        seg = y[start + lag : start + lag + template.size]
        if seg.size < template.size:
            break
        v = float(seg @ template)
        if v > best:
            best, lag_best = v, lag
    if lag_best is None:
        return bar.wave_speed
    return 2 * bar.length / (lag_best * dt)


def _shot(shot: Shot, bar: BarGeometry) -> ShotCalibration:
    """One record's echoes and, with its known impact, its sensitivity (eq. M); InputError when it cannot be fitted."""
    t, y = _uniform(shot.name, shot.time, shot.strain)
    arrival, base, noise, sign, n_pre = _arrival(t, y)
    flags = []
    y = y - base
    if sign > 0:
        flags.append(f"{shot.name}: the first wave reads tensile: the record's sign is inverted (a bridge polarity?); read as compressive")
        y = -y
    if noise == 0:
        noise = 1e-6 * float(np.max(np.abs(y)))  # a noise-free (synthetic) record: the fit needs a scale
    c1 = _coarse_speed(t, y, arrival, bar)
    x = bar.gauge_position
    if min(x, bar.length - x) < END_CLEARANCE * bar.length:
        raise InputError(
            f"{shot.name}: the gauge at {x:.4g} m is within a tenth of the bar's length of an end: its echoes from the two ends "
            "arrive together and cannot be timed apart (calibrate with a gauge nearer the middle)"
        )
    echo = fit_echoes(
        t,
        y,
        arrival_time=arrival,
        noise=noise,
        length=bar.length,
        radius=bar.diameter / 2,
        poisson_ratio=bar.poisson_ratio,
        wave_speed=c1,
        gauge_position=x,
        unknown=bar.unknown,
        fit_position=True,
    )
    c0 = echo.value("wave_speed")
    if echo.reduced_chi2 > ECHO_CHI2_LIMIT:
        flags.append(f"{shot.name}: the echoes depart from the incident wave moved along a uniform bar by {math.sqrt(echo.reduced_chi2):.2g} times the noise")
    amps = [echo.value(n) for n in echo.names if n.startswith("amplitude_")]
    if min(amps) < LOSS_FLAG:
        flags.append(f"{shot.name}: an echo returns with {min(amps):.0%} of the incident wave: an end is not free, or the bar damps")
    impulse, impulse_sd = _impulse(t, y, arrival, 2.0 * (bar.length - echo.value("gauge_position")) / c0, noise, n_pre)
    S, S_sd = math.nan, math.nan
    if shot.impact is not None:
        p, pv_sd, _ = shot.impact.momentum()
        S = p / (bar.density * c0**2 * bar.area * impulse)
        v_sum = p / shot.impact.mass
        S_sd = S * math.hypot(impulse_sd / impulse, pv_sd / v_sum)
    return ShotCalibration(shot.name, echo, arrival, noise, impulse, S, S_sd, tuple(flags))


def _impulse(t, y, arrival, gap, noise, n_pre):
    """(∫(−y) dt over the incident window, from IMPULSE_WINDOW[0]·gap before the arrival to IMPULSE_WINDOW[1]·gap after
    it (``gap`` [s] to the first echo), its standard uncertainty from the white noise and from the baseline (the median
    of ``n_pre`` samples: σ·√(π/2)/√n) over the window)."""
    w = (t >= arrival - IMPULSE_WINDOW[0] * gap) & (t < arrival + IMPULSE_WINDOW[1] * gap)
    dt = float(t[1] - t[0])
    value = -float(np.sum(y[w]) * dt)
    span = float(np.sum(w)) * dt
    sd = math.hypot(noise * dt * math.sqrt(np.sum(w)), noise * math.sqrt(math.pi / 2 / max(n_pre, 1)) * span)
    if not value > 0:
        raise InputError("the incident wave carries no compressive impulse: not a record of an impact on the struck end")
    return value, sd


def pool(values, sds) -> tuple[float, float, float]:
    """(inverse-variance weighted mean, its standard uncertainty widened by the Birge ratio when above 1, the
    χ² of the values about it); a single value: (it, its sd, NaN)."""
    v = np.asarray(values, float)
    s = np.asarray(sds, float)
    if v.size == 1:
        return float(v[0]), float(s[0]), math.nan
    w = 1.0 / np.maximum(s, 1e-300) ** 2
    mean = float(np.sum(w * v) / np.sum(w))
    sd = float(1.0 / math.sqrt(np.sum(w)))
    chi2 = float(np.sum(w * (v - mean) ** 2))
    return mean, sd * max(1.0, math.sqrt(chi2 / (v.size - 1))), chi2


def _agreement(name: str, chi2: float, n: int, what: str) -> Gate | None:
    """The gate ``records-agree[name]``: p of the shots' χ² about their pooled value ≥ AGREEMENT_P (None for one shot)."""
    if n < 2 or not math.isfinite(chi2):
        return None
    from scipy.special import chdtrc  # the χ² survival function (scipy.stats costs 0.4 s to import)

    p = float(chdtrc(n - 1, chi2))
    return at_least(
        f"records-agree[{name}]",
        p,
        AGREEMENT_P,
        f"the records disagree on the {what}: chi2 = {chi2:.3g} over {n} shots (p = {{value:.2g}}, limit {{limit:g}}): a shot is not like the others (a loose gauge, another bar, a second hit)",
    )


def _constant(fits, name: str, shared: float, meaning: str, residual: float, gates: list, what: str) -> Constant:
    """The pooled constant ``name`` of the echo fits, the relative standard uncertainty ``shared`` by every shot added after pooling."""
    vals = [f.value(name) for f in fits]
    sds = [f.half_width(name) / Z95 for f in fits]
    mean, sd, chi2 = pool(vals, sds)
    gate = _agreement(name, chi2, len(vals), what)
    if gate is not None:
        gates.append(gate)
    return Constant(mean, Z95 * math.hypot(sd, shared * mean), residual, meaning, tuple((v, Z95 * s) for v, s in zip(vals, sds)))


def calibrate_bar(shots, bar: BarGeometry) -> BarCalibration:
    """Calibrate ``bar`` from its ``shots`` (module docstring). A shot whose record cannot be fitted is kept with its
    error; InputError when none can."""
    results = []
    for s in shots:
        try:
            results.append(_shot(s, bar))
        except InputError as exc:
            results.append(ShotCalibration(s.name, None, math.nan, math.nan, math.nan, math.nan, math.nan, (), str(exc)))
    good = [r for r in results if r.echo is not None]
    if not good:
        raise InputError(f"no record could be fitted (first: {results[0].name}: {results[0].error})")
    fits = [r.echo for r in good]
    gates: list[Gate] = []
    flags = [f for r in results for f in r.flags] + [f"{r.name}: not fitted ({r.error})" for r in results if r.echo is None]
    worst = max(f.reduced_chi2 for f in fits)
    for r in good:
        gates.append(
            at_most(
                f"echo-fit[{r.name}]",
                r.echo.reduced_chi2,
                ECHO_CHI2_LIMIT,
                f"{r.name}: the echoes depart from the incident wave moved along a uniform bar: residual power {{value:.3g}} times the noise's (limit {{limit:g}})",
            )
        )
    rms = max(f.residual_rms for f in fits)
    meaning = f"rms of the echo fits' residuals, strain (largest over the shots; residual power up to {worst:.3g} times the noise's)"
    c = _constant(fits, "wave_speed", bar.length_sd / bar.length, meaning, rms, gates, "wave speed")  # c0 ∝ L: only p/c0 is seen
    if abs(c.value / bar.wave_speed - 1) > NOMINAL_SPEED_SLACK:
        flags.append(
            f"the wave speed {c.value:.5g} m/s is {c.value / bar.wave_speed - 1:+.1%} from the nominal material's {bar.wave_speed:.5g} m/s: another material, or a wrong length?"
        )
    rel_c = c.half_width / c.value
    rel_rho = Z95 * bar.density_sd / bar.density
    E = Constant(bar.density * c.value**2, bar.density * c.value**2 * math.hypot(2 * rel_c, rel_rho), rms, meaning)
    nu = radius = None
    a = bar.diameter / 2
    if bar.unknown == "poisson_ratio":
        nu = _constant(fits, "poisson_ratio", bar.diameter_sd / bar.diameter, meaning, rms, gates, "Poisson's ratio")  # ν·a is what is seen
    elif bar.unknown == "radius":
        radius = _constant(fits, "radius", 0.0, meaning, rms, gates, "effective radius")
    x = None
    if all("gauge_position" in f.names for f in fits):
        x = _constant(fits, "gauge_position", bar.length_sd / bar.length, meaning, rms, gates, "gauge position")  # δx = x·δL/L
    sensitivity = _sensitivity(good, bar, c, a, gates, shots)
    return BarCalibration(bar, c, E, nu, radius, x, sensitivity, tuple(results), tuple(gates), tuple(flags))


def _sensitivity(good, bar: BarGeometry, c: Constant, a: float, gates: list, shots) -> Constant | None:
    """S pooled over the shots with a known impact; what they share (c0, ρ, d, the ball's mass) added after pooling."""
    known = [r for r in good if math.isfinite(r.sensitivity)]
    if not known:
        return None
    mean, sd, chi2 = pool([r.sensitivity for r in known], [r.sensitivity_sd for r in known])
    gate = _agreement("sensitivity", chi2, len(known), "gauge sensitivity")
    if gate is not None:
        gates.append(gate)
    impact = next(s.impact for s in shots if s.impact is not None)
    shared = math.hypot(2 * c.half_width / Z95 / c.value, bar.density_sd / bar.density, 2 * bar.diameter_sd / bar.diameter, impact.mass_sd / impact.mass)
    residual = math.sqrt(chi2 / (len(known) - 1)) if len(known) > 1 else math.nan
    return Constant(
        mean,
        Z95 * math.hypot(sd, mean * shared),
        residual,
        "the shots' spread about the pooled sensitivity over their own uncertainties (Birge ratio; NaN for one shot)",
        tuple((r.sensitivity, Z95 * r.sensitivity_sd) for r in known),
    )
