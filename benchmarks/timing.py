"""Timing shared by the benchmark scripts."""

import os
import resource
import subprocess
import time

# As a user's shell has it: bytecode cached (this machine's environment sets
# PYTHONDONTWRITEBYTECODE, which makes an editable install recompile its sources
# on every start while pip-installed packages keep their .pyc), one BLAS thread.
USER_ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"} | {"OMP_NUM_THREADS": "1"}


def best(fn, repeat: int = 3) -> float:
    """The shortest of ``repeat`` wall-clock times [s] of ``fn()``."""
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def process(cmd, env=None) -> tuple[float, float]:
    """(wall-clock, CPU user + system) seconds of one whole process ``cmd``, run in ``env``
    (default: this one's): on a shared machine the CPU time is the steadier measure."""
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
    wall = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
