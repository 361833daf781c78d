"""Timing shared by the benchmark scripts."""

import time


def best(fn, repeat: int = 3) -> float:
    """The shortest of ``repeat`` wall-clock times [s] of ``fn()``."""
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)
