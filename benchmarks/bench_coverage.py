"""Coverage of calibrate's uncertainties (issue 9): do the 95 % intervals hold the truth 95 % of the time?

Measured strains are made once per Table II history by direct stepping of a
model four times as fine as the case (800 × 24 elements, 0.25 µs: the stand-in
for the real structure, the limit of refinement), then given independent noise
(1.5 % of each gauge's peak) and gauge offsets for each of N realisations. Each
realisation is calibrated with the default settings (the model checked and
refined within the default budget; standard errors of noise and discretisation
together, widened where the parameters' own convergence over three levels shows
more: studies/calibration.calibrate_tests' path). Printed per parameter: the fraction of realisations whose 95 %
interval (±1.96 SE) holds the true value, the RMS of error/SE, and the mean and
largest relative error.

Usage: python benchmarks/bench_coverage.py [realisations per history, default 10] [data refinement, default 4]
"""

import sys
import time
from dataclasses import replace

import numpy as np

from softimpact.input.beam_case import load_beam_case
from softimpact.input.scaling_constants import start_pulse
from softimpact.models.pulses import SkewedPulse
from softimpact.studies.calibration import DEFAULT_BUDGET, ModelLadder, with_parameter_convergence
from softimpact.workflows.beam_impact import BeamModel
from softimpact.workflows.calibration import Measured, calibrate_checked
from softimpact.workflows.refinement import refine_beam

LBF, INCH = 4.4482216152605, 0.0254
ROWS = [(1166, 44, 30, 355, 0.25), (1932, 90, 21, 250, 0.25), (3058, 215, 13, 158, 0.30), (4026, 325, 10, 120, 0.35)]  # Table II
NAMES = ("peak_force", "time_of_peak", "duration")


def main(n: int = 10, factor: int = 4):
    problem, _ = load_beam_case("paper-long-beam")
    fine = refine_beam(problem, factor)
    ladder = ModelLadder(problem, [r[4] * INCH for r in ROWS])
    max_level = ladder.affordable(DEFAULT_BUDGET)
    rng = np.random.default_rng(20261122)
    z = {k: [] for k in NAMES}
    rel = {k: [] for k in NAMES}
    t_cal = []
    for V, F0, tp, T, r0 in ROWS:
        truth = SkewedPulse(F0 * LBF, tp * 1e-6, T * 1e-6)
        t0 = time.perf_counter()
        model = BeamModel(replace(fine, load=replace(fine.load, contact_radius=r0 * INCH)), outputs="strain")
        clean = model.direct(truth, energy=False, displacement=False)
        print(f"V = {V} in/s: data model {fine.beam.nx} × {fine.beam.nz}, {time.perf_counter() - t0:.0f} s", file=sys.stderr, flush=True)
        t = np.arange(-100e-6, clean.time[-1], 1e-6)
        start = start_pulse("rubber-1/2in", None, V * INCH)
        values = {"peak_force": truth.peak_force, "time_of_peak": truth.time_of_peak, "duration": truth.duration}
        for _ in range(n):
            strains = {}
            for g, eps in zip(problem.gauges, clean.strain):
                y = np.interp(t, clean.time, eps, left=0.0)
                strains[g.name] = y + 0.015 * np.max(np.abs(eps)) * rng.standard_normal(t.size) + rng.normal(0, 30e-6)
            c0 = time.process_time()
            measured = Measured(f"V{V}", t + 100e-6, strains)
            cal = calibrate_checked(ladder, measured, start, radius=r0 * INCH, max_level=max_level)
            cal = with_parameter_convergence(ladder, measured, start, cal, None, False)  # as calibrate_tests does
            t_cal.append(time.process_time() - c0)
            got = {"peak_force": cal.peak_force, "time_of_peak": cal.time_of_peak, "duration": cal.duration}
            for k in NAMES:
                z[k].append((got[k] - values[k]) / cal.standard_errors[k])
                rel[k].append(got[k] / values[k] - 1)
    print(f"{len(ROWS)} histories × {n} noise realisations; data from a ×{factor} model; calibration CPU {np.median(t_cal):.1f} s median per test")
    print(f"{'parameter':14s} {'95 % coverage':>14s} {'RMS error/SE':>13s} {'mean error':>11s} {'largest |error|':>16s}")
    for k in NAMES:
        zk, rk = np.array(z[k]), np.array(rel[k])
        print(f"{k:14s} {np.mean(np.abs(zk) <= 1.96):14.0%} {np.sqrt(np.mean(zk**2)):13.2f} {np.mean(rk):+11.2%} {np.max(np.abs(rk)):16.2%}")


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:3]))
