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


def test_a_later_contact_still_on_at_the_end_is_flagged():
    """A 1-in ball bounces on a thin plate eight times in its first millisecond; a run ending during its eighth contact is
    flagged, though its first contact ended: the force at the last step is not zero."""
    res, heard = _run("900 us", "[90/0]2s", "1 in")
    r = res.result
    assert math.isfinite(res.contact_duration) and len(r.contacts) > 1
    assert r.force[-1] > 0  # independent of the contact list: the force still acts at the last step
    flags = res.summary()["validity"]["flags"]
    assert any("had not ended at the end of the run" in f and "total impulse" in f for f in flags)
    assert heard


def test_a_run_ending_between_contacts_with_the_ball_coming_back_is_flagged():
    """Ended at 1050 µs, between the plate's eighth and ninth contacts, with the ball still moving toward the plate: flagged
    ("another contact may come"); the same run taken to 1200 µs has a contact starting after 1050 µs, the one the flag foretold."""
    res, heard = _run("1050 us", "[90/0]2s", "1 in")
    r = res.result
    assert r.force[-1] == 0 and r.final_velocity > 0
    assert any("still moves toward the target" in f for f in res.summary()["validity"]["flags"]) and heard
    longer, _ = _run("1200 us", "[90/0]2s", "1 in")
    assert any(c.start > 1050e-6 for c in longer.result.contacts)


def test_a_ball_that_leaves_the_target_is_not_flagged():
    """A 1/2-in ball on the long beam makes three contacts and leaves at about −1.1 m/s after 634 µs: a run to 700 µs is not
    flagged (nothing cut, nothing to come)."""
    beam = si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(40, 4))
    with warnings.catch_warnings(record=True) as heard:
        warnings.simplefilter("always")
        res = si.impact(beam, at="3 in", impactor=si.Sphere("steel", "0.5 in", velocity="100 in/s"), time_step="1 us", duration="700 us")
    assert res.result.final_velocity < 0 and res.result.force[-1] == 0
    assert not any(getattr(w.message, "flag", "") == "contact_past_run_end" for w in heard)
