"""One threshold-map row on the von Kármán plate, full against reduced stepping, in one process.

The built-in plate-ss-8in-impact (steel ball 1/2 in, Hertz in Sun's form, the simply supported 8 × 8 in [90/0]5s
T300/934 plate, 48 × 48 MITC9, 0.5 µs steps) with ``kinematics = "von-karman"``, as a threshold map's structure
(:func:`softimpact.studies.thresholds.structure`) for that one ball, and its Davies–Zhang delamination row
(:func:`~softimpact.studies.thresholds.threshold_map`, no law draws: the case's Hertz law has no spread) found twice:

- reduced: ``nonlinear_stepping="von-karman-rom"`` (the plate's reduced model built once in ``structure``, every run on it);
- full: ``nonlinear_stepping="von-karman"`` (every run a Newmark–Newton over the 45 505 DOF).

The reduced row is found first over [``--lo``, ``--hi``] in/s; the full row then over the same range (the same
scan and Brent steps: the two rows' costs compare like for like). Then both models run once at the reduced V*,
for the peak-force error ε there and the threshold shift it predicts, (1 + ε)^(1/β) − 1.

Prints the thresholds, β, the runs each took, CPU and wall times of the builds and the rows, and their ratio.

Usage: python benchmarks/bench_vk_rom_map.py [--lo V] [--hi V] [--duration US] [--elements N]
"""

import argparse
import dataclasses
import math
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from threadpoolctl import threadpool_limits  # noqa: E402

from softimpact.input.impact_case import load_impact_case  # noqa: E402
from softimpact.studies import thresholds as T  # noqa: E402

INCH = 0.0254


@dataclasses.dataclass(frozen=True)
class CaseLaw:
    """The case's contact law as a threshold map's law (``law(m, d, V)``, no spread parameters, no identified range):
    Hertz of the case's ball, whatever the velocity (the map has that one ball)."""

    contact: object
    names: tuple = ()
    values: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0))
    half_widths: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0))
    covariance: None = None
    identified_on: None = None

    def law(self, mass: float, diameter: float, velocity: float):
        return self.contact


def timed(f):
    """(f(), wall [s], CPU [s])."""
    t0, c0 = time.perf_counter(), time.process_time()
    out = f()
    return out, time.perf_counter() - t0, time.process_time() - c0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lo", type=float, default=1000.0, help="velocity range's low end [in/s]")
    ap.add_argument("--hi", type=float, default=4000.0, help="velocity range's high end [in/s]")
    ap.add_argument("--duration", type=float, default=300.0, help="each run's duration [us]")
    ap.add_argument("--elements", type=int, default=48, help="elements a side (MITC9)")
    ap.add_argument("--only", choices=("reduced", "full", "both"), default="both")
    args = ap.parse_args()
    p, _ = load_impact_case("plate-ss-8in-impact")
    t = p.target
    t = replace(t, plate=replace(t.plate, elements=(args.elements, args.elements)), kinematics="von-karman")
    imp = p.impactor
    density = imp.mass / (math.pi / 6.0 * imp.diameter**3)
    law = CaseLaw(p.law)
    dt, duration = t.solver.time_step, args.duration * 1e-6
    lo, hi = args.lo * INCH, args.hi * INCH
    rows, cost = {}, {}
    with threadpool_limits(1, user_api="blas"):
        for stepping in ("von-karman-rom", "von-karman") if args.only == "both" else ("von-karman-rom" if args.only == "reduced" else "von-karman",):
            s, bw, bc = timed(lambda st=stepping: T.structure("plate", t, imp.diameter, density, dt, duration, law, nonlinear_stepping=st))
            (row,), rw, rc = timed(lambda s=s: T.threshold_map(s, law, [imp.diameter], lo, hi, draws=0, strength_quantiles=3, indices=("delamination",)))
            rows[stepping], cost[stepping] = (row, s), (bw, bc, rw, rc)
            d = row.as_dict()
            print(
                f"{stepping:15s} V* {row.nominal / INCH:9.2f} in/s  beta {row.beta:.3f}  runs {row.runs} (+2 for beta)  "
                f"w/h {d.get('deflection_over_thickness', math.nan):.2f}  build {bw:6.2f} s wall {bc:6.2f} s CPU  row {rw:7.1f} s wall {rc:7.1f} s CPU",
                flush=True,
            )
        if len(rows) == 2:
            (r, sr), (f, sf) = rows["von-karman-rom"], rows["von-karman"]
            (_, a), (_, b) = T._run(sr, law, imp.diameter, r.nominal), T._run(sf, law, imp.diameter, r.nominal)
            eps = a.peak_force / b.peak_force - 1.0
            print(
                f"at the reduced V*: peak force {a.peak_force:.2f} N reduced, {b.peak_force:.2f} N full (eps {eps:+.3%}); contact time "
                f"{a.contact_duration / b.contact_duration - 1:+.3%}"
            )
            print(f"threshold: full / reduced - 1 = {f.nominal / r.nominal - 1:+.3%}; predicted (1 + eps)^(1/beta) - 1 = {(1 + eps) ** (1 / f.beta) - 1:+.3%}")
            cr, cf = cost["von-karman-rom"], cost["von-karman"]
            print(f"ratio full / reduced: row {cf[2] / cr[2]:.1f} wall, {cf[3] / cr[3]:.1f} CPU; with builds {(cf[0] + cf[2]) / (cr[0] + cr[2]):.1f} wall")


if __name__ == "__main__":
    main()
