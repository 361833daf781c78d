"""Choice of λ for a non-negative Tikhonov deconvolution: discrepancy, L-curve, GCV with and without a floor."""

import numpy as np
import pytest
from scipy.linalg import toeplitz
from scipy.signal import lfilter

from softimpact.models.pulses import SkewedPulse
from softimpact.models.regularisation import (
    choose_discrepancy,
    choose_gcv,
    choose_l_curve,
    noise_sigma,
    regularisation_curve,
)

# A synthetic convolution problem with a known non-negative solution: a damped-oscillator kernel
# (like a gauge impulse response) applied to an eq-15 pulse; second-difference regulariser.
N = 120
T = np.arange(N, dtype=float)
KERNEL = np.exp(-T / 15) * np.sin(2 * np.pi * T / 20)
G = toeplitz(KERNEL, np.zeros(N))
F_TRUE = SkewedPulse(1.0, 8.0, 40.0)(T)
L = np.diff(np.eye(N), 2, axis=0)
LAMBDAS = np.logspace(-3, 2, 41)
SIGMA = 0.02 * np.max(np.abs(G @ F_TRUE))


def noise(rng, n, window):
    """Unit-variance noise, white (window 1) or correlated by a moving average of ``window`` samples."""
    e = lfilter(np.ones(window) / window, 1, rng.standard_normal(n + 40))[40:]
    return e / e.std()


def problem(seed, window):
    """Noisy data and the σ measured from a separate pre-trigger stretch of the same noise."""
    rng = np.random.default_rng(seed)
    d = G @ F_TRUE + SIGMA * noise(rng, N, window)
    return d, noise_sigma(SIGMA * noise(rng, 300, window))


def errors(d):
    """Relative error of the non-negative solution at every λ of the grid, from the known solution."""
    _, sols = regularisation_curve(G, d, L, LAMBDAS)
    return np.linalg.norm(sols - F_TRUE, axis=1) / np.linalg.norm(F_TRUE)


def at(err, lam):
    return err[int(np.argmin(np.abs(LAMBDAS - lam)))]


def test_noise_sigma_is_robust_to_spikes():
    """The normal-scaled MAD gives σ of Gaussian noise within 10 % even with 2 % of wild samples."""
    x = np.random.default_rng(0).standard_normal(2000) * 3.0
    x[::50] = 1e3
    assert noise_sigma(x) == pytest.approx(3.0, rel=0.1)


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_rules_with_white_noise(seed):
    """White noise: discrepancy within 4×, L-curve within 2.5× and floored GCV within 2× of the grid's best error."""
    d, sigma = problem(seed, 1)
    err = errors(d)
    best = err.min()
    assert at(err, choose_discrepancy(G, d, L, LAMBDAS, sigma).lam) < 4 * best
    assert at(err, choose_l_curve(G, d, L, LAMBDAS).lam) < 2.5 * best
    assert at(err, choose_gcv(G, d, L, LAMBDAS, sigma).lam) < 2 * best
    assert np.all(choose_gcv(G, d, L, LAMBDAS, sigma).solution >= 0)


@pytest.mark.slow
def test_gcv_without_floor_undersmooths_correlated_noise():
    """Correlated noise (6-sample moving average): unfloored GCV loses accuracy (it fits the noise); the floor never does worse."""
    ratios, floored = [], []
    for seed in (0, 1, 2):
        d, sigma = problem(seed, 6)
        err = errors(d)
        plain = choose_gcv(G, d, L, LAMBDAS, floor=False)
        guarded = choose_gcv(G, d, L, LAMBDAS, sigma)
        ratios.append(at(err, plain.lam) / err.min())
        floored.append(at(err, guarded.lam) / err.min())
        assert guarded.lam >= plain.lam
    assert np.mean(ratios) > 1.3
    assert np.all(np.array(floored) <= np.array(ratios) + 1e-12)
