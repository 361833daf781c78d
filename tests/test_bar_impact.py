"""Sphere on an instrumented bar (paper Figs 4-6) against independent solutions."""

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from softimpact.fem.newmark import SolverSpec
from softimpact.input.bar_case import load_bar_case
from softimpact.models.materials import Material
from softimpact.models.specimens import Gauge
from softimpact.workflows.bar_impact import (
    simulate_force,
    simulate_impact,
    without_end_cap,
)


@pytest.fixture(scope="module")
def plain_problem():
    problem, _ = load_bar_case("paper-calibration")
    return without_end_cap(problem)


@pytest.fixture(scope="module")
def plain_result(plain_problem):
    return simulate_impact(plain_problem)


def _impedance_model(problem):
    """Semi-infinite bar: m·ẍ = −Kα^1.5, end velocity F/(ρcA); solved with scipy here."""
    K = problem.contact_law().K
    m, V = problem.projectile.mass, problem.projectile.velocity
    bar = problem.bar
    c = math.sqrt(bar.material.youngs_modulus / bar.material.density)
    Z = bar.material.density * c * bar.area

    def rhs(t, y):
        F = K * max(y[0] - y[2], 0.0) ** 1.5
        return [y[1], -F / m, F / Z]

    def separated(t, y):
        return y[0] - y[2] if t > 1e-7 else 1.0

    separated.terminal, separated.direction = True, -1
    sol = solve_ivp(rhs, (0, 1e-3), [0.0, V, 0.0], rtol=1e-11, atol=1e-16, events=separated, dense_output=True, max_step=1e-7)
    duration = sol.t_events[0][0]
    t = np.linspace(0, duration, 40001)
    y = sol.sol(t)
    F = K * np.maximum(y[0] - y[2], 0) ** 1.5
    return t, F, duration, c


def test_against_semi_infinite_bar_impedance_model(plain_problem, plain_result):
    """Paper case, no end cap, 39 elements: peak force and duration within 1 %, midpoint strain within 3 % and 1.5 µs."""
    t, F, duration, c = _impedance_model(plain_problem)
    r = plain_result
    assert r.peak_force == pytest.approx(F.max(), rel=0.01)
    assert r.contact_duration == pytest.approx(duration, rel=0.01)
    bar = plain_problem.bar
    x = plain_problem.gauges[0].position
    strain_peak = -F.max() / (bar.material.youngs_modulus * bar.area)
    strain_time = t[np.argmax(F)] + x / c
    k = np.argmin(r.strain[0])
    assert r.strain[0, k] == pytest.approx(strain_peak, rel=0.03)
    assert abs(r.time[k] - strain_time) < 1.5e-6


def test_impulse_equals_momentum_change_and_energy_is_kept(plain_problem, plain_result):
    """∫F dt = m(V − v_rebound) to 1e-6, and the total energy drifts by less than 0.5 %."""
    r = plain_result
    m, V = plain_problem.projectile.mass, plain_problem.projectile.velocity
    assert r.separated and len(r.contacts) == 1
    assert r.impulse == pytest.approx(m * (V - r.rebound_velocity), rel=1e-6)
    E = r.energies.mechanical
    assert np.max(np.abs(E - 0.5 * m * V**2)) < 0.005 * 0.5 * m * V**2


def test_end_cap_raises_the_peak_force(plain_problem, plain_result):
    """The paper (Fig 5): the end cap's added inertia raises the maximum contact force."""
    capped, _ = load_bar_case("paper-calibration")
    assert simulate_impact(capped).peak_force > 1.02 * plain_result.peak_force


def test_time_step_convergence_is_second_order(plain_problem):
    """Peak force converges at order ≈ 2 in dt (4, 2, 1 µs, where the time error dominates)."""
    peaks = [simulate_impact(replace(plain_problem, solver=SolverSpec(dt, 150e-6))).peak_force for dt in (4e-6, 2e-6, 1e-6)]
    order = math.log2(abs(peaks[0] - peaks[1]) / abs(peaks[1] - peaks[2]))
    assert 1.7 < order < 2.4


def test_rigid_massive_target_gives_hertz_closed_form(plain_problem):
    """A bar 10⁴× stiffer and denser acts as a rigid wall: Hertz's closed form.

    Energy gives α_max = (5mV²/4K)^(2/5) and the duration 2·(α_max/V)·∫₀¹(1 − s^(5/2))^(-1/2) ds
    = (4/5)·B(2/5, 1/2)·α_max/V = 2.9433·α_max/V, i.e. 3.2181·(m/K)^(2/5)·V^(-1/5)
    (Goldsmith's rounded 3.2145 belongs to this second form, not to α_max/V).
    """
    from scipy.special import beta

    mat = plain_problem.bar.material
    rigid = Material("rigid", mat.youngs_modulus * 1e4, mat.poisson_ratio, mat.density * 1e4)
    problem = replace(plain_problem, bar=replace(plain_problem.bar, material=rigid), solver=SolverSpec(0.1e-6, 120e-6))
    r = simulate_impact(problem)
    K, m, V = problem.contact_law().K, problem.projectile.mass, problem.projectile.velocity
    alpha_max = (5 * m * V**2 / (4 * K)) ** 0.4
    assert r.contact_duration == pytest.approx(0.8 * beta(0.4, 0.5) * alpha_max / V, rel=2e-3)
    assert r.peak_force == pytest.approx(K * alpha_max**1.5, rel=2e-3)


@pytest.fixture(scope="module")
def pulse_on_bar(plain_problem):
    """A 40-µs half-sine end force on the paper bar, gauge at mid-length."""
    F0, tau = 1000.0, 40e-6
    bar = replace(plain_problem.bar, elements=80)
    result = simulate_force(
        bar,
        SolverSpec(0.25e-6, 450e-6),
        (Gauge("mid", bar.length / 2),),
        lambda t: np.where(t < tau, F0 * np.sin(np.pi * t / tau), 0.0),
    )
    return bar, result, F0, tau


def test_wave_arrives_at_x_over_c(pulse_on_bar):
    """The compressive peak reaches the mid-length gauge at τ/2 + x/c, with strain −F0/EA."""
    bar, r, F0, tau = pulse_on_bar
    c = math.sqrt(bar.material.youngs_modulus / bar.material.density)
    eps = r.strain[0]
    k = np.argmin(eps)
    assert abs(r.time[k] - (tau / 2 + bar.length / 2 / c)) < 1e-6
    assert eps[k] == pytest.approx(-F0 / (bar.material.youngs_modulus * bar.area), rel=0.01)


def test_free_end_reflection_is_opposite_and_equal(pulse_on_bar):
    """The pulse returns from the free end as tension of equal amplitude, at τ/2 + 3L/(2c)."""
    bar, r, F0, tau = pulse_on_bar
    c = math.sqrt(bar.material.youngs_modulus / bar.material.density)
    eps = r.strain[0]
    kc, kt = np.argmin(eps), np.argmax(eps)
    assert abs(r.time[kt] - (tau / 2 + 1.5 * bar.length / c)) < 1e-6
    assert eps[kt] == pytest.approx(-eps[kc], rel=0.01)


def test_hertz_bar_through_the_coupled_stepper_is_johnsons_rigid_wall(plain_problem):
    """A bar 10⁴× stiffer and denser, through the one coupled stepper: Johnson's (Contact Mechanics, §11.4)
    rigid-wall closed form, α_max = (15mV²/(16E*√R))^(2/5) with 1/E* = Σ(1 − ν²)/E from the two materials,
    duration 2.94·α_max/V, to 0.3 %; and the momentum balance ∫F dt = m(V − V_rebound) to 1e-9, with an
    elastic rebound V_rebound ≈ −V."""
    from scipy.special import beta

    mat = plain_problem.bar.material
    rigid = Material("rigid", mat.youngs_modulus * 1e4, mat.poisson_ratio, mat.density * 1e4)
    problem = replace(plain_problem, bar=replace(plain_problem.bar, material=rigid, length=2 * plain_problem.bar.length), solver=SolverSpec(0.1e-6, 120e-6))
    r = simulate_impact(problem)
    ball = problem.projectile
    E_star = 1 / ((1 - ball.material.poisson_ratio**2) / ball.material.youngs_modulus + (1 - rigid.poisson_ratio**2) / rigid.youngs_modulus)
    m, V, R = ball.mass, ball.velocity, ball.diameter / 2
    alpha_max = (15 * m * V**2 / (16 * E_star * math.sqrt(R))) ** 0.4
    assert r.contact_duration == pytest.approx(0.8 * beta(0.4, 0.5) * alpha_max / V, rel=3e-3)  # 0.8·B(2/5, 1/2) = 2.9433
    assert np.max(r.approach) == pytest.approx(alpha_max, rel=3e-3)
    assert r.total_impulse == pytest.approx(m * (V - r.rebound_velocity), rel=1e-9)
    assert r.rebound_velocity == pytest.approx(-V, rel=5e-3)


@pytest.mark.parametrize("velocity", [-1.6, 0.0])
def test_a_projectile_not_moving_toward_the_bar_is_refused(plain_problem, velocity):
    """A negative or zero impact velocity is an InputError naming the velocity (it once ran and returned peak 0)."""
    from softimpact.errors import InputError

    with pytest.raises(InputError, match="velocity must be positive"):
        simulate_impact(replace(plain_problem, projectile=replace(plain_problem.projectile, velocity=velocity)))
