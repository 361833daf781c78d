"""First-mode (Pochhammer–Chree) dispersion in a round elastic bar.

A harmonic longitudinal wave exp(i(kz − ωt)) in an infinite round bar of radius
a exists only where the Pochhammer (1876) – Chree (1889) frequency equation
holds (Graff, *Wave Motion in Elastic Solids*, 1975, eq. 8.1.37; Bancroft 1941,
eq. 1):

    (2α/a)(β² + k²) J1(αa) J1(βa) − (β² − k²)² J0(αa) J1(βa)
                                  − 4k²αβ J1(αa) J0(βa) = 0,

    α² = ω²/c_L² − k²,  β² = ω²/c_T² − k²,

with c_L² = (λ + 2μ)/ρ, c_T² = μ/ρ. Writing g(p) = J1(p)/p (even in p, real
for imaginary p: g(is) = I1(s)/s, J0(is) = I0(s)) and P = α²a², Q = β²a²,
K = k²a², the equation is multiplied out into a form that is real and free of
poles for both signs of P and Q (the first mode has P < 0 always and Q < 0 once
c < c_T):

    D = 2P(Q + K) gα gβ − (Q − K)² J0α gβ − 4KP gα J0β = 0.          (D)

The first mode's phase velocity c = ω/k falls from c0 = sqrt(E/ρ) at long
wavelength Λ = 2π/k toward the Rayleigh surface-wave speed c_R as a/Λ → ∞,
dipping slightly below c_R beyond a/Λ ≈ 1.4 and approaching it from below
(Bancroft 1941; Davies 1948, Table 3; its low-frequency limit is Rayleigh–Love,
c/c0 ≈ 1 − ν²π²(a/Λ)², Love 1927 §278). It depends on ν and a/Λ only, and is
tabulated once per ν (cached) over a/Λ ∈ [0, 3] by bracketed root finding
(brentq) that follows the branch from c0, each root bracketed by a window
widened around the previous one.

The radial distribution of the mode (Davies 1948, §3; Tyas & Watson 2001,
eqs 6–9, whose factors are also in Lifshitz & Leber 1994) relates what a
surface gauge sees to what carries the force:

- M1 = ε̄/ε(a): cross-section mean axial strain over the surface strain,
- M2 = σ̄/(E ε̄): mean axial stress over E times the mean axial strain (the
  "dynamic modulus" ratio),

so the axial force of one harmonic is F = E·A·M1·M2·ε(a). From the potentials
φ = J0(αr), ψ_θ = B J1(βr) and σ_rz(a) = 0:

    M1 = 2 gα gβ (K − Q + 2P) / [J0α (K − Q) gβ + 2P gα J0β],
    M2 = [λ(P + K)(K − Q) + 2μK(K − Q) + 4μKP] / [E K (K − Q + 2P)],

both → 1 as a/Λ → 0. :func:`propagate` moves a record along the bar with the
first-mode phase velocity (phase only; apply M1·M2 separately where a surface
gauge must be turned into a force).

Units SI; arrays 1-D with time along the axis.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..errors import InputError
from .sampling import series_problem

__all__ = [
    "RoundBar",
    "phase_velocity_ratio",
    "phase_velocity",
    "rayleigh_speed_ratio",
    "radial_factors",
    "second_mode_cutoff",
    "propagate",
    "disperse",
    "radial_band_edge",
]

RADIAL_LIMIT = 1.25  # M1·M2 beyond this: the mode's surface strain is heading for zero (M1's pole) and a gauge sees too little of it

TABLE_MAX = 3.0  # a/Λ tabulated up to here: c is within 0.6 % of c_R beyond (Bancroft's table ends at a/Λ = 1, Davies' at 2.1)
TABLE_POINTS = 600
GROUP_FLOOR = 0.3  # first-mode group velocity stays above this fraction of c0 (its minimum is ~0.5 c0): sizes the padding
ROLLOFF_START = 0.8  # the raised-cosine taper to zero starts at this fraction of the cutoff frequency


@dataclass(frozen=True)
class RoundBar:
    """A round elastic bar for dispersion: c0 = sqrt(E/ρ) [m/s], ν [-], radius a [m]."""

    wave_speed: float
    poisson_ratio: float
    radius: float

    def __post_init__(self):
        if not (math.isfinite(self.wave_speed) and self.wave_speed > 0):
            raise InputError(f"bar: wave_speed must be positive, got {self.wave_speed!r}")
        if not (0.0 <= self.poisson_ratio < 0.5):
            raise InputError(f"bar: poisson_ratio must lie in [0, 0.5), got {self.poisson_ratio!r}")
        if not (math.isfinite(self.radius) and self.radius > 0):
            raise InputError(f"bar: radius must be positive, got {self.radius!r}")

    @classmethod
    def of(cls, bar) -> RoundBar:
        """A RoundBar, or one built from anything with ``material`` (E, ρ, ν) and ``diameter``."""
        if isinstance(bar, cls):
            return bar
        try:
            m = bar.material
            return cls(m.wave_speed, m.poisson_ratio, bar.diameter / 2.0)
        except AttributeError:
            raise InputError(f"bar: need a RoundBar or an object with material and diameter, got {bar!r}") from None


def _j0_g(p2):
    """(J0(p), J1(p)/p) for p² real of either sign, each scaled by exp(−|Im p|).

    The scale is common to the α and β functions in every term of (D), so it
    cancels; it keeps I0, I1 finite at large imaginary argument.
    """
    from scipy.special import i0e, i1e, j0, j1

    p2 = np.asarray(p2, dtype=float)
    s = np.sqrt(np.abs(p2))
    small = s < 1e-8
    safe = np.where(small, 1.0, s)
    pos = p2 >= 0
    J0 = np.where(pos, j0(s), i0e(s))
    g = np.where(pos, j1(safe) / safe, i1e(safe) / safe)
    return J0, np.where(small, 0.5, g)


def _moduli(nu):
    """(r, u0) = (c_T²/c_L², c0²/c_T²) for Poisson's ratio ν."""
    return (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu)), 2.0 * (1.0 + nu)


def _frequency_function(v, x, nu):
    """(D)/K² at c/c0 = v and ka = x (= 2π a/Λ): zero on a mode."""
    r, u0 = _moduli(nu)
    u = u0 * np.asarray(v, float) ** 2  # c²/c_T²
    K = x * x
    P, Q = K * (r * u - 1.0), K * (u - 1.0)
    J0a, ga = _j0_g(P)
    J0b, gb = _j0_g(Q)
    return (2 * P * (Q + K) * ga * gb - (Q - K) ** 2 * J0a * gb - 4 * K * P * ga * J0b) / (K * K)


def rayleigh_speed_ratio(nu: float) -> float:
    """c_R/c0: root of (2 − ξ²)² = 4 sqrt(1 − rξ²) sqrt(1 − ξ²), ξ = c_R/c_T (Graff eq. 6.3.7)."""
    from scipy.optimize import brentq

    r, u0 = _moduli(nu)
    f = lambda xi: (2 - xi * xi) ** 2 - 4 * math.sqrt(1 - r * xi * xi) * math.sqrt(1 - xi * xi)  # noqa: E731
    xi = brentq(f, 0.5, 1.0 - 1e-12, xtol=1e-14)
    return xi / math.sqrt(u0)


@lru_cache(maxsize=16)
def _table(nu: float) -> tuple[np.ndarray, np.ndarray]:
    """(a/Λ, c/c0) on the first branch, a/Λ ∈ [0, TABLE_MAX]."""
    from scipy.optimize import brentq

    aL = np.linspace(0.0, TABLE_MAX, TABLE_POINTS + 1)
    v = np.empty_like(aL)
    v[0] = 1.0
    for i, y in enumerate(aL[1:], start=1):
        x = 2 * math.pi * y
        f = lambda c, x=x: float(_frequency_function(c, x, nu))  # noqa: E731
        prev = min(v[i - 1], 1.0 - 1e-12)
        # The branch moves little between table points, and not always down: it
        # dips below c_R near a/Λ ≈ 1.4 and comes back up to it (Davies 1948,
        # Table 3). Widen a window around the previous root until it brackets one.
        for width in 1e-5 * 2.0 ** np.arange(20):
            lo, top = prev * (1 - width), min(prev * (1 + width), 1.0)
            if f(lo) * f(top) <= 0:
                break
        else:
            raise RuntimeError(f"Pochhammer equation: first mode lost at a/Λ = {y:g}, ν = {nu:g}")
        v[i] = brentq(f, lo, top, xtol=1e-13, rtol=1e-13)
    return aL, v


def _check_nu(nu):
    if not (0.0 <= nu < 0.5):
        raise InputError(f"poisson_ratio must lie in [0, 0.5), got {nu!r}")
    return float(round(nu, 12))


def phase_velocity_ratio(a_over_wavelength, nu: float):
    """c/c0 of the first longitudinal mode at a/Λ (radius over wavelength), Poisson's ratio ν.

    Beyond the table (a/Λ > 3, where c is within 0.6 % of c_R) c_R/c0 is returned.
    """
    aL, v = _table(_check_nu(nu))
    y = np.asarray(a_over_wavelength, dtype=float)
    if np.any(y < 0):
        raise InputError("a_over_wavelength must be non-negative")
    from scipy.interpolate import CubicSpline

    spline = CubicSpline(aL, v)
    return np.where(y <= TABLE_MAX, spline(np.minimum(y, TABLE_MAX)), rayleigh_speed_ratio(nu))


def phase_velocity(frequency, bar) -> np.ndarray:
    """First-mode phase velocity c(f) [m/s] at frequencies f [Hz] (|f| used) in ``bar``.

    The table in a/Λ maps to frequency through f·a/c0 = (a/Λ)(c/c0), which
    increases along the branch (the group velocity is positive).
    """
    b = RoundBar.of(bar)
    aL, v = _table(_check_nu(b.poisson_ratio))
    fa = aL * v  # f a / c0
    F = np.abs(np.asarray(frequency, dtype=float)) * b.radius / b.wave_speed
    # A cubic spline, not straight lines: kinks in c(f) every table step would put
    # echoes into a propagated record at the inverse of the step (~0.4 ms for a 0.5-in bar).
    ratio = np.where(F <= fa[-1], _fa_spline(b.poisson_ratio)(np.minimum(F, fa[-1])), rayleigh_speed_ratio(b.poisson_ratio))
    return b.wave_speed * ratio


@lru_cache(maxsize=16)
def _fa_spline(nu: float):
    """c/c0 as a cubic spline in f·a/c0 (increasing along the branch)."""
    from scipy.interpolate import CubicSpline

    aL, v = _table(_check_nu(nu))
    return CubicSpline(aL * v, v)


def radial_factors(a_over_wavelength, nu: float) -> tuple[np.ndarray, np.ndarray]:
    """(M1, M2) of the first mode at a/Λ (module docstring; Tyas & Watson 2001).

    M1 = mean axial strain / surface axial strain; M2 = mean axial stress /
    (E · mean axial strain). Force of one harmonic: F = E A M1 M2 ε_surface.
    """
    nu = _check_nu(nu)
    y = np.atleast_1d(np.asarray(a_over_wavelength, dtype=float))
    v = phase_velocity_ratio(y, nu)
    r, u0 = _moduli(nu)
    mu = 1.0  # μ = ρ c_T² with ρ = c_T = 1: every term below is in these units
    lam = mu * (1 - r * 2) / r  # λ = ρ(c_L² − 2c_T²)
    E = u0 * mu
    x = 2 * math.pi * np.maximum(y, 1e-6)
    K = x * x
    u = u0 * v * v
    P, Q = K * (r * u - 1.0), K * (u - 1.0)
    J0a, ga = _j0_g(P)
    J0b, gb = _j0_g(Q)
    M1 = 2 * ga * gb * (K - Q + 2 * P) / (J0a * (K - Q) * gb + 2 * P * ga * J0b)
    M2 = (lam * (P + K) * (K - Q) + 2 * mu * K * (K - Q) + 4 * mu * K * P) / (E * K * (K - Q + 2 * P))
    shape = np.shape(a_over_wavelength)
    return M1.reshape(shape), M2.reshape(shape)


def second_mode_cutoff(bar) -> float:
    """Frequency [Hz] at which the second longitudinal mode L(0,2) starts to propagate.

    At k = 0, (D) factors into gβ·(2P gα − Q J0α) = 0 (besides ω = 0): the
    lowest root in Ω = ωa/c_T of J1(Ω) = 0 or 2√r Ω J1(√r Ω) = Ω² J0(√r Ω).
    Above it a gauge record holds more than the first mode (Graff §8.1).
    """
    from scipy.optimize import brentq
    from scipy.special import j0, j1

    b = RoundBar.of(bar)
    r, u0 = _moduli(b.poisson_ratio)
    sr = math.sqrt(r)
    h = lambda W: 2 * sr * W * j1(sr * W) - W * W * j0(sr * W)  # noqa: E731
    grid = np.linspace(0.5, 3.8317, 400)
    vals = h(grid)
    k = np.flatnonzero(np.sign(vals[:-1]) != np.sign(vals[1:]))
    omega = brentq(h, grid[k[0]], grid[k[0] + 1]) if k.size else 3.831705970207512
    cT = b.wave_speed / math.sqrt(u0)
    return omega * cT / (2 * math.pi * b.radius)


def propagate(t, signal, distance: float, bar, cutoff: float | None = None) -> np.ndarray:
    """``signal`` (on uniform ``t``) moved by ``distance`` [m] along the bar, first mode.

    Positive distance: toward the far end (the wave arrives later, dispersed);
    negative: back toward the struck end (dispersion removed). Returned on the
    same clock and grid as the input. Each harmonic e^{iωt} is multiplied by
    exp(−i ω d / c(f)) (a delay d/c(f)); numpy's FFT sign convention.

    Care taken:
    - zero padding to a power of two at least n + |d|/(0.3 c0)/dt + n/4 samples (the slowest
      first-mode energy travels at about 0.5 c0), so
      nothing wraps around; what moves outside [t0, t_end] is dropped;
    - DC passes unchanged (k = 0: the impulse is kept);
    - the Nyquist bin of an even-length transform is set to zero (its phase
      cannot be shifted in a real signal);
    - the first mode is the whole story only below the second-mode cutoff
      (:func:`second_mode_cutoff`, or ``cutoff`` [Hz] if given): harmonics are
      tapered to zero by a raised cosine from 0.8·cutoff to cutoff. With
      distance = 0 the signal is returned untouched.
    """
    t = np.asarray(t, dtype=float)
    y = np.asarray(signal, dtype=float)
    problem = series_problem(t, y, min_samples=4, uniform=True)
    if problem is not None:
        raise InputError(f"propagate: {problem}")
    dt = (t[-1] - t[0]) / (t.size - 1)
    if not math.isfinite(distance):
        raise InputError(f"propagate: distance must be finite, got {distance!r}")
    if distance == 0:
        return y.copy()
    b = RoundBar.of(bar)
    f_cut = second_mode_cutoff(b) if cutoff is None else float(cutoff)
    if not f_cut > 0:
        raise InputError(f"propagate: cutoff must be positive, got {cutoff!r}")
    n = t.size
    c_min = GROUP_FLOOR * b.wave_speed
    need = n + int(math.ceil(abs(distance) / c_min / dt)) + n // 4
    nfft = 1 << (need - 1).bit_length()
    Y = np.fft.rfft(y, nfft)
    f = np.fft.rfftfreq(nfft, dt)
    c = phase_velocity(f, b)
    Y = Y * np.exp(-2j * np.pi * f * distance / c)
    taper = np.clip((f - ROLLOFF_START * f_cut) / ((1 - ROLLOFF_START) * f_cut), 0.0, 1.0)
    Y = Y * 0.5 * (1 + np.cos(np.pi * taper))
    if nfft % 2 == 0:
        Y[-1] = 0.0
    return np.fft.irfft(Y, nfft)[:n]


def disperse(t, signal, distance: float, bar, surface_to_force: bool = False) -> np.ndarray:
    """The dispersion of a move by ``distance`` [m] alone, without its bulk delay d/c0.

    Each harmonic is multiplied by exp(−i ω d (1/c(f) − 1/c0)): :func:`propagate`
    followed by an advance of d/c0, in one transform, so that a pulse stays where
    it is on the clock and only its shape changes. Forward (d > 0) it is causal
    (c ≤ c0 for every harmonic); backward (d < 0) it removes the dispersion a
    move of |d| added. ``surface_to_force``: each harmonic is also multiplied by
    M1·M2 (:func:`radial_factors`), turning a surface strain into force/(E A);
    the band then ends at :func:`radial_band_edge` (M1 has a pole where the
    surface strain of the mode vanishes, below the second-mode cutoff). Padding,
    DC, Nyquist and the taper to the band's end as in :func:`propagate`.
    """
    t = np.asarray(t, dtype=float)
    y = np.asarray(signal, dtype=float)
    if t.ndim != 1 or t.shape != y.shape or t.size < 4:
        raise InputError("disperse: t and signal must be 1-D arrays of equal length >= 4")
    dt = (t[-1] - t[0]) / (t.size - 1)
    if not dt > 0 or np.max(np.abs(np.diff(t) - dt)) > 1e-6 * dt:
        raise InputError("disperse: t must be uniform and increasing")
    if not math.isfinite(distance):
        raise InputError(f"disperse: distance must be finite, got {distance!r}")
    if distance == 0 and not surface_to_force:
        return y.copy()
    b = RoundBar.of(bar)
    f_cut = second_mode_cutoff(b)
    if surface_to_force:
        f_cut = min(f_cut, radial_band_edge(b))
    n = t.size
    # The dispersive part of the move shifts a harmonic by at most |d|(1/c_R − 1/c0) < 1.2 |d|/c0.
    need = n + int(math.ceil(1.2 * abs(distance) / b.wave_speed / dt)) + n // 4
    nfft = 1 << (need - 1).bit_length()
    # The padding joins the last sample back to the first by a raised cosine: a record
    # that ends mid-wave would otherwise be a step, whose slowly decaying ringing
    # (the taper's and M1·M2's kernels) wraps around onto the start.
    k = np.arange(nfft - n) / (nfft - n)
    buf = np.concatenate((y, y[-1] + (y[0] - y[-1]) * 0.5 * (1 - np.cos(np.pi * k))))
    Y = np.fft.rfft(buf)
    f = np.fft.rfftfreq(nfft, dt)
    c = phase_velocity(f, b)
    Y = Y * np.exp(-2j * np.pi * f * distance * (1.0 / c - 1.0 / b.wave_speed))
    if surface_to_force:
        M1, M2 = radial_factors(f * b.radius / c, b.poisson_ratio)
        Y = Y * M1 * M2
    taper = np.clip((f - ROLLOFF_START * f_cut) / ((1 - ROLLOFF_START) * f_cut), 0.0, 1.0)
    Y = Y * 0.5 * (1 + np.cos(np.pi * taper))
    if nfft % 2 == 0:
        Y[-1] = 0.0
    return np.fft.irfft(Y, nfft)[:n]


def radial_band_edge(bar) -> float:
    """Frequency [Hz] where M1·M2 first reaches RADIAL_LIMIT: the end of the band in which a surface gauge measures force.

    Past it M1 (mean over surface strain) runs to a pole, near a/Λ ≈ 0.46 at
    ν = 0.33, where the first mode's axial surface strain vanishes: there the
    gauge sees nothing of a harmonic that carries force, and multiplying by
    M1·M2 would amplify noise without bound.
    """
    b = RoundBar.of(bar)
    aL, v = _table(_check_nu(b.poisson_ratio))
    M1, M2 = radial_factors(aL, b.poisson_ratio)
    over = np.flatnonzero(M1 * M2 >= RADIAL_LIMIT)
    k = int(over[0]) if over.size else aL.size - 1
    return float(aL[k] * v[k] * b.wave_speed / b.radius)
