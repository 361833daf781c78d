"""The report's section on the empirical model beside the classical ones it replaces (Hertz, Wilbeck)."""

from __future__ import annotations

import numpy as np

from ...models.empirical import PRESETS, PROJECTILES, HertzModel, WilbeckModel
from ...models.materials import lookup
from ...output import plots
from ...output.files import figure_bytes
from ...output.report import Section
from ...units import INCH, display
from .notes import SYSTEM

__all__ = ["comparison_section"]


def comparison_section(figures: bool, files: dict) -> Section:
    """The empirical model beside the classical ones it replaces."""
    fu, tu, vu = display(SYSTEM, "force"), display(SYSTEM, "time"), display(SYSTEM, "velocity")
    proj = PROJECTILES["rubber-1/2in"]
    m, d = proj.mass, proj.diameter
    models = {
        "empirical (Table I, eq 15)": PRESETS[proj.law],
        "Hertz, elastic sphere on rigid Al": HertzModel(lookup("silicone rubber"), lookup("Al 6061-T6")),
        "Wilbeck, steady flow ρV²A": WilbeckModel(m / (np.pi / 6 * d**3)),
    }
    rows = []
    for v_in in (1000, 2000, 3000, 4000, 5000):
        V = v_in * INCH
        row = [f"{V * vu.factor:.0f}"]
        for mod in models.values():
            p = mod.parameters(m, d, V)
            row += [f"{p.peak_force * fu.factor:.1f}", f"{p.duration * tu.factor:.0f}"]
        rows.append(row)
    figs = []
    if figures:
        V = 1166 * INCH
        curves = []
        for label, mod in models.items():
            pl = mod.pulse(m, d, V)
            t = np.linspace(0, 1.3 * pl.duration, 800)
            curves.append((label, t, pl(t)))
        files["models/force-models-1166.png"] = figure_bytes(
            plots.predicted_forces(curves, SYSTEM, "1/2-in rubber ball at 1166 in/s: empirical vs classical models")
        )
        figs.append(("models/force-models-1166.png", "The skewed empirical pulse beside the classical models at 1166 in/s"))
    header = [f"V [{vu.label}]"] + [f"{name}: {q}" for name in models for q in (f"F0 [{fu.label}]", f"T [{tu.label}]")]
    return Section(
        "Empirical model against the classical ones",
        [
            "The paper's finding: F0 grows like V² and T like 1/V, where elastic (Hertz) impact predicts V^1.2 and V^-0.2. "
            "The hydrodynamic (Wilbeck) model shares the empirical V² and 1/V trends."
        ],
        [("1/2-in silicone ball", header, rows)],
        figs,
    )
