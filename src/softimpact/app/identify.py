"""``softimpact identify``: a soft projectile's contact law from a series of bar tests."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..fem.bar import Rod
from ..gates import passed_if
from ..input.series import load_series
from ..input.series_records import read_series_records
from ..output.identify import approach_record, identify_files
from ..studies.series import failed_reductions, reduce_series
from ..units import display
from ..workflows.identification import identify_series, predict_pulses, unfixed_parameters
from . import Outcome, Progress, no_progress
from .options import display_system
from .series import require_readers

__all__ = ["identify"]


def identify(*, series_name: str, law: str = "soft", units: str | None = None, figures: bool = True, points=(), progress: Progress = no_progress) -> Outcome:
    """Identify one contact law from a series (file or built-in name): law.json (with predictive
    intervals of F0, t_F0, T, I at the tested impacts and at ``points``, (mass [kg], diameter [m],
    velocity [m/s]) each), closure table, predictions.csv and figures. The printed summary gives
    the pulses' intervals, not the parameters' (those the data do not fix are named). ``law``: the
    family, "soft" (the visco-elastic soft law) or "crushing" (an ice sphere's crushing strength law;
    law.json's ``family`` says "crushing"); ``units``: the display system of the line and figures (None: the series')."""
    series = load_series(series_name)
    series = replace(series, units=display_system(units, series.units))
    require_readers(series)  # the lab formats' optional readers, before any record is read
    reduced = reduce_series(series, *read_series_records(series), progress=progress)
    warnings = failed_reductions(reduced)
    rod = Rod.of(series.bar)
    family = law
    tests, law, approaches, cl = identify_series(rod, reduced, True, progress, family=family)
    predictions = predict_pulses(law, tests, rod, cl, points)
    files = identify_files(series, tests, law, approaches, cl, figures, predictions=predictions)  # law.json of either family (formats/law_json.py)
    err = np.abs(cl.errors)
    rel = np.array([p.half_widths / np.abs(p.values) for p in predictions if p.tested])
    unfixed = unfixed_parameters(law)
    pars = (
        f"95 % predictive intervals at the tested impacts: F0 ±{rel[:, 0].max():.1%}, t_F0 ±{rel[:, 1].max():.1%}, "
        f"T ±{rel[:, 2].max():.1%}, I ±{rel[:, 3].max():.1%} at most (predictions.csv)"
    )
    if unfixed:
        warnings = (*warnings, f"parameters the data do not fix (their ± means nothing alone; the predictions hold): {', '.join(unfixed)}")
    over_bar = approach_record(tests, approaches, law, series.bar.diameter / 2)["contact_radius_over_bar_radius"][1]
    if over_bar > 1.0:  # the identification's own envelope: the ball's contact must lie on the bar's face
        warnings = (
            *warnings,
            f"the identified law's contact radius reaches {over_bar:.3g} times the bar's radius on its own tests: the contact overhung "
            "the bar's end, where the bar's flat-face model of the contact does not hold",
        )
    worst = int(np.argmax(err.max(axis=1)))
    lu = display(series.units, "length")
    gates = (
        passed_if(
            "bounds",
            not law.at_bounds,
            f"the fit ended on the bound of {', '.join(law.at_bounds)}: the estimate is the edge of the search, not a minimum",
        ),
    )
    if family == "crushing":  # the law itself in the line: two numbers, the strength at the reference rate and the exponent
        (sigma, m), (hs, hm) = law.values, law.half_widths
        # in the display system asked for (--units): psi in in-lbf-s; MPa in SI (a strength's own scale: SI's GPa would read 0.0089)
        su = display(series.units, "stress")
        strength = f"{sigma / 1e6:.4g} MPa" if series.units == "SI" else f"{sigma * su.factor:.4g} {su.label}"
        what = f"crushing strength {strength} ±{hs / sigma:.1%} at {law.reference_rate:.4g} 1/s, rate exponent {m:.4g} ±{hm:.2g}"
    else:
        what = f"d_ref {law.d_ref * lu.factor:.3g} {lu.label}"
    line = (
        f"{pars} ({what})\n"
        f"closure over {len(tests)} tests: max |error| F0 {err[:, 0].max():.1%}, T {err[:, 1].max():.1%}, I {err[:, 2].max():.1%}, "
        f"t_F0 {np.abs(cl.peak_time_errors).max():.1%} "
        f"(worst {cl.names[worst]}); law.json"
    )
    inputs = (series.path, *(t.record for t in series.tests), *((series.bar_file,) if series.bar_file else ()))
    return Outcome(files, line, inputs, tuple(warnings), gates)
