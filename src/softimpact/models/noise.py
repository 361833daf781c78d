"""Measurement noise: robust estimates of the standard deviation of white noise."""

from __future__ import annotations

import math

import numpy as np

__all__ = ["robust_sigma", "white_noise_sigma"]


def robust_sigma(samples: np.ndarray, axis: int = -1) -> np.ndarray | float:
    """σ of noise on ``samples`` that carry no signal (a pre-trigger part, a residual).

    The median absolute deviation scaled to the normal distribution
    (``scipy.stats.median_abs_deviation(scale="normal")``): a few spikes or a
    pulse's edge move it little. Shape: ``samples`` without ``axis``.
    """
    from scipy.stats import median_abs_deviation

    return median_abs_deviation(np.asarray(samples, float), axis=axis, scale="normal")


def white_noise_sigma(y: np.ndarray, axis: int = -1) -> np.ndarray | float:
    """σ of white noise on ``y`` from its first differences, insensitive to a smooth pulse.

    The differences of white noise of σ have σ·√2; their :func:`robust_sigma`
    estimates that (a smooth pulse moves few differences far). Shape: ``y``
    without ``axis``.
    """
    return robust_sigma(np.diff(np.asarray(y, float), axis=axis), axis=axis) / math.sqrt(2.0)
