"""Whole-process timings: `softimpact beam` against a plain scikit-fem script, and `softimpact --help`.

Both beam runs are whole processes (interpreter start, imports, assembly, 1000
Newmark steps, output), measured alternately in one run of this script:
- `softimpact beam paper-long-beam --no-figures` (writes its CSV and JSON);
- `python benchmarks/plain_beam.py`: the same mesh and steps with scikit-fem + splu.
Usage: python benchmarks/bench_startup.py [repeats]
"""

import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
BIN = Path(sys.executable).parent


def timed(cmd) -> float:
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - t0


def main(repeats: int = 5):
    print(f"machine: {platform.machine()}, python {platform.python_version()}; best and median of {repeats} whole processes")
    with tempfile.TemporaryDirectory() as tmp:
        runs = {
            "softimpact beam paper-long-beam --no-figures": [str(BIN / "softimpact"), "beam", "paper-long-beam", "--no-figures", "--out", tmp],
            "plain scikit-fem + splu script": [sys.executable, str(HERE / "plain_beam.py")],
            "softimpact --help": [str(BIN / "softimpact"), "--help"],
        }
        times = {name: [] for name in runs}
        for _ in range(repeats):
            for name, cmd in runs.items():
                times[name].append(timed(cmd))
    for name, ts in times.items():
        ts.sort()
        print(f"  {name:48s} best {ts[0]:.2f} s, median {ts[len(ts) // 2]:.2f} s")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
