"""How far the paper's discretisations are from converged (mesh and dt refined together).

Beam: paper-long-beam, Table II histories 1 and 4, mesh 200 × 6 with dt 1 µs,
then × 2 and × 4 (800 × 24, dt 0.25 µs: a few minutes on one core). The impulse
responses do not depend on the history, so each level is built once, with the
patch wide enough for both rows' contact radii.
Bar: paper-calibration (end cap on, as in the case), 39 elements with dt 0.5 µs,
then × 2 and × 4.

Usage: python benchmarks/converge_paper.py [--beam-levels 3] [--skip-beam]
"""

import argparse
import sys
import time

import numpy as np

from softimpact.input.bar_case import load_bar_case
from softimpact.input.beam_case import load_beam_case
from softimpact.workflows.bar_impact import simulate_impact
from softimpact.workflows.beam_impact import BeamModel
from softimpact.workflows.calibration import first_lobe_peak, first_zero_crossing
from softimpact.workflows.convergence import convergence_study
from softimpact.workflows.refinement import refine_bar, refine_beam


def show(title, study):
    print(f"\n{title}")
    print(f"{'output':28s} {'status':12s} {'p':>6s} {'finest':>12s} {'extrapolated':>12s}  errors per level (relative)   GCI_fine")
    for o in study.outputs:
        fin = "history" if o.kind == "history" else f"{o.finest:12.6g}"
        ext = "" if o.kind == "history" else f"{o.extrapolated:12.6g}"
        errs = " ".join(f"{e:8.2e}" for e in o.errors)
        print(f"{o.name:28s} {o.status:12s} {o.order:6.2f} {fin:>12s} {ext:>12s}  {errs}   {o.gci_fine:8.2e}")


def beam(levels):
    rows = (1, 4)
    problems = {h: load_beam_case("paper-long-beam", history=h)[0] for h in rows}
    base = problems[rows[0]]
    radius = max(p.load.contact_radius for p in problems.values())

    def run(f):
        t0 = time.perf_counter()
        model = BeamModel(refine_beam(base, f), patch_radius=radius)
        out = {}
        for h, p in problems.items():
            r = model.respond(p.load.history, p.load.contact_radius)
            for i, g in enumerate(p.gauges):
                y = r.strain[i]
                out[f"h{h}_{g.name}_first_peak"] = first_lobe_peak(r.time, y)
                out[f"h{h}_{g.name}_first_zero_us"] = first_zero_crossing(r.time, y) * 1e6
                out[f"h{h}_{g.name}_max_abs"] = float(np.max(np.abs(y)))
                out[f"h{h}_{g.name}_history"] = y[::f]
                out[f"h{h}_{g.name}_history_300us"] = y[::f][:301]
        print(f"  beam level ×{f}: {time.perf_counter() - t0:.1f} s", file=sys.stderr, flush=True)
        return out

    show("Beam, paper-long-beam (200 × 6, dt 1 µs, × 2, × 4): gauge strains", convergence_study(run, [2**k for k in range(levels)], 2.0, formal_order=2))


def bar():
    problem = load_bar_case("paper-calibration")[0]

    def run(f):
        r = simulate_impact(refine_bar(problem, f))
        return {
            "peak_force_N": r.peak_force,
            "time_of_peak_us": r.time_of_peak * 1e6,
            "contact_duration_us": r.contact_duration * 1e6,
            "impulse_N_s": r.impulse,
            "force_history": r.force[::f],
            "midpoint_strain_history": r.strain[0][::f],
            "midpoint_peak_strain": float(np.max(np.abs(r.strain[0]))),
        }

    show("Bar, paper-calibration with end cap (39 elements, dt 0.5 µs, × 2, × 4)", convergence_study(run, (1, 2, 4), 2.0, formal_order=2))


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--beam-levels", type=int, default=3)
    ap.add_argument("--skip-beam", action="store_true")
    a = ap.parse_args()
    bar()
    if not a.skip_beam:
        beam(a.beam_levels)
