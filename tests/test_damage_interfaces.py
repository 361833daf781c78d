"""The interface shear averaged around the load: equal to the axisymmetric (plate) and beam equilibrium under Hertz's
pressure integrated numerically here, finite and converging as the contact concentrates while the value at the
contact's edge diverges, and reported per interface in the damage block."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from softimpact.models.failure import interlaminar_shear
from softimpact.models.laminate import PLIES, Stack
from softimpact.workflows.damage import RADIAL_DIRECTIONS, impact_damage, mean_shear_resultant

PLY = PLIES["T300/934"]
X = PLY.strength


def _hertz(F, a):
    """Hertz's pressure p(r) = (3F/(2πa²))·sqrt(1 − r²/a²) on the disc r < a (total F)."""
    return lambda r: 3 * F / (2 * math.pi * a * a) * math.sqrt(max(0.0, 1 - (r / a) ** 2))


def _plate_mean_by_quadrature(F, a, R):
    """(1/πR²)∫₀^R q(r)·2πr dr with q(r) = F(r)/(2πr), F(r) = ∫₀^r p·2πs ds, by nested quadrature."""
    p = _hertz(F, a)

    def enclosed(r):
        return quad(lambda s: p(s) * 2 * math.pi * s, 0, min(r, a))[0]

    return quad(lambda r: enclosed(r), 0, R, points=[a], limit=200)[0] / (math.pi * R * R)


def _beam_mean_by_quadrature(F, a, R, b):
    """Mean of V(x)/b over 0 ≤ x ≤ R, V(x) = ∫₀^x w, w(x) = ∫ p(sqrt(x² + y²)) dy across the disc: by quadrature."""
    p = _hertz(F, a)

    def line_load(x):
        half = math.sqrt(max(0.0, a * a - x * x))
        return 2 * quad(lambda y: p(math.hypot(x, y)), 0, half)[0] if half > 0 else 0.0

    def shear(x):
        return quad(line_load, 0, min(x, a))[0]

    return quad(shear, 0, R, points=[a], limit=200)[0] / (R * b)


@pytest.mark.parametrize("a_over_R", [0.05, 0.4, 1.0])
def test_mean_resultant_is_the_equilibrium_under_hertz_pressure(a_over_R):
    """The disc mean F·(R − 3πa/16)/(πR²) (plate) and the length mean F·(R − 3a/8)/(2bR) (beam) equal the mean of the
    equilibrium resultant with Hertz's pressure integrated numerically, to 1e-6."""
    F, R, b = 1000.0, 4e-3, 25e-3
    a = a_over_R * R
    assert float(mean_shear_resultant(F, a, R, None)) == pytest.approx(_plate_mean_by_quadrature(F, a, R), rel=1e-6)
    assert float(mean_shear_resultant(F, a, R, b)) == pytest.approx(_beam_mean_by_quadrature(F, a, R, b), rel=1e-6)


def test_mean_converges_as_the_contact_concentrates_while_the_edge_value_diverges():
    """Halving the contact radius a (R fixed) four times: the disc mean's change halves each time (first order in a,
    towards the point load's F/(πR)), while the resultant at the contact's edge F/(2πa) doubles each time."""
    F, R = 1000.0, 3e-3
    a = R / 4 / 2.0 ** np.arange(5)
    mean = mean_shear_resultant(F, a, R, None)
    steps = np.abs(np.diff(mean))
    assert np.allclose(steps[1:] / steps[:-1], 0.5, rtol=1e-9)
    assert abs(mean[-1] - F / (math.pi * R)) < steps[-1] * 1.0000001
    edge = F / (2 * math.pi * a)
    assert np.allclose(edge[1:] / edge[:-1], 2.0)


def test_mean_refuses_a_radius_inside_the_contact():
    """An averaging disc smaller than the contact disc is refused (the formula assumes the disc covers the contact)."""
    with pytest.raises(Exception, match="radius"):
        mean_shear_resultant(1.0, 2e-3, 1e-3, None)


@pytest.mark.parametrize("width", [None, 25e-3])
def test_damage_block_lists_the_mean_interface_shear_with_its_radius(width):
    """impact_damage on a [90/0]2s plate (beam of width 25 mm) with F(t) a half sine and a Hertz-like a(t): each
    interface between 90° and 0° plies has shear_mean_Pa = its equilibrium shear per unit resultant × max_t
    F·(R − 3πa/16)/(πR²) (F·(R − 3a/8)/(2bR)), R = max a + h (written out here), not above its point value
    shear_max_Pa, and the damage block carries the largest of them."""
    stack = Stack(PLY, (90.0, 0.0, 90.0, 0.0, 0.0, 90.0, 0.0, 90.0))
    t = np.linspace(0, 1e-4, 401)
    F = 2000.0 * np.sin(math.pi * t / t[-1])
    a = 1.5e-3 * np.sqrt(F / F.max())
    zero = np.zeros((3, t.size))
    d = impact_damage(stack, X, {"at_load": (zero, zero)}, F, a, width, time=t).summary()
    R = a.max() + stack.thickness
    if width is None:
        q = np.max(F * (R - 3 * math.pi * a / 16) / (math.pi * R * R))
    else:
        q = np.max(F * (R - 3 * a / 8) / (2 * width * R))
    directions = RADIAL_DIRECTIONS if width is None else (0.0,)
    unit = np.max([np.hypot(s.tau_xz, s.tau_yz) for s in (interlaminar_shear(PLY, stack.angles, X, dd) for dd in directions)], axis=0)
    assert len(d["interfaces"]) == 6
    for i in d["interfaces"]:
        k = int(i["between"].split()[1].split("/")[0]) - 1  # the interface below ply k + 1
        assert i["shear_mean_radius_m"] == pytest.approx(R, rel=1e-12)
        assert i["shear_mean_Pa"] == pytest.approx(unit[k] * q, rel=1e-9)
        assert 0 < i["shear_mean_Pa"] <= i["shear_max_Pa"]
    assert d["interface_shear_mean_max_Pa"] == max(i["shear_mean_Pa"] for i in d["interfaces"])
