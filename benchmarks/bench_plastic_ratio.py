"""The elastic–plastic von Kármán plate against the elastic von Kármán plate of the same mesh and steps, in one
process (CPU seconds; the target: at most 3×).

    python benchmarks/bench_plastic_ratio.py

Runs the built-in ``hail-al-skin`` (a 50.8-mm hailstone at 40 m/s on the quarter of a clamped 250-mm, 2-mm
Al 2024-T3 panel, 12 × 12 MITC9, 1000 steps of 2 µs) twice: as given (elastic–plastic) and with
``plate.plasticity = false`` (elastic), each through the same coupled stepper. Prints each run's CPU, Newton
iterations and the ratio; record them in BENCHMARKS.md with the machine and the date."""

import time


def run(plastic: bool):
    from dataclasses import replace

    from softimpact.cases import KINDS
    from softimpact.input.impact_case import load_impact_case

    problem, _ = load_impact_case("hail-al-skin")
    if not plastic:
        target = problem.target
        problem = replace(problem, target=replace(target, plasticity=False))
    t0 = time.process_time()
    out = KINDS["impact"].execute(problem, figures=False)
    cpu = time.process_time() - t0
    s = out.summary
    return cpu, s.get("newton_iterations"), s["peak_force_N"], s["damage"]


def main():
    elastic = run(False)
    plastic = run(True)
    for name, (cpu, its, peak, dmg) in (("elastic", elastic), ("elastic-plastic", plastic)):
        extra = f"dent {dmg.get('dent_depth_m', 0) * 1e3:.3g} mm, plastic work {dmg.get('plastic_work_J', 0):.3g} J" if "dent_depth_m" in dmg else ""
        print(f"{name:16s} CPU {cpu:7.2f} s, Newton iterations {its}, peak force {peak / 1e3:.3g} kN {extra}")
    print(f"ratio elastic-plastic / elastic: {plastic[0] / elastic[0]:.2f}")


if __name__ == "__main__":
    main()
