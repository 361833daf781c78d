"""Reference dents for the elastic–plastic plate (issue 40), from the independent axisymmetric and strip codes of
tests/_support/plastic_reference.py, each with its discretisation error estimated by refinement.

The material is illustrative, Al 2024-T3-like (E 73 GPa, ν 0.33, ρ 2780 kg/m³, σ_y0 345 MPa, linear hardening
H 700 MPa against the equivalent plastic strain): the brief's numbers, not a sourced catalogue entry.

Cases (all clamped, edges immovable in their plane, von Kármán kinematics):

- ``plate-static``: circular plate R = 100 mm, h = 2 mm, uniform pressure raised to k·p_y in 40 steps and removed in 40,
  k = 2, 4, 8, with p_y = 4σ_y0h²/(3R²√(1 − ν + ν²)) the classical small-deflection first-yield pressure (208.5 kPa);
- ``strip-impulse-20`` and ``strip-impulse-80``: strip L = 200 mm, h = 2 mm (plane strain, per metre of width), uniform
  initial velocity 20 and 80 m/s;
- ``plate-yield-onset``: the pressure at which the clamped plate (von Kármán) starts to yield, against mesh and layers;
- ``plate-mass``: the circular plate struck at its centre by a 0.1-kg rigid mass at 30 m/s acting on a 5-mm-radius disc
  (penalty contact, 1000× the plate's static stiffness under that disc).

For each quantity the value of the base discretisation (the middle rung of three ladders: elements, layers, and load
steps or Δt, each halving or doubling) and the changes to the coarser / finer rung; ``est. error`` sums the base's
error estimated on each ladder (Richardson at the observed order where the ladder is monotone, else its larger change).
Usage: python benchmarks/plastic_reference.py [--case NAME] (prints markdown; CPU seconds per case at the end).
"""

import argparse
import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from _support import plastic_reference as pr  # noqa: E402

R, L, H = 0.1, 0.2, 0.002
P_Y = pr.first_yield_pressure_clamped_circular(R, H)


def static(k):
    """The clamped circular plate loaded to k·p_y and unloaded; the ladder's third knob is the number of load steps."""

    def run(elements, layers, steps):
        r = pr.circular_plate(pr.Pressure(k * P_Y, steps=steps), radius=R, thickness=H, elements=elements, layers=layers)
        return {
            "loaded centre deflection [mm]": 1e3 * r.peak_centre_deflection,
            "permanent centre deflection [mm]": 1e3 * r.permanent_centre_deflection,
            "plastic work [J]": r.plastic_work[-1],
            "plastic zone area [mm²]": 1e6 * r.plastic_zone_area,
            "largest ε̄_p": r.max_plastic_strain,
            "energy error": r.energy_error,
        }

    return run, (64, 16, 40), ((32, 64, 128), (8, 16, 32), (20, 40, 80)), "load steps"


def dynamic(make, strip=False):
    """A transient; the ladder's third knob is Δt [µs]. The strip's plastic zone is a band's width per metre [mm]."""
    zone_name, zone_scale = ("yielded band width [mm]", 1e3) if strip else ("plastic zone area [mm²]", 1e6)

    def run(elements, layers, dt_us):
        r = make(elements, layers, dt_us * 1e-6)
        return {
            "peak centre deflection [mm]": 1e3 * r.peak_centre_deflection,
            "time of peak [µs]": 1e6 * r.time_of_peak,
            "permanent, springback from the peak [mm]": 1e3 * r.peak_springback_centre_deflection,
            "permanent, springback from the end [mm]": 1e3 * r.permanent_centre_deflection,
            "late mean deflection [mm]": 1e3 * r.late_mean_centre_deflection,
            "plastic work / work in": r.plastic_work[-1] / r.work_in,
            zone_name: zone_scale * r.plastic_zone_area,
            "largest ε̄_p": r.max_plastic_strain,
            "work in [J or J/m]": r.work_in,
            "energy error": r.energy_error,
            "snapped through (1 = yes)": float(r.snapped_through),
            "settled (1 = yes)": float(r.settled),
        }

    return run, (32, 16, 1.0), ((16, 32, 64), (8, 16, 32), (2.0, 1.0, 0.5)), "Δt [µs]"


CASES = {
    **{f"plate-static-{k}py": static(k) for k in (2, 4, 8)},
    "strip-impulse-20": dynamic(lambda n, z, dt: pr.strip(pr.Impulse(20.0), length=L, thickness=H, elements=n, layers=z, dt=dt), strip=True),
    "strip-impulse-80": dynamic(lambda n, z, dt: pr.strip(pr.Impulse(80.0), length=L, thickness=H, elements=n, layers=z, dt=dt), strip=True),
    "plate-mass": dynamic(lambda n, z, dt: pr.circular_plate(pr.MassImpact(0.1, 30.0, 0.005), radius=R, thickness=H, elements=n, layers=z, dt=dt)),
}


def ladder(run, base, rungs):
    """The runs of the three ladders (each knob over its rungs, the others at the base), the base run shared."""
    results = {}
    for knob, values in enumerate(rungs):
        for v in values:
            key = tuple(v if k == knob else base[k] for k in range(3))
            if key not in results:
                results[key] = run(*key)
    return results


def base_error(coarse, base, fine):
    """The base value's error estimated from one ladder: with a monotone ladder, Richardson's |fine − base|·2^p/(2^p − 1)
    at the observed order p = log2((base − coarse)/(fine − base)) (p kept within [0.5, 4]); otherwise (an oscillating
    or flat ladder) the larger of the two changes."""
    d1, d2 = base - coarse, fine - base
    if d1 * d2 > 0 and abs(d1) > abs(d2):
        p = min(max(math.log2(d1 / d2), 0.5), 4.0)
        return abs(d2) * 2**p / (2**p - 1)
    return max(abs(d1), abs(d2))


def report(name, run, base, rungs, third):
    cpu = time.process_time()
    results = ladder(run, base, rungs)
    cpu = time.process_time() - cpu
    names = ("elements", "layers", third)
    print(f"\n### {name}\n")
    print("| quantity | base | " + " | ".join(f"{names[k]} {rungs[k][0]} / {rungs[k][2]}" for k in range(3)) + " | est. error |")
    print("|---|---|---|---|---|---|")
    for q, value in results[tuple(base)].items():
        cells, err = [], 0.0
        for k in range(3):
            lo, hi = (results[tuple(rungs[k][j] if i == k else base[i] for i in range(3))][q] for j in (0, 2))
            cells.append(f"{lo - value:+.3g} / {hi - value:+.3g}")
            err += base_error(lo, value, hi)
        print(f"| {q} | {value:.6g} | " + " | ".join(cells) + f" | {err:.2g} |")
    print(f"\n{len(results)} runs, {cpu:.0f} s CPU")


def yield_onset(elements, layers):
    """The pressure [Pa] at which plastic flow starts in the clamped circular plate (von Kármán), by bisection on a
    monotone elastic path (whether a load to p in 8 steps leaves plastic work): it is sampled at the outermost Gauss
    point and layer point, so it converges from above with the mesh and the layers."""
    lo, hi = P_Y, 3 * P_Y
    while hi - lo > 1e-5 * P_Y:
        p = 0.5 * (lo + hi)
        run = pr.circular_plate(pr.Pressure(p, steps=8, unload=False), radius=R, thickness=H, elements=elements, layers=layers)
        lo, hi = (lo, p) if run.plastic_work[-1] > 0 else (p, hi)
    return hi


def report_onset():
    cpu = time.process_time()
    print("\n### plate-yield-onset (clamped circular plate, von Kármán: the onset of plastic flow)\n")
    print("| elements | layers | onset [kPa] | onset / p_y |")
    print("|---|---|---|---|")
    onset = {}
    for n, z in ((32, 16), (64, 16), (128, 16), (64, 8), (64, 32)):
        onset[n, z] = p = yield_onset(n, z)
        print(f"| {n} | {z} | {1e-3 * p:.2f} | {p / P_Y:.4f} |")
    base, ext = onset[64, 16], onset[64, 16]
    for coarse, fine in (((32, 16), (128, 16)), ((64, 8), (64, 32))):
        ratio = (base - onset[coarse]) / (onset[fine] - base)
        q = math.log2(ratio)
        ext += (onset[fine] - base) * 2**q / (2**q - 1)
        print(f"| ladder {coarse} → {fine}: observed order {q:.2f} | | | |")
    print(f"| extrapolated (Richardson on both ladders) | | {1e-3 * ext:.1f} | {ext / P_Y:.3f} |")
    print(f"\n{time.process_time() - cpu:.0f} s CPU")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", choices=sorted([*CASES, "plate-yield-onset"]), action="append", help="the cases to run (default: all)")
    args = parser.parse_args()
    print(f"p_y = {P_Y:.1f} Pa (clamped circular plate R = {R} m, h = {H} m)")
    for name in args.case or [*CASES, "plate-yield-onset"]:
        report_onset() if name == "plate-yield-onset" else report(name, *CASES[name])


if __name__ == "__main__":
    main()
