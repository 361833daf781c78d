"""Tail-shape ambiguity: α's whose intervals cover what the records cannot tell apart (issue 22, item 3)."""

import math

import numpy as np
import pytest

from softimpact.models.pulse_fit import fit_main_pulse
from softimpact.studies.series import with_tail_shapes
from softimpact.workflows.reduction import TAIL_FAMILIES, fit_tail_shapes
from softimpact.workflows.scaling import TestPoint, fit_groups

from _support.constants import INCH

# Table I's 1/2-in ball (α1 4.25, α2 0.93, α3 0.25) for the main pulse, written here independently of the code
ALPHA = {"alpha1": 4.25, "alpha2": 0.93, "alpha3": 0.25}
MASS, D = 1.1e-3, 0.5 * INCH
VELOCITIES = [v * INCH for v in (1000, 1500, 2000, 2500, 3000, 3500)]


def _record(V, rng, level=0.12, start=0.45, decay=0.6):
    """Eq (15) with Table I's α's, plus a tail that ramps in linearly under the falling main pulse from
    ``start``·T to ``level``·F0 at T and then decays exponentially over ``decay``·T; 1 % noise."""
    F0 = ALPHA["alpha1"] * MASS * V**2 / (2 * D)
    T = ALPHA["alpha2"] * D / V
    tp = ALPHA["alpha3"] * T
    t = np.arange(0.0, 3.0 * T, T / 400)
    main = np.where(t < tp, F0 * np.sin(np.pi * t / (2 * tp)), np.where(t < T, F0 * np.cos(np.pi * (t - tp) / (2 * (T - tp))), 0.0))
    ramp = level * F0 * np.clip((t - start * T) / ((1 - start) * T), 0, 1)
    tail = np.where(t < T, ramp, level * F0 * np.exp(-(t - T) / (decay * T)))
    return t, main + tail + 0.01 * F0 * rng.standard_normal(t.size)


@pytest.fixture(scope="module")
def series():
    """Six synthetic tests (1000-3500 in/s): the reported (main-pulse) points and each record's tail-family fits."""
    rng = np.random.default_rng(22)
    points, shapes = [], {}
    for k, V in enumerate(VELOCITIES):
        t, F = _record(V, rng)
        main = fit_main_pulse(t, F).fit.pulse
        name = f"V{k}"
        points.append(TestPoint(name, V, MASS, D, main.peak_force, main.time_of_peak, main.duration, float(np.trapezoid(F, t))))
        shapes[name] = fit_tail_shapes(t, F)
    return points, shapes


def test_every_tail_family_is_fitted(series):
    """Each record gets the six families (knee, ramp-under, linear, power law, free ramp, early ramp) with a finite AIC."""
    _, shapes = series
    for fits in shapes.values():
        assert tuple(f.family for f in fits) == TAIL_FAMILIES and all(math.isfinite(f.aic) for f in fits)


@pytest.mark.parametrize("name", ["alpha2", "alpha3"])
def test_intervals_with_the_tail_shape_term_contain_the_truth(series, name):
    """With tails that ramp in under the main pulse, α2 and α3 with the tail_shape term contain Table I's
    values that made the records; the term is a separate, positive half-width."""
    points, shapes = series
    (fit,) = with_tail_shapes(fit_groups(points), shapes).values()
    term = fit.tail_shape
    assert term is not None and term.half_widths[name] > 0
    lo, hi = term.interval(name, fit.origin[name])
    assert lo <= ALPHA[name] <= hi, (name, fit.origin[name].slope_ci, term.half_widths[name], term.aic)
