"""``softimpact identify``: a soft projectile's contact law from a series of bar tests."""

from __future__ import annotations

import numpy as np

from ..errors import InputError
from ..fem.bar import Rod
from ..output.identify import identify_files
from ..workflows.identification import BarTest, closure, refine
from ..workflows.identification import identify as fit_law
from . import Outcome, Progress, no_progress
from .series import _reduce

__all__ = ["bar_tests", "identify_series", "identify"]


def bar_tests(reduced) -> list[BarTest]:
    """The reduced tests of a series as BarTests: force from first contact up to where the record holds
    it, resampled evenly at the reduction's own (median) step."""
    out = []
    for r in reduced:
        if r.reduction is None:
            continue
        red = r.reduction
        dt = float(np.median(np.diff(red.time)))
        t = np.arange(0.0, min(red.valid_until, red.time[-1]) + 0.5 * dt, dt)
        t = t[t <= red.time[-1]]
        out.append(BarTest(r.test.name, t, np.interp(t, red.time, red.force), r.test.mass, r.test.diameter, r.test.velocity))
    if len(out) < 2:
        raise InputError("identify: need at least two reduced tests")
    return out


def identify_series(series, reduced, refined: bool = True, progress: Progress = no_progress):
    """Fit the law on the reconstructed F(α, α̇), refine it on the coupled bar simulations, run the
    closure. Returns (tests, law, approaches, closure)."""
    tests = bar_tests(reduced)
    rod = Rod.of(series.bar)
    progress(0, 3, "fitting F(alpha)")
    law, approaches = fit_law(tests, rod)
    if refined:
        progress(1, 3, "refining on coupled bar runs")
        # one coupled bar run per diameter per evaluation, 200 steps per pulse (refine's docstring)
        law = refine(law, tests, rod)
    progress(2, 3, "closure")
    cl = closure(law, tests, rod)
    progress(3, 3, "closure")
    return tests, law, approaches, cl


def identify(series_name: str, figures: bool = True, progress: Progress = no_progress) -> Outcome:
    """Identify one contact law from a series (file or built-in name): law.json, closure table and figures."""
    series, reduced, warnings = _reduce(series_name, progress)
    tests, law, approaches, cl = identify_series(series, reduced, True, progress)
    files = identify_files(series, tests, law, approaches, cl, figures)
    err = np.abs(cl.errors)
    fitted = [(n, v, h) for n, v, h in zip(law.names, law.values, law.half_widths) if h > 0]
    held = [f"{n} {v:g}" for n, v, h in zip(law.names, law.values, law.half_widths) if not h > 0]
    pars = "  ".join(f"{n} {v:.4g}±{h:.2g}" for n, v, h in fitted) + (f"  (held: {', '.join(held)})" if held else "")
    worst = int(np.argmax(err.max(axis=1)))
    line = (
        f"{pars} (d_ref {law.d_ref * 1e3:.3g} mm)\n"
        f"closure over {len(tests)} tests: max |error| F0 {err[:, 0].max():.1%}, T {err[:, 1].max():.1%}, I {err[:, 2].max():.1%}, "
        f"t_F0 {np.abs(cl.peak_time_errors).max():.1%} "
        f"(worst {cl.names[worst]}); law.json"
    )
    inputs = (series.path, *(t.record for t in series.tests))
    return Outcome(files, line, inputs, warnings)
