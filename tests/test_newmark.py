"""Newmark stepping against the exact single-DOF oscillator."""

import numpy as np
import pytest

from softimpact.errors import InputError
from softimpact.fem.newmark import NewmarkParameters, NewmarkStepper

OMEGA = 2 * np.pi * 1000.0  # rad/s


def _free_vibration(dt, T=5e-3):
    M, K = np.array([[1.0]]), np.array([[OMEGA**2]])
    steps = int(round(T / dt))
    stepper = NewmarkStepper(M, K, dt)
    u, v, _ = stepper.run(np.zeros((1, steps + 1)), u0=np.array([1.0]))
    t = np.arange(steps + 1) * dt
    return t, u[0], v[0]


def test_second_order_convergence():
    """Average acceleration converges at order 2 to u = cos(ωt) (fitted rate 1.9-2.1)."""
    errs, dts = [], [2e-5, 1e-5, 5e-6, 2.5e-6]
    for dt in dts:
        t, u, _ = _free_vibration(dt)
        errs.append(np.max(np.abs(u - np.cos(OMEGA * t))))
    rate = np.polyfit(np.log(dts), np.log(errs), 1)[0]
    assert 1.9 < rate < 2.1


def test_energy_is_conserved_exactly_for_linear_undamped():
    """Average acceleration conserves ½kv²... ½v² + ½ω²u² to round-off."""
    _, u, v = _free_vibration(2e-5)
    E = 0.5 * v**2 + 0.5 * OMEGA**2 * u**2
    assert np.max(np.abs(E / E[0] - 1)) < 1e-12


def test_unstable_parameters_are_refused():
    """β < γ/2 is only conditionally stable and is refused."""
    with pytest.raises(InputError, match="beta"):
        NewmarkParameters(beta=0.1, gamma=0.5)
