"""Measurement noise: robust estimates of the standard deviation of white noise."""

from __future__ import annotations

import math
from statistics import NormalDist

import numpy as np

__all__ = ["robust_sigma", "white_noise_sigma"]

NORMAL_QUARTILE = NormalDist().inv_cdf(0.75)  # Φ⁻¹(3/4) = 0.6744897…: MAD of a unit normal


def robust_sigma(samples: np.ndarray, axis: int = -1) -> np.ndarray | float:
    """σ of noise on ``samples`` that carry no signal (a pre-trigger part, a residual).

    The median absolute deviation scaled to the normal distribution, MAD/Φ⁻¹(3/4):
    a few spikes or a pulse's edge move it little. Shape: ``samples`` without ``axis``.
    It equals ``scipy.stats.median_abs_deviation(scale="normal")`` (tests/test_noise.py),
    computed here with numpy because importing scipy.stats costs 0.4 s of every
    command's start.
    """
    x = np.asarray(samples, float)
    deviation = np.abs(x - np.median(x, axis=axis, keepdims=True))
    return np.median(deviation, axis=axis) / NORMAL_QUARTILE


def white_noise_sigma(y: np.ndarray, axis: int = -1) -> np.ndarray | float:
    """σ of white noise on ``y`` from its first differences, insensitive to a smooth pulse.

    The differences of white noise of σ have σ·√2; their :func:`robust_sigma`
    estimates that (a smooth pulse moves few differences far). Shape: ``y``
    without ``axis``.
    """
    return robust_sigma(np.diff(np.asarray(y, float), axis=axis), axis=axis) / math.sqrt(2.0)
