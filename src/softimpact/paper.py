"""``softimpact paper``: the whole paper on the built-in cases, into one report."""

from __future__ import annotations

import time

import click

from .io import write_outputs
from .report import bar_files, bar_section, render_report

__all__ = ["run_paper", "NOTES"]

# The assumptions and errata the report lists (from shared/paper/NOTES.md).
NOTES = [
    "Bar: Al 6061-T6, E = 10.0e6 psi, ν = 0.33, 0.0975 lb/in³ (handbook). End cap: Al 6061-T6, 1.0 in diameter, "
    "0.25 in long (length assumed), modelled as a mass lumped at the struck end.",
    "Steel ball: 5/8 in, E = 30.0e6 psi, ν = 0.29, 0.283 lb/in³ (handbook); its mass, 16.4 g, follows from the density.",
    "Time zero is first contact; compressive force positive; strain tension positive.",
]


def run_paper(out, figures: bool = True, echo=print) -> None:
    """Run every section, then write all files and report.html atomically."""
    from .cases import load_bar_case
    from .workflows.bar_impact import simulate_impact, without_end_cap

    t0 = time.perf_counter()
    files: dict[str, bytes | str] = {}
    sections = []
    steps = ["bar calibration (Figs 4-6)"]
    with click.progressbar(steps, label="softimpact paper", item_show_func=lambda s: s or "") as bar:
        for step in bar:
            if step.startswith("bar calibration"):
                problem, _ = load_bar_case("paper-calibration")
                result = simulate_impact(problem)
                plain = simulate_impact(without_end_cap(problem))
                files.update(bar_files(result, plain, figures, prefix="bar-calibration/"))
                sections.append(bar_section(result, plain, "bar-calibration/"))
    if not figures:
        for s in sections:
            s.figures = []
    files["report.html"] = render_report("softimpact: the paper, end to end", sections, NOTES)
    write_outputs(out, files)
    echo(f"report: {out}/report.html ({len(files)} files, {time.perf_counter() - t0:.1f} s)")
