"""Strain-gauge bridges: volts → strain against the resistor network itself."""

import pytest

from softimpact.errors import InputError
from softimpact.models.bridge import CONFIGURATIONS, Bridge, shunt_strain

RG, GF, VEX, GAIN, NU = 350.0, 2.1, 5.0, 100.0, 0.33


def network_ratio(configuration, eps, nu=NU, rg=RG, lead=0.0, shunt=None):
    """V_o/V_ex = R3/(R3+R4) − R2/(R1+R2) from the arm resistances, computed directly.

    Arms as NI describes each configuration (R4 the main active gauge); each
    external gauge arm carries one lead of resistance ``lead`` (three-wire);
    ``shunt`` puts a resistor across the R4 gauge.
    """
    x = GF * eps
    arms = {  # ΔR/R of R1, R2, R3, R4 and whether each is an external (leaded) gauge
        "quarter": ((0, 0, 0, x), (False, False, True, True)),  # R3 the completion resistor, leaded in 3-wire
        "half-poisson": ((0, 0, -nu * x, x), (False, False, True, True)),
        "half-bending": ((0, 0, -x, x), (False, False, True, True)),
        "full-bending": ((-x, x, -x, x), (False, False, False, False)),
        "full-bending-poisson": ((-nu * x, nu * x, -x, x), (False, False, False, False)),
        "full-axial-poisson": ((-nu * x, x, -nu * x, x), (False, False, False, False)),
    }[configuration]
    R = [rg * (1 + d) for d in arms[0]]
    if shunt is not None:
        R[3] = R[3] * shunt / (R[3] + shunt)
    R = [r + (lead if leaded else 0.0) for r, leaded in zip(R, arms[1])]
    R1, R2, R3, R4 = R
    return R3 / (R3 + R4) - R2 / (R1 + R2)


@pytest.mark.parametrize("configuration", CONFIGURATIONS)
@pytest.mark.parametrize("eps", [-8000e-6, -500e-6, 3e-6, 1200e-6, 20000e-6])
def test_strain_recovered_from_the_resistor_network(configuration, eps):
    """Volts computed from the bridge's resistances read back as the strain that made them (1e-10)."""
    bridge = Bridge(configuration, GF, VEX, GAIN, poisson_ratio=NU)
    volts = GAIN * VEX * network_ratio(configuration, eps)
    assert float(bridge.strain(volts)) == pytest.approx(eps, rel=1e-10, abs=1e-15)


@pytest.mark.parametrize("configuration", ["quarter", "half-poisson", "half-bending"])
def test_lead_resistance_of_three_wire_connections_is_corrected(configuration):
    """With 2 Ω leads in series with the gauge arms, the lead factor (1 + R_L/R_g) restores the strain exactly."""
    eps = 1500e-6
    bridge = Bridge(configuration, GF, VEX, GAIN, poisson_ratio=NU, lead_resistance=2.0)
    volts = GAIN * VEX * network_ratio(configuration, eps, lead=2.0)
    assert float(bridge.strain(volts)) == pytest.approx(eps, rel=1e-10)


def test_quarter_bridge_nonlinearity_matters_at_large_strain():
    """At 1 % strain the linear reading −4V_r/GF is off by about GF·ε/2 ≈ 1 % (TN-507), the exact one is not."""
    eps = 0.01
    vr = network_ratio("quarter", eps)
    linear = -4 * vr / GF
    assert linear / eps - 1 == pytest.approx(-GF * eps / 2, rel=0.05)
    assert float(Bridge("quarter", GF, 1.0).strain(vr)) == pytest.approx(eps, rel=1e-12)


def test_polarity_flips_the_sign():
    """An inverting chain (polarity −1) reads the same strain from the negated volts."""
    volts = GAIN * VEX * network_ratio("quarter", 700e-6)
    b = Bridge("quarter", GF, VEX, GAIN, polarity=-1)
    assert float(b.strain(-volts)) == pytest.approx(700e-6, rel=1e-12)


def test_shunt_strain_closed_form():
    """A 100 kΩ shunt on a 350 Ω, GF 2 gauge simulates −350/(2·100350) = −1743.9 µε."""
    assert shunt_strain(350.0, 100e3, 2.0) == pytest.approx(-350.0 / (2.0 * 100350.0))
    assert shunt_strain(350.0, 100e3, 2.0) == pytest.approx(-1743.9e-6, rel=1e-4)


@pytest.mark.parametrize("configuration", CONFIGURATIONS)
def test_shunt_calibration_removes_a_gain_error(configuration):
    """A chain whose true gain is 3 % low, calibrated by its own shunt step, reads strain correctly again."""
    true_gain = 0.97 * GAIN
    bridge = Bridge(configuration, GF, VEX, GAIN, poisson_ratio=NU)
    step = true_gain * VEX * network_ratio(configuration, 0.0, shunt=59.88e3)
    calibrated = bridge.shunt_calibrated(59.88e3, step)
    assert bridge.shunt_scale_factor(59.88e3, step) == pytest.approx(1 / 0.97, rel=1e-12)
    volts = true_gain * VEX * network_ratio(configuration, 900e-6)
    assert float(calibrated.strain(volts)) == pytest.approx(900e-6, rel=1e-10)
    assert float(bridge.strain(volts)) == pytest.approx(0.97 * 900e-6, rel=1e-3)  # uncalibrated: 3 % low


def test_quarter_shunt_step_reads_the_shunt_strain():
    """On a nominal quarter bridge, the shunt step converts to exactly ε_shunt = −R_g/(GF(R_g+R_s))."""
    bridge = Bridge("quarter", GF, VEX, GAIN)
    step = GAIN * VEX * network_ratio("quarter", 0.0, shunt=100e3)
    assert float(bridge.strain(step)) == pytest.approx(shunt_strain(RG, 100e3, GF), rel=1e-12)


@pytest.mark.parametrize(
    ("kwargs", "word"),
    [
        (dict(configuration="third"), "configuration"),
        (dict(gauge_factor=0.0), "gauge_factor"),
        (dict(excitation=-5.0), "excitation"),
        (dict(gain=float("nan")), "gain"),
        (dict(configuration="half-poisson", poisson_ratio=None), "poisson_ratio"),
        (dict(configuration="full-axial-poisson", poisson_ratio=0.7), "poisson_ratio"),
        (dict(lead_resistance=-1.0), "lead_resistance"),
        (dict(configuration="full-bending", lead_resistance=1.0), "lead_resistance"),
        (dict(polarity=2), "polarity"),
        (dict(gauge_resistance=0.0), "gauge_resistance"),
    ],
)
def test_bad_parameters_name_the_argument(kwargs, word):
    """Each invalid parameter raises InputError whose one-line message names it."""
    args = dict(configuration="quarter", gauge_factor=GF, excitation=VEX) | kwargs
    with pytest.raises(InputError, match=word) as info:
        Bridge(**args)
    assert "\n" not in str(info.value)


def test_shunt_step_of_wrong_sign_is_rejected():
    """A shunt step whose sign contradicts the polarity is an InputError naming measured_step."""
    bridge = Bridge("quarter", GF, VEX, GAIN)
    step = GAIN * VEX * network_ratio("quarter", 0.0, shunt=100e3)
    with pytest.raises(InputError, match="measured_step"):
        bridge.shunt_calibrated(100e3, -step)
