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
import sys
import tempfile
from importlib import resources
from pathlib import Path

from timing import USER_ENV, process

BIN = Path(sys.executable).parent
TESTS = [("long-V1166.csv", "1166 in/s", "0.25 in"), ("long-V4026.csv", "4026 in/s", "0.35 in")]


def main(repeats: int = 3):
    data = resources.files("softimpact") / "data" / "series" / "paper-long-calibration"
    print(f"load average {os.getloadavg()[0]:.1f}; best and median of {repeats} whole processes")
    with tempfile.TemporaryDirectory() as tmp:
        for name, velocity, radius in TESTS:
            cmd = [str(BIN / "softimpact"), "calibrate", "paper-long-beam", "--measured", str(data / name), "--velocity", velocity]
            cmd += ["--contact-radius", radius, "--no-figures", "--out", tmp]
            process(cmd, USER_ENV)  # warm-up
            runs = [process(cmd, USER_ENV) for _ in range(repeats)]
            wall = sorted(w for w, _ in runs)
            cpu = sorted(c for _, c in runs)
            print(f"  {name:16s} wall {wall[0]:.2f} / {wall[len(wall) // 2]:.2f} s   CPU {cpu[0]:.2f} / {cpu[len(cpu) // 2]:.2f} s")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 3)
