"""A coupled run whose first contact has not ended when the run does says so, as a validity flag and a warning: its
peak force, impulse and the target's peaks cover the run only."""

import math
import warnings

import pytest

import softimpact as si
from softimpact.models.validity import ValidityWarning


def _run(duration: str):
    plate = si.Plate(length="8 in", width="8 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(4, 4))
    with warnings.catch_warnings(record=True) as heard:
        warnings.simplefilter("always")
        res = si.impact(plate, at=("4 in", "4 in"), impactor=si.Sphere("steel", "0.5 in", velocity="100 in/s"), time_step="1 us", duration=duration, units="SI")
    return res, [w for w in heard if issubclass(w.category, ValidityWarning) and getattr(w.message, "flag", "") == "contact_past_run_end"]


@pytest.mark.parametrize("duration,cut", [("20 us", True), ("400 us", False)])
def test_a_run_that_ends_in_contact_is_flagged(duration, cut):
    """A Hertz impact lasting 160 µs, run for 20 µs, is flagged (its contact duration unknown); run for 400 µs, not."""
    res, heard = _run(duration)
    flags = res.summary()["validity"]["flags"]
    assert any("had not ended at the end of the run" in f for f in flags) is cut
    assert bool(heard) is cut
    assert math.isnan(res.contact_duration) is cut
