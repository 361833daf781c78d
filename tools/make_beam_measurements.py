"""Generate the built-in synthetic calibration series `paper-long-calibration` and
`paper-short-calibration` (measured strains + series files).

"Measured" strains are computed by a finer model than the one calibration uses
(300 × 8 elements, 0.5 µs instead of 200 × 6, 1 µs), driven by the histories of
Tables II and III, with 1.5 % noise, a gauge offset and a 100-µs pre-trigger.
Run from the repository root: python tools/make_beam_measurements.py
"""

from dataclasses import replace
from pathlib import Path

import numpy as np

from softimpact.fem.newmark import SolverSpec
from softimpact.input.beam_case import load_beam_case, table_rows
from softimpact.models.pulses import SkewedPulse
from softimpact.workflows.beam_impact import BeamLoad, BeamModel
from softimpact.workflows.synthetic import beam_measurement

IN, LBF = 0.0254, 4.4482216152605
OUT = Path("src/softimpact/data/series")


def main():
    rng = np.random.default_rng(19870601)
    for beam in ("long", "short"):
        case = f"paper-{beam}-beam"
        problem, _ = load_beam_case(case)
        name = f"paper-{beam}-calibration"
        folder = OUT / name
        folder.mkdir(parents=True, exist_ok=True)
        table = "II" if beam == "long" else "III"
        lines = [
            f"# Synthetic measured strains for the {beam} beam (the paper's records are not available):",
            f"# computed by a finer model (300 x 8 elements, 0.5 us) from the force histories of Table {table},",
            "# with 1.5 % noise, gauge offsets and a 100-us pre-trigger (tools/make_beam_measurements.py).",
            f'title = "Calibration of the {beam} beam against synthetic strains (Table {table} histories)"',
            f'case = "{case}"',
            'projectile = "rubber-1/2in"',
            f'synthetic = "strains computed by a 300 x 8, 0.5-us model from the Table {table} histories, 1.5 % noise, offsets"',
        ]
        for row in table_rows(case):
            pulse = SkewedPulse(row["peak_force"], row["time_of_peak"], row["duration"])
            p = replace(
                problem,
                beam=replace(problem.beam, nx=300, nz=8),
                solver=SolverSpec(0.5e-6, problem.solver.duration),
                load=BeamLoad(problem.load.position, row["contact_radius"], pulse),
            )
            t, strains = beam_measurement(
                BeamModel(p), pulse, pre_trigger=100e-6, noise=0.015, offsets=rng.normal(0, 30e-6, len(p.gauges)), rng=rng, sample_interval=1e-6
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
            print(stem, t.size)
        (OUT / f"{name}.toml").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
