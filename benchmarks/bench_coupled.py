"""Coupled-impact benchmark: the long paper beam (200 × 6, 2800 DOF), dt = 0.5 µs, 1200 steps.

Prints, measured here in one script on the same mesh and steps:
- a prescribed-force run (BeamModel.direct, no energies) of the coupled run's own force history;
- the coupled run (steel ball 0.5 in at 100 in/s, Hertz with E2 = 7.9 GPa), without and with the
  energy histories, its Newton iterations and back-substitutions.
Then, as whole processes (interpreter start, imports, case parsing, assembly, stepping, output),
alternated: `softimpact impact paper-long-beam-impact --no-figures` (2000 steps of 0.5 µs)
against `softimpact beam` on the same beam, mesh and steps (paper-long-beam with its
time step set to 0.5 µs), and both at the beam case's own 1000 steps of 1 µs.
Usage: python benchmarks/bench_coupled.py [repeats]
"""

import math
import platform
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from timing import best, process  # noqa: E402

from softimpact.models.contact_laws import HertzLaw  # noqa: E402
from softimpact.models.materials import Material  # noqa: E402
from softimpact.workflows.coupled import Impactor, simulate_coupled  # noqa: E402

from _support.constants import INCH  # noqa: E402
from _support.coupled import beam_structure, long_beam_model  # noqa: E402


def main():
    steel = Material("steel", 30.0e6 * 4.4482216152605 / INCH**2, 0.29, 0.283 * 0.45359237 / INCH**3)
    d, V = 0.5 * INCH, 100 * INCH
    m = steel.density * math.pi * d**3 / 6
    t0 = time.perf_counter()
    model = long_beam_model(time_step=0.5e-6, duration=600e-6)
    build = time.perf_counter() - t0
    law = HertzLaw.sphere_on_laminate(d / 2, steel, 7.9e9)
    st = beam_structure(model, 3 * INCH, d / 2)
    imp = Impactor(m, d, V)
    solver = model.problem.solver
    res = simulate_coupled(st, law, imp, solver, energy=False, stepper=model.stepper)
    F = res.force
    # the prescribed run spreads F over the fixed r0 = R patch (eq 10 law), same mesh and steps
    t_pre = best(lambda: model.direct(F, energy=False))
    t_cpl = best(lambda: simulate_coupled(st, law, imp, solver, energy=False, stepper=model.stepper))
    t_cple = best(lambda: simulate_coupled(st, law, imp, solver, energy=True, stepper=model.stepper), repeat=1)
    n = solver.steps
    print(f"python {platform.python_version()}, {platform.machine()}; {model.plane.n} DOF, {n} steps of {solver.time_step * 1e6:g} us")
    print(f"assembly + factorisation          {build:7.3f} s")
    print(f"prescribed force (direct)         {t_pre:7.3f} s   {t_pre / n * 1e6:6.1f} us/step")
    print(f"coupled, no energies              {t_cpl:7.3f} s   {t_cpl / n * 1e6:6.1f} us/step   ratio {t_cpl / t_pre:.2f}")
    print(f"coupled, with energy histories    {t_cple:7.3f} s   {t_cple / n * 1e6:6.1f} us/step")
    print(f"Newton iterations {res.newton_iterations} ({res.newton_iterations / n:.1f}/step incl. free flight), contacts {len(res.contacts)}")


def whole_process(repeats: int = 5):
    from softimpact.input.toml import builtin_cases

    exe = str(Path(sys.executable).parent / "softimpact")
    cases = builtin_cases()
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        beam = cases["paper-long-beam"].read_text()
        impact = cases["paper-long-beam-impact"].read_text()
        (tmp / "beam-05us.toml").write_text(beam.replace('time_step = "1 us"', 'time_step = "0.5 us"'))
        (tmp / "impact-1us.toml").write_text(impact.replace('time_step = "0.5 us"', 'time_step = "1 us"'))
        out = str(tmp / "out")
        runs = {
            "impact paper-long-beam-impact (2000 x 0.5 us)": [exe, "impact", "paper-long-beam-impact", "--no-figures", "--out", out],
            "beam paper-long-beam at 0.5 us (2000 x 0.5 us)": [exe, "beam", str(tmp / "beam-05us.toml"), "--no-figures", "--out", out],
            "impact at 1 us (1000 x 1 us)": [exe, "impact", str(tmp / "impact-1us.toml"), "--no-figures", "--out", out],
            "beam paper-long-beam (1000 x 1 us)": [exe, "beam", "paper-long-beam", "--no-figures", "--out", out],
        }
        times = {name: [] for name in runs}
        for _ in range(repeats):
            for name, cmd in runs.items():
                times[name].append(process(cmd))
    print(f"whole processes, best and median of {repeats}, alternated (wall-clock; CPU user + system):")
    for name, ts in times.items():
        wall = sorted(t[0] for t in ts)
        cpu = sorted(t[1] for t in ts)
        print(
            f"  softimpact {name:48s} wall best {wall[0]:.2f} s, median {wall[len(ts) // 2]:.2f} s; CPU best {cpu[0]:.2f} s, median {cpu[len(ts) // 2]:.2f} s"
        )


if __name__ == "__main__":
    main()
    whole_process(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
