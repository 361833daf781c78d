"""Wheatstone bridges of strain gauges: measured volts → strain, exact formulas.

The bridge (National Instruments, *Measuring Strain with Strain Gages*,
white paper 3642, and the NI-DAQmx "Strain Gage Configuration Types";
Vishay Micro-Measurements Tech Note TN-507-1, "Wheatstone Bridge
Nonlinearity") has arms R1–R4 and an output

    V_o = V_ex · [R3/(R3 + R4) − R2/(R1 + R2)],

with R4 the (first) active gauge. The ratio V_r = V_o/V_ex (strained minus
unstrained; here V_r = polarity · V/(gain · V_ex)) gives the strain by these
closed forms, exact (not linearised) for the arms stated:

========================  ===========  ==============================================  ===========================
configuration             NI name      ε                                                active arms
========================  ===========  ==============================================  ===========================
``quarter``               quarter I    −4V_r / (GF (1 + 2V_r)) · (1 + R_L/R_g)          R4 = +ε
``half-poisson``          half I       −4V_r / (GF [(1 + ν) − 2V_r(ν − 1)]) · (1+R_L/R_g)  R4 = +ε, R3 = −νε
``half-bending``          half II      −2V_r / GF · (1 + R_L/R_g)                       R4 = +ε, R3 = −ε
``full-bending``          full I       −V_r / GF                                        R1, R3 = −ε; R2, R4 = +ε
``full-bending-poisson``  full II      −2V_r / (GF (1 + ν))                             R4 = +ε, R3 = −ε, R2 = +νε, R1 = −νε
``full-axial-poisson``    full III     −2V_r / (GF [(ν + 1) − V_r(ν − 1)])              R2, R4 = +ε; R1, R3 = −νε
========================  ===========  ==============================================  ===========================

A gauge in tension thus makes V_o negative ("NI wiring"); ``polarity = −1``
for a chain that inverts (compression reading positive). The quarter-bridge
term 1/(1 + 2V_r) is Vishay's nonlinearity correction (TN-507-1, eq. 3): about
0.1 % per 1000 µε at GF = 2. The lead-wire factor (1 + R_L/R_g) is for
three-wire connections, where one lead of resistance R_L sits in series with
the gauge arm and one with its neighbour (exact: the bridge sees R_g + R_L).

Shunt calibration (NI white paper 3642, "Shunt calibration"; TN-514): a
resistor R_s across the R4 gauge lowers it to R_g R_s/(R_g + R_s), the
resistance change of a strain ε_shunt = −R_g/(GF (R_g + R_s)). The output step
expected from it is computed from the arms (exact, any configuration, the other
arms at rest); the measured step then fixes the chain's true gain, so that
amplifier and excitation errors cancel: ``shunt_calibrated`` returns the bridge
with that gain, ``shunt_scale_factor`` the ratio nominal/true gain.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError

__all__ = ["Bridge", "CONFIGURATIONS", "shunt_strain"]

CONFIGURATIONS = (
    "quarter",
    "half-poisson",
    "half-bending",
    "full-bending",
    "full-bending-poisson",
    "full-axial-poisson",
)
_NEEDS_POISSON = {"half-poisson", "full-bending-poisson", "full-axial-poisson"}
_LEAD_CORRECTED = {"quarter", "half-poisson", "half-bending"}  # NI gives lead factors only for these


def shunt_strain(gauge_resistance: float, shunt_resistance: float, gauge_factor: float) -> float:
    """Strain simulated by a shunt R_s across a gauge R_g: −R_g/(GF (R_g + R_s))."""
    return -gauge_resistance / (gauge_factor * (gauge_resistance + shunt_resistance))


def _positive(name, value):
    if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
        raise InputError(f"bridge: {name} must be a positive number, got {value!r}")


@dataclass(frozen=True)
class Bridge:
    """A strain-gauge bridge and its signal chain (module docstring for the formulas).

    configuration: one of CONFIGURATIONS; gauge_factor GF [-]; excitation V_ex [V];
    gain of the amplifier [V/V]; poisson_ratio ν (for the Poisson configurations);
    gauge_resistance R_g [Ω]; lead_resistance R_L [Ω] per lead (three-wire);
    polarity ±1 (−1 when the chain inverts).
    """

    configuration: str
    gauge_factor: float
    excitation: float
    gain: float = 1.0
    poisson_ratio: float | None = None
    gauge_resistance: float = 350.0
    lead_resistance: float = 0.0
    polarity: int = 1

    def __post_init__(self):
        if self.configuration not in CONFIGURATIONS:
            raise InputError(f"bridge: configuration must be one of {', '.join(CONFIGURATIONS)}, got {self.configuration!r}")
        _positive("gauge_factor", self.gauge_factor)
        _positive("excitation", self.excitation)
        _positive("gain", self.gain)
        _positive("gauge_resistance", self.gauge_resistance)
        if not (isinstance(self.lead_resistance, (int, float)) and math.isfinite(self.lead_resistance) and self.lead_resistance >= 0):
            raise InputError(f"bridge: lead_resistance must be zero or positive, got {self.lead_resistance!r}")
        if self.lead_resistance > 0 and self.configuration not in _LEAD_CORRECTED:
            raise InputError(f"bridge: lead_resistance is corrected only for quarter and half bridges, not {self.configuration!r} (use shunt calibration)")
        if self.polarity not in (1, -1):
            raise InputError(f"bridge: polarity must be 1 or -1, got {self.polarity!r}")
        if self.configuration in _NEEDS_POISSON:
            nu = self.poisson_ratio
            if not (isinstance(nu, (int, float)) and 0 <= nu < 0.5):
                raise InputError(f"bridge: poisson_ratio in [0, 0.5) is needed for {self.configuration!r}, got {nu!r}")

    @property
    def _lead_factor(self) -> float:
        return 1.0 + self.lead_resistance / self.gauge_resistance

    def ratio(self, volts):
        """V_r = polarity · V/(gain · V_ex), the bridge output per volt of excitation."""
        return self.polarity * np.asarray(volts, dtype=float) / (self.gain * self.excitation)

    def strain(self, volts):
        """Strain [-] (tension positive) from the recorded volts, by the table's formula."""
        vr = self.ratio(volts)
        gf, nu, c = self.gauge_factor, self.poisson_ratio, self.configuration
        if c == "quarter":
            eps = -4 * vr / (gf * (1 + 2 * vr))
        elif c == "half-poisson":
            eps = -4 * vr / (gf * ((1 + nu) - 2 * vr * (nu - 1)))
        elif c == "half-bending":
            eps = -2 * vr / gf
        elif c == "full-bending":
            eps = -vr / gf
        elif c == "full-bending-poisson":
            eps = -2 * vr / (gf * (1 + nu))
        else:  # full-axial-poisson
            eps = -2 * vr / (gf * ((nu + 1) - vr * (nu - 1)))
        return eps * self._lead_factor

    def shunt_ratio(self, shunt_resistance: float) -> float:
        """V_r expected when R_s shunts the R4 gauge, the bridge otherwise at rest (exact, from the arms)."""
        _positive("shunt_resistance", shunt_resistance)
        rg, rl = self.gauge_resistance, self.lead_resistance
        r4 = rg * shunt_resistance / (rg + shunt_resistance) + rl
        r3 = rg + rl
        return r3 / (r3 + r4) - 0.5

    def shunt_scale_factor(self, shunt_resistance: float, measured_step: float) -> float:
        """Nominal gain over the true gain implied by a measured shunt step [V] (1 = chain as nominal)."""
        if not (isinstance(measured_step, (int, float)) and math.isfinite(measured_step) and measured_step != 0):
            raise InputError(f"bridge: measured_step must be a non-zero voltage, got {measured_step!r}")
        expected = self.shunt_ratio(shunt_resistance)
        true_gain = self.polarity * measured_step / (self.excitation * expected)
        if true_gain <= 0:
            raise InputError(
                f"bridge: measured_step {measured_step!r} V has the wrong sign for polarity {self.polarity} "
                f"(a shunt should give {self.polarity * expected:+.3g} V per V of excitation and gain)"
            )
        return self.gain / true_gain

    def shunt_calibrated(self, shunt_resistance: float, measured_step: float) -> Bridge:
        """This bridge with the gain that makes the measured shunt step read the shunt's simulated strain."""
        scale = self.shunt_scale_factor(shunt_resistance, measured_step)
        return dataclasses.replace(self, gain=self.gain / scale)
