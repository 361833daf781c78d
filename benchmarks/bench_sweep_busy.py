"""The plate's Monte Carlo beside a busy process: chunk times with the BLAS threads as they were (OpenBLAS's
default, one per core) and held to one (:data:`softimpact.cases.sweep.BLAS_THREADS`, the sweep's default now).

The sweep of the built-in plate-ss-8in-impact (steel ball 1/2 in, Hertz, the 48 × 48 MITC9 plate, 0.5 µs steps;
its duration cut to ``--duration`` µs, default 600, the contact lasting about 224 µs) over the impact velocity,
uniform in 50–150 in/s, ``--runs`` runs in chunks of ``--chunk``, as ``softimpact sweep --workers 0`` runs it: the
group's contact kernels built once (timed apart), then chunk after chunk in this process. A busy process
(``yes > /dev/null``) holds a core the whole time. The chunks alternate between the two settings, so the machine's
other load moves both alike; each chunk's wall-clock and CPU times are printed, then the medians.

Usage: python benchmarks/bench_sweep_busy.py [--runs N] [--chunk C] [--duration US] [--no-busy]
"""

import argparse
import os
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

from threadpoolctl import threadpool_info, threadpool_limits

from softimpact.cases.sweep import plan_sweep, prepare_group, run_chunk
from softimpact.input.sweep_spec import load_sweep_spec
from softimpact.input.toml import builtin_cases

SPEC = """
[sweep]
case = "impact.toml"
method = "monte-carlo"
runs = {runs}
seed = 11
chunk = {chunk}
outputs = ["peak_force_N", "contact_duration_s"]
[[sweep.parameter]]
key = "impactor.velocity"
distribution = {{ uniform = ["50 in/s", "150 in/s"] }}
"""


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=200)
    ap.add_argument("--chunk", type=int, default=25)
    ap.add_argument("--duration", type=float, default=600.0)
    ap.add_argument("--no-busy", action="store_true")
    args = ap.parse_args()
    cases = builtin_cases()
    blas = [(i["internal_api"], i["num_threads"]) for i in threadpool_info() if i["user_api"] == "blas"]
    with tempfile.TemporaryDirectory() as d:
        d = Path(d)
        impact = cases["plate-ss-8in-impact"].read_text()
        impact = impact.replace('"plate-ss-8in"', f'"{cases["plate-ss-8in"]}"').replace('duration = "1000 us"', f'duration = "{args.duration:g} us"')
        (d / "impact.toml").write_text(impact)
        (d / "mc.toml").write_text(SPEC.format(runs=args.runs, chunk=args.chunk))
        plan = plan_sweep(load_sweep_spec(d / "mc.toml"))
        base, outputs = str(d), plan.spec.outputs
        busy = None if args.no_busy else subprocess.Popen("exec yes > /dev/null", shell=True)
        try:
            t0, c0 = time.perf_counter(), time.process_time()
            with threadpool_limits(1, user_api="blas"):
                prepared = prepare_group(plan.kind, [data for c in plan.chunks for _, data in c.items], base, len(plan.runs), outputs)
            build = (time.perf_counter() - t0, time.process_time() - c0)
            times = {"default BLAS threads": [], "one BLAS thread": []}
            for i, chunk in enumerate(plan.chunks):
                name = "default BLAS threads" if i % 2 == 0 else "one BLAS thread"
                t0, c0 = time.perf_counter(), time.process_time()
                with threadpool_limits(None if i % 2 == 0 else 1, user_api="blas"):
                    rows = run_chunk(plan.kind, prepared, chunk.items, base, outputs)
                wall, cpu = time.perf_counter() - t0, time.process_time() - c0
                times[name].append((wall, cpu))
                failed = sum(r["error"] is not None for r in rows)
                print(
                    f"chunk {i:2d} ({len(chunk.items)} runs, {name:20s}): wall {wall:7.2f} s, CPU {cpu:7.2f} s{f', {failed} failed' if failed else ''}",
                    flush=True,
                )
        finally:
            if busy is not None:
                busy.terminate()
                busy.wait()
    print(f"BLAS pools {blas} on {os.cpu_count()} cores; busy process: {'none' if args.no_busy else 'yes > /dev/null'}; load {os.getloadavg()}")
    print(f"kernel build (one BLAS thread): wall {build[0]:.1f} s, CPU {build[1]:.1f} s")
    for name, ts in times.items():
        if ts:
            print(
                f"{name:20s}: median chunk wall {statistics.median(t[0] for t in ts):7.2f} s, CPU {statistics.median(t[1] for t in ts):7.2f} s over {len(ts)} chunks"
            )


if __name__ == "__main__":
    main()
