"""Plate sweep throughput (issue 13): runs per second for a velocity sweep of one plate (one
PlateModel, its impulse responses built once by reciprocity, one FFT product a run), with the
damage indices, in a plain loop and on a local Dask cluster of 1 and 2 workers.

The plate is the paper report's (:func:`softimpact.app.paper.thresholds.paper_plate_case`): the quarter of
the built-in 8 × 8 in simply supported [90/0]5s plate, 32 × 32 MITC4 elements, 400 steps of 1 µs,
struck at the centre by the 1/2-in rubber ball under the empirical law; damage read under the
impact point (6 pseudo-gauges) and at one gauge 1 in away (6 more).

Usage: python benchmarks/bench_sweep_plate.py [--runs N]

Times are wall clock from the plan to the last run (cluster start-up included); the engine's
build is timed apart. Prints a Markdown table row.
"""

import argparse
import tempfile
import time
from pathlib import Path

from softimpact.cases.sweep import execute, plan_sweep
from softimpact.input.sweep_spec import load_sweep_spec

CASE = """
title = "Quarter of the 8 x 8 in simply supported [90/0]5s plate (paper report's mesh)"
units = "in-lbf-s"
[plate]
length = "4 in"
width = "4 in"
elements = [32, 32]
element = "mitc4"                # the report's element (MITC9 is the default)
support = { x0 = "simply-supported", x1 = "symmetry", y0 = "simply-supported", y1 = "symmetry" }
[plate.laminate]
ply = "T300/934"
layup = "[90/0]5s"
[load]
position = ["4 in", "4 in"]
contact_radius = "0.25 in"
grow = true
history = { shape = "empirical", projectile = "rubber-1/2in", velocity = "3000 in/s" }
[solver]
time_step = "1 us"
duration = "400 us"
[[gauges]]
name = "g1"
position = ["3 in", "4 in"]
"""

SPEC = """
[sweep]
case = "plate.toml"
method = "monte-carlo"
runs = {runs}
chunk = 100
outputs = ["peak_force_N", "strain_g1.peak_abs", "damage.max_strain", "damage.tsai_wu", "damage.hashin", "damage.delamination"]
[[sweep.parameter]]
key = "load.history.velocity"
distribution = {{ uniform = ["1000 in/s", "8000 in/s"] }}
"""


def timed(runs: int, workers: int) -> tuple[float, int]:
    with tempfile.TemporaryDirectory() as d:
        (Path(d) / "plate.toml").write_text(CASE)
        (Path(d) / "spec.toml").write_text(SPEC.format(runs=runs))
        plan = plan_sweep(load_sweep_spec(str(Path(d) / "spec.toml")))
        t0 = time.perf_counter()
        rows, computed = execute(plan, None, workers)
        assert all(r["error"] is None for r in rows.values()), [r["error"] for r in rows.values() if r["error"]][:3]
        return time.perf_counter() - t0, computed


def engine_build() -> tuple[float, float]:
    """(prepare: model + impulse responses [s], one run on it [s])."""
    import tomllib

    from softimpact.cases import PlateKind as PlateCase

    data = tomllib.loads(CASE)
    t0 = time.perf_counter()
    model = PlateCase().prepare(data, Path("."), 2)
    t1 = time.perf_counter()
    for _ in range(20):
        PlateCase().run(model, data, Path("."))
    return t1 - t0, (time.perf_counter() - t1) / 20


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=1000)
    a = ap.parse_args()
    build, run = engine_build()
    print(f"prepare (model + impulse responses): {build:.2f} s; one run on it: {run * 1e3:.1f} ms")
    print("| sweep | runs | plain loop | Dask, 1 worker | Dask, 2 workers |")
    print("|---|---|---|---|---|")
    cells = []
    for workers in (0, 1, 2):
        dt, computed = timed(a.runs, workers)
        cells.append(f"{dt:.1f} s ({computed / dt:.3g} runs/s)")
    print(f"| plate velocity, one structure (engine) | {a.runs} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
