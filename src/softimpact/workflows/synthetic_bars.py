"""Synthetic records of a lab's bars made by the package's own FE (labelled synthetic): a known impact on a
free–free bar for its calibration, and two-bar (split Hopkinson) tests.

- :func:`ball_impact`: a steel ball strikes the end of the bar; the coupled impact (Hertz contact, the
  Hermite rod of :mod:`softimpact.fem.bar`, :func:`softimpact.fem.impact.simulate_coupled`) gives the
  contact force F(t) and the ball's rebound.
- :func:`free_bar_record`: the gauge's strain of a free–free bar struck at x = 0 by F(t), every wave
  moved along its path by the first longitudinal (Pochhammer–Chree) mode
  (:func:`softimpact.models.dispersion.propagate`), d'Alembert's sum

      −E A ε(x, t) = Σ_k [D_{x + 2kL} F](t) − [D_{2L − x + 2kL} F](t).

  The 1-D FE carries no Pochhammer–Chree dispersion (its rod has no radius), so the waves are moved by the
  package's dispersion model; without it (ν = 0: c(f) = c0 below the cutoff) the sum is the FE's own gauge
  record of a free–free rod under F(t) (tests/test_bar_calibration.py checks that).
- :func:`strain_to_volts`: the bridge's volts of a strain (the inverse of
  :meth:`softimpact.models.bridge.Bridge.strain`).
- :func:`split_bar_test`: incident bar, specimen and transmitted bar (:mod:`softimpact.fem.split_bar`)
  loaded by a pressure pulse on the incident bar's free end; the two gauges' strains.

Units SI; time along the last axis.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..fem.bar import BarModel, Rod
from ..fem.impact import simulate_coupled
from ..fem.newmark import SolverSpec
from ..models.contact_laws import HertzLaw
from ..models.dispersion import RoundBar, propagate
from ..models.materials import Material
from ..models.specimens import Impactor

__all__ = ["BallImpact", "ball_impact", "free_bar_record", "strain_to_volts", "add_noise"]


@dataclass(frozen=True)
class BallImpact:
    """The force of a ball on the end of a bar: ``time`` [s] from first contact, ``force`` [N], the ball's
    ``mass`` [kg], ``velocity`` and ``rebound`` [m/s] (its speed away from the bar after the contact)."""

    time: np.ndarray
    force: np.ndarray
    mass: float
    velocity: float
    rebound: float


def ball_impact(
    bar: Material, length: float, diameter: float, ball: Material, ball_diameter: float, velocity: float, *, elements: int = 200, time_step: float = 0.1e-6
) -> BallImpact:
    """A ball of ``ball`` (material) and ``ball_diameter`` [m] striking at ``velocity`` [m/s] the end of a bar of ``bar``
    (material), ``length`` and ``diameter`` [m]: Hertz contact on the rod of ``elements`` elements, stepped at
    ``time_step`` until the ball has left (the force's impulse is then m(V + V_r))."""
    rod = Rod(length, math.pi * diameter**2 / 4, bar.youngs_modulus, bar.density, elements)
    mass = ball.density * math.pi / 6 * ball_diameter**3
    law = HertzLaw.sphere_on_flat(ball_diameter / 2, ball, bar)
    *_, duration = law.rigid_impact(mass, velocity)
    solver = SolverSpec(time_step, 4.0 * duration)
    model = BarModel(rod, solver, [0.5 * length])
    r = simulate_coupled(
        model.contact_structure(), law, Impactor(mass, ball_diameter, velocity), solver, stepper=model.stepper, energy=False, stop_after=0.2 * duration
    )
    return BallImpact(r.time, r.force, mass, velocity, -float(r.rebound_velocity))


def free_bar_record(t, time, force, *, length: float, gauge_position: float, bar: Material, diameter: float, poisson_ratio: float | None = None) -> np.ndarray:
    """The gauge strain [-] on the clock ``t`` (uniform; force applied from t = 0) of a free–free bar struck by ``force``
    [N] (on its own ``time`` [s]), every wave moved by the first mode with ``poisson_ratio`` (default the material's;
    module docstring). Arrivals up to the end of ``t``."""
    t = np.asarray(t, float)
    F = np.interp(t, time, force, left=0.0, right=0.0)
    c = bar.wave_speed
    EA = bar.youngs_modulus * math.pi * diameter**2 / 4
    rb = RoundBar(c, bar.poisson_ratio if poisson_ratio is None else poisson_ratio, diameter / 2)
    eps = np.zeros_like(t)
    k = 0
    while (2 * k * length + gauge_position) / c < t[-1]:
        for path, sign in ((gauge_position + 2 * k * length, -1.0), (2 * length - gauge_position + 2 * k * length, 1.0)):
            if path / c < t[-1]:
                eps += sign * propagate(t, F, path, rb) / EA
        k += 1
    return eps


def strain_to_volts(strain, bridge) -> np.ndarray:
    """The recorded volts that ``bridge`` (:class:`softimpact.models.bridge.Bridge`) reads as ``strain``: Newton's
    iteration on V_r (each bridge's ε(V_r) is smooth and monotone), from its linear reading."""
    eps = np.asarray(strain, float)
    unit = bridge.gain * bridge.excitation * bridge.polarity
    h = 1e-9
    slope0 = (bridge.strain(h * unit) - bridge.strain(-h * unit)) / (2 * h)
    vr = eps / slope0
    for _ in range(30):
        f = bridge.strain(vr * unit) - eps
        d = (bridge.strain((vr + h) * unit) - bridge.strain((vr - h) * unit)) / (2 * h)
        step = f / d
        vr = vr - step
        if np.max(np.abs(step)) <= 1e-15 * max(float(np.max(np.abs(vr))), 1e-30):
            break
    return vr * unit


def add_noise(y, sigma: float, rng: np.random.Generator) -> np.ndarray:
    """``y`` with white Gaussian noise of standard deviation ``sigma`` (the recorder's)."""
    y = np.asarray(y, float)
    return y + sigma * rng.standard_normal(y.shape)


def loading_pulse(amplitude: float, rise: float, flat: float):
    """F(t) [N]: a striker's pressure pulse on the incident bar, raised-cosine rise and fall of ``rise`` [s] each about
    a ``flat`` [s] plateau of ``amplitude`` [N] (a pulse-shaped striker's, without its dispersion)."""

    def force(t: float) -> float:
        if t <= 0.0:
            return 0.0
        if t < rise:
            return amplitude * 0.5 * (1 - math.cos(math.pi * t / rise))
        if t < rise + flat:
            return amplitude
        if t < 2 * rise + flat:
            return amplitude * 0.5 * (1 + math.cos(math.pi * (t - rise - flat) / rise))
        return 0.0

    return force


def split_bar_test(
    setup, force, *, incident_gauge: float, transmitted_gauge: float, time_step: float, duration: float, pre_trigger: float, sample_interval: float
):
    """The two gauges' records of a two-bar test (:func:`softimpact.fem.split_bar.simulate_split_bar`): (time [s] on a
    clock that starts ``pre_trigger`` before the load, incident-bar strain, transmitted-bar strain), sampled every
    ``sample_interval`` [s], and the FE's own result (face forces, mean strain) for the checks."""
    from ..fem.split_bar import simulate_split_bar

    r = simulate_split_bar(setup, force, time_step=time_step, duration=duration, incident_gauges=[incident_gauge], transmitted_gauges=[transmitted_gauge])
    t = np.arange(0.0, pre_trigger + duration, sample_interval)
    inc = np.interp(t - pre_trigger, r.time, r.incident_strain[0], left=0.0)
    tr = np.interp(t - pre_trigger, r.time, r.transmitted_strain[0], left=0.0)
    return t, inc, tr, r


__all__ += ["loading_pulse", "split_bar_test"]
