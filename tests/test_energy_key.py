"""One energy-check key (issue 28): the bar's summary.json writes `energy_balance_relative`, the spread of the mechanical energy over the impact KE."""

import pytest

import softimpact as si


def test_bar_energy_balance_is_the_mechanical_energy_spread_over_the_impact_energy():
    """The bar's `energy_balance_relative` is (max − min) of the mechanical energy over ½mv² of the projectile (computed here), small for the elastic Hertz contact; the old key is gone."""
    res = si.run(si.load("paper-calibration"), figures=False)
    summary = res.summary()
    assert "energy_drift_relative" not in summary
    p = res.problem.projectile
    ke0 = 0.5 * p.mass * p.velocity**2  # the impact kinetic energy, the mechanical energy at first contact
    e = res.result.energies.mechanical
    assert e[0] == pytest.approx(ke0, rel=1e-12)
    assert summary["energy_balance_relative"] == pytest.approx((e.max() - e.min()) / ke0, rel=1e-9)
    assert 0 <= summary["energy_balance_relative"] < 1e-3  # Hertz is elastic: what is left is the stepping's error
