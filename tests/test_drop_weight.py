"""A drop weight's striker (``impactor.striker = true``): a hemispherical tup of a diameter on a carriage of a
given mass, named by its energy as ASTM D7136 names an impact (v = sqrt(2E/m))."""

import math

import pytest

from softimpact.errors import InputError
from softimpact.input.impact_case import impact_problem, load_impact_case
from softimpact.input.toml import load_toml, locate


def _data(**impactor) -> dict:
    data = load_toml(locate("d7136-drop-weight"))
    data["impactor"] = impactor
    return data


def test_the_builtin_drop_weight_has_the_velocity_of_its_energy():
    """30 J on 5.5 kg: v = sqrt(2·30/5.5) = 3.303 m/s; the carriage's mass, not a steel sphere's (16.7 g)."""
    problem, _ = load_impact_case("d7136-drop-weight")
    assert problem.impactor.mass == 5.5
    assert problem.impactor.diameter == pytest.approx(0.016)
    assert problem.impactor.velocity == pytest.approx(math.sqrt(2 * 30 / 5.5), rel=1e-12)
    assert 0.5 * problem.impactor.mass * problem.impactor.velocity**2 == pytest.approx(30.0, rel=1e-12)


def test_a_velocity_gives_the_same_striker_as_its_energy():
    base = {"striker": True, "material": "steel", "diameter": "16 mm", "mass": "5.5 kg"}
    by_energy, _ = impact_problem(_data(**base, energy="30 J"))
    by_velocity, _ = impact_problem(_data(**base, velocity=f"{math.sqrt(60 / 5.5)} m/s"))
    assert by_velocity.impactor.velocity == pytest.approx(by_energy.impactor.velocity, rel=1e-12)


@pytest.mark.parametrize(
    ("impactor", "named"),
    [
        ({"striker": True, "material": "steel", "diameter": "16 mm", "mass": "5.5 kg", "energy": "30 J", "velocity": "3 m/s"}, "impactor.velocity"),
        ({"striker": True, "material": "steel", "diameter": "16 mm", "mass": "5.5 kg"}, "impactor.velocity"),
        ({"striker": True, "material": "steel", "diameter": "16 mm", "energy": "30 J"}, "impactor.mass"),
        ({"striker": "yes", "material": "steel", "diameter": "16 mm", "mass": "5.5 kg", "energy": "30 J"}, "impactor.striker"),
        ({"striker": True, "threat": {"hail": "38.1 mm"}, "mass": "5.5 kg", "energy": "30 J"}, "impactor.striker"),
        ({"striker": True, "material": "steel", "diameter": "16 mm", "mass": "5.5 kg", "energy": "-30 J"}, "impactor.energy"),
    ],
)
def test_a_striker_that_cannot_be_built_is_refused_naming_the_key(impactor, named):
    with pytest.raises(InputError, match=named.replace(".", r"\.")):
        impact_problem(_data(**impactor))


def test_a_near_field_narrower_than_the_contact_is_refused_at_once():
    """The contact may reach the striker's diameter (16 mm) from the impact point: a near field of 16 mm half-width is
    refused when the case is read, naming the key and the default, not after the model is built."""
    data = load_toml(locate("d7136-drop-weight"))
    data["damage"]["near_field"] = "16 mm"
    with pytest.raises(InputError, match=r"damage\.near_field.*16 mm"):
        impact_problem(data)
