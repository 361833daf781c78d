"""Eq (15) pulses and the force models of eqs (4)-(7), Hertz and Wilbeck."""

import math

import pytest
from scipy.integrate import quad

from softimpact.errors import InputError
from softimpact.models.empirical import PRESETS, PROJECTILES, HertzModel, ScalingLaw, WilbeckModel
from softimpact.models.materials import lookup
from softimpact.models.pulses import SkewedPulse, TailedPulse

from _support.constants import INCH, LBF


@pytest.mark.parametrize("skew", [0.05, 0.25, 0.5, 0.9])
def test_skewed_impulse_is_2F0T_over_pi(skew):
    """∫F dt of eq (15) by quadrature equals 2·F0·T/π whatever t_F0."""
    p = SkewedPulse(100.0, skew * 400e-6, 400e-6)
    numeric = quad(p, 0, 400e-6, points=[p.time_of_peak], epsabs=0, epsrel=1e-12)[0]
    assert numeric == pytest.approx(2 * 100.0 * 400e-6 / math.pi, rel=1e-9)
    assert p.impulse == pytest.approx(numeric, rel=1e-9)


def test_skewed_pulse_shape():
    """F(t_F0) = F0, F = 0 at 0 and from T on, continuous at t_F0."""
    p = SkewedPulse(10.0, 1e-5, 1e-4)
    assert p(1e-5) == pytest.approx(10.0)
    assert p(0.0) == 0.0 and p(1e-4) == pytest.approx(0.0, abs=1e-12) and p(2e-4) == 0.0
    assert p(1e-5 - 1e-12) == pytest.approx(p(1e-5 + 1e-12), rel=1e-6)


def test_bad_pulse_refused():
    """t_F0 must lie inside (0, T)."""
    with pytest.raises(InputError, match="time_of_peak"):
        SkewedPulse(10.0, 2e-4, 1e-4)


def test_tail_carries_the_requested_impulse():
    """The tailed pulse integrates (by quadrature) to the impulse it was built for, and is continuous."""
    main = SkewedPulse(100.0, 1e-4, 4e-4)
    tailed = TailedPulse.with_impulse(main, 0.04, 1.1 * main.impulse)
    numeric = quad(tailed, 0, 60 * tailed.decay, points=[1e-4, tailed.tail_start], limit=200, epsrel=1e-10)[0]
    assert numeric == pytest.approx(1.1 * main.impulse, rel=1e-6)
    ts = tailed.tail_start
    assert tailed(ts - 1e-12) == pytest.approx(tailed(ts + 1e-12), rel=1e-6)


def test_table_one_notes_cross_check():
    """NOTES.md: the eq-15 pulse carries α1·α2/(2π) of 2mV: 0.63 (1/2 in) and 0.66 (3/8 in)."""
    for name, expected in (("silicone-1/2in", 0.63), ("silicone-3/8in", 0.66)):
        law = PRESETS[name]
        m, d, V = 1e-3, 0.01, 30.0
        pulse = law.pulse(m, d, V)
        assert pulse.impulse / (2 * m * V) == pytest.approx(expected, abs=0.005)
        assert law.pulse(m, d, V, tail=True).impulse == pytest.approx(law.alpha4 * 2 * m * V, rel=1e-9)


def test_eq4_gives_36_lbf_at_1166_in_s():
    """NOTES.md: eq (4) with Table I gives 36 lbf for the 1/2-in, 1.1-g ball at 1166 in/s."""
    proj = PROJECTILES["rubber-1/2in"]
    F0 = PRESETS[proj.law].parameters(proj.mass, proj.diameter, 1166 * INCH).peak_force
    assert F0 / LBF == pytest.approx(36.0, abs=0.5)


def test_empirical_scaling_with_velocity():
    """Eqs (4)-(7): F0 ∝ V², T ∝ 1/V, t_F0/T constant, I ∝ V."""
    law = ScalingLaw(4.0, 1.0, 0.25, 0.7)
    a, b = law.parameters(1e-3, 0.01, 20.0), law.parameters(1e-3, 0.01, 40.0)
    assert b.peak_force / a.peak_force == pytest.approx(4.0)
    assert b.duration / a.duration == pytest.approx(0.5)
    assert b.time_of_peak / b.duration == pytest.approx(0.25)
    assert b.impulse / a.impulse == pytest.approx(2.0)


def test_hertz_exponents():
    """The classical model: F0 grows like V^1.2 and the duration like V^-0.2 (log-log slopes)."""
    model = HertzModel(lookup("silicone rubber"), lookup("Al 6061-T6"))
    m, d = 1.1e-3, 0.0127
    a, b = model.parameters(m, d, 25.0), model.parameters(m, d, 100.0)
    assert math.log(b.peak_force / a.peak_force) / math.log(4) == pytest.approx(1.2, abs=1e-9)
    assert math.log(b.duration / a.duration) / math.log(4) == pytest.approx(-0.2, abs=1e-9)
    pulse = model.pulse(m, d, 25.0)
    assert pulse.force.max() == pytest.approx(a.peak_force, rel=1e-3)
    assert pulse.impulse == pytest.approx(2 * m * 25.0, rel=1e-3)  # elastic: the ball leaves at −V


def test_wilbeck_is_perfectly_plastic():
    """Steady-flow force ρV²A(t): impulse mV (no rebound), peak ρV²πd²/4 at d/(2V)."""
    rho, d, V = 1000.0, 0.0127, 50.0
    m = rho * math.pi / 6 * d**3
    model = WilbeckModel(rho)
    pulse = model.pulse(m, d, V)
    assert pulse.impulse == pytest.approx(m * V, rel=1e-4)
    assert pulse.force.max() == pytest.approx(rho * V**2 * math.pi * d**2 / 4, rel=1e-4)
