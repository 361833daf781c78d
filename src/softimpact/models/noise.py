"""Measurement noise: a robust estimate of the standard deviation of white noise."""

from __future__ import annotations

import math

import numpy as np

__all__ = ["white_noise_sigma"]


def white_noise_sigma(y: np.ndarray, axis: int = -1) -> np.ndarray | float:
    """σ of white noise on ``y`` from its first differences, insensitive to a smooth pulse.

    The differences of white noise of σ have σ·√2; their median absolute
    deviation, scaled to the normal distribution, estimates that robustly
    (a smooth pulse moves few differences far). Shape: ``y`` without ``axis``.
    """
    from scipy.stats import median_abs_deviation

    d = np.diff(np.asarray(y, float), axis=axis)
    return median_abs_deviation(d, axis=axis, scale="normal") / math.sqrt(2.0)
