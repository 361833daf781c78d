"""Contact laws of models.contact_laws: consistency of force, tangents, energy, radius, memory."""

import math

import pytest
from scipy.integrate import quad
from scipy.special import beta as beta_fn

from softimpact.models.contact_laws import (
    HertzLaw,
    HuntCrossleyLaw,
    SoftProjectileLaw,
    YangSunLaw,
    YangSunState,
    branch_of,
    laminate_modulus,
)
from softimpact.models.materials import Material
from softimpact.models.protocols import ContactLaw, HistoryLaw

STEEL = Material("steel", 207e9, 0.29, 7830.0)
AL = Material("al", 69e9, 0.33, 2700.0)
R = 0.00635

HERTZ = HertzLaw.sphere_on_laminate(R, STEEL, 7.9e9)
LAWS = {
    "hertz": HERTZ,
    "hunt-crossley": HuntCrossleyLaw(HERTZ.K, R, 0.6, 2.5, form="hunt-crossley"),
    "lankarani-nikravesh": HuntCrossleyLaw(HERTZ.K, R, 0.6, 2.5),
    "soft": SoftProjectileLaw(1.1e-3, 0.0127, 50.0, 2.0, 1.3, 2.5),
    "yang-sun-branch": YangSunLaw(HERTZ, 2e-5).branch(YangSunState(8e-5)),
}


def test_laminate_modulus_by_hand():
    """Sun's E*: 1/E* = (1 − ν_s²)/E_s + 1/E_2, evaluated by hand, and K = (4/3)·sqrt(R)·E*."""
    e = 1 / ((1 - 0.29**2) / 207e9 + 1 / 7.9e9)
    assert laminate_modulus(STEEL, 7.9e9) == pytest.approx(e, rel=1e-14)
    assert HERTZ.K == pytest.approx(4 / 3 * math.sqrt(R) * e, rel=1e-14)


def test_rigid_impact_duration_constant():
    """Rigid-wall duration = (4/5)·B(2/5, 1/2)·α_max/V = 2.9433·α_max/V = 3.2181·(m/K)^(2/5)·V^(−1/5)."""
    m, V = 8.4e-3, 2.54
    a, F, T = HERTZ.rigid_impact(m, V)
    assert T == pytest.approx(0.8 * beta_fn(0.4, 0.5) * a / V, rel=1e-7)
    assert T == pytest.approx(0.8 * beta_fn(0.4, 0.5) * 1.25**0.4 * (m / HERTZ.K) ** 0.4 * V**-0.2, rel=1e-7)
    assert 0.8 * beta_fn(0.4, 0.5) * 1.25**0.4 == pytest.approx(3.2181, abs=1e-4)


@pytest.mark.parametrize("name", sorted(LAWS))
def test_laws_satisfy_protocol(name):
    """Every law (and every memory branch) is a ContactLaw."""
    assert isinstance(LAWS[name], ContactLaw)


@pytest.mark.parametrize("name", sorted(LAWS))
@pytest.mark.parametrize("rate", [0.7, -0.3])
def test_tangents_are_derivatives(name, rate):
    """stiffness = ∂F/∂α and damping = ∂F/∂α̇, by central differences away from kinks."""
    law = LAWS[name]
    for a in (3e-5, 5e-5, 7e-5):
        h, hr = 1e-10, 1e-6
        dfa = (law.force(a + h, rate) - law.force(a - h, rate)) / (2 * h)
        dfr = (law.force(a, rate + hr) - law.force(a, rate - hr)) / (2 * hr)
        assert law.stiffness(a, rate) == pytest.approx(dfa, rel=1e-5)
        assert law.damping(a, rate) == pytest.approx(dfr, rel=1e-5, abs=1e-9)


@pytest.mark.parametrize("name", ["hertz", "soft"])
def test_energy_is_integral_of_static_force(name):
    """energy(α) = ∫0^α F(s, 0) ds by quadrature for elastic laws."""
    law = LAWS[name]
    a = 6e-5
    assert law.energy(a) == pytest.approx(quad(lambda s: law.force(s, 0.0), 0, a, epsabs=0, epsrel=1e-12)[0], rel=1e-9)


@pytest.mark.parametrize("name", sorted(LAWS))
@pytest.mark.parametrize("alpha", [-1e-5, 0.0])
def test_no_tension(name, alpha):
    """No force, stiffness, damping, radius or energy without overlap."""
    law = LAWS[name]
    assert law.force(alpha, 1.0) == 0.0 and law.stiffness(alpha, 1.0) == 0.0 and law.damping(alpha, 1.0) == 0.0
    assert law.radius(alpha) == 0.0 and law.energy(alpha) == 0.0


@pytest.mark.parametrize("name", ["hunt-crossley", "soft"])
def test_rate_laws_clip_at_zero(name):
    """A fast-opening contact pulls nothing: F = 0 (and zero tangents) when the rate factor goes negative."""
    law = LAWS[name]
    assert law.force(5e-5, -1e3) == 0.0 and law.stiffness(5e-5, -1e3) == 0.0 and law.damping(5e-5, -1e3) == 0.0


def test_radii():
    """Hertz a = sqrt(Rα); the soft law a = sqrt(dα), the flattened sphere's a² = 2Rα − α² to first order."""
    assert HERTZ.radius(4e-5) == pytest.approx(math.sqrt(R * 4e-5), rel=1e-15)
    soft = LAWS["soft"]
    a = 1e-4
    assert soft.radius(a) == pytest.approx(math.sqrt(2 * (soft.diameter / 2) * a - a * a), rel=a / soft.diameter)


def test_yang_sun_permanent_indentation():
    """α_p = 0 below α_cr and α_m(1 − (α_cr/α_m)^(2/5)) above (Yang & Sun 1982)."""
    law = YangSunLaw(HERTZ, 2e-5)
    assert law.permanent(1.5e-5) == 0.0
    assert law.permanent(8e-5) == pytest.approx(8e-5 * (1 - 0.25**0.4), rel=1e-14)


def test_yang_sun_unloading_curve():
    """Below α_m the force is F_m((α − α_p)/(α_m − α_p))^{5/2}; continuous at α_m, zero at α_p."""
    law = YangSunLaw(HERTZ, 2e-5)
    am = 8e-5
    br = law.branch(YangSunState(am))
    Fm, ap = HERTZ.K * am**1.5, am * (1 - 0.25**0.4)
    assert br.force(am) == pytest.approx(Fm, rel=1e-14)
    assert br.force(ap) == 0.0 and br.force(0.5 * ap) == 0.0
    a = 0.5 * (ap + am)
    assert br.force(a) == pytest.approx(Fm * 0.5**2.5, rel=1e-13)
    assert br.force(1.1 * am) == pytest.approx(HERTZ.K * (1.1 * am) ** 1.5, rel=1e-14)


def test_yang_sun_state_is_explicit_and_frozen():
    """advance returns a new state on loading past α_m and the same object otherwise; nothing mutates."""
    law = YangSunLaw(HERTZ, 2e-5)
    s0 = law.initial_state()
    s1 = law.advance(s0, 5e-5, 1.0)
    assert s0 == YangSunState(0.0) and s1 == YangSunState(5e-5)
    assert law.advance(s1, 4e-5, -1.0) is s1
    with pytest.raises(AttributeError):  # dataclasses.FrozenInstanceError
        s1.alpha_max = 1.0
    assert isinstance(law, HistoryLaw) and branch_of(HERTZ, None) is HERTZ


def test_yang_sun_recoverable_energy():
    """The branch energy is the integral of the unloading curve from α_p (quadrature)."""
    law = YangSunLaw(HERTZ, 2e-5)
    br = law.branch(YangSunState(8e-5))
    a = 6e-5
    ref = quad(lambda s: br.force(s), law.permanent(8e-5), a, epsrel=1e-12)[0]
    assert br.energy(a) == pytest.approx(ref, rel=1e-9)


def test_hunt_crossley_damping_factors():
    """D = 3(1 − e)/(2v) (Hunt–Crossley) and 3(1 − e²)/(4v) (Lankarani–Nikravesh)."""
    assert LAWS["hunt-crossley"].D == pytest.approx(1.5 * 0.4 / 2.5, rel=1e-15)
    assert LAWS["lankarani-nikravesh"].D == pytest.approx(0.75 * (1 - 0.36) / 2.5, rel=1e-15)


def test_soft_law_velocity_scaling():
    """F·d/(mV²) depends on α/d and α̇/V only: doubling V at the same α/d, α̇/V quadruples F."""
    a, b = SoftProjectileLaw(1.1e-3, 0.0127, 25.0, 2.0, 1.3, 2.5), SoftProjectileLaw(1.1e-3, 0.0127, 50.0, 2.0, 1.3, 2.5)
    assert b.force(3e-3, 20.0) == pytest.approx(4 * a.force(3e-3, 10.0), rel=1e-14)


@pytest.mark.parametrize("bad", [dict(k=-1.0), dict(p=0.0), dict(c=-0.1), dict(velocity=0.0)])
def test_soft_law_validation(bad):
    """Invalid parameters are rejected with a message naming the parameter."""
    args = dict(mass=1e-3, diameter=0.01, velocity=20.0, k=1.0, p=1.0, c=0.5) | bad
    with pytest.raises(Exception, match=next(iter(bad))):
        SoftProjectileLaw(**args)


def test_a_law_is_a_name_or_an_object_resolved_in_one_table():
    """resolve_law: "hertz" is the pair's own Hertz law, an object is returned as it is, and a name that needs
    parameters or is unknown, or an object that is no law, is an InputError naming ``law``."""
    from softimpact.errors import InputError
    from softimpact.models.contact_laws import CONTACT_LAWS, law_name, resolve_law

    assert resolve_law("hertz", lambda: HERTZ) is HERTZ
    lossy = HuntCrossleyLaw(HERTZ.K, HERTZ.R, 0.5, 2.0)
    assert resolve_law(lossy, lambda: HERTZ) is lossy and law_name(lossy) == "hunt-crossley" and law_name(HERTZ) == "hertz"
    assert set(CONTACT_LAWS) == {"hertz", "hertz-unloading", "hunt-crossley", "identified", "crushing", "hydrodynamic"}
    for bad in ("hunt-crossley", "rubber", 3.0):
        with pytest.raises(InputError) as exc:
            resolve_law(bad, lambda: HERTZ)
        assert exc.value.argument == "law"
