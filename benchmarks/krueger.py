"""Krueger's NASA DCB and MMB benchmarks through the stacked cohesive plate's interface code, against the benchmarks.

The computations of tests/test_krueger.py (its module docstring says what and why), printed as tables with their CPU
time (time.process_time: the machine is shared):

- ``closure``: the crack-closure critical loads (LEFM, the benchmarks' own definition) of the DCB at mid-width and over
  the width's mean, a = 30–40 mm, and of the MMB with its mode ratio (0.125-mm elements, a 1-mm extension);
- ``dcb``: the cohesive DCB's peak load per crack length (0.25-mm elements, N = 30 MPa), its process zone in elements;
- ``mesh``: the cohesive DCB's peak at a0 = 30 mm on 0.5-, 0.25- and 0.125-mm elements, and at N = 20 MPa;
- ``mmb``: the cohesive MMB's peak per mode ratio (N = 60 MPa), and at 0.5 with N = 120 MPa on 0.0625-mm elements;
- ``curve``: the cohesive DCB from a0 = 30 mm towards a load-point opening of 2.6 mm (the crack past 40 mm), the load
  against the benchmark's critical points (δ_crit, P_crit), which lie on its propagation branch (as far as the path
  gets: it stops where an increment fails, and says so);
- ``solvers``: the DCB's peak at a0 = 30 mm by the staggered passes against Newton's, and their cost.

Usage: python benchmarks/krueger.py [section ...]   (all sections: about 15 minutes of one core)
"""

import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parents[1] / "tests"))

from test_krueger import (  # noqa: E402  (the test's own computations)
    DCB_BENCHMARK,
    MMB_BENCHMARK,
    D,
    M,
    _dcb_closure,
    _dcb_peak,
    dcb_law,
    dcb_specimen,
    mmb_law,
    mmb_specimen,
)

from softimpact.errors import SolverFailed  # noqa: E402
from softimpact.fem.plate_specimens import critical_load, onset_force, release_rates, trial_damage  # noqa: E402
from softimpact.fem.quasistatic import QuasiStatic, linear_response  # noqa: E402
from softimpact.models.krueger import DCB_OPENING  # noqa: E402


def pct(value, reference):
    return f"{(value / reference - 1) * 100:+.2f} %"


def closure():
    print("## Crack closure through the plate's interface (0.125-mm elements, 1-mm extension)\n")
    print("| a (mm) | benchmark (N) | mid-width (N) | error | width mean (N) | error | G_mid/G_mean | CPU (s) |")
    print("|---|---|---|---|---|---|---|---|")
    for a, P in DCB_BENCHMARK.items():
        t = time.process_time()
        r = _dcb_closure(a)
        mid, mean = r.critical_load(D.GIc, D.GIc, D.eta, "middle"), r.critical_load(D.GIc, D.GIc, D.eta)
        ratio = r.total[-1] / (r.mean_I + r.mean_II + r.mean_III)
        print(f"| {a} | {P} | {mid:.2f} | {pct(mid, P)} | {mean:.2f} | {pct(mean, P)} | {ratio:.4f} | {time.process_time() - t:.1f} |")
    print("\n| G_II/G_T | benchmark (N) | plate's G_II/G_T | crack closure (N) | error | CPU (s) |")
    print("|---|---|---|---|---|---|")
    for ratio, (_, P) in MMB_BENCHMARK.items():
        t = time.process_time()
        r = release_rates(mmb_specimen(ratio, M.a0 - 0.5e-3, 0.125e-3), 1e-3)
        mixity = (r.mean_II + r.mean_III) / (r.mean_I + r.mean_II + r.mean_III)
        Pc = r.critical_load(M.GIc, M.GIIc, M.eta)
        print(f"| {ratio} | {P} | {mixity:.3f} | {Pc:.1f} | {pct(Pc, P)} | {time.process_time() - t:.1f} |")
    print()


def _peak_row(label, spec_crit, reference, element, t):
    spec, crit = spec_crit
    n = spec.model.n
    print(
        f"| {label} | {reference} | {crit.load:.2f} | {pct(crit.load, reference)} | {crit.zone * 1e3:.3f} mm = {crit.zone / element:.1f} | "
        f"{n} | {crit.path.force.size} | {crit.fallbacks} | {time.process_time() - t:.1f} |"
    )


HEADER = "| {} | benchmark (N) | peak (N) | error | process zone at mid-width (elements) | DOFs | increments | Newton → staggered | CPU (s) |\n|---|---|---|---|---|---|---|---|---|"


def dcb():
    print("## Cohesive DCB: the peak load per crack length (0.25-mm elements, N = 30 MPa, K = 50·E33/t)\n")
    print(HEADER.format("a (mm)"))
    for a, P in DCB_BENCHMARK.items():
        t = time.process_time()
        _peak_row(a, _dcb_peak(a), P, 0.25e-3, t)
    print()


def mesh():
    print("## Cohesive DCB at a0 = 30 mm: mesh and strength\n")
    print(HEADER.format("elements, N"))
    for h, N in ((0.5e-3, 30e6), (0.25e-3, 30e6), (0.125e-3, 30e6), (0.25e-3, 20e6)):
        t = time.process_time()
        _peak_row(f"{h * 1e3:g} mm, {N / 1e6:.0f} MPa", _dcb_peak(30, element=h, law=dcb_law(N)), DCB_BENCHMARK[30], h, t)
    print()


def mmb():
    print("## Cohesive MMB: the peak load per mode ratio (tip control, S = N·sqrt(G_IIc/G_Ic))\n")
    print(HEADER.format("G_II/G_T, elements, N"))
    runs = [(r, 0.25e-3, 60e6, 0.2e-6) for r in MMB_BENCHMARK] + [(0.5, 0.0625e-3, 120e6, 0.05e-6)]
    for ratio, h, N, inc in runs:
        t = time.process_time()
        spec = mmb_specimen(ratio, M.a0, h, law=mmb_law(N), fine=(0.0, 3e-3 if h > 0.1e-3 else 2e-3), control="tip")
        crit = critical_load(spec, near=0.8 * MMB_BENCHMARK[ratio][1], increment=inc)
        _peak_row(f"{ratio}, {h * 1e3:g} mm, {N / 1e6:.0f} MPa", (spec, crit), MMB_BENCHMARK[ratio][1], h, t)
    print()


def curve():
    print("## Cohesive DCB from a0 = 30 mm through propagation: the load at the benchmark's critical openings\n")
    t = time.process_time()
    spec = dcb_specimen(30e-3, 0.25e-3, fine=12e-3)
    per_newton = float(spec.control @ linear_response(spec.model, spec.load, spec.fixed))  # control per N, elastic
    path = QuasiStatic(spec.model, load=spec.load, fixed=spec.fixed, trial_damage=trial_damage(spec.model))
    first = 0.999 * onset_force(spec) * per_newton
    start = 50.0 * per_newton
    targets = np.concatenate(([first], np.linspace(first, start, 9)[1:], np.arange(start, 2.6e-3 * spec.share, 0.01 * start)[1:]))
    reason = "reached 2.6 mm"
    for target in targets:
        try:
            path.advance(target)
        except SolverFailed as error:
            reason = str(error)
            break
    result = path.result()
    delta, force = result.displacement / spec.share, result.force
    print(
        f"{force.size} increments to {delta[-1] * 1e3:.3f} mm ({reason}); peak {force.max():.2f} N; {path.fallbacks} increments retaken by the staggered passes; CPU {time.process_time() - t:.0f} s\n"
    )
    print("| a (mm) | δ_crit (mm) | benchmark P_crit (N) | cohesive P at δ_crit (N) | error |")
    print("|---|---|---|---|---|")
    for a, opening in DCB_OPENING.items():
        mm = round(a * 1e3)
        if opening > delta[-1]:
            print(f"| {mm} | {opening * 1e3:.3f} | {DCB_BENCHMARK[mm]} | not reached | |")
            continue
        P = float(np.interp(opening, delta, force))
        print(f"| {mm} | {opening * 1e3:.3f} | {DCB_BENCHMARK[mm]} | {P:.2f} | {pct(P, DCB_BENCHMARK[mm])} |")
    print()


def solvers():
    print("## The damage within an increment: Newton against the staggered passes (DCB, a0 = 30 mm, 0.25 mm)\n")
    print("| scheme | peak (N) | increments | iterations (passes) | factorisations | CPU (s) |")
    print("|---|---|---|---|---|---|")
    for damage in ("newton", "iterate"):
        t = time.process_time()
        spec = dcb_specimen(30e-3, 0.25e-3, coarse=12e-3)
        EI = D.ply.E1 * D.width * D.arm**3 / 12
        crit = critical_load(spec, near=0.85 * math.sqrt(D.width * EI * D.GIc) / 33e-3, step=0.02, damage=damage)
        p = crit.path
        print(f"| {damage} | {crit.load:.3f} | {p.force.size} | {p.iterations.sum()} | {p.factorisations.sum()} | {time.process_time() - t:.1f} |")
    print()


SECTIONS = {"closure": closure, "dcb": dcb, "mesh": mesh, "mmb": mmb, "curve": curve, "solvers": solvers}


def main(names):
    for name in names or SECTIONS:
        SECTIONS[name]()


if __name__ == "__main__":
    main(sys.argv[1:])
