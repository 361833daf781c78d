"""Coupled impact on a plate: the built-in plate-ss-8in-impact (steel ball 1/2 in at 100 in/s on the
SS 8 × 8 in [90/0]5s plate, 48 × 48 MITC4, 6815 DOF), dt = 0.5 µs.

Prints, in one script on the same mesh and steps (1200 × 0.5 µs):
- a prescribed-force run (PlateModel.direct, no energies) of the coupled run's own force history;
- the coupled run (Hertz, Sun's form with E3 = 7.9 GPa), without and with the energy histories.
Then, as whole processes (interpreter start, imports, case parsing, assembly, stepping, output,
``--no-figures``), alternated: `softimpact impact plate-ss-8in-impact` (2000 × 0.5 µs) against
`softimpact plate` on plate-ss-8in with its step set to 0.5 µs and its duration to 1000 µs (2000 × 0.5 µs),
and both at the plate case's own 1 µs (1000 steps).
Usage: python benchmarks/bench_plate_impact.py [repeats]
"""

import platform
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from timing import USER_ENV, best, process  # noqa: E402

from softimpact.fem.newmark import SolverSpec  # noqa: E402
from softimpact.input.impact_case import load_impact_case  # noqa: E402
from softimpact.workflows.coupled import impact_model, simulate_coupled  # noqa: E402

STEPS = 1200


def main():
    p, _ = load_impact_case("plate-ss-8in-impact")
    t = p.target
    p = replace(p, target=replace(t, solver=SolverSpec(0.5e-6, STEPS * 0.5e-6, t.solver.newmark)))
    t0 = time.perf_counter()
    model = impact_model(p)
    build = time.perf_counter() - t0
    st = model.contact_structure(p.position, model.contact_reach(p.position, p.impactor.diameter))
    run = lambda energy: simulate_coupled(st, p.law, p.impactor, p.solver, energy=energy, stepper=model.stepper)  # noqa: E731
    res = run(False)
    F = res.force
    # the prescribed run: the same force history on the model's own 0.25-in patch (eq 10), same mesh and steps
    t_pre = best(lambda: model.direct(F, energy=False, snapshots=()))
    t_cpl = best(lambda: run(False))
    t_cple = best(lambda: run(True), repeat=1)
    n = p.solver.steps
    print(f"python {platform.python_version()}, {platform.machine()}; {model.fe.n} DOF, {n} steps of {p.solver.time_step * 1e6:g} us")
    print(f"assembly + factorisation          {build:7.3f} s")
    print(f"prescribed force (direct)         {t_pre:7.3f} s   {t_pre / n * 1e6:6.1f} us/step")
    print(f"coupled, no energies              {t_cpl:7.3f} s   {t_cpl / n * 1e6:6.1f} us/step   ratio {t_cpl / t_pre:.2f}")
    print(f"coupled, with energy histories    {t_cple:7.3f} s   {t_cple / n * 1e6:6.1f} us/step")
    print(f"Newton iterations {res.newton_iterations} ({res.newton_iterations / n:.2f}/step incl. free flight), contacts {len(res.contacts)}")


def whole_process(repeats: int = 3):
    from softimpact.input.toml import builtin_cases

    exe = str(Path(sys.executable).parent / "softimpact")
    cases = builtin_cases()
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        # `softimpact plate` defaults to MITC9, `impact` reads its target with MITC4: name the element
        # so that both commands run the same 48 × 48 MITC4 model.
        plate = cases["plate-ss-8in"].read_text().replace("elements = [48, 48]", 'elements = [48, 48]\nelement = "mitc4"')
        impact = cases["plate-ss-8in-impact"].read_text()
        (tmp / "plate-05us.toml").write_text(plate.replace('time_step = "1 us"', 'time_step = "0.5 us"'))
        (tmp / "plate-1us.toml").write_text(plate)
        (tmp / "impact-1us.toml").write_text(
            impact.replace('time_step = "0.5 us"', 'time_step = "1 us"').replace('"plate-ss-8in"', f'"{cases["plate-ss-8in"]}"')
        )
        out = str(tmp / "out")
        runs = {
            "impact plate-ss-8in-impact (2000 x 0.5 us)": [exe, "impact", "plate-ss-8in-impact", "--no-figures", "--out", out],
            "plate plate-ss-8in at 0.5 us (2000 x 0.5 us)": [exe, "plate", str(tmp / "plate-05us.toml"), "--no-figures", "--out", out],
            "impact at 1 us (1000 x 1 us)": [exe, "impact", str(tmp / "impact-1us.toml"), "--no-figures", "--out", out],
            "plate plate-ss-8in (1000 x 1 us)": [exe, "plate", str(tmp / "plate-1us.toml"), "--no-figures", "--out", out],
        }
        times = {name: [] for name in runs}
        for _ in range(repeats):
            for name, cmd in runs.items():
                times[name].append(process(cmd, USER_ENV))
    print(f"whole processes, best and median of {repeats}, alternated (wall-clock; CPU user + system):")
    for name, ts in times.items():
        wall = sorted(x[0] for x in ts)
        cpu = sorted(x[1] for x in ts)
        print(
            f"  softimpact {name:46s} wall best {wall[0]:.2f} s, median {wall[len(ts) // 2]:.2f} s; CPU best {cpu[0]:.2f} s, median {cpu[len(ts) // 2]:.2f} s"
        )


if __name__ == "__main__":
    main()
    whole_process(int(sys.argv[1]) if len(sys.argv) > 1 else 3)
