"""``softimpact identify``: a soft projectile's contact law from a series of bar tests."""

from __future__ import annotations

import numpy as np

from ..fem.bar import Rod
from ..input.series import load_series
from ..input.series_records import read_series_records
from ..output.identify import identify_files
from ..studies.series import failed_reductions, reduce_series
from ..workflows.identification import identify_series
from . import Outcome, Progress, no_progress

__all__ = ["identify"]


def identify(*, series_name: str, figures: bool = True, progress: Progress = no_progress) -> Outcome:
    """Identify one contact law from a series (file or built-in name): law.json, closure table and figures."""
    series = load_series(series_name)
    reduced = reduce_series(series, *read_series_records(series), progress=progress)
    warnings = failed_reductions(reduced)
    tests, law, approaches, cl = identify_series(Rod.of(series.bar), reduced, True, progress)
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
    return Outcome(files, line, inputs, tuple(warnings))
