"""Contact kernels against direct coupled stepping (issue 21), in one process.

Prints:
1. the 8-in plate (plate-ss-8in-impact: MITC9 48 × 48, 27 455 DOF, 2000 steps of 0.5 µs) and the long
   beam (paper-long-beam-impact: 200 × 6 Q4, 2800 DOF, 2000 steps of 0.5 µs): the model's assembly and
   factorisation; one direct coupled run (``run_impact(method="direct")``, energies off as a sweep runs
   it); the kernel build (:func:`softimpact.workflows.coupled.impact_kernels`) and its ratio to the direct
   run; the median of repeated kernel runs (``ContactKernels.run``) of the case's steel ball through
   Hertz's law and of a 1/2-in silicone-rubber ball at 2000 in/s through the identified law with its
   Maxwell arm (tests/data/law-v-main.json, with its Newton iterations), and of the whole
   ``run_impact(method="kernels")`` (summary scalars included); each law's largest force difference
   from direct stepping over the peak force;
2. the cost growth with the mesh: the plate at 16², 32², 48² MITC9 (DOF, direct run, build, run);
3. with ``--mc``: `softimpact sweep` Monte Carlo of 1000 coupled runs on the 48² plate (velocity
   U(1000, 5000) in/s, diameter U(3/8, 1/2) in, the law's parameters drawn from law.json), on 2 Dask
   workers, the wall time of the whole process (start, kernel build, runs, files).
Usage: python benchmarks/bench_kernels.py [repeats] [--mc | --only-mc] [--no-growth]
The same cases as an asv suite (a history over commits): benchmarks/asv/kernels.py, BENCHMARKS.md.
"""

import os
import platform
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from softimpact.input.impact_case import impact_problem, load_impact_case
from softimpact.input.toml import load_toml, locate
from softimpact.workflows.coupled import impact_kernels, impact_model, run_impact

LAW = Path(__file__).resolve().parent.parent / "tests" / "data" / "law-v-main.json"

RUBBER = """
title = "1/2-in silicone-rubber ball at 2000 in/s (identified law)"
[target]
case = "{target}"
[impactor]
material = "silicone rubber"
diameter = "0.5 in"
velocity = "{velocity}"
[contact]
law = "identified"
law_file = "law.json"
[solver]
time_step = "0.5 us"
duration = "1000 us"
"""

SPEC = """
[sweep]
case = "impact.toml"
method = "monte-carlo"
runs = 1000
seed = 1
chunk = 100
outputs = ["peak_force_N", "contact_duration_s", "gauges.g1.peak_tensile_strain"]
[[sweep.parameter]]
key = "impactor.velocity"
distribution = { uniform = ["1000 in/s", "5000 in/s"] }
[[sweep.parameter]]
key = "impactor.diameter"
distribution = { uniform = ["0.375 in", "0.5 in"] }
[[sweep.parameter]]
key = "contact"
from = "law.json"
"""


def _timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return time.perf_counter() - t0, out


def _median(fn, repeats: int) -> tuple[float, float]:
    """(median, best) of ``repeats`` wall-clock times [s] of ``fn()``."""
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), min(times)


def _plate_case(folder: Path, elements: int) -> str:
    text = locate("plate-ss-8in").read_text()
    path = folder / f"plate-{elements}.toml"
    path.write_text(re.sub(r"elements = \[48, 48\]", f"elements = [{elements}, {elements}]", text))
    return path.name


def _rubber(folder: Path, target: str):
    (folder / "rubber.toml").write_text(RUBBER.format(target=target, velocity="2000 in/s"))
    return impact_problem(load_toml(folder / "rubber.toml"), folder)[0]


def structure(name: str, steel, rubber, repeats: int) -> dict:
    """Model, direct run, kernel build and kernel runs of one target."""
    t_model, model = _timed(lambda: impact_model(steel))
    t_direct, (_, direct) = _timed(lambda: run_impact(steel, model, energy=False, method="direct"))
    t_build, kernels = _timed(lambda: impact_kernels(steel, model))
    imp = steel.impactor
    run = _median(lambda: kernels.run(steel.law, imp.mass, imp.velocity), repeats)
    whole = _median(lambda: run_impact(steel, model, energy=False, method="kernels", kernels=kernels), repeats)
    ri = rubber.impactor
    soft = _median(lambda: kernels.run(rubber.law, ri.mass, ri.velocity), repeats)
    fast = kernels.run(steel.law, imp.mass, imp.velocity)
    err = float(abs(fast.force - direct.force).max() / direct.force.max())
    contact = int((fast.force > 0).sum())
    slow = kernels.run(rubber.law, ri.mass, ri.velocity)
    soft_contact = int((slow.force > 0).sum())
    _, soft_direct = run_impact(rubber, model, energy=False, method="direct")
    soft_err = float(abs(slow.force - soft_direct.force).max() / soft_direct.force.max())
    print(
        f"{name}: {model.size} DOF, {steel.solver.steps} steps; model {t_model:.2f} s; direct coupled run {t_direct:.3f} s; "
        f"kernel build {t_build:.3f} s = {t_build / t_direct:.2f} x direct; kernel run (Hertz, {contact} steps in contact) median {run[0] * 1e3:.1f} ms "
        f"(best {run[1] * 1e3:.1f}), run_impact on kernels {whole[0] * 1e3:.1f} ms; identified law ({soft_contact} steps in contact, "
        f"{slow.newton_iterations} Newton iterations) median {soft[0] * 1e3:.1f} ms (best {soft[1] * 1e3:.1f}); "
        f"max |F_kernels - F_direct| / F_peak = {err:.1e} (Hertz), {soft_err:.1e} (identified law)",
        flush=True,
    )
    return {"direct": t_direct, "build": t_build, "run": run, "soft": soft}


def monte_carlo(folder: Path) -> float:
    shutil.copy(LAW, folder / "law.json")
    (folder / "impact.toml").write_text(RUBBER.format(target="plate-ss-8in", velocity="2000 in/s"))
    (folder / "spec.toml").write_text(SPEC)
    exe = Path(sys.executable).parent / "softimpact"
    env = dict(os.environ, OMP_NUM_THREADS="1", PYTHONWARNINGS="ignore")
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run([str(exe), "sweep", str(folder / "spec.toml"), "--out", str(folder / "mc"), "--workers", "2", "--no-figures"], check=True, env=env)
    wall = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    import json

    s = json.loads((folder / "mc" / "summary.json").read_text())
    print(
        f"Monte Carlo, 1000 coupled runs on the 48² plate, 2 workers: {wall:.1f} s wall (whole process, kernel build included); "
        f"CPU {cpu:.1f} s (workers reaped); {s['succeeded']} succeeded, {s['failed']} failed, {s['groups']} group(s)",
        flush=True,
    )
    return wall


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    repeats = int(args[0]) if args else 7
    print(
        f"{platform.node()} {platform.processor() or platform.machine()}, Python {platform.python_version()}, {os.cpu_count()} cores; "
        f"load {os.getloadavg()[0]:.2f} {os.getloadavg()[1]:.2f} {os.getloadavg()[2]:.2f}; {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}",
        flush=True,
    )
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        shutil.copy(LAW, folder / "law.json")
        if "--only-mc" in sys.argv:
            monte_carlo(folder)
            return
        beam, _ = load_impact_case("paper-long-beam-impact")
        structure("long beam 200x6", beam, _rubber(folder, "paper-long-beam"), repeats)
        meshes = (48,) if "--no-growth" in sys.argv else (16, 32, 48)
        for n in meshes:
            steel, _ = load_impact_case("plate-ss-8in-impact")
            target = _plate_case(folder, n)
            data = load_toml(locate("plate-ss-8in-impact"))
            data["target"]["case"] = target
            steel = impact_problem(data, folder)[0]
            structure(f"plate MITC9 {n}x{n}", steel, _rubber(folder, target), repeats)
        if "--mc" in sys.argv:
            monte_carlo(folder)


if __name__ == "__main__":
    main()
