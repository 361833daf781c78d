"""Whole-process timings: `softimpact beam` against a plain scikit-fem script, and `softimpact --help`.

Both beam runs are whole processes (interpreter start, imports, assembly, 1000
Newmark steps, output), measured alternately in one run of this script:
- `softimpact beam paper-long-beam --no-figures` (writes its CSV and JSON);
- `python benchmarks/plain_beam.py`: the same mesh and steps with scikit-fem + splu.
Bytecode is cached as in a user's environment (timing.USER_ENV) and each command is
run once before timing, which also fills softimpact's unit-factor cache (a
fresh folder here) as a user's first run does; the same command with the cache
turned off (``SOFTIMPACT_CACHE_DIR=""``: pint imported every run, as on a first
run) is timed beside it. Wall clock suffers from whatever else the machine runs; the CPU time of each
process (user + system) much less, so both are printed. BLAS is held to one
thread in both processes (OMP_NUM_THREADS=1).
Usage: python benchmarks/bench_startup.py [repeats]
"""

import os
import platform
import sys
import tempfile
from pathlib import Path

from timing import USER_ENV, process

HERE = Path(__file__).resolve().parent
BIN = Path(sys.executable).parent


def main(repeats: int = 5):
    print(f"machine: {platform.machine()}, python {platform.python_version()}; best and median of {repeats} whole processes")
    with tempfile.TemporaryDirectory() as tmp, tempfile.TemporaryDirectory() as cache:
        beam = [str(BIN / "softimpact"), "beam", "paper-long-beam", "--no-figures", "--out", tmp]
        env = USER_ENV | {"SOFTIMPACT_CACHE_DIR": cache}
        runs = {
            "softimpact beam paper-long-beam --no-figures": (beam, env),
            "  the same, unit cache off (pint imported)": (beam, env | {"SOFTIMPACT_CACHE_DIR": ""}),
            "plain scikit-fem + splu script": ([sys.executable, str(HERE / "plain_beam.py")], env),
            "softimpact --help": ([str(BIN / "softimpact"), "--help"], env),
        }
        times = {name: [] for name in runs}
        for cmd, e in runs.values():  # warm-up: bytecode written, files in the page cache, unit cache filled
            process(cmd, e)
        for _ in range(repeats):
            for name, (cmd, e) in runs.items():
                times[name].append(process(cmd, e))
    print(f"  load average {os.getloadavg()[0]:.1f}; wall clock (best, median) and CPU time (best, median), one BLAS thread each")
    for name, ts in times.items():
        wall = sorted(w for w, _ in ts)
        cpu = sorted(c for _, c in ts)
        print(f"  {name:48s} wall {wall[0]:.2f} / {wall[len(wall) // 2]:.2f} s   CPU {cpu[0]:.2f} / {cpu[len(cpu) // 2]:.2f} s")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
