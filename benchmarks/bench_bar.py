"""Time the paper's calibration case (39 Hermite elements, 800 steps of 0.5 µs).

Prints the best of several runs, split into assembly and solve.
Usage: python benchmarks/bench_bar.py
"""

import platform
import time

import numpy as np

from softimpact.fem.bar import Rod, assemble_rod
from softimpact.input.bar_case import load_bar_case
from softimpact.workflows.bar_impact import simulate_impact


def best(fn, repeat=15):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times), float(np.median(times))


def main():
    problem, _ = load_bar_case("paper-calibration")
    simulate_impact(problem)  # warm up imports
    total = best(lambda: simulate_impact(problem))
    assembly = best(lambda: assemble_rod(Rod.of(problem.bar)))
    print(f"machine: {platform.processor() or platform.machine()}, python {platform.python_version()}")
    print(f"paper calibration case, {problem.solver.steps} steps, 80 DOF")
    print(f"  whole run (assembly + solve + post): best {total[0] * 1e3:.1f} ms, median {total[1] * 1e3:.1f} ms")
    print(f"  assembly (scikit-fem):               best {assembly[0] * 1e3:.1f} ms")
    print(f"  solve + post (difference):           best {(total[0] - assembly[0]) * 1e3:.1f} ms")
    try:
        import openseespy  # noqa: F401
    except ImportError:
        print("  openseespy not importable: reference figure from the issue, about 70 ms for the solve")


if __name__ == "__main__":
    main()
