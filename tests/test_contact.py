"""Hertz contact, eqs (1)-(3): models.contact_laws.HertzLaw."""

import math

import numpy as np
import pytest

from softimpact.models.contact_laws import HertzLaw
from softimpact.models.materials import Material

STEEL = Material("steel", 207e9, 0.29, 7830.0)
AL = Material("al", 69e9, 0.33, 2700.0)


def test_flat_constant_matches_eq3_by_hand():
    """K = 4/3·sqrt(R)·k1k2/(k1+k2) with k = E/(1-ν²), evaluated by hand here."""
    R = 0.008
    k1, k2 = 207e9 / (1 - 0.29**2), 69e9 / (1 - 0.33**2)
    expected = 4 / 3 * math.sqrt(R) * k1 * k2 / (k1 + k2)
    assert math.isclose(HertzLaw.sphere_on_flat(R, STEEL, AL).K, expected, rel_tol=1e-14)


def test_sphere_on_huge_sphere_tends_to_flat():
    """Eq (2) tends to eq (3) as the second radius grows without bound."""
    flat = HertzLaw.sphere_on_flat(0.008, STEEL, AL).K
    huge = HertzLaw.sphere_on_sphere(0.008, 8e6, STEEL, AL).K
    assert math.isclose(huge, flat, rel_tol=1e-8)


def test_stiffness_and_energy_are_consistent_with_force():
    """stiffness = dF/dα and d(energy)/dα = F, by central differences."""
    law = HertzLaw(6.8e9, 0.008)
    a = np.linspace(1e-6, 1e-4, 7)
    h = 1e-10
    assert np.allclose(law.stiffness(a), (law.force(a + h) - law.force(a - h)) / (2 * h), rtol=1e-6)
    assert np.allclose(law.force(a), (law.energy(a + h) - law.energy(a - h)) / (2 * h), rtol=1e-6)


@pytest.mark.parametrize("alpha", [-1e-5, 0.0])
def test_no_tension(alpha):
    """No force, stiffness or energy when the bodies do not overlap (scalar and array paths)."""
    law = HertzLaw(6.8e9, 0.008)
    assert law.force(alpha) == 0.0 and law.stiffness(alpha) == 0.0 and law.energy(alpha) == 0.0
    assert law.force(np.array([alpha]))[0] == 0.0
