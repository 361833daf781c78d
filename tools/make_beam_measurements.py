"""Generate the built-in synthetic calibration series `paper-long-calibration` and
`paper-short-calibration` (measured strains + series files).

"Measured" strains are computed by a model 8× as fine as the case in mesh and in time step
(1600 × 48 elements, 0.125 µs: level 3 of the calibration ladder, finer than any level calibrate
uses at its default budget, so that the calibrated histories can be scored against the Tables), through its response
engine, driven by the histories of Tables II and III, with 1.5 % noise, a gauge offset and a
100-µs pre-trigger. About 5 minutes per beam. Run from the repository root:
python tools/make_beam_measurements.py
"""

from pathlib import Path

import numpy as np

from softimpact.input.beam_case import load_beam_case, table_rows
from softimpact.models.pulses import SkewedPulse
from softimpact.studies.calibration import ModelLadder
from softimpact.workflows.synthetic import beam_measurement

IN, LBF = 0.0254, 4.4482216152605
LEVEL = 3  # refined 2**3 = 8× in mesh and in time step
OUT = Path("src/softimpact/data/series")


def main():
    rng = np.random.default_rng(19870601)
    for beam in ("long", "short"):
        case = f"paper-{beam}-beam"
        problem, _ = load_beam_case(case)
        rows = table_rows(case)
        model = ModelLadder(problem, [row["contact_radius"] for row in rows])(LEVEL)
        b, dt = model.problem.beam, model.problem.solver.time_step
        name = f"paper-{beam}-calibration"
        folder = OUT / name
        folder.mkdir(parents=True, exist_ok=True)
        table = "II" if beam == "long" else "III"
        lines = [
            f"# Synthetic measured strains for the {beam} beam (the paper's records are not available):",
            f"# computed by a model 8x as fine as the case ({b.nx} x {b.nz} elements, {dt * 1e6:g} us) from the force histories of Table {table},",
            "# with 1.5 % noise, gauge offsets and a 100-us pre-trigger (tools/make_beam_measurements.py).",
            f'title = "Calibration of the {beam} beam against synthetic strains (Table {table} histories)"',
            f'case = "{case}"',
            'projectile = "rubber-1/2in"',
            f'synthetic = "strains computed by a {b.nx} x {b.nz}, {dt * 1e6:g}-us model (8x the case) from the Table {table} histories, 1.5 % noise, offsets"',
        ]
        for row in rows:
            pulse = SkewedPulse(row["peak_force"], row["time_of_peak"], row["duration"])
            offsets = rng.normal(0, 30e-6, len(problem.gauges))
            t, strains = beam_measurement(
                model, pulse, pre_trigger=100e-6, noise=0.015, offsets=offsets, rng=rng, sample_interval=1e-6, radius=row["contact_radius"], engine=True
            )
            v = round(row["velocity"] / IN)
            stem = f"{beam}-V{v}"
            header = "time_us," + ",".join(f"microstrain_{g}" for g in strains)
            body = [f"{a * 1e6:.1f}," + ",".join(f"{strains[g][i] * 1e6:.3f}" for g in strains) for i, a in enumerate(t)]
            (folder / f"{stem}.csv").write_text(header + "\n" + "\n".join(body) + "\n")
            lines += [
                "",
                "[[test]]",
                f'measured = "{name}/{stem}.csv"',
                f'velocity = "{v} in/s"',
                f'contact_radius = "{row["contact_radius"] / IN:g} in"',
                f"[test.reference]   # Table {table}",
                f'peak_force = "{row["peak_force"] / LBF:g} lbf"',
                f'time_of_peak = "{row["time_of_peak"] * 1e6:g} us"',
                f'duration = "{row["duration"] * 1e6:g} us"',
                f'contact_radius = "{row["contact_radius"] / IN:g} in"',
            ]
            print(stem, t.size, flush=True)
        (OUT / f"{name}.toml").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
