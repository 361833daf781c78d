"""The crushing family of the identification: an ice sphere's crushing strength law identified from
bar tests (:mod:`softimpact.workflows.identification`'s step 1, then this fit in place of its step 2).

The law (:class:`softimpact.models.crushing_law.CrushingLaw`) is F = A(s)·[σ_c(ṡ/d) + ρ·ṡ²] with the
crushed length s and its rate ṡ fixed by the centre-of-mass approach α and α̇ (s from α = X(s),
ṡ = α̇/φ(s/d)); the density ρ = m/(π·d³/6) is each test's own. What the bar records can fix is the
strength law σ_c(ε̇) = σ_ref·(ε̇/ε̇_ref)^m_c over the tests' strain rates ε̇ ≈ V/d:

- ``strength_ref`` σ_ref [Pa]: the strength at the reference rate ε̇_ref, the geometric mean of the
  tests' V/d (where σ_ref and m_c are least correlated);
- ``rate_exponent`` m_c [-].

Below :data:`RATE_FLOOR` the strength ramps linearly to 0 (the catalogue law's regularisation,
:class:`~softimpact.models.projectiles.PowerLawStrength`; it acts only in the last instants of a crush that
stops). The fit: nonlinear least squares of the law's force along each test's reconstructed α, α̇ against the
measured force, residuals scaled by each test's F0·sqrt(n) so every test weighs the same (as the visco-elastic
fit), over the samples of the main pulse where the crush still runs at ṡ ≥ :data:`FIT_RATE_FRACTION`·V. Why: the
approach integrates the measured force (ẋ = V − ∫F/m), so the force's noise makes a random walk in α̇; where a
crush stops (ṡ → 0) that error is the size of ṡ itself and the fit is biased (measured on synthetic records with 2 %
noise: the rate exponent off by up to 4 of its Jacobian half-widths with every sample, within them from ṡ ≥ V/2).

Each test's first contact is fitted too: a shift δ_i of its time origin (the approach taken as α − V·δ_i, the
sphere moving at V before contact), within ±:data:`START_SHIFT_FRACTION`·d/V. Why: a reduced record's first contact
is the start of the eq-(15) pulse fitted to it (:mod:`softimpact.workflows.reduction`), whose rise starts flat, while
a crush's force rises linearly from contact (A(s) ≈ π·d·s); on the built-in hail-ice-series (synthetic records, the
truth known) that origin came 4.5–10 µs early, i.e. up to 1 mm of approach at 105 m/s, and without the shifts the
strength came out 12 % low and the exponent 0.10 for 0.15 (16 and 3 of their half-widths); with them, within their
half-widths (tests/test_identify_crushing.py). On force records that start at contact the shifts come out within
±1.4 µs of 0 (the test's records with 2 % noise) and 0 to round-off without noise. The samples in the fit are chosen once,
on the record's own origin.

95 % intervals: with :data:`JACKKNIFE_MIN_TESTS` tests or more, the delete-one-test jackknife's covariance
((n − 1)/n·Σ(θ₋ᵢ − θ̄)(θ₋ᵢ − θ̄)ᵀ) and Student's t with n − 1 degrees of freedom: the tests are independent,
the samples within one are not (that random walk), and the Jacobian's s²·(JᵀJ)⁻¹, which takes them as
independent, covered the truth 12 times in 16 (6 tests, 8 noise draws, measured; the jackknife on 12 tests: 16 of 16). With fewer
tests, ±1.96·sqrt(diag(s²·(JᵀJ)⁻¹)). The law is memoryless and its force is exact along the true α, α̇ (noise-free
synthetic records give the parameters to 1e-8): no second stage on coupled runs (the closure runs them).

Private part of :mod:`softimpact.workflows.identification` (import the names from there).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..fem.bar import Rod
from ..models.crushing_law import CONSUMED, CrushingLaw, sphere_crush_depths
from ..models.projectiles import JONES_1997_FRESHWATER, PowerLawStrength
from ._identification_fit import Z95, Approach, BarTest, reconstruct_approach, unfixed_parameters

__all__ = ["CRUSHING_PARAMETERS", "RATE_FLOOR", "CrushingIdentifiedLaw", "identify_crushing", "crushing_force"]

CRUSHING_PARAMETERS = ("strength_ref", "rate_exponent")  # the order of CrushingIdentifiedLaw.values
RATE_FLOOR = JONES_1997_FRESHWATER.rate_range[0]  # 1/s: below it σ_c ramps to 0 (the catalogue law's regularisation, not fitted)
# bounds of the fit: a strength from 10 kPa to 10 GPa, an exponent within PowerLawStrength's [0, 1)
CRUSHING_LOWER = np.array([1e4, 0.0])
CRUSHING_UPPER = np.array([1e10, 0.99])
FIT_RATE_FRACTION = 0.5  # fit only where ṡ ≥ this × V: the first half of the crush's rate (module docstring)
JACKKNIFE_MIN_TESTS = 4  # from this many tests the intervals are the delete-one-test jackknife's (module docstring)
CRUSHING_SCALE = np.array([1e6, 0.1])  # the parameters' typical sizes (the fit's x_scale)
CRUSHING_START = (10e6, 0.15)  # σ_ref [Pa], m_c where the fit starts: the order of Jones 1997's freshwater ice
START_SHIFT_FRACTION = 0.05  # bound of each test's fitted first-contact shift, a fraction of d/V (module docstring)
SHIFT_SCALE = 1e-6  # s: the shifts' typical size (the fit's x_scale)


@dataclass(frozen=True)
class CrushingIdentifiedLaw:
    """An ice sphere's crushing law identified from bar tests (module docstring): ``values`` (σ_ref [Pa],
    m_c [-]) in the order of :data:`CRUSHING_PARAMETERS`, their 95 % ``half_widths`` and ``covariance`` (2, 2),
    ``reference_rate`` ε̇_ref [1/s], ``rms_per_test`` rms(F_model − F)/F0 over each main pulse, ``cost`` the
    fit's ½Σr², ``identified_on`` the tests' velocities, diameters and strain rates V/d ([min, max] each),
    ``at_bounds`` the parameters that ended on a bound of the fit. ``d_ref`` [m]: the largest tested diameter
    (the law has no size scaling; kept for law.json's layout)."""

    names: tuple[str, ...]
    values: np.ndarray
    half_widths: np.ndarray
    reference_rate: float
    d_ref: float
    rms_per_test: np.ndarray
    cost: float
    identified_on: dict | None = None
    covariance: np.ndarray | None = None
    at_bounds: tuple = ()
    start_shifts: np.ndarray | None = None  # s: each test's fitted first contact after the record's (module docstring)
    method: str = "bar tests (softimpact identify)"  # how the strength was measured: the strength law's source

    family = "crushing"  # law.json's family (a class attribute, not a field)
    has_memory = False

    @property
    def strength(self) -> PowerLawStrength:
        """σ_c(ε̇) = σ_ref·(ε̇/ε̇_ref)^m_c, measured over the tests' strain rates V/d (the validity range: a run below or
        above them is an extrapolation), ramped to zero below RATE_FLOOR as in the fit."""
        if self.identified_on and "strain_rate_1_s" in self.identified_on:
            lo, hi = (float(x) for x in self.identified_on["strain_rate_1_s"])
        else:  # no record of the tests' rates: the fit's floor up to the reference rate
            lo, hi = RATE_FLOOR, self.reference_rate
        hi = max(hi, 2.0 * RATE_FLOOR)
        lo = min(max(lo, RATE_FLOOR), 0.5 * hi)
        sigma, m = (float(v) for v in self.values)
        return PowerLawStrength(
            sigma, min(max(m, 0.0), CRUSHING_UPPER[1]), (lo, hi), self.reference_rate, f"identified from {self.method}", ramp_below=RATE_FLOOR
        )

    def law(self, mass: float, diameter: float, velocity: float) -> CrushingLaw:
        """The crushing law of one sphere (``mass`` [kg], ``diameter`` [m]; ``velocity`` [m/s] not needed)."""
        return CrushingLaw(mass, diameter, self.strength)

    @property
    def coefficient_at_1_per_s(self) -> float:
        """The strength law's coefficient at 1 s⁻¹, σ_ref·ε̇_ref^(−m_c) [Pa] (the catalogue's form, Jones 1997's A)."""
        return float(self.values[0] * self.reference_rate ** (-self.values[1]))

    @property
    def unfixed_parameters(self) -> tuple[str, ...]:
        return unfixed_parameters(self)


def _geometry(a: Approach, test: BarTest):
    """(A(s) [m²], ṡ [m/s], ρ [kg/m³], in contact) along a test's reconstructed α, α̇ over its main pulse."""
    d = test.diameter
    m = a.main_pulse
    alpha, rate = a.approach[m], a.rate[m]
    u = sphere_crush_depths(np.maximum(alpha, 0.0) / d)
    phi = (1.0 - u) ** 2 * (1.0 + 2.0 * u)
    live = (alpha > 0.0) & (rate > 0.0) & (u < CONSUMED)
    s = u * d
    sdot = np.where(live, rate / np.where(live, phi, 1.0), 0.0)
    area = np.where(live, np.pi * s * (d - s), 0.0)
    rho = test.mass / (math.pi / 6.0 * d**3)
    return area, sdot, rho, live


def _in_fit(a: Approach, test: BarTest) -> np.ndarray:
    """The samples of a test's main pulse the fit uses: those crushing at ṡ ≥ FIT_RATE_FRACTION·V (module docstring)."""
    sdot = _geometry(a, test)[1]
    keep = np.zeros(a.force.size, bool)
    keep[np.flatnonzero(a.main_pulse)] = sdot >= FIT_RATE_FRACTION * test.velocity
    return keep


def crushing_force(values, reference_rate: float, geometry, diameter: float) -> np.ndarray:
    """The law's force [N] on a test's (A, ṡ, ρ, live) of :func:`_geometry`: A·[σ_c(ṡ/d) + ρ·ṡ²], σ_c the
    power law above RATE_FLOOR and its linear ramp below (as :class:`PowerLawStrength` evaluates it)."""
    sigma_ref, m = values
    area, sdot, rho, live = geometry
    rate = sdot / diameter
    floor = sigma_ref * (RATE_FLOOR / reference_rate) ** m
    with np.errstate(divide="ignore", invalid="ignore"):
        sigma = np.where(rate >= RATE_FLOOR, sigma_ref * (np.maximum(rate, RATE_FLOOR) / reference_rate) ** m, floor * rate / RATE_FLOOR)
    return np.where(live, area * (sigma + rho * sdot * sdot), 0.0)


def _at_bounds(x) -> tuple[str, ...]:
    """The crushing law's parameters (values ``x``) within 1 % of a bound of the search (their names)."""
    return tuple(
        name
        for name, xi, lo, hi in zip(CRUSHING_PARAMETERS, x, CRUSHING_LOWER, CRUSHING_UPPER)
        if abs(xi - lo) <= 0.01 * max(abs(lo), 1e-2) or abs(xi - hi) <= 0.01 * abs(hi)
    )


def identify_crushing(tests, rod: Rod) -> tuple[CrushingIdentifiedLaw, tuple[Approach, ...]]:
    """Fit one crushing strength law, and each test's first contact, to all tests (module docstring); returns the
    law and the approaches, their α from the fitted first contact, with their ``fitted_force``."""
    from dataclasses import replace

    from scipy.optimize import least_squares
    from scipy.sparse import lil_matrix
    from scipy.stats import t as t_dist

    tests = tuple(tests)
    if len(tests) < 2:
        raise InputError("identify: need at least two tests")
    n = len(tests)
    approaches = tuple(reconstruct_approach(t, rod) for t in tests)
    approaches = tuple(replace(a, main_pulse=_in_fit(a, t)) for a, t in zip(approaches, tests))
    rates = [t.velocity / t.diameter for t in tests]
    reference = float(math.exp(np.mean(np.log(rates))))
    meas = [a.force[a.main_pulse] for a in approaches]
    F0s = [float(a.force.max()) for a in approaches]
    weights = [1.0 / (F0 * math.sqrt(f.size)) for F0, f in zip(F0s, meas)]
    bound = np.array([START_SHIFT_FRACTION * t.diameter / t.velocity for t in tests])
    lower = np.concatenate([CRUSHING_LOWER, -bound])
    upper = np.concatenate([CRUSHING_UPPER, bound])
    scale = np.concatenate([CRUSHING_SCALE, np.full(n, SHIFT_SCALE)])

    def shifted(i: int, shift: float) -> Approach:
        a = approaches[i]
        return replace(a, approach=a.approach - tests[i].velocity * shift)

    geometries: dict = {}  # (test, shift) -> _geometry: the strength's steps of the Jacobian leave the shifts, and the crush depths, as they were

    def force(z, i: int) -> np.ndarray:
        key = (i, float(z[2 + i]))
        if key not in geometries:
            if len(geometries) > 64 * n:
                geometries.clear()
            geometries[key] = _geometry(shifted(i, key[1]), tests[i])
        return crushing_force(z[:2], reference, geometries[key], tests[i].diameter)

    def fit(keep, start):
        keep = list(keep)
        sparsity = lil_matrix((sum(meas[i].size for i in keep), 2 + n), dtype=int)  # a shift moves its own test only
        sparsity[:, :2] = 1
        row = 0
        for i in keep:
            sparsity[row : row + meas[i].size, 2 + i] = 1
            row += meas[i].size

        def residual(z):
            return np.concatenate([weights[i] * (force(z, i) - meas[i]) for i in keep])

        return least_squares(residual, start, bounds=(lower, upper), x_scale=scale, jac_sparsity=sparsity)

    every = range(n)
    sol = fit(every, np.concatenate([CRUSHING_START, np.zeros(n)]))
    if n >= JACKKNIFE_MIN_TESTS:
        # delete-one-test jackknife: the tests are independent, the samples within one are not (the
        # approach integrates the force's noise); each refit starts from the whole fit
        drops = np.array([fit([j for j in every if j != i], sol.x).x[:2] for i in every])
        dev = drops - drops.mean(axis=0)
        cov = (n - 1) / n * dev.T @ dev
        half = t_dist.ppf(0.975, n - 1) * np.sqrt(np.maximum(np.diag(cov), 0.0))
    else:
        s = np.maximum(np.abs(sol.x), scale)  # the columns of J differ by ~1e14 in Pa against s: invert J·diag(s)
        Js = sol.jac.toarray() * s
        dof = max(sol.fun.size - sol.x.size, 1)
        cov = (float(sol.fun @ sol.fun) / dof * np.linalg.pinv(Js.T @ Js) * np.outer(s, s))[:2, :2]
        half = Z95 * np.sqrt(np.maximum(np.diag(cov), 0.0))
    fits = [force(sol.x, i) for i in every]
    rms = np.array([math.sqrt(np.mean((f - y) ** 2)) / F0 for f, y, F0 in zip(fits, meas, F0s)])
    v, d = [float(t.velocity) for t in tests], [float(t.diameter) for t in tests]
    ranges = {"velocity_m_s": [min(v), max(v)], "diameter_m": [min(d), max(d)], "strain_rate_1_s": [min(rates), max(rates)]}
    x = sol.x[:2]
    shifts = sol.x[2:].copy()
    law = CrushingIdentifiedLaw(CRUSHING_PARAMETERS, x.copy(), half, reference, max(d), rms, float(sol.cost), ranges, cov, _at_bounds(x), shifts)
    return law, tuple(replace(shifted(i, shifts[i]), fitted_force=f) for i, f in zip(every, fits))
