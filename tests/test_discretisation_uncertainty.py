"""The discretisation uncertainty of a calibrated parameter (studies.calibration.discretisation_uncertainty)
against sequences whose limit is known in closed form."""

import math

import pytest

from softimpact.studies.calibration import discretisation_uncertainty
from softimpact.workflows.convergence import richardson


def _sequence(limit, c, ratio, order, levels=3):
    """f_k = limit + c·(h/r^k)^p, coarse → fine: an exactly p-th-order sequence."""
    return [limit + c * ratio ** (-order * k) for k in range(levels)]


@pytest.mark.parametrize("order", [2.0, 1.7])
def test_monotone_sequence_gives_its_true_error(order):
    """For an exactly p-th-order sequence (p ≤ the formal 2) the uncertainty is the finest level's true error |f3 − f∞|."""
    values = _sequence(10.0, 0.8, 2.0, order)
    conv = richardson(values, 2.0, 2.0, "peak_force")
    assert discretisation_uncertainty(conv, "peak_force", 20.0) == pytest.approx(abs(values[-1] - 10.0), rel=1e-9)


def test_alternating_sequence_is_bounded_by_its_last_change():
    """f_k = f∞ + c·(−0.4)^k: the limit lies between the two finest levels, so |f3 − f2| bounds the error and is used."""
    values = [5.0 + 0.3 * (-0.4) ** k for k in range(3)]
    conv = richardson(values, 2.0, 2.0, "duration")
    assert conv.status == "oscillatory"
    u = discretisation_uncertainty(conv, "duration", 20.0)
    assert u == pytest.approx(abs(values[2] - values[1]))
    assert u >= abs(values[2] - 5.0)


def test_unresolved_rise_keeps_the_first_order_bound_for_the_time_of_peak_only():
    """With fewer than 10 steps in the rise on the coarsest level, t_F0's uncertainty is at least |f3 − f2|
    (the order a first-order tail would give); F0's stays the Richardson estimate (one third of it at p = 2)."""
    values = _sequence(1.0, 0.2, 2.0, 2.0)
    conv = richardson(values, 2.0, 2.0, "time_of_peak", rise_steps=5.0)
    last = abs(values[2] - values[1])
    assert discretisation_uncertainty(conv, "time_of_peak", 5.0) == pytest.approx(last)
    assert discretisation_uncertainty(conv, "peak_force", 5.0) == pytest.approx(last / 3.0)


def test_round_off_only_when_every_level_agrees():
    """Three levels equal to round-off: zero. Two finest levels that agree exactly after a first change of 1 (a fit
    stuck, e.g. on a bound) are not converged: that change is kept as the uncertainty."""
    assert discretisation_uncertainty(richardson([2.0, 2.0, 2.0], 2.0, 2.0, "x"), "peak_force", 20.0) == 0.0
    conv = richardson([1.0, 2.0, 2.0], 2.0, 2.0, "x")
    assert discretisation_uncertainty(conv, "peak_force", 20.0) == pytest.approx(1.0)


@pytest.mark.parametrize("values", [[1.0, 1.1, 1.4], [1.0, 1.0 + 1e-3, 1.3]])
def test_diverging_keeps_at_least_the_last_change(values):
    """Differences that grow (no order can be observed): the whole range, never less than the last change |f3 − f2|."""
    conv = richardson(values, 2.0, 2.0, "x")
    assert conv.status == "diverging"
    u = discretisation_uncertainty(conv, "peak_force", 20.0)
    assert u == pytest.approx(max(values) - min(values))
    assert u >= abs(values[2] - values[1])


def test_unknown_rise_and_missing_level():
    """A rise of unknown resolution (NaN steps) keeps t_F0's first-order bound; a level without a finite value gives NaN."""
    values = _sequence(1.0, 0.2, 2.0, 2.0)
    conv = richardson(values, 2.0, 2.0, "time_of_peak")
    assert discretisation_uncertainty(conv, "time_of_peak", float("nan")) == pytest.approx(abs(values[2] - values[1]))
    assert math.isnan(discretisation_uncertainty(richardson([1.0, float("nan"), 1.2], 2.0, 2.0, "x"), "peak_force", 20.0))
