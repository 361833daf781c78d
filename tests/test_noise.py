"""The robust noise estimate against scipy's median_abs_deviation and against the σ of known noise."""

import numpy as np
import pytest
from scipy.stats import median_abs_deviation

from softimpact.models.noise import robust_sigma, white_noise_sigma


def test_equals_scipy_median_abs_deviation_normal_scale():
    """Same values as scipy.stats.median_abs_deviation(scale="normal"), along either axis."""
    x = np.random.default_rng(1).standard_t(3, size=(4, 501))
    assert np.allclose(robust_sigma(x, axis=1), median_abs_deviation(x, axis=1, scale="normal"), rtol=1e-14)
    assert np.allclose(robust_sigma(x, axis=0), median_abs_deviation(x, axis=0, scale="normal"), rtol=1e-14)


def test_white_noise_under_a_pulse():
    """σ of white noise recovered within 3 % under a smooth pulse that dwarfs it (200 000 samples)."""
    t = np.linspace(0, 1, 200_000)
    y = 50 * np.exp(-(((t - 0.5) / 0.05) ** 2)) + 0.2 * np.random.default_rng(2).standard_normal(t.size)
    assert white_noise_sigma(y) == pytest.approx(0.2, rel=0.03)
