"""The one check of a sampled series (models.sampling) and the four places that use it."""

import numpy as np
import pytest

from softimpact.errors import InputError
from softimpact.models.sampling import series_problem

T = np.linspace(0.0, 1e-3, 101)
Y = np.sin(2e3 * np.pi * T)


def _with(a, k, v):
    a = a.copy()
    a[k] = v
    return a


@pytest.mark.parametrize(
    "t, y, kw, phrase",
    [
        (T, Y[:-1], {}, "1-D columns of one length"),
        (T[:3], Y[:3], {"min_samples": 4}, "too short: 3 samples (need at least 4)"),
        (_with(T, 5, np.nan), Y, {}, "time: 1 NaN or infinite values (first at sample 5)"),
        (T, _with(Y, 0, np.inf), {"what": "strain"}, "strain: 1 NaN or infinite values (first at sample 0)"),
        (_with(T, 10, T[9]), Y, {}, "time is not strictly increasing at sample 10"),
        (_with(T, 10, T[10] + 0.3 * (T[1] - T[0])), Y, {"uniform": True}, "not evenly spaced"),
    ],
)
def test_each_fault_is_named(t, y, kw, phrase):
    """Each broken property of a series is reported by its own phrase, samples numbered from 0 (their index)."""
    assert phrase in series_problem(t, y, **kw)


def test_a_good_series_has_no_problem():
    """An evenly sampled finite series of one length passes every check, the uniform one too."""
    assert series_problem(T, Y, min_samples=101, uniform=True) is None


def test_the_users_raise_with_the_shared_phrase():
    """Conditioning, dispersion and the reduction all refuse a repeated time stamp with the shared phrase."""
    from softimpact.models.dispersion import RoundBar, propagate
    from softimpact.workflows.conditioning import condition_record
    from softimpact.workflows.reduction import Record, _validate

    t = _with(T, 10, T[9])
    with pytest.raises(InputError, match="conditioning: time is not strictly increasing at sample 10"):
        condition_record(t, Y, 0.1, 1.0, 5000.0)
    with pytest.raises(InputError, match="propagate: time is not strictly increasing at sample 10"):
        propagate(t, Y, 0.1, RoundBar(5000.0, 0.3, 0.01))
    with pytest.raises(InputError, match="rec: time is not strictly increasing at sample 10"):
        _validate(Record("rec", t, Y))
