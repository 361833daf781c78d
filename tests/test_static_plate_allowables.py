"""A static plate run checks its mid-surface strains against the ply allowables: a von Kármán plate pressed far past
first-ply failure says so, where it used to report w/h 150 without a flag."""

import math
import warnings

import pytest

import softimpact as si
from softimpact.models.laminate import PLIES, Stack
from softimpact.models.validity import ValidityWarning
from softimpact.workflows.plate_impact import membrane_strain_index


def test_membrane_index_of_a_stretch_along_x_is_the_weaker_ply_s_closed_form():
    """ε_x = 0.1 % on [0/90]s: the 90° plies carry it across their fibres, index ε·E2/Yt; the 0° plies ε·E1/Xt (smaller)."""
    stack = Stack(PLIES["T300/934"], (0.0, 90.0, 90.0, 0.0))
    ply = stack.ply
    E1, E2 = ply.E1, ply.E2  # the plane-stress compliance's 1/S11 and 1/S22: the allowable strains are X/E1 and Y/E2
    eps = 1e-3
    expected = max(eps / (ply.strength.Yt / E2), eps / (ply.strength.Xt / E1))
    assert membrane_strain_index(stack, [[eps, 0.0, 0.0]]) == pytest.approx(expected, rel=1e-12)
    assert membrane_strain_index(stack, [[0.0, 0.0, 0.0]]) == 0.0


@pytest.mark.parametrize("pressure, failed", [("20 psi", False), ("1e6 psi", True)])
def test_a_plate_pressed_past_its_allowables_is_flagged(pressure, failed):
    """A clamped 8-in [90/0]2s T300/934 plate: 20 psi (w/h about 4, index under 1) passes; 1e6 psi (w/h about 150) is flagged."""
    plate = si.Plate(length="8 in", width="8 in", laminate=si.Laminate("T300/934", "[90/0]2s"), elements=(4, 4), kinematics="von-karman", support="clamped")
    with warnings.catch_warnings(record=True) as heard:
        warnings.simplefilter("always")
        v = si.press(plate, pressure=pressure, load_steps=10).summary()["validity"]
    assert any(issubclass(w.category, ValidityWarning) and "lower bound" in str(w.message) for w in heard) is failed
    assert (v["membrane_strain_index"] > 1.0) is failed
    assert any("lower bound" in f and "ply allowables" in f for f in v["flags"]) is failed
    assert math.isfinite(v["deflection_over_thickness"])


def test_a_linear_plate_reports_no_membrane_index():
    """On a linear symmetric plate the mid-surface strains are zero whatever the load: no index is reported (its w/h flag speaks)."""
    plate = si.Plate(length="8 in", width="8 in", laminate=si.Laminate("T300/934", "[90/0]2s"), elements=(4, 4), kinematics="linear", support="clamped")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        v = si.press(plate, pressure="200 psi").summary()["validity"]
    assert "membrane_strain_index" not in v and v["deflection_over_thickness"] > 0.5
