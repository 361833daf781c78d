"""A contact law given to the API as an object goes by its CONTACT_LAWS name, as a case file's `contact.law` names it."""

import pytest

import softimpact as si
from softimpact.models.contact_laws import HertzLaw, HuntCrossleyLaw


@pytest.mark.parametrize(
    "law, name",
    [(HertzLaw(K=1e9, R=6.35e-3), "hertz"), (HuntCrossleyLaw(K=1e9, R=6.35e-3, restitution=0.8, impact_velocity=2.54), "hunt-crossley")],
)
def test_a_law_object_runs_under_its_table_name(law, name):
    """si.impact with a law object: the problem's law_name is the table's name (the validity envelopes of the Hertz family key on it), not the class name."""
    beam = si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(40, 4))
    res = si.impact(beam, at="3 in", impactor=si.Sphere("steel", "0.5 in", velocity="100 in/s"), law=law, time_step="1 us", duration="60 us")
    assert res.problem.law_name == name
