"""The echoes of a struck free–free bar, fitted for its wave speed, its dispersion and its gauge's position.

A free–free bar (length L, radius a) struck at x = 0 by a short pulse carries it to a gauge at x, then
back and forth between its free ends. With the incident part of the record as a template s0 (the
record over a window about the first arrival, tapered), every later arrival j at the gauge is that
same wave moved further along the bar by a path p_j, reflected once (sign −1) or twice (sign +1):

- from the far end:   p = 2(L − x) + 2kL, sign −1 (k = 0, 1, …);
- from the struck end: p = 2kL,           sign +1 (k = 1, 2, …),

and moved by the first longitudinal (Pochhammer–Chree) mode (:mod:`softimpact.models.dispersion`):
each harmonic f of the template is delayed by p/c(f), with c(f) = c0·v(f·a/c0, ν) the mode's phase
velocity (Graff 1975, eq. 8.1.37; Bancroft 1941). The model of arrival j is

    y_j(t) = s_j · A_j · F⁻¹[ S0(f) · exp(−2πi f p_j / c(f)) ],              (E)

fitted by least squares over a window about each arrival for c0, the dispersion's unknown (ν, or the
radius a with ν given), the gauge's position x (when arrivals from both ends are in the record) and one
amplitude A_j per arrival (a free end reflects everything: A_j near 1; a loss shows as A_j < 1).
Only p/c0 and the shape change are observed: c0 is known as well as L is (c0 ∝ L, its share is
added by the caller), and at long wavelength the dispersion is Rayleigh–Love's c/c0 ≈ 1 − ν²π²(a/Λ)²
(Love 1927 §278), which fixes ν·a only: the radius must be measured to give ν, or ν given to give a.

ν enters through v(·, ν), tabulated per ν by root finding (0.3 s a table): the fit interpolates in ν
(quadratic through three tables :data:`NU_STEP` apart, recentred on the estimate until it lies within
half a step of the middle one; v is even in ν and nearly quadratic over a step: the interpolation moves
c(f) by less than 5e-6 of c0 up to 100 kHz in a 20-mm steel bar, checked in tests/test_bar_calibration.py).

Intervals. The template is measured too: its noise n0 enters every arrival's model through (E), so the
residuals are r = n − G n0 with one G for all arrivals (the same n0 seen through each move). The
covariance of the fitted parameters is the sandwich

    C = σ² (JᵀJ)⁻¹ [JᵀJ + (GᵀJ)ᵀ(GᵀJ)] (JᵀJ)⁻¹,

σ the record's noise (its pre-trigger part), J the Jacobian; GᵀJ applies each move's adjoint (the
conjugate transfer function) to J's columns. It is widened by the reduced χ² where the residuals exceed
what the noise explains (a model error: the FE's, a bar's joint, a gauge's own response).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..models.dispersion import RoundBar, phase_velocity, second_mode_cutoff

__all__ = ["NU_STEP", "Arrival", "EchoFit", "arrivals", "fit_echoes"]

NU_STEP = 0.025  # spacing of the ν tables the fit interpolates between (module docstring)
TEMPLATE_TAPER = 0.25  # fraction of the template window tapered (Tukey) at its two ends
LEAD = 0.25  # a window starts this fraction of the gap between arrivals before its arrival
GUARD = 2e-6  # s kept clear at a window's end before the next arrival
MAX_ARRIVALS = 8  # later arrivals fitted at most (the first ones: least dispersed, least attenuated)
RECENTRE = 4  # times the ν tables are recentred on the estimate at most
FD_STEP = 1e-6  # relative step of the Jacobian's central differences
Z95 = 1.959963984540054  # two-sided 95 % point of the normal distribution


@dataclass(frozen=True)
class Arrival:
    """A later arrival at the gauge: its sign relative to the incident wave, which end sent it back
    (``"far"`` or ``"struck"``) and its round number k (module docstring)."""

    sign: int
    end: str
    k: int

    def path(self, length: float, x: float) -> float:
        """Its path beyond the incident wave's [m]: 2(L − x) + 2kL from the far end, 2kL from the struck end."""
        return 2.0 * (length - x) + 2.0 * self.k * length if self.end == "far" else 2.0 * self.k * length


@dataclass(frozen=True)
class EchoFit:
    """The fit of (E) to one record.

    ``names``: the fitted parameters in order (``wave_speed``, then ``poisson_ratio`` or ``radius``
    when fitted, ``gauge_position`` when fitted, then ``amplitude_<j>``); ``values``, ``covariance``
    (the sandwich, widened by ``reduced_chi2`` when it exceeds 1); ``noise`` σ of the record;
    ``residual_rms`` of the residuals over the windows (strain), ``reduced_chi2`` = residual power over
    the power the noise explains; ``arrivals`` fitted; ``time`` the record's clock, ``template`` and
    ``model`` (the fitted arrivals, on that clock, NaN outside their windows) for the figures."""

    names: tuple[str, ...]
    values: np.ndarray
    covariance: np.ndarray
    noise: float
    residual_rms: float
    reduced_chi2: float
    arrivals: tuple[Arrival, ...]
    time: np.ndarray
    template: np.ndarray
    model: np.ndarray
    data: np.ndarray

    def value(self, name: str) -> float:
        return float(self.values[self.names.index(name)])

    def half_width(self, name: str) -> float:
        """Half-width of the 95 % interval of a parameter (normal: many samples)."""
        k = self.names.index(name)
        return float(Z95 * math.sqrt(max(self.covariance[k, k], 0.0)))


def arrivals(length: float, x: float, wave_speed: float, duration: float, both_ends: bool) -> tuple[Arrival, ...]:
    """The later arrivals within ``duration`` [s] after the incident one (at most MAX_ARRIVALS), in time order;
    those from the far end only when ``both_ends``."""
    out = []
    for k in range(0, MAX_ARRIVALS + 1):
        for a in ((Arrival(-1, "far", k),) if both_ends else ()) + ((Arrival(1, "struck", k),) if k >= 1 else ()):
            if a.path(length, x) / wave_speed < duration:
                out.append(a)
    out.sort(key=lambda a: a.path(length, x))
    return tuple(out[:MAX_ARRIVALS])


def _nu_nodes(nu: float) -> tuple[float, float, float]:
    """Three ν tables NU_STEP apart about ``nu``, inside [0, 0.5)."""
    mid = min(max(round(nu / NU_STEP) * NU_STEP, NU_STEP), 0.5 - 2 * NU_STEP)
    return (round(mid - NU_STEP, 6), round(mid, 6), round(mid + NU_STEP, 6))


def _phase_speed(f, c0: float, nu: float, radius: float, nodes) -> np.ndarray:
    """c(f) [m/s] of the first mode, quadratic in ν through the tables at ``nodes`` (None: ν's own table)."""
    if nodes is None:
        return phase_velocity(f, RoundBar(c0, nu, radius))
    vals = [phase_velocity(f, RoundBar(c0, n, radius)) for n in nodes]
    out = np.zeros_like(vals[0])
    for i, ni in enumerate(nodes):
        w = 1.0
        for j, nj in enumerate(nodes):
            if j != i:
                w *= (nu - nj) / (ni - nj)
        out = out + w * vals[i]
    return out


class _Problem:
    """The record, its windows and the template's spectrum, for one fit (module docstring)."""

    def __init__(self, t, y, arrival_time, gap, noise, length, radius, nu, wave_speed, x, unknown, fit_position, found):
        self.t, self.y, self.noise, self.length, self.x0 = t, y, noise, length, x
        self.radius, self.nu, self.unknown, self.fit_position = radius, nu, unknown, fit_position
        n = t.size
        self.n = n
        dt = float(t[1] - t[0])
        lead = LEAD * gap
        span = gap - GUARD
        tm = (t >= arrival_time - lead) & (t < arrival_time - lead + span)
        if tm.sum() < 16:
            raise InputError(f"the gap between arrivals ({gap * 1e6:.1f} us) holds too few samples to fit the echoes")
        from scipy.signal.windows import tukey

        w = np.zeros(n)
        w[tm] = tukey(int(tm.sum()), TEMPLATE_TAPER)
        self.taper = w
        self.template = w * y
        self.arrivals = found
        self.masks = [
            (t >= arrival_time + a.path(length, x) / wave_speed - lead) & (t < arrival_time + a.path(length, x) / wave_speed - lead + span) for a in found
        ]
        longest = max(a.path(length, x) for a in found)
        need = n + int(math.ceil(1.2 * longest / wave_speed / dt)) + n // 4
        self.nfft = 1 << (need - 1).bit_length()
        self.f = np.fft.rfftfreq(self.nfft, dt)
        self.S0 = np.fft.rfft(self.template, self.nfft)
        f_cut = second_mode_cutoff(RoundBar(wave_speed, nu, radius))
        ramp = np.clip((self.f - 0.8 * f_cut) / (0.2 * f_cut), 0.0, 1.0)
        self.band = 0.5 * (1 + np.cos(np.pi * ramp))  # the first mode alone below the second's cutoff (as models.dispersion)
        self.nodes = _nu_nodes(nu) if unknown == "poisson_ratio" else None

    def unpack(self, theta):
        """(c0, ν, a, x, amplitudes) of a parameter vector."""
        i = 1
        c0, nu, radius, x = float(theta[0]), self.nu, self.radius, self.x0
        if self.unknown == "poisson_ratio":
            nu, i = float(theta[1]), 2
        elif self.unknown == "radius":
            radius, i = float(theta[1]), 2
        if self.fit_position:
            x, i = float(theta[i]), i + 1
        return c0, nu, radius, x, np.asarray(theta[i:], float)

    def transfers(self, theta) -> list[np.ndarray]:
        c0, nu, radius, x, _ = self.unpack(theta)
        c = _phase_speed(self.f, c0, nu, radius, self.nodes)
        return [np.exp(-2j * np.pi * self.f * a.path(self.length, x) / c) * self.band for a in self.arrivals]

    def models(self, theta) -> list[np.ndarray]:
        amps = self.unpack(theta)[4]
        return [a.sign * A * np.fft.irfft(self.S0 * H, self.nfft)[: self.n] for a, A, H in zip(self.arrivals, amps, self.transfers(theta))]

    def residuals(self, theta) -> np.ndarray:
        return np.concatenate([(self.y[m] - yy[m]) / self.noise for m, yy in zip(self.masks, self.models(theta))])

    def jacobian(self, theta) -> np.ndarray:
        """∂r/∂θ: the amplitudes' columns exact (the model is linear in them), the others by central differences."""
        theta = np.asarray(theta, float)
        k = theta.size - len(self.arrivals)
        models = self.models(theta)
        amps = theta[k:]
        cols = []
        for i in range(k):
            h = FD_STEP * max(abs(theta[i]), 1e-3)
            up, down = theta.copy(), theta.copy()
            up[i] += h
            down[i] -= h
            cols.append((self.residuals(up) - self.residuals(down)) / (2 * h))
        J = np.zeros((sum(int(m.sum()) for m in self.masks), theta.size))
        if k:
            J[:, :k] = np.column_stack(cols)
        row = 0
        for j, (m, yy) in enumerate(zip(self.masks, models)):
            rows = int(m.sum())
            J[row : row + rows, k + j] = -(yy[m] / amps[j] if amps[j] != 0 else 0.0) / self.noise
            row += rows
        return J

    def template_share(self, theta, J) -> np.ndarray:
        """Gᵀ J (n, p): the template's noise (per sample, in units of σ) seen through every arrival's model (module docstring)."""
        amps = self.unpack(theta)[4]
        out = np.zeros((self.n, J.shape[1]))
        row = 0
        for a, A, H, m in zip(self.arrivals, amps, self.transfers(theta), self.masks):
            rows = int(m.sum())
            block = np.zeros((self.nfft, J.shape[1]))
            block[: self.n][m] = J[row : row + rows]
            back = np.fft.irfft(np.fft.rfft(block, axis=0) * np.conj(H)[:, None], self.nfft, axis=0)[: self.n]
            out += a.sign * A * self.taper[:, None] * back  # the residual is y − model: its sign does not matter in GGᵀ
            row += rows
        return out


def fit_echoes(
    t,
    y,
    *,
    arrival_time: float,
    noise: float,
    length: float,
    radius: float,
    poisson_ratio: float,
    wave_speed: float,
    gauge_position: float,
    unknown: str = "poisson_ratio",
    fit_position: bool = True,
) -> EchoFit:
    """Fit (E) to a record (module docstring): ``t`` uniform [s], ``y`` strain less its baseline (the incident wave
    compressive, negative), ``arrival_time`` of the incident wave at the gauge, ``noise`` σ of the record; the bar's
    ``length`` and ``radius`` [m], ``poisson_ratio``, and first guesses of ``wave_speed`` [m/s] and ``gauge_position``
    [m]. ``unknown``: ``"poisson_ratio"``, ``"radius"`` or ``"none"`` (the dispersion's parameters given);
    ``fit_position``: fit x (needs arrivals from the far end). InputError when the record holds no later arrival."""
    from scipy.optimize import least_squares

    if unknown not in ("poisson_ratio", "radius", "none"):
        raise InputError(f"unknown must be poisson_ratio, radius or none, got {unknown!r}", "unknown")
    gaps = (2.0 * (length - gauge_position), 2.0 * gauge_position) if fit_position else (2.0 * length,)
    gap = min(gaps) / wave_speed
    found = arrivals(length, gauge_position, wave_speed, t[-1] - arrival_time - (1 - LEAD) * gap, fit_position)
    if not found:
        raise InputError(
            f"the record ends {(t[-1] - arrival_time) * 1e6:.0f} us after the incident wave: no echo of it to time (record at least {2 * length / wave_speed * 1e6:.0f} us)"
        )
    nu, x = poisson_ratio, gauge_position
    sol, problem = None, None
    for _ in range(RECENTRE):
        problem = _Problem(t, y, arrival_time, gap, noise, length, radius, nu, wave_speed, x, unknown, fit_position, found)
        start = [wave_speed] + ([nu] if unknown == "poisson_ratio" else [radius] if unknown == "radius" else [])
        start += [x] if fit_position else []
        start += list(sol.x[-len(found) :]) if sol is not None else [1.0] * len(found)
        scale = (
            [1e-3 * wave_speed]
            + ([0.01] if unknown == "poisson_ratio" else [0.01 * radius] if unknown == "radius" else [])
            + ([1e-3 * length] if fit_position else [])
        )
        scale += [0.01] * len(found)
        lower = [0.5 * wave_speed] + ([0.0] if unknown == "poisson_ratio" else [0.2 * radius] if unknown == "radius" else []) + ([0.0] if fit_position else [])
        upper = (
            [2.0 * wave_speed]
            + ([0.4999] if unknown == "poisson_ratio" else [5.0 * radius] if unknown == "radius" else [])
            + ([length] if fit_position else [])
        )
        lower += [0.0] * len(found)
        upper += [2.0] * len(found)
        sol = least_squares(problem.residuals, np.clip(start, lower, upper), x_scale=np.array(scale), bounds=(lower, upper), jac=problem.jacobian)
        c0, nu_fit, _, x_fit, _ = problem.unpack(sol.x)
        wave_speed, x = c0, (x_fit if fit_position else x)
        if unknown != "poisson_ratio" or abs(nu_fit - problem.nodes[1]) <= 0.5 * NU_STEP:
            break
        nu = nu_fit
    return _result(problem, sol, t, y, found)


def _result(problem: _Problem, sol, t, y, found) -> EchoFit:
    """The EchoFit of a finished least-squares ``sol`` (module docstring: the sandwich covariance)."""
    J = sol.jac
    r = sol.fun
    JtJ = J.T @ J
    inv = np.linalg.pinv(JtJ)
    GJ = problem.template_share(sol.x, J)
    cov = inv @ (JtJ + GJ.T @ GJ) @ inv
    n_res, p = r.size, sol.x.size
    # the residual power the noise explains: its own plus the template's, seen through each move
    expected = 1.0 + float(np.sum(problem.taper**2)) * len(found) / max(n_res, 1) * _band_fraction(problem)
    chi2 = float(r @ r) / max(n_res - p, 1) / expected
    cov = cov * max(chi2, 1.0)
    names = ["wave_speed"] + ([problem.unknown] if problem.unknown != "none" else []) + (["gauge_position"] if problem.fit_position else [])
    names += [f"amplitude_{j + 1}" for j in range(len(found))]
    model = np.full(t.size, np.nan)
    for m, yy in zip(problem.masks, problem.models(sol.x)):
        model[m] = yy[m]
    data = np.where(np.isnan(model), np.nan, y)
    return EchoFit(
        tuple(names),
        sol.x.copy(),
        cov,
        problem.noise,
        float(np.sqrt(np.mean((r * problem.noise) ** 2))),
        chi2,
        found,
        t,
        problem.template,
        model,
        data,
    )


def _band_fraction(problem: _Problem) -> float:
    """The share of white noise's power that passes the band (the moves keep only the first mode's band)."""
    return float(np.mean(problem.band**2))
