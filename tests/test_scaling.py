"""Scaling laws, eqs (4)-(7): fits recover known constants; intervals are honest."""

import numpy as np
import pytest

from softimpact.models.empirical import ScalingLaw
from softimpact.models.materials import lookup
from softimpact.models.specimens import BarSpec
from softimpact.workflows.reduction import Record, reduce_record
from softimpact.workflows.scaling import TestPoint, fit_groups, fit_line
from softimpact.workflows.synthetic import gauge_model, synthetic_record

from _support.constants import INCH

KNOWN = {0.5 * INCH: (ScalingLaw(4.25, 0.93, 0.25, 0.68), 1.1e-3), 0.375 * INCH: (ScalingLaw(4.0, 1.03, 0.20, 0.74), 0.46e-3)}


@pytest.fixture(scope="module")
def series_fit():
    """A series made by the bar FE from known α's (with tails and 1 % noise), reduced and fitted."""
    bar = BarSpec(lookup("Al 6061-T6"), 36 * INCH, 0.5 * INCH, 96)
    gauge = gauge_model(bar, 18 * INCH, 0.5e-6, 2.6e-3)
    rng = np.random.default_rng(42)
    points = []
    for d, (law, m) in KNOWN.items():
        for v_in in (1000, 2000, 3000, 4000, 5000):
            V = v_in * INCH
            pulse = law.pulse(m, d, V, tail=True)
            length = min(2.4e-3, 250e-6 + max(5 * pulse.main.duration, pulse.duration))
            t, y = synthetic_record(
                gauge,
                pulse,
                pre_trigger=250e-6,
                length=length,
                sample_interval=1e-6,
                noise=0.01,
                offset=rng.normal(0, 1e-5),
                clock_start=rng.uniform(0, 1),
                rng=rng,
            )
            r = reduce_record(Record(f"{d}-{v_in}", t, y), bar, 18 * INCH)
            points.append(TestPoint(r.name, V, m, d, r.peak_force, r.time_of_peak, r.duration, r.impulse))
    return fit_groups(points)


@pytest.mark.parametrize("d", list(KNOWN))
@pytest.mark.parametrize("name, tol", [("alpha1", 0.03), ("alpha2", 0.03), ("alpha3", 0.10), ("alpha4", 0.03)])
def test_known_constants_are_fitted_back(series_fit, d, name, tol):
    """Each group's α1, α2, α4 within 3 % and α3 within 10 % of the values the records were made with."""
    label = f"{d / INCH:.4g} in"
    assert series_fit[label].origin[name].slope == pytest.approx(getattr(KNOWN[d][0], name), rel=tol)


def test_pooled_group_exists(series_fit):
    """With two diameters there is a pooled fit over all ten tests."""
    assert len(series_fit["pooled"].points) == 10


def test_exact_line_through_origin():
    """Data exactly on y = 2x give slope 2, R² = 1 and a zero-width interval."""
    f = fit_line([1, 2, 3, 4], [2, 4, 6, 8])
    assert f.slope == pytest.approx(2) and f.r2 == pytest.approx(1)
    assert f.slope_ci[1] - f.slope_ci[0] == pytest.approx(0, abs=1e-12)


@pytest.mark.parametrize("origin", [True, False])
def test_confidence_intervals_cover_95_percent(origin):
    """Over 2000 noisy draws the 95 % interval holds the true slope 93-97 % of the time."""
    rng = np.random.default_rng(0)
    x = np.linspace(1, 5, 6)
    hits = 0
    for _ in range(2000):
        y = 1.5 * x + (0 if origin else 2.0) + rng.normal(0, 0.3, x.size)
        lo, hi = fit_line(x, y, origin).slope_ci
        hits += lo <= 1.5 <= hi
    assert 0.93 <= hits / 2000 <= 0.97


def test_repeat_shots_at_one_velocity():
    """Repeat shots at one velocity leave the affine fit undetermined (NaN), not a math error; the fit through the origin stands."""
    x, y = [2.0, 2.0, 2.0], [3.9, 4.0, 4.1]
    origin, affine = fit_line(x, y), fit_line(x, y, through_origin=False)
    assert origin.slope == pytest.approx(2.0)
    assert np.isnan(affine.slope) and np.isnan(affine.intercept)


def test_exact_data_gives_zero_width_intervals():
    """Data exactly on a line through the origin: the slope is exact and its interval has zero width."""
    fit = fit_line([1.0, 2.0, 3.0], [2.0, 4.0, 6.0])
    assert fit.slope == 2.0 and fit.slope_ci == (2.0, 2.0) and fit.r2 == 1.0
