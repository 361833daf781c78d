"""Coupled impact with cohesive interfaces against the linear direct run, in one process.

The built-in plate-ss-8in-impact-cohesive (steel ball 1 in at 5 m/s — or the velocity given — on the SS 8 × 8 in
[90/0]5s plate as a quarter with symmetry edges, 24 × 24 MITC9: the element size of the whole plate's 48 × 48;
three sublaminates tied at the two 0/90 interfaces nearest the mid-plane), stepped ``steps`` × 1 µs:

- the cohesive run (:data:`softimpact.fem.steppers.STEPPERS` ``"cohesive"``), its model's assembly and first
  factorisation timed apart (they come with the first step);
- the linear direct run of the same quarter plate (one FSDT plate of the whole laminate), same impactor and steps;
- the linear direct run of the whole 48 × 48 plate (plate-ss-8in), same impactor and steps.

With ``--whole`` the cohesive run is on the whole 48 × 48 plate (plate-ss-8in stacked three deep, the same
interfaces and interface law, written to a temporary case file from the built-in one) and is compared with the
linear direct run of the same whole plate.

Usage: python benchmarks/bench_cohesive_impact.py [steps] [velocity_m_s] [--whole]
"""

import platform
import sys
import tempfile
import time
from dataclasses import replace
from importlib.resources import files
from pathlib import Path

from softimpact.fem.newmark import SolverSpec
from softimpact.input.impact_case import load_impact_case
from softimpact.workflows.coupled import run_impact
from softimpact.workflows.plate_impact import PlateProblem


def whole_plate_case(folder: Path) -> Path:
    """The built-in cohesive case with its target the whole plate-ss-8in, written into ``folder``."""
    text = (files("softimpact") / "data" / "cases" / "plate-ss-8in-impact-cohesive.toml").read_text()
    path = folder / "cohesive-whole.toml"
    path.write_text(text.replace('case = "plate-ss-8in-quarter"', 'case = "plate-ss-8in"'))
    return path


def main(steps: int = 200, velocity: float | None = None, whole: bool = False):
    with tempfile.TemporaryDirectory() as folder:
        p, _ = load_impact_case(whole_plate_case(Path(folder)) if whole else "plate-ss-8in-impact-cohesive")
    t = p.target
    solver = SolverSpec(1e-6, steps * 1e-6, t.solver.newmark)
    imp = p.impactor if velocity is None else replace(p.impactor, velocity=velocity)
    coh = replace(p, target=replace(t, solver=solver), impactor=imp)
    t0 = time.perf_counter()
    model = coh.model()
    build = time.perf_counter() - t0
    t0 = time.perf_counter()
    _, res = run_impact(coh, model, method="cohesive")
    t_coh = time.perf_counter() - t0
    names = list(res.strain_names)
    area = res.strain[names.index("delaminated_area_m2")][-1]
    zone = res.strain[names.index("process_zone_area_m2")].max()

    fields = {f: getattr(t, f) for f in PlateProblem.__dataclass_fields__}
    lin = replace(coh, target=replace(PlateProblem(**fields), solver=solver))
    t0 = time.perf_counter()
    m_lin, r_lin = run_impact(lin, method="direct")
    t_lin = time.perf_counter() - t0

    full, _ = load_impact_case("plate-ss-8in-impact")
    full = replace(full, target=replace(full.target, solver=solver), impactor=imp, law=p.law)
    t0 = time.perf_counter()
    m_full, r_full = run_impact(full, method="direct")
    t_full = time.perf_counter() - t0

    print(f"python {platform.python_version()}, {platform.machine()}; {steps} steps of 1 us, ball at {imp.velocity:g} m/s")
    label = "whole 48 x 48" if whole else "quarter"
    print(f"cohesive {label} (3 sublaminates)  {model.size:7d} DOF  build {build:7.2f} s  run {t_coh:8.2f} s  ({t_coh / steps * 1e3:7.1f} ms/step)")
    print(f"   solves {res.solves}, factorisations {model.stepper.factorisations}, peak force {res.peak_force:.1f} N")
    print(f"   delaminated area {area * 1e6:.4g} mm2, process zone up to {zone * 1e6:.4g} mm2 (whole plate)")
    print(
        f"linear {label}, direct{' ' * (21 - len(label))}{m_lin.size:7d} DOF  run {t_lin:8.2f} s  ({t_lin / steps * 1e3:7.1f} ms/step)  peak {r_lin.peak_force:.1f} N"
    )
    print(
        f"linear whole 48 x 48, direct       {m_full.size:7d} DOF  run {t_full:8.2f} s  ({t_full / steps * 1e3:7.1f} ms/step)  peak {r_full.peak_force:.1f} N"
    )
    print(f"cohesive / linear {label}: {(build + t_coh) / t_lin:.1f}x; cohesive / linear whole 48 x 48: {(build + t_coh) / t_full:.1f}x")


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a != "--whole"]
    main(int(args[0]) if args else 200, float(args[1]) if len(args) > 1 else None, "--whole" in sys.argv[1:])
