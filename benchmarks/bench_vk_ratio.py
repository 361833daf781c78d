"""Large deflection at design-study speed: a coupled von Kármán impact on the 48 × 48 MITC9 plate against
the linear direct run, both in this one process (a loaded machine moves both alike: the ratio is the measure).

The built-in plate-ss-8in-impact (steel ball 1/2 in at 100 in/s, Hertz in Sun's form, on the simply supported
8 × 8 in [90/0]5s plate, 48 × 48 MITC9, 0.5 µs steps), cut to ``--steps`` steps (default 500: 250 µs, the
contact lasts about 224 µs), without energy histories:

- linear: ``run_impact(method="direct")`` on the linear plate (27 455 DOF; its Newmark factor built once);
- von Kármán: ``run_impact(method="von-karman")`` on the same plate with ``kinematics = "von-karman"``,
  immovable edges (45 505 DOF with the membrane DOFs; modified Newton, one monolithic Newton a step).

Prints the model builds, the runs (best of ``--repeat``, alternated), the stepping ratio and the ratio with
the builds, the peak forces and contact times of both, and the von Kármán run's Newton iterations and
factorisations.

Usage: python benchmarks/bench_vk_ratio.py [--steps N] [--repeat R]
"""

import argparse
import platform
import sys
import time
from dataclasses import replace
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from threadpoolctl import threadpool_limits  # noqa: E402

from softimpact.fem.newmark import SolverSpec  # noqa: E402
from softimpact.input.impact_case import load_impact_case  # noqa: E402
from softimpact.workflows.coupled import impact_model, run_impact  # noqa: E402


def problems(steps: int):
    """(linear, von Kármán) impact problems of the built-in case, ``steps`` steps of its 0.5 µs."""
    p, _ = load_impact_case("plate-ss-8in-impact")
    t = p.target
    dt = t.solver.time_step
    lin = replace(p, target=replace(t, solver=SolverSpec(dt, steps * dt, t.solver.newmark)))
    return lin, replace(lin, target=replace(lin.target, kinematics="von-karman"))


def timed(fn):
    """((wall-clock, CPU) seconds, fn())."""
    t0, c0 = time.perf_counter(), time.process_time()
    out = fn()
    return (time.perf_counter() - t0, time.process_time() - c0), out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", type=int, default=500)
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args()
    lin, vk = problems(args.steps)
    with threadpool_limits(1, user_api="blas"):
        b_lin, m_lin = timed(lambda: (m := impact_model(lin), m.stepper)[0])  # the linear factor built here
        b_vk, m_vk = timed(lambda: impact_model(vk))
        t_lin, t_vk = [], []
        for _ in range(args.repeat):
            dt, (_, r_lin) = timed(lambda: run_impact(lin, m_lin, energy=False, method="direct"))
            t_lin.append(dt)
            f0 = m_vk.stepper.factorisations
            dt, (_, r_vk) = timed(lambda: run_impact(vk, m_vk, energy=False, method="von-karman"))
            t_vk.append(dt)
            factors = m_vk.stepper.factorisations - f0
    n = args.steps
    a, b = min(x[0] for x in t_lin), min(x[0] for x in t_vk)
    ca, cb = min(x[1] for x in t_lin), min(x[1] for x in t_vk)
    b_lin, b_vk = b_lin[0], b_vk[0]
    print(f"python {platform.python_version()}, {platform.machine()}; {n} steps of {lin.solver.time_step * 1e6:g} us, one BLAS thread")
    print(f"linear plate      {m_lin.size:>6} DOF  build {b_lin:6.2f} s  run {a:7.2f} s ({a / n * 1e3:5.1f} ms/step)")
    print(f"von Karman plate  {m_vk.size:>6} DOF  build {b_vk:6.2f} s  run {b:7.2f} s ({b / n * 1e3:5.1f} ms/step)")
    print(
        f"ratio von Karman / linear: stepping {b / a:.2f} wall, {cb / ca:.2f} CPU ({ca:.1f} s against {cb:.1f} s); with the builds {(b + b_vk) / (a + b_lin):.2f} wall"
    )
    print(f"peak force  linear {r_lin.peak_force:8.2f} N, von Karman {r_vk.peak_force:8.2f} N")
    print(f"contact     linear {r_lin.contact_duration * 1e6:8.2f} us, von Karman {r_vk.contact_duration * 1e6:8.2f} us")
    print(f"von Karman: {factors} factorisations in the last run, Newton iterations {r_vk.newton_iterations}")


if __name__ == "__main__":
    main()
