"""Two-bar (split Hopkinson, Kolsky) analysis: the incident, reflected and transmitted waves to the specimen's
stress, strain rate and strain at rate, the dynamic equilibrium check, and a rate-dependent strength fitted
across tests.

The set-up: a specimen of length L_s and area A_s between an incident bar (E_I, A_I, c_I, gauge at x_I from the
specimen's face) and a transmitted bar (E_T, A_T, c_T, gauge at x_T from it). The incident bar's gauge reads
the incident wave ε_I, then, 2x_I/c_I later, the wave the specimen reflects, ε_R; the transmitted bar's gauge
reads the wave it passes on, ε_T. Each wave is moved to the specimen's face: by its bulk delay x/c (and, with
``dispersion``, the first-mode dispersion of that move and the surface-to-force factor,
:func:`softimpact.models.dispersion.disperse`), on one clock τ whose zero is the incident wave's arrival at the
front face. Then (one-dimensional waves; strains tension +, the results compression +):

    front force  F1 = −E_I A_I (ε_I + ε_R),         back force  F2 = −E_T A_T ε_T,
    face velocities  v1 = c_I (ε_R − ε_I),          v2 = −c_T ε_T,
    stress   one-wave σ₁ = F2/A_s (back face),  two-wave σ₂ = F1/A_s (front face),  three-wave σ₃ = (F1 + F2)/(2A_s),
    strain rate  three-wave ε̇₃ = (v1 − v2)/L_s,     one-wave ε̇₁ = 2 c_I ε_R / L_s,
    strain   ε = ∫ ε̇ dτ (engineering: L_s and A_s the specimen's initial ones).

The one-wave strain rate assumes equilibrium (F1 = F2) between identical bars (ε_T = ε_I + ε_R): it is the
classic Kolsky reading; the three-wave one assumes nothing of the specimen. These are the formulas of the
classic analysis (Gray 2000, "Classic split-Hopkinson pressure bar testing", ASM Handbook vol. 8; Chen & Song
2011, *Split Hopkinson (Kolsky) Bar*, ch. 1), as transcribed in public code that cites both
(Wino1301/DynaMat-Platform, dynamat/mechanical/shpb/core/stress_strain.py: stress from ε_T, from ε_I + ε_R,
strain rate 2cε_R/L and c(ε_I − ε_R − ε_T)/L) and in Edgar-Mendonca/SHPB-Analysis (README: v1 = c(ε_I − ε_R),
v2 = cε_T, mean stress (P1 + P2)/(2A_s)); the two texts themselves were not retrieved.

Dynamic equilibrium. The specimen's stress is uniform only once waves have crossed it several times. The
check: R(τ) = 2(F1 − F2)/(F1 + F2) of the forces smoothed over :data:`EQUILIBRIUM_SMOOTHING` (the record's noise
is magnified in F1, the small difference of two large waves), while the mean force exceeds :data:`LOADED_FRACTION`
of its peak; the
window where |R| ≤ :data:`EQUILIBRIUM_TOLERANCE` (5 %, the tolerance quoted for Gray's chapter in the public
summaries, which were all that could be read of it) is reported, and a flag raised when the specimen was out of
equilibrium over the part of the curve that is used: when no window holds, when it holds less than
:data:`PLATEAU_IN_WINDOW` of the plateau (the strength is then one face's), or when it starts after the stress has
passed half its peak (the rise, where the modulus is read, was not in equilibrium: no modulus).

Per test, from the three-wave stress–strain curve inside the equilibrium window: the ``modulus`` (slope of σ
against ε over the rise between :data:`MODULUS_BAND` of the peak, with its standard error), the ``strength``
(the mean stress over the plateau, where σ₃ is within :data:`PLATEAU` of its peak: a flow stress, or a brittle
specimen's peak less a few per cent, robust to the ringing of the records) and the strain rate there (the mean
ε̇₃ over the same samples).

Across tests (:func:`fit_rate_law`): σ = σ_ref·(ε̇/ε̇_ref)^m by least squares on log σ against log ε̇, ε̇_ref
the geometric mean of the tests' rates, 95 % intervals from Student's t with n − 2 degrees of freedom, and the
range of rates measured (the law's validity envelope).

Units SI; time along the last axis.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..models.dispersion import RoundBar, disperse
from ..models.noise import robust_sigma
from ..models.sampling import series_problem

__all__ = [
    "BarSide",
    "Specimen",
    "ShpbSettings",
    "ShpbRecord",
    "ShpbResult",
    "RateLaw",
    "analyse_test",
    "fit_rate_law",
    "EQUILIBRIUM_TOLERANCE",
    "LOADED_FRACTION",
    "MODULUS_BAND",
    "PLATEAU",
]

EQUILIBRIUM_TOLERANCE = 0.05  # |2(F1 − F2)/(F1 + F2)| within this: equilibrium (module docstring)
LOADED_FRACTION = 0.1  # R is judged only while the mean force exceeds this fraction of its peak (noise elsewhere)
EQUILIBRIUM_SMOOTHING = 4e-6  # s: the forces are smoothed over this long for R (a few transits of a mm-long specimen; :func:`_equilibrium`)
MODULUS_BAND = (0.1, 0.6)  # the modulus is the slope of the rise between these fractions of the peak stress
PLATEAU = 0.05  # the strength and its strain rate: means over the samples within this fraction of the peak stress
PLATEAU_IN_WINDOW = 0.8  # the strength is in equilibrium when this share of its plateau lies in the equilibrium window
DETECTION_SIGMAS = 8.0  # the incident wave's arrival: beyond this many σ of the pre-trigger noise ...
DETECTION_FRACTION = 0.05  # ... and this fraction of the record's largest excursion
PRETRIGGER_MIN = 20
LEAD = 0.02  # the incident window opens this fraction of 2x_I/c_I before the arrival (the front's foot)


@dataclass(frozen=True)
class BarSide:
    """One bar as the analysis needs it: ``youngs_modulus`` E [Pa], ``density`` ρ [kg/m³], ``diameter`` [m],
    ``gauge_distance`` [m] from the gauge to the specimen's face, ``length`` [m], ``poisson_ratio`` (dispersion)."""

    youngs_modulus: float
    density: float
    diameter: float
    gauge_distance: float
    length: float
    poisson_ratio: float = 0.3

    def __post_init__(self):
        for name in ("youngs_modulus", "density", "diameter", "length"):
            if not getattr(self, name) > 0:
                raise InputError(f"{name} must be positive, got {getattr(self, name)!r}", name)
        if not 0.0 < self.gauge_distance < self.length:
            raise InputError(f"the gauge must lie on the bar: {self.gauge_distance!r} m from the specimen on a {self.length!r}-m bar", "gauge_distance")

    @property
    def wave_speed(self) -> float:
        return math.sqrt(self.youngs_modulus / self.density)

    @property
    def area(self) -> float:
        return math.pi * self.diameter**2 / 4

    @property
    def impedance(self) -> float:
        """ρ c A [N·s/m]."""
        return self.density * self.wave_speed * self.area

    def round_bar(self) -> RoundBar:
        return RoundBar(self.wave_speed, self.poisson_ratio, self.diameter / 2)


@dataclass(frozen=True)
class Specimen:
    """The specimen as tested: ``length`` L_s and ``diameter`` [m] (initial), ``density`` [kg/m³] (None: not known)."""

    length: float
    diameter: float
    density: float | None = None

    def __post_init__(self):
        for name in ("length", "diameter"):
            if not getattr(self, name) > 0:
                raise InputError(f"specimen {name} must be positive, got {getattr(self, name)!r}", name)

    @property
    def area(self) -> float:
        return math.pi * self.diameter**2 / 4


@dataclass(frozen=True)
class ShpbSettings:
    """``dispersion``: move each wave to its face with the first-mode dispersion (and the surface-to-force factor);
    ``transmitted_delay`` [s]: the transmitted record's clock behind the incident's (0: one recorder, one trigger)."""

    dispersion: bool = False
    transmitted_delay: float = 0.0
    equilibrium_tolerance: float = EQUILIBRIUM_TOLERANCE


@dataclass(frozen=True)
class ShpbRecord:
    """One test's two records (strain, tension +) on their clocks [s]."""

    name: str
    incident_time: np.ndarray
    incident: np.ndarray
    transmitted_time: np.ndarray
    transmitted: np.ndarray


@dataclass(frozen=True)
class ShpbResult:
    """One test analysed (module docstring). Histories on ``time`` [s] from the incident wave's arrival at the front
    face: the face ``incident``, ``reflected``, ``transmitted`` strains; ``front_force``, ``back_force`` [N];
    ``stress_one``, ``stress_two``, ``stress_three`` [Pa]; ``strain_rate_one``, ``strain_rate_three`` [1/s];
    ``strain_one``, ``strain_three``; ``equilibrium_ratio`` R (NaN where the specimen is not loaded). Scalars:
    ``equilibrium_window`` (start, end) [s] (NaN, NaN: none), whether it holds the plateau (``equilibrium_at_strength``)
    and the rise (``equilibrium_in_rise``), ``modulus`` [Pa] and its standard error (NaN when the rise is not in
    equilibrium), ``strength`` [Pa] (the plateau's mean stress) and the ``strain_rate`` there [1/s]; ``flags``: what
    puts the strength in doubt (sentences); ``notes``: what puts only the modulus in doubt."""

    name: str
    time: np.ndarray
    incident: np.ndarray
    reflected: np.ndarray
    transmitted: np.ndarray
    front_force: np.ndarray
    back_force: np.ndarray
    stress_one: np.ndarray
    stress_two: np.ndarray
    stress_three: np.ndarray
    strain_rate_one: np.ndarray
    strain_rate_three: np.ndarray
    strain_one: np.ndarray
    strain_three: np.ndarray
    equilibrium_ratio: np.ndarray
    equilibrium_window: tuple[float, float]
    equilibrium_at_strength: bool
    equilibrium_in_rise: bool
    modulus: float
    modulus_se: float
    strength: float
    strain_rate: float
    flags: tuple[str, ...]
    notes: tuple[str, ...] = ()


@dataclass(frozen=True)
class RateLaw:
    """σ = σ_ref·(ε̇/ε̇_ref)^m fitted across tests (module docstring): ``strength_ref`` σ_ref [Pa], ``exponent`` m,
    ``reference_rate`` ε̇_ref [1/s], the 95 % half-widths of σ_ref and m, their ``covariance`` (of log σ_ref and m),
    ``rate_range`` (lowest, highest) [1/s] of the tests, ``residual`` rms of log σ about the law, the ``points``
    (rate, strength) fitted and their test ``names``."""

    strength_ref: float
    exponent: float
    reference_rate: float
    strength_ref_half_width: float
    exponent_half_width: float
    covariance: np.ndarray
    rate_range: tuple[float, float]
    residual: float
    points: tuple[tuple[float, float], ...]
    names: tuple[str, ...]

    def __call__(self, rate):
        """σ [Pa] at ``rate`` [1/s]."""
        return self.strength_ref * (np.asarray(rate, float) / self.reference_rate) ** self.exponent

    @property
    def coefficient_at_1_per_s(self) -> float:
        """A of σ = A·(ε̇/1 s⁻¹)^m [Pa]: σ_ref·ε̇_ref^(−m)."""
        return self.strength_ref * self.reference_rate ** (-self.exponent)


def _uniform(what: str, t, y):
    t = np.asarray(t, float)
    y = np.asarray(y, float)
    problem = series_problem(t, y, min_samples=64, what="strain")
    if problem is not None:
        raise InputError(f"{what}: {problem}")
    dt = float(np.median(np.diff(t)))
    if np.max(np.abs(np.diff(t) - dt)) > 0.01 * dt:
        grid = np.arange(t[0], t[-1] + 0.5 * dt, dt)
        y, t = np.interp(grid, t, y), grid
    return t, y, dt


def _baseline(what: str, y, before: int):
    """(median, robust σ) of the samples before index ``before``."""
    if before < PRETRIGGER_MIN:
        raise InputError(f"{what}: only {before} samples before the wave arrives: record more pre-trigger (at least {PRETRIGGER_MIN})")
    return float(np.median(y[:before])), float(robust_sigma(y[:before]))


def _first_arrival(what: str, t, y):
    """(arrival time, its index, baseline, noise, sign) of a record's first wave (module constants)."""
    head = max(PRETRIGGER_MIN, y.size // 50)
    base, sig = float(np.median(y[:head])), float(robust_sigma(y[:head]))
    dev = y - base
    level = max(DETECTION_SIGMAS * sig, DETECTION_FRACTION * float(np.max(np.abs(dev))))
    above = np.flatnonzero(np.abs(dev) > level)
    if above.size == 0:
        raise InputError(f"{what}: no wave leaves the record's noise")
    i = int(above[0])
    sign = 1 if dev[i] > 0 else -1
    j = i
    while j > 0 and sign * dev[j - 1] > 2 * sig:
        j -= 1
    base, sig = _baseline(what, y, max(j - 5, 0))
    return float(t[j]), j, base, sig, sign


def _face_waves(rec: ShpbRecord, incident: BarSide, transmitted: BarSide, settings: ShpbSettings):
    """(τ, ε_I, ε_R, ε_T at the faces, flags, duration): the three waves moved to the specimen's faces (module docstring)."""
    flags = []
    ti, yi, dt = _uniform(f"{rec.name}: incident record", rec.incident_time, rec.incident)
    tt, yt, _ = _uniform(f"{rec.name}: transmitted record", rec.transmitted_time, rec.transmitted)
    tt = tt - settings.transmitted_delay
    t_a, _, base_i, _, sign = _first_arrival(f"{rec.name}: incident record", ti, yi)
    yi = yi - base_i
    if sign > 0:
        flags.append(f"{rec.name}: the incident wave reads tensile: the incident record's sign is inverted (a bridge polarity?); read as compressive")
        yi = -yi
    ci, ct = incident.wave_speed, transmitted.wave_speed
    xi, xt = incident.gauge_distance, transmitted.gauge_distance
    split = 2 * xi / ci  # the reflected wave reaches the gauge this long after the incident one
    lead = LEAD * split
    # the transmitted record's baseline: before the transmitted wave can arrive
    t_arrive_t = t_a + xi / ci + xt / ct
    n_pre_t = int(np.searchsorted(tt, t_arrive_t - lead))
    base_t, _ = _baseline(f"{rec.name}: transmitted record", yt, n_pre_t)
    yt = yt - base_t
    in_inc = (ti >= t_a - lead) & (ti < t_a - lead + split)
    in_ref = (ti >= t_a - lead + split) & (ti < t_a - lead + 2 * split)
    peak = float(np.max(np.abs(yi[in_inc])))
    tail = np.abs(yi[in_inc][-max(3, int(0.05 * in_inc.sum())) :])
    if float(np.max(tail)) > 0.05 * peak:
        flags.append(
            f"{rec.name}: the incident wave is still {float(np.max(tail)) / peak:.0%} of its peak when its reflection reaches the gauge "
            f"({split * 1e6:.0f} us after it): the two overlap at the gauge; the analysis stops there"
        )
    # how long the faces are seen: the incident window, the reflected one, the transmitted gauge's clear time
    clear_t = 2 * (transmitted.length - xt) / ct
    duration = min(split, clear_t, ti[-1] - (t_a - lead + split), tt[-1] - (t_arrive_t - lead)) - lead
    if duration <= 0:
        raise InputError(f"{rec.name}: the records end before the reflected and transmitted waves have passed their gauges")
    inc_w, ref_w = np.where(in_inc, yi, 0.0), np.where(in_ref, yi, 0.0)
    in_tr = (tt >= t_arrive_t - lead) & (tt < t_arrive_t - lead + clear_t)
    tr_w = np.where(in_tr, yt, 0.0)
    if settings.dispersion:
        inc_w = disperse(ti, inc_w, xi, incident.round_bar(), surface_to_force=True)
        ref_w = disperse(ti, ref_w, -xi, incident.round_bar(), surface_to_force=True)
        tr_w = disperse(tt, tr_w, -xt, transmitted.round_bar(), surface_to_force=True)
        flags.append(f"{rec.name}: each wave moved to its face with the first-mode (Pochhammer-Chree) dispersion of its bar")
    tau = np.arange(-lead, duration, dt)
    t_face = t_a + xi / ci  # the incident wave's arrival at the front face, on the incident record's clock
    eps_i = np.interp(tau + t_face - xi / ci, ti, inc_w, left=0.0, right=0.0)
    eps_r = np.interp(tau + t_face + xi / ci, ti, ref_w, left=0.0, right=0.0)
    eps_t = np.interp(tau + t_face + xt / ct, tt, tr_w, left=0.0, right=0.0)
    return tau, eps_i, eps_r, eps_t, flags


def _equilibrium(tau, F1, F2, tolerance):
    """(R(τ), the window (start, end) where |R| ≤ tolerance the longest while loaded, loaded mask, its indices).

    R is computed from the forces smoothed over EQUILIBRIUM_SMOOTHING (a quadratic Savitzky–Golay filter): the front
    force is the small difference ε_I + ε_R of two large waves, so its record noise is magnified (5 % of R per sample
    for a specimen 20 times softer than the bars, at 0.5 % noise); equilibrium is a matter of several wave transits,
    which the filter keeps."""
    from scipy.signal import savgol_filter

    dt = float(tau[1] - tau[0])
    window = max(5, int(round(EQUILIBRIUM_SMOOTHING / dt)) | 1)
    if window < F1.size:
        F1, F2 = savgol_filter(F1, window, 2), savgol_filter(F2, window, 2)
    mean = 0.5 * (F1 + F2)
    loaded = mean > LOADED_FRACTION * float(np.max(mean))
    with np.errstate(divide="ignore", invalid="ignore"):
        R = np.where(loaded, 2 * (F1 - F2) / (F1 + F2), np.nan)
    ok = loaded & (np.abs(np.nan_to_num(R, nan=np.inf)) <= tolerance)
    best, start, run_start = (0, -1, -1), None, None
    for i, v in enumerate(np.append(ok, False)):
        if v and run_start is None:
            run_start = i
        elif not v and run_start is not None:
            if i - run_start > best[0]:
                best = (i - run_start, run_start, i - 1)
            run_start = None
    if best[0] == 0:
        return R, (math.nan, math.nan), loaded, None
    start = best[1]
    return R, (float(tau[best[1]]), float(tau[best[2]])), loaded, (start, best[2])


def _properties(stress, strain, rate, window):
    """(modulus, its standard error, strength, strain rate at it, share of the plateau in the window) from the three-wave
    curve: the plateau is every sample within PLATEAU of the peak stress, the strength and its rate their means (inside the
    window where it holds); the modulus the slope of σ against ε over the rise between MODULUS_BAND of the peak, inside
    the window (NaN with fewer than four samples there)."""
    k_pk = int(np.argmax(stress))
    peak = float(stress[k_pk])
    plateau = stress >= (1 - PLATEAU) * peak
    inside = np.zeros(stress.size, bool)
    if window is not None:
        inside[window[0] : window[1] + 1] = True
    share = float(np.sum(plateau & inside) / np.sum(plateau))
    use = plateau & inside if share > 0 else plateau
    strength, rate_at = float(np.mean(stress[use])), float(np.mean(rate[use]))
    rise = np.arange(stress.size) <= k_pk
    band = rise & inside & (stress >= MODULUS_BAND[0] * peak) & (stress <= MODULUS_BAND[1] * peak)
    if band.sum() < 4:
        return math.nan, math.nan, strength, rate_at, share
    coef, cov = np.polyfit(strain[band], stress[band], 1, cov=True)
    return float(coef[0]), float(math.sqrt(cov[0, 0])), strength, rate_at, share


def analyse_test(rec: ShpbRecord, incident: BarSide, transmitted: BarSide, specimen: Specimen, settings: ShpbSettings = ShpbSettings()) -> ShpbResult:
    """One test's waves at the faces, its stresses, strain rates and strains, its equilibrium and its properties
    (module docstring)."""
    tau, eps_i, eps_r, eps_t, flags = _face_waves(rec, incident, transmitted, settings)
    Ls, As = specimen.length, specimen.area
    ci, ct = incident.wave_speed, transmitted.wave_speed
    F1 = -incident.youngs_modulus * incident.area * (eps_i + eps_r)
    F2 = -transmitted.youngs_modulus * transmitted.area * eps_t
    v1, v2 = ci * (eps_r - eps_i), -ct * eps_t
    rate3 = (v1 - v2) / Ls
    rate1 = 2 * ci * eps_r / Ls
    dt = float(tau[1] - tau[0])
    strain3 = np.concatenate(([0.0], np.cumsum(0.5 * (rate3[1:] + rate3[:-1])) * dt))
    strain1 = np.concatenate(([0.0], np.cumsum(0.5 * (rate1[1:] + rate1[:-1])) * dt))
    s1, s2, s3 = F2 / As, F1 / As, 0.5 * (F1 + F2) / As
    R, window, loaded, idx = _equilibrium(tau, F1, F2, settings.equilibrium_tolerance)
    if abs(incident.impedance / transmitted.impedance - 1) > 0.01:
        flags.append(
            f"{rec.name}: the bars' impedances differ by {incident.impedance / transmitted.impedance - 1:+.0%}: the one-wave strain rate 2c e_R/L assumes identical bars"
        )
    E, E_se, strength, rate_at, share = _properties(s3, strain3, rate3, idx)
    tol = f"{settings.equilibrium_tolerance:.0%}"
    at_strength = share >= PLATEAU_IN_WINDOW
    in_rise = idx is not None and idx[0] <= int(np.argmax(s3 >= 0.5 * float(np.max(s3))))
    if idx is None:
        flags.append(f"{rec.name}: not in dynamic equilibrium: the faces' forces never agree within {tol} while the specimen is loaded")
    elif not at_strength:
        flags.append(
            f"{rec.name}: not in dynamic equilibrium at the strength: the faces' forces agree within {tol} over {share:.0%} of the plateau only "
            f"({window[0] * 1e6:.1f} to {window[1] * 1e6:.1f} us): the strength is one face's, not the specimen's (specimen too long, or loaded too fast, for its wave speed)"
        )
    notes = []
    if idx is not None and not in_rise:
        notes.append(
            f"{rec.name}: not in dynamic equilibrium during the rise: the faces' forces agree within {tol} only from {window[0] * 1e6:.1f} us, "
            "when the stress has passed half its peak: no modulus is read from the rise"
        )
        E, E_se = math.nan, math.nan
    return ShpbResult(
        rec.name,
        tau,
        eps_i,
        eps_r,
        eps_t,
        F1,
        F2,
        s1,
        s2,
        s3,
        rate1,
        rate3,
        strain1,
        strain3,
        R,
        window,
        at_strength,
        in_rise,
        E,
        E_se,
        strength,
        rate_at,
        tuple(flags),
        tuple(notes),
    )


def fit_rate_law(points, names) -> RateLaw:
    """σ = σ_ref·(ε̇/ε̇_ref)^m through the tests' (strain rate [1/s], strength [Pa]) ``points`` (module docstring);
    InputError with fewer than three tests, or with rates that do not span a range."""
    pts = np.asarray(points, float)
    if pts.ndim != 2 or pts.shape[0] < 3:
        raise InputError(f"a rate law needs at least three tests at different rates, got {len(points)}")
    if not np.all(pts > 0):
        raise InputError("every test fitted to a rate law needs a positive strain rate and strength")
    x, y = np.log(pts[:, 0]), np.log(pts[:, 1])
    if np.ptp(x) < math.log(1.2):
        raise InputError(f"the tests' strain rates span {math.exp(np.ptp(x)):.3g}x only: a rate law needs rates at least 20 % apart")
    ref = float(np.exp(np.mean(x)))
    X = np.column_stack([np.ones_like(x), x - math.log(ref)])
    coef, *_ = np.linalg.lstsq(X, y, rcond=None)
    resid = y - X @ coef
    dof = pts.shape[0] - 2
    s2 = float(resid @ resid) / dof
    cov = s2 * np.linalg.inv(X.T @ X)
    from scipy.special import stdtrit  # Student's t quantile (scipy.stats costs 0.4 s to import)

    t = float(stdtrit(dof, 0.975))
    sigma_ref = float(math.exp(coef[0]))
    return RateLaw(
        sigma_ref,
        float(coef[1]),
        ref,
        sigma_ref * (math.exp(t * math.sqrt(cov[0, 0])) - 1),
        t * math.sqrt(cov[1, 1]),
        cov,
        (float(pts[:, 0].min()), float(pts[:, 0].max())),
        math.sqrt(float(resid @ resid) / pts.shape[0]),
        tuple((float(a), float(b)) for a, b in pts),
        tuple(names),
    )
