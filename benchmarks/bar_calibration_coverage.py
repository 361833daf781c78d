"""Coverage of `calibrate-bar`'s 95 % intervals over noise seeds, on the tests' hidden bar (tests/_support/lab_bars.py).

The bar: steel, 1 m long, 20 mm across, its modulus hidden (c0 = 5097.8 m/s, 1 % above the catalogue steel
the calibration starts from), ν = 0.29, the gauge at 0.5 m with a true gauge factor of 2.11 read with a
nominal 2.00. Each shot: a steel ball of 8 mm at 3 m/s (its force from the coupled FE, its rebound measured
to 1 %), the gauge's record with the first-mode dispersion of every wave, white noise of 0.5 % of the peak,
sampled at 2.5 MHz for 1.1 ms. Each seed is one shot calibrated alone.

Printed: per constant, the number of seeds whose interval holds the truth, a one-sided 95 % Clopper–Pearson
lower bound of the coverage, the median half-width, the mean and standard deviation of the standardised
error z = (estimate − truth)/σ (σ = half-width/1.96: 0 and 1 if the intervals are honest), and the CPU time.

Usage: python benchmarks/bar_calibration_coverage.py [seeds, default 100]
"""

import math
import platform
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from softimpact.models.materials import lookup  # noqa: E402
from softimpact.workflows.bar_calibration import BarGeometry, KnownImpact, Shot, calibrate_bar  # noqa: E402

from _support import lab_bars as lb  # noqa: E402


def main(seeds: int = 100) -> None:
    from scipy.stats import beta

    steel = lookup("steel")
    geometry = BarGeometry(lb.LENGTH, lb.DIAMETER, lb.DENSITY, lb.GAUGE, steel.poisson_ratio, steel.wave_speed)
    truth = {
        "wave_speed": math.sqrt(lb.HIDDEN_E / lb.DENSITY),
        "poisson_ratio": lb.HIDDEN_NU,
        "gauge_position": lb.GAUGE,
        "sensitivity": lb.NOMINAL_GF / lb.HIDDEN_GF,
    }
    z = {k: [] for k in truth}
    width = {k: [] for k in truth}
    t0 = time.process_time()
    for seed in range(1000, 1000 + seeds):
        t, strain, imp, rebound = lb.calibration_shot(seed)
        shot = Shot("s", t, strain, KnownImpact(imp.mass, lb.BALL_VELOCITY, rebound=rebound, rebound_sd=lb.REBOUND_SD * imp.rebound))
        cal = calibrate_bar([shot], geometry)
        for name, value in truth.items():
            c = getattr(cal, name)
            z[name].append((c.value - value) / (c.half_width / 1.959964))
            width[name].append(c.half_width / value)
    cpu = time.process_time() - t0
    print(
        f"machine: {platform.processor() or platform.machine()}, python {platform.python_version()}; {seeds} seeds, {cpu:.1f} s CPU ({cpu / seeds:.2f} s a shot)"
    )
    for name in truth:
        zz = np.array(z[name])
        hits = int(np.sum(np.abs(zz) <= 1.959964))
        lower = float(beta.ppf(0.05, hits, seeds - hits + 1)) if hits > 0 else 0.0
        print(
            f"  {name:15s} covered {hits}/{seeds} (95 % lower bound {lower:.3f}); median half-width {np.median(width[name]):.2e} of the value; "
            f"z mean {zz.mean():+.2f}, sd {zz.std(ddof=1):.2f}"
        )


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 100)
