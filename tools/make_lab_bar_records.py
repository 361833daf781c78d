"""Generate the built-in synthetic calibration `lab-bar-calibration` (records + calibration file): five steel balls
on a lab's 1-m, 20-mm steel bar whose wave speed, Poisson's ratio and gauge factor are hidden, for
`softimpact calibrate-bar lab-bar-calibration`.

The truth (the tests' hidden bar, tests/_support/lab_bars.py): E = 204 GPa (c0 = 5097.8 m/s, 1 % above the
catalogue steel the file names), ν = 0.29, ρ = 7850 kg/m³, the gauge at 0.5 m, its true gauge factor 2.11 (the
file says 2.00, the nominal one). Each shot: a steel ball of 8 mm at 2.0 to 4.0 m/s (five shots); the coupled impact (Hertz
contact on the FE rod, 200 elements, 0.1-us step) gives the force and the ball's rebound; the gauge's record is the
free-free bar's d'Alembert sum with every wave moved by the first longitudinal mode (workflows/synthetic_bars.py);
the quarter bridge (5 V, gain 500, tension reading positive) turns it into volts; white noise of 0.5 % of the peak volts;
500 us of pre-trigger (the baseline's uncertainty dominates the impulse's); 1.5 ms sampled at 2.5 MHz. The rebound written is the FE's with a measurement error of 1 % (seeded), its
uncertainty 1 %. Run from the repository root: python tools/make_lab_bar_records.py
"""

import math
from pathlib import Path

import numpy as np

from softimpact.models.bridge import Bridge
from softimpact.models.materials import Material, lookup
from softimpact.workflows.synthetic_bars import add_noise, ball_impact, free_bar_record, strain_to_volts

OUT = Path("src/softimpact/data/series")
NAME = "lab-bar-calibration"
HIDDEN = Material("hidden steel", 204.0e9, 0.29, 7850.0)
LENGTH, DIAMETER, GAUGE = 1.0, 0.020, 0.5
TRUE_GF, NOMINAL_GF = 2.11, 2.00
BALL = 0.008
VELOCITIES = (2.0, 2.5, 3.0, 3.5, 4.0)
NOISE, PRE, SAMPLE, DURATION = 0.005, 500e-6, 0.4e-6, 1500e-6
SEED = 20260101


def main():
    rng = np.random.default_rng(SEED)
    bridge = Bridge("quarter", TRUE_GF, 5.0, 500.0, polarity=-1)  # tension reads positive volts (the file's polarity = 1)
    folder = OUT / NAME
    folder.mkdir(parents=True, exist_ok=True)
    shots = []
    for k, V in enumerate(VELOCITIES, start=1):
        imp = ball_impact(HIDDEN, LENGTH, DIAMETER, lookup("steel"), BALL, V)
        t = np.arange(0.0, DURATION, SAMPLE)
        eps = free_bar_record(t, imp.time + PRE, imp.force, length=LENGTH, gauge_position=GAUGE, bar=HIDDEN, diameter=DIAMETER)
        volts = strain_to_volts(eps, bridge)
        volts = add_noise(volts, NOISE * float(np.max(np.abs(volts))), rng)
        rebound = imp.rebound * (1 + 0.01 * rng.standard_normal())
        name = f"ball-{k}.csv"
        with open(folder / name, "w") as fh:
            fh.write("time (us),gauge (mV)\n")
            for a, b in zip((t - PRE) * 1e6, volts * 1e3):
                fh.write(f"{a:.2f},{b:.5f}\n")
        shots.append((name, imp.mass, V, rebound, 0.01 * imp.rebound))
        print(f"{name}: V {V} m/s, rebound {imp.rebound:.4f} m/s (written {rebound:.4f}), peak {np.max(np.abs(volts)) * 1e3:.2f} mV")
    lines = [
        "# Synthetic calibration records (SYNTHETIC, not measurements): five steel balls on a lab's steel bar whose wave",
        "# speed, Poisson's ratio and gauge factor are hidden. The truth: E = 204 GPa (c0 = 5097.8 m/s), nu = 0.29,",
        "# density 7850 kg/m3, gauge factor 2.11 (the nominal 2.00 below), the gauge at 0.5 m (tools/make_lab_bar_records.py,",
        f"# seed {SEED}). `softimpact calibrate-bar lab-bar-calibration` should recover them within their intervals.",
        'title = "A lab\'s 20-mm steel bar, gauge A (SYNTHETIC, truth: c0 5097.8 m/s, nu 0.29, GF 2.11)"',
        'units = "SI"',
        'synthetic = "records of the coupled bar FE (steel balls, Hertz) with first-mode dispersion, quarter bridge, 0.5 % noise"',
        "",
        "[bar]",
        'material = "steel"',
        'length = "1.000 m"',
        'length_uncertainty = "0.2 mm"',
        'diameter = "20.00 mm"',
        'density = "7850 kg/m^3"',
        "",
        "[gauge]",
        'position = "500 mm"',
        'bridge = "quarter"',
        f"gauge_factor = {NOMINAL_GF}",
        'excitation = "5 V"',
        "gain = 500",
        "",
    ]
    for name, m, V, vr, vr_sd in shots:
        lines += [
            "[[shot]]",
            f'record = "{NAME}/{name}"',
            f'ball = {{ mass = "{m * 1e3:.5f} g", velocity = "{V} m/s", rebound = "{vr:.4f} m/s", rebound_uncertainty = "{vr_sd:.4f} m/s" }}',
            "",
        ]
    (OUT / f"{NAME}.toml").write_text("\n".join(lines))
    print("c0", math.sqrt(HIDDEN.youngs_modulus / HIDDEN.density))


if __name__ == "__main__":
    main()
