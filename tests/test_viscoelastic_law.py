"""The soft-projectile law with a Maxwell arm: closed-form relaxation, rigid-wall impact against
scipy's solve_ivp, tangents, and its scaling."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from softimpact.errors import InputError
from softimpact.fem.impact import ContactStructure, integrate_impact
from softimpact.models.contact_laws import SoftProjectileLaw, ViscoelasticSoftLaw
from softimpact.models.protocols import ContactLaw, HistoryLaw
from softimpact.workflows.identification import arm_stress

M, D, V = 0.4641e-3, 0.009525, 50.8  # the 3/8-in rubber ball of the built-in series
K, P, C, KAPPA, THETA = 1.8, 0.9, 0.6, 8.0, 0.3  # a law chosen here


def _law(velocity=V, **kw) -> ViscoelasticSoftLaw:
    args = {"k": K, "p": P, "c": C, **{k: v for k, v in kw.items() if k in ("k", "p", "c")}}
    base = SoftProjectileLaw(M, D, velocity, **args)
    return ViscoelasticSoftLaw(base, kw.get("kappa", KAPPA), kw.get("theta", THETA))


def _drive(law, alpha, dt):
    """Step the law along a prescribed approach history alpha[j] = α(j·dt), rate by differences; force per step."""
    law = law.for_time_step(dt)
    state, out = law.initial_state(), [0.0]
    for j in range(1, alpha.size):
        rate = (alpha[j] - alpha[j - 1]) / dt
        out.append(law.branch(state).force(alpha[j], rate))
        state = law.advance(state, alpha[j], rate)
    return np.array(out), state


@pytest.mark.parametrize("steps_per_ramp", [3, 40])
def test_ramp_and_hold_follow_the_maxwell_closed_form(steps_per_ramp):
    """Ramp α at a constant rate r for t1, then hold: σ = κ·(r/d)·τ·(1 − e^(−t/τ)) on the ramp and
    σ(t1)·e^(−(t−t1)/τ) on the hold, τ = θ·d/V (the standard linear solid's relaxation); the
    step update is exact for a piecewise-linear approach, so at any step size."""
    law = _law(c=0.0)
    tau = THETA * D / V
    r, t1 = 0.3 * V, 0.5 * D / V
    dt = t1 / steps_per_ramp
    t = np.arange(4 * steps_per_ramp + 1) * dt
    alpha = np.minimum(t, t1) * r
    F, _ = _drive(law, alpha, dt)
    sig = np.where(t <= t1, KAPPA * r / D * tau * (1 - np.exp(-t / tau)), KAPPA * r / D * tau * (1 - math.exp(-t1 / tau)) * np.exp(-(t - t1) / tau))
    scale = M * V * V / D
    expected = scale * (K * (alpha / D) ** P + sig)
    assert np.allclose(F[1:], expected[1:], rtol=1e-12)
    # and the identification's filter along a sampled history gives the same σ
    assert np.allclose(arm_stress(alpha / D, dt * V / D, KAPPA, THETA), sig, rtol=1e-12, atol=1e-15)


def test_energy_dissipated_over_a_strain_cycle():
    """A sinusoidal strain cycle ε = ε̄ + ε0·sin(ωt) at ωτ = 1, once the start-up transient has died: the
    arm dissipates ∮σ dε = π·κ·ε0²·ωτ/(1 + (ωτ)²) = π·κ·ε0²/2 per cycle (the loss of a Maxwell element);
    σ read off the law's own force, F/(mV²/d) − k·(α/d)^p."""
    law = _law(c=0.0)
    tau = THETA * D / V
    w = 1.0 / tau
    e0, n = 0.05, 1000
    period = 2 * math.pi / w
    dt = period / n
    t = np.arange(8 * n + 1) * dt
    strain = (0.2 + e0 * np.sin(w * t)) * np.minimum(t / period, 1.0)  # ramped in over the first cycle
    F, _ = _drive(law, strain * D, dt)
    sig = F / (M * V * V / D) - K * strain**P
    last = slice(7 * n, 8 * n + 1)
    work = np.trapezoid(sig[last], strain[last])
    assert work == pytest.approx(math.pi * KAPPA * e0**2 / 2.0, rel=1e-4)


def _rigid_wall() -> ContactStructure:
    """A one-DOF target 10⁹ times stiffer than the contact: a rigid wall to ~1e-8."""
    return ContactStructure(
        M=np.array([[1.0]]),
        K=np.array([[1e15]]),
        surface_x=np.array([0.0]),
        surface_dofs=np.array([0]),
        load_sign=1.0,
        center=0.0,
        approach_row=np.array([1.0]),
        outputs=np.zeros((0, 1)),
    )


def _reference(law: ViscoelasticSoftLaw):
    """m·ẍ = −F(x, ẋ, σ), σ̇ = κ·ẋ/d − σ·V/(θ·d) while x > 0, by solve_ivp (Radau, tight tolerances) to separation."""
    b = law.base

    def force(y):
        x, v, s = y
        return max(b.force_unclipped(x, v) + b.scale * s, 0.0) if x > 0 else 0.0

    def rhs(t, y):
        x, v, s = y
        return [v, -force(y) / M, law.kappa * v / D - s * V / (law.theta * D)]

    def apart(t, y):
        return y[0] if t > 1e-9 else 1.0

    apart.terminal, apart.direction = True, -1
    T = 3 * D / V
    sol = solve_ivp(rhs, (0, T), [0.0, V, 0.0], method="Radau", rtol=1e-10, atol=[1e-13, 1e-9, 1e-12], events=apart, dense_output=True)
    t = np.linspace(0, sol.t[-1], 4001)
    F = np.array([force(sol.sol(tt)) for tt in t])
    return t, F, sol.y[1, -1]


def test_rigid_wall_impact_agrees_with_solve_ivp():
    """The coupled solver (Newmark + Newton, the law's exact step) on a rigid wall gives the peak force,
    its time, the impulse and the rebound velocity of the same law integrated as an ODE by solve_ivp."""
    law = _law()
    t, F, v_out = _reference(law)
    T = t[-1]
    h = integrate_impact(_rigid_wall(), law, M, V, T / 2000, 4000, energy=False, stop_after=0.05 * T)
    assert np.max(h.force) == pytest.approx(F.max(), rel=1e-3)
    assert h.time[np.argmax(h.force)] == pytest.approx(t[np.argmax(F)], rel=5e-3)
    assert np.trapezoid(h.force, h.time) == pytest.approx(np.trapezoid(F, t), rel=1e-4)
    assert h.impactor_velocity[-1] == pytest.approx(v_out, rel=1e-3)
    assert v_out < 0  # it rebounds


def test_rigid_wall_pulse_scales_with_velocity():
    """F·d/(mV²) against t·V/d is the same at 25 and 100 m/s on a rigid wall (Table I's scaling): the arm's
    relaxation time θ·d/V keeps the law within it."""
    out = []
    for v in (25.0, 100.0):
        law = _law(velocity=v)
        T = D / v
        h = integrate_impact(_rigid_wall(), law, M, v, T / 800, 3000, energy=False, stop_after=0.05 * T)
        out.append((h.time * v / D, h.force * D / (M * v * v)))
    grid = np.linspace(0, 1.0, 201)
    a, b = (np.interp(grid, tt, ff) for tt, ff in out)
    assert np.max(np.abs(a - b)) < 1e-6 * np.max(a)


def test_branch_tangents_by_differences():
    """A step's branch is a ContactLaw whose ∂F/∂α and ∂F/∂α̇ match central differences (Newton's tangents)."""
    law = _law().for_time_step(2e-6)
    assert isinstance(law, HistoryLaw)
    state = law.advance(law.initial_state(), 1e-3, 20.0)
    br = law.branch(state)
    assert isinstance(br, ContactLaw)
    a, r = 1.2e-3, 15.0
    h_a, h_r = 1e-9, 1e-4
    assert br.stiffness(a, r) == pytest.approx((br.force(a + h_a, r) - br.force(a - h_a, r)) / (2 * h_a), rel=1e-6)
    assert br.damping(a, r) == pytest.approx((br.force(a, r + h_r) - br.force(a, r - h_r)) / (2 * h_r), rel=1e-6)
    assert br.force(-1e-4, r) == 0.0 and br.force(a, -1e3) == 0.0  # no tension


@pytest.mark.parametrize("rate", [-1e3, -40.0, 0.0, 15.0])
def test_response_is_force_and_central_difference_tangents(rate):
    """The one-call (F, ∂F/∂α, ∂F/∂α̇) of a Maxwell branch and of the plain soft law: F as the arithmetic of
    the module docstring's law, the tangents as central differences, all zero where the force is clipped."""
    law = _law().for_time_step(2e-6)
    state = law.advance(law.initial_state(), 1e-3, 20.0)
    br = law.branch(state)
    E = math.exp(-2e-6 / (THETA * D / V))
    sigma = 0.0 * E + KAPPA * (-math.expm1(-2e-6 / (THETA * D / V))) / (2e-6 / (THETA * D / V)) * (1e-3 / D)
    for model, arm in ((br, True), (law.base, False)):
        for a in (-1e-4, 2e-4, 1.2e-3):
            f, k, c = model.response(a, rate)
            expect = 0.0
            if a > 0.0:
                s = sigma * E + KAPPA * (-math.expm1(-2e-6 / (THETA * D / V))) / (2e-6 / (THETA * D / V)) * (a / D - 1e-3 / D) if arm else 0.0
                expect = max(M * V**2 / D * (K * (a / D) ** P * (1.0 + C * rate / V) + s), 0.0)
            assert f == pytest.approx(expect, rel=1e-12, abs=1e-12)
            if f == 0.0:
                assert k == 0.0 and c == 0.0
                continue
            h_a, h_r = 1e-9 * a, 1e-6 * max(abs(rate), 1.0)
            assert k == pytest.approx((model.force(a + h_a, rate) - model.force(a - h_a, rate)) / (2 * h_a), rel=1e-6)
            assert c == pytest.approx((model.force(a, rate + h_r) - model.force(a, rate - h_r)) / (2 * h_r), rel=1e-6)
            assert (f, k, c) == (model.force(a, rate), model.stiffness(a, rate), model.damping(a, rate))


def test_unbound_law_and_bad_parameters_are_refused():
    """Without the time step the law refuses to step; κ and θ must be positive."""
    with pytest.raises(ValueError, match="time step"):
        _law().branch(_law().initial_state())
    for kw in ({"kappa": 0.0}, {"theta": -1.0}):
        with pytest.raises(InputError):
            _law(**kw)
