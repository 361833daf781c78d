"""Synthetic gauge records made by the package's own bar FE (labelled synthetic).

The paper's figure data are not available; demonstration series and tests use
records computed here: a force pulse drives the Hermite bar (through its
impulse response at the gauge, :mod:`softimpact.fem.response`), and the gauge
strain gets a pre-trigger, white noise, a baseline offset and an arbitrary clock.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..fem.bar import Rod, assemble_rod
from ..fem.newmark import NewmarkStepper
from ..fem.response import ImpulseResponse
from ..models.specimens import BarSpec

__all__ = ["GaugeModel", "gauge_model", "synthetic_record"]


@dataclass
class GaugeModel:
    """The bar's strain response at one gauge to an end force, on a step of ``dt`` [s]."""

    engine: ImpulseResponse
    dt: float
    steps: int

    def strain(self, force) -> tuple[np.ndarray, np.ndarray]:
        """Gauge strain for the pulse ``force`` (callable of t) applied from t = 0."""
        t = np.arange(self.steps + 1) * self.dt
        return t, self.engine.respond(force(t))[0]


def gauge_model(bar: BarSpec, gauge_position: float, dt: float, duration: float) -> GaugeModel:
    """Assemble the bar and compute its gauge impulse response once."""
    model = assemble_rod(Rod.of(bar))
    steps = int(round(duration / dt))
    stepper = NewmarkStepper(model.M, model.K, dt)
    e0 = np.zeros(model.n)
    e0[model.end_dof] = 1.0
    probe = model.strain_probe([gauge_position]).toarray()
    return GaugeModel(ImpulseResponse(stepper, e0, steps, outputs=probe), dt, steps)


def synthetic_record(
    gauge: GaugeModel,
    force,
    *,
    pre_trigger: float,
    length: float,
    sample_interval: float,
    noise: float,
    offset: float,
    clock_start: float,
    rng: np.random.Generator,
) -> tuple[np.ndarray, np.ndarray]:
    """A record (time [s], strain) of ``length`` [s] sampled every ``sample_interval``.

    Contact starts ``pre_trigger`` after the record starts; ``noise`` is the
    standard deviation as a fraction of the peak |strain|; ``offset`` is added
    (strain); the record's clock starts at ``clock_start``.
    """
    t, eps = gauge.strain(lambda tt: force(tt - pre_trigger))
    ts = np.arange(0.0, length, sample_interval)
    if ts[-1] > t[-1]:
        raise ValueError("the gauge model is shorter than the record asked for")
    y = np.interp(ts, t, eps)
    y = y + noise * np.max(np.abs(y)) * rng.standard_normal(ts.size) + offset
    return ts + clock_start, y


def beam_measurement(
    model,
    pulse,
    *,
    pre_trigger: float,
    noise: float,
    offsets,
    rng: np.random.Generator,
    sample_interval: float | None = None,
    radius: float | None = None,
    engine: bool = False,
):
    """Synthetic measured gauge strains of a beam model driven by ``pulse`` (direct stepping, or with
    ``engine`` its response engine: the same strains to round-off, cheaper for many pulses on one model).

    Returns (time [s] on a record clock starting ``pre_trigger`` before contact, {gauge: strain}).
    ``noise``: σ as a fraction of each gauge's peak |strain|; ``offsets``: one per gauge; ``radius``:
    the contact radius r0 [m] (default the problem's).
    """
    result = model.respond(pulse, radius) if engine else model.direct(pulse, energy=False, displacement=False, radius=radius)
    dt = model.problem.solver.time_step
    step = sample_interval or dt
    t_model = result.time
    t = np.arange(-pre_trigger, t_model[-1] + 0.5 * step, step)
    out = {}
    for g, eps, off in zip(model.problem.gauges, result.strain, offsets):
        y = np.interp(t, t_model, eps, left=0.0)
        out[g.name] = y + noise * np.max(np.abs(eps)) * rng.standard_normal(t.size) + off
    return t + pre_trigger, out
