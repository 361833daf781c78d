"""Outputs of ``softimpact reduce`` and ``fit``: tests.csv, history-<test>.csv, scaling.json, Figs 7–15."""

from __future__ import annotations

import math

import numpy as np

from ..formats._json import json_text
from ..formats.scaling_json import scaling_summary
from ..models.pulse_fit import TAIL_DELTA_AIC
from ..units import display
from .files import csv_text, figure_bytes
from .report import Section, stem

__all__ = ["reduction_files", "scaling_files", "scaling_section", "scaling_text", "scaling_data", "tail_shape_spread", "TABLE_I"]


# tests.csv's columns of a reduction (after the test's own record, velocity_m_s, mass_kg, diameter_m), in order
REDUCTION_COLUMNS = (
    "peak_force_N",
    "time_of_peak_s",
    "duration_s",
    "impulse_N_s",
    "valid_until_s",
    "flags",
    "duration_threshold_s",
    "time_of_max_s",
    "impulse_uncertainty_N_s",
    "direct_until_s",
    "fit_peak_force_N",
    "fit_rms_N",
    "first_contact_record_time_s",
    "whole_record_peak_force_N",
    "whole_record_time_of_peak_s",
    "whole_record_duration_s",
)
RECORD_COLUMNS = {  # tests.csv column → the record's own metadata key (input/records/), as read
    "record_format": "source_format",
    "record_channel": "channel",
    "record_unit": "unit",
    "sample_rate_Hz": "sample_rate",
    "record_start_s": "time_start",
    "pretrigger_samples": "pretrigger_samples",
    "trigger": "trigger",
    "record_date": "date",
}


def _reduction_values(item, r):
    """(column, value) of one reduced test's reduction columns and tail-shape columns, in tests.csv's order."""
    return (
        ("peak_force_N", r.peak_force),
        ("time_of_peak_s", r.time_of_peak),
        ("duration_s", r.duration),
        ("impulse_N_s", r.impulse),
        ("valid_until_s", r.valid_until),
        ("flags", "; ".join(r.flags).replace(",", ";")),
        ("duration_threshold_s", r.duration_threshold),
        ("time_of_max_s", r.time_of_max),
        ("impulse_uncertainty_N_s", r.impulse_uncertainty),
        ("direct_until_s", r.direct_until),
        ("fit_peak_force_N", r.fit.peak_force),
        ("fit_rms_N", r.fit_rms),
        ("first_contact_record_time_s", r.first_contact_record_time),
        ("whole_record_peak_force_N", r.whole_fit.peak_force if r.whole_fit is not None else math.nan),
        ("whole_record_time_of_peak_s", r.whole_fit.time_of_peak if r.whole_fit is not None else math.nan),
        ("whole_record_duration_s", r.whole_fit.duration if r.whole_fit is not None else math.nan),
        *tail_shape_spread(item.tail_shapes).items(),
    )


def _test_columns(cols: dict, item, series, corrected: bool) -> None:
    """Append one test's own columns to ``cols``: what it is, its status, its record's metadata, the dispersion."""
    t = item.test
    cols["record"].append(str(t.record.name))
    cols["velocity_m_s"].append(t.velocity)
    cols["mass_kg"].append(t.mass)
    cols["diameter_m"].append(t.diameter)
    cols["status"].append(item.status)
    conditioned = item.conditioning
    cols["rejected_because"].append(_text(item.rejected))
    rejected = item.rejected
    cols["conditioning_notes"].append(_text([f for f in (conditioned.flags if conditioned is not None else ()) if f not in rejected]))
    meta = item.metadata
    for k, m in RECORD_COLUMNS.items():
        v = meta.get(m)
        cols[k].append(v if isinstance(v, (int, float)) and not isinstance(v, bool) else ("" if v is None else _text([str(v)])))
    cols["dispersion"].append(series.dispersion)
    if corrected:
        u = item.uncorrected
        cols["uncorrected_peak_force_N"].append(u.peak_force if u is not None else math.nan)


def reduction_files(series, reduced, figures: bool = True, prefix: str = "") -> dict[str, bytes | str]:
    """tests.csv, history-<test>.csv per test, Fig 7 per test."""
    from . import plots

    cols = {k: [] for k in ("record", "velocity_m_s", "mass_kg", "diameter_m", *REDUCTION_COLUMNS, *TAIL_COLUMNS)}
    reduction_cols = list(cols)[4:]
    corrected = series.dispersion != "none"
    for k in ("status", "rejected_because", "conditioning_notes", *RECORD_COLUMNS, "dispersion") + (("uncorrected_peak_force_N",) if corrected else ()):
        cols[k] = []
    files: dict[str, bytes | str] = {}
    for item in reduced:
        t, r = item.test, item.reduction
        _test_columns(cols, item, series, corrected)
        if r is None:
            for k in reduction_cols:
                cols[k].append("error: " + item.error.replace(",", ";") if k == "flags" else math.nan)
            continue
        for k, v in _reduction_values(item, r):
            cols[k].append(v)
        files[f"{prefix}history-{stem(t.name)}.csv"] = csv_text({"time_s": r.time, "force_N": r.force})
        if figures:
            files[f"{prefix}fig07-force-{stem(t.name)}.png"] = figure_bytes(plots.force_history(r, series.units))
            if corrected and item.uncorrected is not None:
                files[f"{prefix}dispersion-{stem(t.name)}.png"] = figure_bytes(plots.dispersion_comparison(r, item.uncorrected, series.units))
    files[prefix + "tests.csv"] = csv_text({k: np.array(v, dtype=object) for k, v in cols.items()})
    return files


TAIL_COLUMNS = ("tail_best_family", "tail_families_not_rejected", "tail_shape_peak_force_N", "tail_shape_time_of_peak_s", "tail_shape_duration_s")


def tail_shape_spread(shapes) -> dict:
    """One test's tail-shape columns for tests.csv: the best tail family by AIC, those within
    TAIL_DELTA_AIC of it, and half the range of their F0 [N], t_F0, T [s] (for information: the α's tail_shape
    term takes every family, :func:`softimpact.workflows.scaling.tail_shape_term`)."""
    if not shapes:
        return {k: ("" if k.startswith("tail_best") or k.startswith("tail_families") else math.nan) for k in TAIL_COLUMNS}
    best = min(shapes, key=lambda s: s.aic)
    ok = [s for s in shapes if s.aic - best.aic < TAIL_DELTA_AIC]

    def half_range(key):
        v = [getattr(s, key) for s in ok]
        return 0.5 * (max(v) - min(v))

    return dict(zip(TAIL_COLUMNS, (best.family, " ".join(s.family for s in ok), half_range("peak_force"), half_range("time_of_peak"), half_range("duration"))))


def scaling_text(fits) -> str:
    """The text of scaling.json (:func:`scaling_data`)."""
    return json_text(scaling_data(fits))


def scaling_data(fits) -> dict:
    """scaling.json (:mod:`softimpact.formats.scaling_json`) with, per group, its ``tail_shape`` term:
    the tail families' AICs, the best, those within ΔAIC < TAIL_DELTA_AIC (for information), each
    family's α's and the half-width its fit's standard errors give them (``error_half_width``), per α
    the half-width added to each side of its 95 % interval (the largest over every family of its
    distance from the reported α plus its error), the widened interval, the α's the records do not
    bound better than the tail's shape (``not_bounded_by_data``) and a sentence saying so."""
    data = scaling_summary(fits)

    def term(g):
        t = g.tail_shape
        if t is None:
            return None
        return {
            "aic": t.aic,
            "best": t.best,
            "not_rejected": list(t.accepted),
            "delta_aic_threshold": TAIL_DELTA_AIC,
            "alphas": t.alphas,
            "error_half_width": t.errors,
            "half_width": t.half_widths,
            "lower_extra": t.lower_extra,
            "ci95_with_tail_shape": {n: list(t.interval(n, line)) for n, line in g.origin.items()},
            "not_bounded_by_data": list(t.unbounded),
            "statement": _unbounded_text(g),
        }

    for label, g in fits.items():
        if label != "pooled":
            data["groups"][label]["tail_shape"] = term(g)
    data["pooled"]["tail_shape"] = term(fits["pooled"] if "pooled" in fits else next(iter(fits.values())))
    return data


def _unbounded_text(g) -> str:
    """One sentence: which α's of group ``g`` the records cannot bound better than the tail's unknown shape."""
    t = g.tail_shape
    if not t.unbounded:
        return "the records bound every alpha better than the tail's shape: the tail-shape term is smaller than each 95 % interval"
    parts = ", ".join(f"{n} to +/-{t.half_widths[n]:.3g} (statistical +/-{0.5 * (g.origin[n].slope_ci[1] - g.origin[n].slope_ci[0]):.3g})" for n in t.unbounded)
    return (
        f"the records cannot bound {parts}: a tail that ramps in under the main pulse, in a shape the records do not fix, "
        "would move the main pulse by more than the scatter does; the 95 % intervals are widened by the spread over every tail family"
    )


def _text(items) -> str:
    """Sentences joined for one CSV cell (commas would split it)."""
    return "; ".join(items).replace(",", ";")


def scaling_files(fits, system: str, figures: bool = True, prefix: str = "") -> dict[str, bytes | str]:
    from . import plots

    files: dict[str, bytes | str] = {prefix + "scaling.json": scaling_text(fits)}
    if figures:
        files[prefix + "fig08-peak-force.png"] = figure_bytes(plots.scaling_peak_force(fits, system))
        files[prefix + "fig09-inverse-duration.png"] = figure_bytes(plots.scaling_duration(fits, system))
        files[prefix + "fig10-skewness.png"] = figure_bytes(plots.scaling_skewness(fits, system))
        files[prefix + "fig11-impulse.png"] = figure_bytes(plots.scaling_impulse(fits, system))
    return files


# The paper's Table I (α1–α4 per ball diameter); α3 of the 1/2-in ball was lost.
TABLE_I = {"0.375 in": (4.00, 1.03, 0.25, 0.74), "0.5 in": (4.25, 0.93, None, 0.66)}


def _tail_shape_paragraph(fits) -> list[str]:
    """The report's paragraph on the tail-shape widening of the α intervals (none without tail shapes)."""
    paragraphs = []
    terms = [(label, g.tail_shape) for label, g in fits.items() if g.tail_shape is not None]
    if terms:
        paragraphs.append(
            "The tail's shape is not known, and where the tail ramps in under the falling main pulse it moves T and tF0. Six "
            "tail families (a knee with an exponential decay; a tail ramping in linearly under the main pulse then decaying "
            "exponentially, linearly or as a power law; a free ramp, concave or convex, ending before or after T, then a stretched "
            "exponential; the same free ramp starting at first contact) are fitted to every record. The true tail is in none of "
            "them, so none is rejected on its AIC: for every family but the last the distance of its α's from the reported ones "
            "plus what its own fit's standard errors (tail parameters free) leave of them is taken, and the largest is added to "
            "each side of the 95 % interval (last column; tail_shape in scaling.json, per test in tests.csv)."
        )
        paragraphs.append(
            "A tail that already rises under the peak adds to the recorded F0, so α1 can only be too high by it: the lower bound "
            "of α1 alone is moved down by half the distance of the last family's α1 below the reported one (lower_extra in "
            "scaling.json). "
            + "; ".join(
                f"{label}: best by AIC {t.best}, α1 ±{t.half_widths['alpha1']:.3f} and {t.lower_extra.get('alpha1', 0.0):.3f} lower, "
                f"α2 ±{t.half_widths['alpha2']:.3f}, α3 ±{t.half_widths['alpha3']:.3f}"
                + (f", not bounded by the records better than the tail's shape: {', '.join(t.unbounded)}" if t.unbounded else "")
                for label, t in terms
            )
            + "."
        )
    return paragraphs


def scaling_section(fits, series, reduced, prefix: str, figures: bool) -> Section:
    """Report section: the series, its reductions and Table I beside the fitted constants."""
    rows = []
    for label, g in fits.items():
        paper = TABLE_I.get(label)
        for i, name in enumerate(("alpha1", "alpha2", "alpha3", "alpha4")):
            f = g.origin[name]
            ref = "—" if paper is None or paper[i] is None else f"{paper[i]:.3g}"
            widened = ""
            if g.tail_shape is not None:
                lo, hi = g.tail_shape.interval(name, f)
                widened = f"[{lo:.3f}, {hi:.3f}]"
            rows.append([label, name, f"{f.slope:.3f}", f"[{f.slope_ci[0]:.3f}, {f.slope_ci[1]:.3f}]", f"{f.r2:.4f}", ref, widened])
    fu, tu = display(series.units, "force"), display(series.units, "time")
    vu, iu = display(series.units, "velocity"), display(series.units, "impulse")
    trows = []
    for item in reduced:
        r = item.reduction
        if r is None:
            trows.append([item.test.name, f"{item.test.velocity * vu.factor:.0f}", "—", "—", "—", "—", item.error])
        else:
            trows.append(
                [
                    item.test.name,
                    f"{item.test.velocity * vu.factor:.0f}",
                    f"{r.peak_force * fu.factor:.1f}",
                    f"{r.time_of_peak * tu.factor:.1f}",
                    f"{r.duration * tu.factor:.1f}",
                    f"{r.impulse * iu.factor:.4g}",
                    "; ".join(r.flags),
                ]
            )
    figs = [
        (prefix + n, c)
        for n, c in (
            ("fig08-peak-force.png", "Figs 8 and 12: F0 against mV²/(2d)"),
            ("fig09-inverse-duration.png", "Figs 9 and 13: 1/T against V"),
            ("fig10-skewness.png", "Figs 10 and 14: tF0/T against V"),
            ("fig11-impulse.png", "Figs 11 and 15: I against 2mV, with I = 2mV"),
        )
    ]
    first = next((i for i in reduced if i.reduction is not None), None)
    if first is not None:
        figs.insert(0, (f"{prefix}fig07-force-{stem(first.test.name)}.png", f"Fig 7: force history of {first.test.name}, with F0, tF0 and T"))
    paragraphs = [
        "Each record is reduced to the contact force at the struck end by separating the incident wave from its reflections "
        "(d'Alembert, exact for the non-dispersive bar), so pulses longer than the reflection return time 2(L−x)/c are handled. "
        "T comes from a least-squares fit of eq (15) to the main pulse; I integrates the whole history, tail included.",
    ]
    paragraphs += _tail_shape_paragraph(fits)
    if series.synthetic:
        paragraphs.insert(0, "SYNTHETIC DATA: " + series.synthetic + ". The paper's own figure data are not available.")
    return Section(
        series.title,
        paragraphs,
        [
            (f"Reduced tests ({fu.label}, {tu.label}, {iu.label})", ["test", f"V [{vu.label}]", "F0", "tF0", "T", f"I [{iu.label}]", "flags"], trows),
            (
                "Table I: scaling constants fitted through the origin, with 95 % intervals, beside the paper's",
                ["group", "constant", "fitted", "95 % interval", "R²", "paper (Table I)", "95 % with tail shape"],
                rows,
            ),
        ],
        figs if figures else [],
    )
