"""The reduced-order von Kármán plate against the full one: a coupled impact on the 48 × 48 MITC9 plate.

The built-in plate-ss-8in-impact (steel ball 1/2 in, Hertz in Sun's form, the simply supported 8 × 8 in [90/0]5s
plate, 48 × 48 MITC9, 0.5 µs steps) with ``kinematics = "von-karman"`` (immovable edges), at ``--velocity`` in/s
(default 400: the plate past w/h ≈ 0.5 under the ball), ``--steps`` steps (the run stops 20 µs after separation):

- full: ``run_impact(method="von-karman")`` (45 505 DOF, one monolithic Newton a step);
- reduced: :class:`softimpact.fem.vk_rom.PlateVKROM` built once (timed apart), then
  :class:`~softimpact.fem.vk_rom.ReducedVonKarmanStepper` runs (best of ``--repeat``, wall-clock and CPU);
- linear: ``run_impact(method="direct")`` on the linear plate, for the size of the nonlinear effect.

Prints peak force and contact time of each, the reduced model's errors against the full one, and the times.

Usage: python benchmarks/bench_vk_rom.py [--velocity V] [--steps N] [--configs R:RN,...] [--repeat K]
"""

import argparse
import sys
import time
from dataclasses import replace
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from threadpoolctl import threadpool_limits  # noqa: E402

from softimpact.fem.impact import coupled_result  # noqa: E402
from softimpact.fem.newmark import SolverSpec  # noqa: E402
from softimpact.fem.vk_rom import NONLINEAR, VECTORS, PlateVKROM, ReducedVonKarmanStepper  # noqa: E402
from softimpact.input.impact_case import load_impact_case  # noqa: E402
from softimpact.workflows.coupled import impact_model, run_impact  # noqa: E402

INCH = 0.0254
STOP_AFTER = 20e-6  # [s] after separation


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--velocity", type=float, default=400.0)
    ap.add_argument("--steps", type=int, default=600)
    ap.add_argument("--configs", default=f"{VECTORS}:{NONLINEAR}", help="reduced models to try, vectors:nonlinear[,...]")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    p, _ = load_impact_case("plate-ss-8in-impact")
    t = p.target
    dt = t.solver.time_step
    t = replace(t, solver=SolverSpec(dt, args.steps * dt, t.solver.newmark))
    lin = replace(p, target=t, impactor=replace(p.impactor, velocity=args.velocity * INCH))
    vk = replace(lin, target=replace(t, kinematics="von-karman"))
    with threadpool_limits(1, user_api="blas"):
        _, r_lin = run_impact(lin, energy=False, method="direct", stop_after=STOP_AFTER)
        m = impact_model(vk)
        t0, c0 = time.perf_counter(), time.process_time()
        _, full = run_impact(vk, m, energy=False, method="von-karman", stop_after=STOP_AFTER)
        t_full, c_full = time.perf_counter() - t0, time.process_time() - c0
        st = m.contact_structure(vk.position, m.contact_reach(vk.position, vk.impactor.diameter))
        thick = m.vk.plate.section.thickness
        print(f"{args.velocity:g} in/s, {m.vk.n} DOF full, max w/h {abs(full.target_displacement).max() / thick:.2f}")
        print(f"linear      peak {r_lin.peak_force:9.2f} N  contact {r_lin.contact_duration * 1e6:8.2f} us")
        print(f"full VK     peak {full.peak_force:9.2f} N  contact {full.contact_duration * 1e6:8.2f} us  run {t_full:8.2f} s wall, {c_full:8.2f} s CPU")
        print(
            f"linear - full: peak {r_lin.peak_force / full.peak_force - 1:+.3%}, contact {r_lin.contact_duration / full.contact_duration - 1:+.3%}", flush=True
        )
        for config in args.configs.split(","):
            vectors, nonlinear = (int(x) for x in config.split(":"))
            t0, c0 = time.perf_counter(), time.process_time()
            rom = PlateVKROM(m.vk, st.approach_row, vectors, nonlinear, C=st.C)
            t_build, c_build = time.perf_counter() - t0, time.process_time() - c0
            runs = []
            for _ in range(args.repeat):
                t0, c0 = time.perf_counter(), time.process_time()
                s = ReducedVonKarmanStepper(
                    st, vk.law, vk.impactor.mass, vk.impactor.velocity, dt, args.steps, vk.solver.newmark, engine=rom, energy=False, stop_after=STOP_AFTER
                )
                red = coupled_result(s.run(), vk.impactor, tuple(st.output_names))
                runs.append((time.perf_counter() - t0, time.process_time() - c0))
            print(
                f"reduced {rom.r:3d} vectors ({rom.rn:2d} nonlinear): peak {red.peak_force:9.2f} N ({red.peak_force / full.peak_force - 1:+.3%}), "
                f"contact {red.contact_duration * 1e6:8.2f} us ({red.contact_duration / full.contact_duration - 1:+.3%}); "
                f"run {min(x[0] for x in runs):6.3f} s wall, {min(x[1] for x in runs):6.3f} s CPU (best of {args.repeat}); build {t_build:.2f} s wall, {c_build:.2f} s CPU",
                flush=True,
            )


if __name__ == "__main__":
    main()
