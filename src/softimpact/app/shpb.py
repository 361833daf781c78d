"""``softimpact shpb``: two-bar (split Hopkinson) tests → stress–strain curves at rate, the equilibrium check, and a
rate-dependent strength that becomes a crushing law (law.json) for impact and bar cases.

Each test's records are read (any lab format, volts through each bar's bridge) and analysed
(:func:`softimpact.workflows.shpb.analyse_test`); a test whose strength was not measured in dynamic equilibrium
fails its gate ``equilibrium[test]`` (exit 3 unless ``--accept-poor``) and is left out of the rate law. With three
tests or more in equilibrium at rates 20 % apart, the rate law σ = σ_ref·(ε̇/ε̇_ref)^m is fitted
(:func:`softimpact.workflows.shpb.fit_rate_law`) and written as a crushing law.json (``family`` "crushing",
``method`` "two-bar (split Hopkinson) tests ...", ``identified_on.strain_rate_1_s`` the rates measured: the law's
validity envelope), which an impact or bar case uses with ``[contact] law = "identified"``,
``law_file = "law.json"``: runs whose crushing strain rate V/d lies within the rates measured are not flagged.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..errors import InputError
from ..formats._json import json_text
from ..formats.law_json import law_json
from ..gates import at_least, quality
from ..input.shpb_series import load_shpb_series, read_shpb_records
from ..output.shpb import rate_law_summary, shpb_files, test_summary
from ..workflows.identification import CRUSHING_PARAMETERS, CrushingIdentifiedLaw
from ..workflows.shpb import ShpbSettings, analyse_test, fit_rate_law
from . import Outcome, Progress, no_progress
from .options import display_system

__all__ = ["shpb", "crushing_law_of"]

METHOD = "two-bar (split Hopkinson) tests (softimpact shpb)"


def crushing_law_of(law, density: float | None) -> CrushingIdentifiedLaw:
    """The crushing law (law.json's family "crushing") of a rate law fitted across two-bar tests: σ_ref and m with their
    95 % half-widths, ε̇_ref, the rates measured as its envelope, the specimens' ``density`` [kg/m³] (None: not known)
    as the material it holds for; no size (a material's strength)."""
    on = {"strain_rate_1_s": [float(law.rate_range[0]), float(law.rate_range[1])]}
    if density is not None:
        on["projectile"] = {"density_kg_m3": [float(density), float(density)]}
    residuals = np.array([math.log(s / float(law(r))) for r, s in law.points])
    return CrushingIdentifiedLaw(
        CRUSHING_PARAMETERS,
        np.array([law.strength_ref, law.exponent]),
        np.array([law.strength_ref_half_width, law.exponent_half_width]),
        law.reference_rate,
        math.nan,
        residuals,
        0.5 * float(residuals @ residuals),
        on,
        method=METHOD,
    )


def shpb(*, series_name: str, units: str | None = None, figures: bool = True, progress: Progress = no_progress) -> Outcome:
    """Analyse a two-bar series (file or built-in name; module docstring); ``units``: the figures' display system."""
    series = load_shpb_series(series_name)
    series = replace(series, units=display_system(units, series.units))
    records = read_shpb_records(series)
    results, errors, warnings, gates = [], {}, [], []
    for i, ((rec, _), test) in enumerate(zip(records, series.tests)):
        settings = ShpbSettings(dispersion=series.dispersion != "none", transmitted_delay=test.transmitted_delay)
        try:
            r = analyse_test(rec, series.incident, series.transmitted, test.specimen, settings)
        except InputError as exc:
            results.append(None)
            errors[test.name] = str(exc)
            warnings.append(f"{test.name}: not analysed ({exc})")
        else:
            results.append(r)
            warnings += list(r.flags)
            gates.append(
                at_least(
                    f"equilibrium[{test.name}]",
                    1.0 if r.equilibrium_at_strength else 0.0,
                    1.0,
                    f"{test.name}: the strength was not measured in dynamic equilibrium (the faces' forces differ by more than 5 %)",
                )
            )
        progress(i + 1, len(series.tests), "analysing")
    if all(r is None for r in results):
        raise InputError(f"no test of the series could be analysed (first: {next(iter(errors.values()))})")
    usable = [(t, r) for t, r in zip(series.tests, results) if r is not None and r.equilibrium_at_strength and r.strain_rate > 0 and r.strength > 0]
    law, law_error = None, ""
    try:
        law = fit_rate_law([(r.strain_rate, r.strength) for _, r in usable], [t.name for t, _ in usable])
    except InputError as exc:
        law_error = str(exc)
        warnings.append(f"no rate law: {exc}")
    files = shpb_files(results, series, law, figures)
    summary = {
        "series": str(series.path),
        "synthetic": series.synthetic,
        "dispersion": series.dispersion,
        "tests": {t.name: test_summary(r, t.specimen) for t, r in zip(series.tests, results) if r is not None},
        "failed": errors,
        "rate_law": rate_law_summary(law) if law is not None else {"not_fitted": law_error},
        "quality": quality(gates),
    }
    line = f"{len(results) - len(errors)} of {len(results)} tests analysed"
    if law is not None:
        densities = {t.specimen.density for t, _ in usable}
        density = densities.pop() if len(densities) == 1 else None
        files["law.json"] = law_json(crushing_law_of(law, density), [t.name for t, _ in usable], series=str(series.path))
        line += (
            f"; strength {law.strength_ref / 1e6:.4g} MPa at {law.reference_rate:.4g} /s, exponent {law.exponent:.3f} +/- {law.exponent_half_width:.3f}, "
            f"rates {law.rate_range[0]:.4g}-{law.rate_range[1]:.4g} /s; law.json"
        )
    files["summary.json"] = json_text(summary)
    inputs = (series.path, *dict.fromkeys(p for t in series.tests for p in (t.incident[0], t.transmitted[0])), *series.bar_files)
    return Outcome(files, line, tuple(inputs), tuple(warnings), tuple(gates))
