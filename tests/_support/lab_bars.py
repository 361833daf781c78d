"""A lab's bars with hidden constants, and their synthetic records (the package's own bar FE): for the tests of
``calibrate-bar`` and ``shpb``. The hidden constants are written here once; the tests compare what the
analyses recover with them."""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from softimpact.models.bridge import Bridge
from softimpact.models.materials import Material, lookup

# --- the free-free bar to calibrate: a steel bar whose wave speed, gauge factor and Poisson's ratio are hidden ---
HIDDEN_E = 204.0e9  # Pa: c0 = sqrt(E/rho) = 5097.8 m/s, 1 % above the catalogue steel's nominal 5046 m/s
HIDDEN_NU = 0.29
HIDDEN_GF = 2.11  # the gauge's true factor (the nominal one is 2.00)
NOMINAL_GF = 2.00
DENSITY = 7850.0  # kg/m^3, taken as measured (its uncertainty 0)
LENGTH, DIAMETER, GAUGE = 1.0, 0.020, 0.5  # m
BALL_DIAMETER, BALL_VELOCITY = 0.008, 3.0  # m, m/s: a steel ball
REBOUND_SD = 0.01  # the rebound's measurement: 1 % of it, one sigma
NOISE = 0.005  # recorder noise, one sigma, as a fraction of the record's largest reading
SAMPLE, PRE, LENGTH_S = 0.4e-6, 500e-6, 1500e-6  # s: sample interval (2.5 MHz), pre-trigger, record length (five echoes)
HIDDEN_BAR = Material("hidden steel", HIDDEN_E, HIDDEN_NU, DENSITY, "the tests' hidden bar")
TRUE_BRIDGE = Bridge("quarter", HIDDEN_GF, 5.0, 500.0, polarity=-1)  # tension reads positive volts
NOMINAL_BRIDGE = Bridge("quarter", NOMINAL_GF, 5.0, 500.0, polarity=-1)


@lru_cache(maxsize=4)
def ball_force(youngs_modulus: float = HIDDEN_E):
    """The steel ball's force on the hidden bar (coupled FE) and the clean gauge strain of its free-free bar."""
    from softimpact.workflows.synthetic_bars import ball_impact, free_bar_record

    bar = Material("bar", youngs_modulus, HIDDEN_NU, DENSITY)
    imp = ball_impact(bar, LENGTH, DIAMETER, lookup("steel"), BALL_DIAMETER, BALL_VELOCITY)
    t = np.arange(0.0, LENGTH_S, SAMPLE)
    eps = free_bar_record(t, imp.time + PRE, imp.force, length=LENGTH, gauge_position=GAUGE, bar=bar, diameter=DIAMETER)
    return imp, t, eps


def calibration_shot(seed: int, youngs_modulus: float = HIDDEN_E):
    """A record of the ball on the hidden bar, through the true bridge, with noise, read with the nominal gauge factor:
    (time [s] from the ball's contact, strain as recorded, the ball, its measured rebound)."""
    from softimpact.workflows.synthetic_bars import add_noise, strain_to_volts

    imp, t, eps = ball_force(youngs_modulus)
    rng = np.random.default_rng(seed)
    volts = strain_to_volts(eps, TRUE_BRIDGE)
    volts = add_noise(volts, NOISE * float(np.max(np.abs(volts))), rng)
    rebound = imp.rebound * (1 + REBOUND_SD * rng.standard_normal())
    return t - PRE, NOMINAL_BRIDGE.strain(volts), imp, rebound


# --- the two-bar set-up: aluminium bars, a 6-mm specimen of 12.7 mm diameter ---
BAR_E, BAR_RHO, BAR_D = 68.9e9, 2700.0, 0.01905
INCIDENT_LENGTH, INCIDENT_GAUGE = 1.0, 0.5  # m; the gauge from the struck end
TRANSMITTED_LENGTH, TRANSMITTED_GAUGE = 0.8, 0.3  # m; the gauge from the specimen
SPEC_D, SPEC_RHO = 0.0127, 917.0


def split_bar(spec_length: float, spec_modulus: float, law, elements: int = 12):
    """The FE set-up (:class:`softimpact.fem.split_bar.SplitBar`) with the specimen given."""
    from softimpact.fem.bar import Rod
    from softimpact.fem.split_bar import SplitBar

    area = math.pi * BAR_D**2 / 4
    return SplitBar(
        Rod(INCIDENT_LENGTH, area, BAR_E, BAR_RHO, 400),
        Rod(spec_length, math.pi * SPEC_D**2 / 4, spec_modulus, SPEC_RHO, elements),
        Rod(TRANSMITTED_LENGTH, area, BAR_E, BAR_RHO, 320),
        law,
    )


def split_bar_records(spec_length: float, spec_modulus: float, law, bar_stress: float, rise: float, elements: int = 12):
    """(time, incident-bar strain, transmitted-bar strain, the FE's result) of a test loaded by a pulse of ``bar_stress``
    [Pa] in the incident bar, rising in ``rise`` [s], 100 us flat."""
    from softimpact.workflows.synthetic_bars import loading_pulse, split_bar_test

    setup = split_bar(spec_length, spec_modulus, law, elements)
    pulse = loading_pulse(bar_stress * math.pi * BAR_D**2 / 4, rise, 100e-6)
    return split_bar_test(
        setup,
        pulse,
        incident_gauge=INCIDENT_GAUGE,
        transmitted_gauge=TRANSMITTED_GAUGE,
        time_step=0.1e-6,
        duration=480e-6,
        pre_trigger=50e-6,
        sample_interval=0.2e-6,
    )


def bar_sides():
    """The analysis's view of the two bars (:class:`softimpact.workflows.shpb.BarSide`)."""
    from softimpact.workflows.shpb import BarSide

    return (
        BarSide(BAR_E, BAR_RHO, BAR_D, INCIDENT_LENGTH - INCIDENT_GAUGE, INCIDENT_LENGTH, 0.33),
        BarSide(BAR_E, BAR_RHO, BAR_D, TRANSMITTED_GAUGE, TRANSMITTED_LENGTH, 0.33),
    )
