"""One default calibration of a test, as a whole process (issue 9: under 5 s on the standard machine).

`softimpact calibrate paper-long-beam --measured <record> --velocity V --no-figures`
on two records of the built-in long-beam calibration series, with the default
settings: the model's discretisation checked against one refinement and refined
within the default budget (here to 400 × 12 elements, 0.5 µs), least squares with
the model error corrected, and the deconvolution beside it. Wall clock and CPU
time (user + system of the process); bytecode cached, one BLAS thread.

Usage: python benchmarks/bench_calibrate.py [repeats]
"""

import os
import resource
import subprocess
import sys
import tempfile
import time
from importlib import resources
from pathlib import Path

BIN = Path(sys.executable).parent
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"} | {"OMP_NUM_THREADS": "1"}
TESTS = [("long-V1166.csv", "1166 in/s", "0.25 in"), ("long-V4026.csv", "4026 in/s", "0.35 in")]


def timed(cmd) -> tuple[float, float]:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=ENV)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main(repeats: int = 3):
    data = resources.files("softimpact") / "data" / "series" / "paper-long-calibration"
    print(f"load average {os.getloadavg()[0]:.1f}; best and median of {repeats} whole processes")
    with tempfile.TemporaryDirectory() as tmp:
        for name, velocity, radius in TESTS:
            cmd = [str(BIN / "softimpact"), "calibrate", "paper-long-beam", "--measured", str(data / name), "--velocity", velocity]
            cmd += ["--contact-radius", radius, "--no-figures", "--out", tmp]
            timed(cmd)  # warm-up
            runs = [timed(cmd) for _ in range(repeats)]
            wall = sorted(w for w, _ in runs)
            cpu = sorted(c for _, c in runs)
            print(f"  {name:16s} wall {wall[0]:.2f} / {wall[len(wall) // 2]:.2f} s   CPU {cpu[0]:.2f} / {cpu[len(cpu) // 2]:.2f} s")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 3)
