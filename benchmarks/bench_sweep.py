"""Sweep throughput (issue 13): runs per second for a velocity sweep on one structure (the
response engine) and for a sweep that changes the structure every run (a new model and
direct stepping each), in a plain loop and on a local Dask cluster of 1 and 2 workers.

Usage: python benchmarks/bench_sweep.py [--runs N] [--structures M]

Times are wall clock from the spec read to the last run (cluster start-up included, and
reported apart); no output files are written. Prints a Markdown table.
"""

import argparse
import tempfile
import time
from pathlib import Path

from softimpact.cases.sweep import execute, plan_sweep
from softimpact.input.sweep_spec import load_sweep_spec

VELOCITY = """
[sweep]
case = "paper-long-beam"
method = "monte-carlo"
runs = {runs}
chunk = 100
outputs = ["peak_force_N", "strain_g1.peak", "strain_g2.peak"]
[[sweep.parameter]]
key = "load.history"
value = {{ shape = "empirical", projectile = "rubber-1/2in", velocity = "1166 in/s" }}
[[sweep.parameter]]
key = "load.history.velocity"
distribution = {{ uniform = ["1000 in/s", "5000 in/s"] }}
"""

STRUCTURE = (
    VELOCITY
    + """
[[sweep.parameter]]
key = "beam.laminate.ply.E2"
distribution = {{ normal = ["7.9 GPa", "0.4 GPa"] }}
"""
)


def timed(text: str, workers: int) -> tuple[float, int]:
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "spec.toml"
        path.write_text(text)
        plan = plan_sweep(load_sweep_spec(str(path)))
        t0 = time.perf_counter()
        rows, computed = execute(plan, None, workers)
        assert all(r["error"] is None for r in rows.values())
        return time.perf_counter() - t0, computed


def cluster_start() -> float:
    from softimpact.cases.sweep import _client

    t0 = time.perf_counter()
    client, cluster = _client(2, None)
    dt = time.perf_counter() - t0
    client.close()
    cluster.close()
    return dt


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=1000)
    ap.add_argument("--structures", type=int, default=40)
    a = ap.parse_args()
    print("| sweep | runs | plain loop | Dask, 1 worker | Dask, 2 workers |")
    print("|---|---|---|---|---|")
    for name, text, n in (("velocity, one structure (engine)", VELOCITY, a.runs), ("structure changes every run", STRUCTURE, a.structures)):
        cells = []
        for workers in (0, 1, 2):
            dt, computed = timed(text.format(runs=n), workers)
            cells.append(f"{dt:.1f} s ({computed / dt:.3g} runs/s)")
        print(f"| {name} | {n} | " + " | ".join(cells) + " |")
    print(f"\nLocalCluster of 2 workers: start-up and shut-down {cluster_start():.1f} s")


if __name__ == "__main__":
    main()
