"""A coupled run with a contact not ended when the run does says so, as a validity flag and a warning: the first
contact's peak force and impulse, or the total impulse and the target's peaks, cover the run only."""

import math
import warnings

import pytest

import softimpact as si
from softimpact.models.validity import ValidityWarning


def _run(duration: str, layup: str = "[90/0]5s", ball: str = "0.5 in"):
    plate = si.Plate(length="8 in", width="8 in", laminate=si.Laminate("T300/934", layup), elements=(4, 4))
    with warnings.catch_warnings(record=True) as heard:
        warnings.simplefilter("always")
        res = si.impact(plate, at=("4 in", "4 in"), impactor=si.Sphere("steel", ball, velocity="100 in/s"), time_step="1 us", duration=duration, units="SI")
    return res, [w for w in heard if issubclass(w.category, ValidityWarning) and getattr(w.message, "flag", "") == "contact_past_run_end"]


@pytest.mark.parametrize("duration,cut", [("20 us", True), ("400 us", False)])
def test_a_run_that_ends_in_contact_is_flagged(duration, cut):
    """A Hertz impact lasting 160 µs, run for 20 µs, is flagged (its contact duration unknown); run for 400 µs, not."""
    res, heard = _run(duration)
    flags = res.summary()["validity"]["flags"]
    assert any("had not ended at the end of the run" in f for f in flags) is cut
    assert bool(heard) is cut
    assert math.isnan(res.contact_duration) is cut


@pytest.mark.parametrize("duration,cut", [("900 us", True), ("1050 us", False)])
def test_a_later_contact_still_on_at_the_end_is_flagged(duration, cut):
    """A 1-in ball on a thin plate bounces on it eight times in its first millisecond; a run ending during a later contact is flagged, though
    its first contact ended (the force at the last step is not zero), and a run ending after the last contact is not."""
    res, heard = _run(duration, "[90/0]2s", "1 in")
    r = res.result
    assert math.isfinite(res.contact_duration) and len(r.contacts) > 1
    assert bool(r.force[-1] > 0) is cut  # independent of the contact list: the force still acts at the last step
    flags = res.summary()["validity"]["flags"]
    assert any("had not ended at the end of the run" in f and "total impulse" in f for f in flags) is cut
    assert bool(heard) is cut
