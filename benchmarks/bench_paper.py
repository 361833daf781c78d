"""`softimpact paper` whole, with the figures: the wall time of the run and each task's CPU and wall time.

The report's computations and sections run as tasks on the machine's cores (softimpact.studies.tasks); this
script runs `paper(figures=True)` in this process (the command's function, without writing the files), prints
the load average before and after (a wall time means something only on a quiet machine), the wall time, the
sum of the tasks' CPU times, and each task's CPU and wall time, costliest first.
Usage: python benchmarks/bench_paper.py [workers]   (default: the cores this process may use; 1: one process)
"""

import os
import platform
import sys
import time

os.environ.setdefault("MPLBACKEND", "Agg")


def main(workers=None):
    from softimpact.app.paper import paper

    print(f"machine: {platform.machine()}, {os.cpu_count()} cores, python {platform.python_version()}")
    print(f"load average before: {os.getloadavg()[0]:.2f}")
    timings = []
    t0 = time.perf_counter()
    out = paper(figures=True, workers=workers, timings=timings)
    wall = time.perf_counter() - t0
    print(f"load average after: {os.getloadavg()[0]:.2f}")
    print(f"softimpact paper (figures): wall {wall:.1f} s, tasks' CPU {sum(c for _, c, _ in timings):.1f} s, {len(out.files)} files")
    for name, cpu, w in sorted(timings, key=lambda t: -t[1]):
        print(f"  {name:60s} CPU {cpu:6.2f} s  wall {w:6.2f} s")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else None)
