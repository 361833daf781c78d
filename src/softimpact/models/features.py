"""Features of a sampled history: the first zero crossing and the first lobe's peak.

Used by the beam summary (when the bending strain first changes sign) and by
calibration (the paper compares the first lobe of the gauge strains).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["first_zero_crossing", "first_lobe_peak"]


def first_zero_crossing(t, y, fraction: float = 0.25) -> float:
    """Time at which y first changes sign after its first excursion beyond ``fraction``·max|y|."""
    big = np.flatnonzero(np.abs(y) > fraction * np.max(np.abs(y)))
    if big.size == 0:
        return math.nan
    k0 = big[0]
    later = np.flatnonzero(np.sign(y[k0:]) == -np.sign(y[k0]))
    if later.size == 0:
        return math.nan
    k = k0 + later[0]
    return float(t[k - 1] + (t[k] - t[k - 1]) * y[k - 1] / (y[k - 1] - y[k]))


def first_lobe_peak(t, y, fraction: float = 0.25) -> float:
    """Largest |y| of the first main lobe: from the first excursion beyond ``fraction``·max|y|
    to the first zero crossing after it (the strain amplitude the paper compares)."""
    z = first_zero_crossing(t, y, fraction)
    sel = t <= z if math.isfinite(z) else np.ones(t.size, bool)
    return float(np.max(np.abs(y[sel])))
