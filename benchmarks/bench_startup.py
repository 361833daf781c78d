"""Whole-process timings: `softimpact beam` against a plain scikit-fem script, and `softimpact --help`.

Both beam runs are whole processes (interpreter start, imports, assembly, 1000
Newmark steps, output), measured alternately in one run of this script:
- `softimpact beam paper-long-beam --no-figures` (writes its CSV and JSON);
- `python benchmarks/plain_beam.py`: the same mesh and steps with scikit-fem + splu.
Bytecode is cached as in a user's environment (see ENV) and each command is
run once before timing. Wall clock suffers from whatever else the machine runs; the CPU time of each
process (user + system) much less, so both are printed. BLAS is held to one
thread in both processes (OMP_NUM_THREADS=1).
Usage: python benchmarks/bench_startup.py [repeats]
"""

import os
import platform
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
# As a user's shell has it: bytecode cached (this machine's environment sets
# PYTHONDONTWRITEBYTECODE, which makes an editable install recompile its sources
# on every start while pip-installed packages keep their .pyc), one BLAS thread.
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"} | {"OMP_NUM_THREADS": "1"}
BIN = Path(sys.executable).parent


def timed(cmd) -> tuple[float, float]:
    """Wall time and CPU time (user + system, from the child's resource usage) of a whole process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=ENV)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main(repeats: int = 5):
    print(f"machine: {platform.machine()}, python {platform.python_version()}; best and median of {repeats} whole processes")
    with tempfile.TemporaryDirectory() as tmp:
        runs = {
            "softimpact beam paper-long-beam --no-figures": [str(BIN / "softimpact"), "beam", "paper-long-beam", "--no-figures", "--out", tmp],
            "plain scikit-fem + splu script": [sys.executable, str(HERE / "plain_beam.py")],
            "softimpact --help": [str(BIN / "softimpact"), "--help"],
        }
        times = {name: [] for name in runs}
        for cmd in runs.values():  # warm-up: bytecode written, files in the page cache
            timed(cmd)
        for _ in range(repeats):
            for name, cmd in runs.items():
                times[name].append(timed(cmd))
    print(f"  load average {os.getloadavg()[0]:.1f}; wall clock (best, median) and CPU time (best, median), one BLAS thread each")
    for name, ts in times.items():
        wall = sorted(w for w, _ in ts)
        cpu = sorted(c for _, c in ts)
        print(f"  {name:48s} wall {wall[0]:.2f} / {wall[len(wall) // 2]:.2f} s   CPU {cpu[0]:.2f} / {cpu[len(cpu) // 2]:.2f} s")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
