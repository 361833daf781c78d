"""What a usable sampled series is: the checks every reader and workflow of a record makes.

A series is a time column t [s] and a value column y of one length, every value
finite, t strictly increasing; some uses also need at least so many samples or an
even step. :func:`series_problem` says, in a phrase, the first of these a series
breaks; the caller adds whose series it is (a file, a record's name, a function)
and raises its own error.
"""

from __future__ import annotations

import numpy as np

__all__ = ["series_problem", "UNIFORM_TOLERANCE"]

UNIFORM_TOLERANCE = 1e-6  # of the mean step: a clock that departs less is evenly spaced (rounding of t0 + k·dt)


def series_problem(t: np.ndarray, y: np.ndarray, *, min_samples: int = 2, what: str = "signal", uniform: bool = False) -> str | None:
    """The first thing wrong with (``t``, ``y``) as a sampled series, in a phrase; None when nothing is.

    In order: 1-D columns of one length; at least ``min_samples`` samples; every
    value finite (``what`` names the value column); time strictly increasing; with
    ``uniform``, every step within UNIFORM_TOLERANCE of the mean step. Samples are
    numbered from 0 in the phrases (the index into the columns, as the record readers say).
    """
    t = np.asarray(t)
    y = np.asarray(y)
    if t.ndim != 1 or y.ndim != 1 or t.shape != y.shape:
        return f"time and {what} must be 1-D columns of one length, got shapes {t.shape} and {y.shape}"
    if t.size < min_samples:
        return f"too short: {t.size} samples (need at least {min_samples})"
    for name, column in (("time", t), (what, y)):
        bad = ~np.isfinite(column)
        if bad.any():
            return f"{name}: {int(bad.sum())} NaN or infinite values (first at sample {int(np.argmax(bad))})"
    d = np.diff(t)
    if np.any(d <= 0):
        k = int(np.argmax(d <= 0))
        return f"time is not strictly increasing at sample {k + 1} ({float(t[k]):.9g} s then {float(t[k + 1]):.9g} s): repeated or unordered time stamps"
    if uniform:
        dt = (t[-1] - t[0]) / (t.size - 1)
        if np.max(np.abs(d - dt)) > UNIFORM_TOLERANCE * dt:
            return "time is not evenly spaced"
    return None
