"""Outputs of ``softimpact identify``: law.json, closure.csv, approach-<test>.csv, figures."""

from __future__ import annotations

import numpy as np

from ..formats._json import json_text
from ..formats.law_json import law_summary, projectile_record
from ..units import display
from .files import csv_text, figure_bytes

__all__ = ["closure_columns", "identify_files", "closure_figure", "force_approach_figure", "predictions_summary", "prediction_columns"]

PREDICTION_NOTE = (
    "95 % predictive intervals of the pulse on the bar: the parameters' covariance carried through coupled bar runs "
    "(gradient at each diameter's median tested velocity) and, in quadrature, the RMS relative closure error of that "
    "figure over the tests (what the law cannot reproduce). Read these, not the parameters' ±: parameters listed under "
    "unfixed_parameters are not determined by the data (95 % half-width above the value, or |correlation| > 0.99) "
    "although the pulses they predict are."
)


def predictions_summary(law, predictions) -> dict:
    """law.json's additions: ``covariance`` (names, matrix), ``unfixed_parameters``, ``predictions``
    (per point m, d, V, tested, and F0, t_F0, T, I each with value, ci95_half_width and its parameter part)."""
    out = {"unfixed_parameters": list(law.unfixed_parameters), "at_bounds": list(law.at_bounds)}
    if law.covariance is not None:
        out["covariance"] = {"names": list(law.names), "matrix": np.asarray(law.covariance).tolist()}
    if predictions:
        out["predictions_note"] = PREDICTION_NOTE
        out["predictions"] = [
            {
                "mass_kg": p.mass,
                "diameter_m": p.diameter,
                "velocity_m_s": p.velocity,
                "tested": p.tested,
                **{
                    f: {"value": float(v), "ci95_half_width": float(h), "ci95_half_width_parameters": float(hp)}
                    for f, v, h, hp in zip(p.figures, p.values, p.half_widths, p.parameter_half_widths)
                },
            }
            for p in predictions
        ]
    return out


def prediction_columns(predictions) -> dict:
    """predictions.csv: one row per point, each figure's value and 95 % half-width."""
    cols = {
        "diameter_m": np.array([p.diameter for p in predictions]),
        "mass_kg": np.array([p.mass for p in predictions]),
        "velocity_m_s": np.array([p.velocity for p in predictions]),
        "tested": np.array([float(p.tested) for p in predictions]),
    }
    for j, f in enumerate(predictions[0].figures if len(predictions) else ()):
        cols[f] = np.array([p.values[j] for p in predictions])
        cols[f"{f}_ci95_half_width"] = np.array([p.half_widths[j] for p in predictions])
    return cols


def closure_columns(tests, closure) -> dict:
    """One row per test: diameter, velocity, measured and simulated F0, T, I and their relative errors; then
    the same for t_F0 (of the eq-15 fits)."""
    m, s, e = closure.measured, closure.simulated, closure.errors
    cols = {
        "test": np.array(closure.names),
        "diameter_m": np.array([t.diameter for t in tests]),
        "velocity_m_s": np.array([t.velocity for t in tests]),
    }
    for j, (key, unit) in enumerate((("peak_force", "N"), ("duration", "s"), ("impulse", "N_s"))):
        cols[f"measured_{key}_{unit}"] = m[:, j]
        cols[f"simulated_{key}_{unit}"] = s[:, j]
        cols[f"error_{key}"] = e[:, j]
    if closure.peak_times is not None:
        cols["measured_time_of_peak_s"] = closure.peak_times[:, 0]
        cols["simulated_time_of_peak_s"] = closure.peak_times[:, 1]
        cols["error_time_of_peak"] = closure.peak_time_errors
    return cols


def closure_figure(tests, closure, system: str, title: str = "Closure: measured force and the identified law on the coupled bar"):
    """Measured force histories (solid) beside the coupled bar simulations with the identified law (dashed)."""
    from .plots import _figure, curve_colors

    tu, fu = display(system, "time"), display(system, "force")
    fig, ax = _figure(7.5, 4.8)
    colors = curve_colors(len(tests))
    for i, (t, cl_t, cl_f) in enumerate(zip(tests, closure.time, closure.force)):
        c = colors[i]
        T = closure.measured[i, 1]
        keep = t.time <= 1.5 * T
        ax.plot(t.time[keep] * tu.factor, t.force[keep] * fu.factor, color=c, lw=1.2, label=t.name)
        keep = cl_t <= 1.5 * T
        ax.plot(cl_t[keep] * tu.factor, cl_f[keep] * fu.factor, color=c, lw=1.2, ls="--")
    ax.set_xlabel(f"time since first contact [{tu.label}]")
    ax.set_ylabel(f"contact force [{fu.label}]")
    ax.set_title(title + " (dashed)", fontsize=10)
    ax.legend(fontsize=7, ncol=2)
    return fig


def force_approach_figure(tests, law, approaches, system: str):
    """Measured F against the reconstructed approach α/d (main pulses), and the fitted law on the same α, α̇
    (and, for a law with memory, the same α history)."""
    from .plots import _figure, curve_colors

    fu = display(system, "force")
    fig, ax = _figure(7.5, 4.8)
    colors = curve_colors(len(tests))
    for i, (t, a) in enumerate(zip(tests, approaches)):
        c = colors[i]
        m = a.main_pulse
        ax.plot(a.approach[m] / t.diameter, a.force[m] * fu.factor, color=c, lw=1.0, label=t.name)
        if a.fitted_force is not None:
            ax.plot(a.approach[m] / t.diameter, a.fitted_force * fu.factor, color=c, lw=1.0, ls="--")
    ax.set_xlabel("approach α / d (impactor minus bar end, from the measured force)")
    ax.set_ylabel(f"contact force [{fu.label}]")
    ax.set_title("Force against approach: measured (solid), identified law (dashed)", fontsize=10)
    ax.legend(fontsize=7, ncol=2)
    return fig


def approach_record(tests, approaches, law, bar_radius: float) -> dict:
    """What the law's own geometry reached on the bar tests it was identified on (law.json's ``identified_on``): the
    range over the tests of each one's largest approach over its diameter, α_max/d (the approach the law is known to,
    checked where it is used: :func:`softimpact.models.validity.identified_contact_validity`), and of its largest contact
    radius, the law's own a(α_max) (:meth:`radius`), over the bar's radius (the patch must lie on the bar's face)."""
    from ..models.protocols import HistoryLaw, StepBoundLaw

    over_d, over_bar = [], []
    for t, a in zip(tests, approaches):
        alpha = float(np.max(a.approach[a.main_pulse])) if np.any(a.main_pulse) else float(np.max(a.approach))
        over_d.append(alpha / t.diameter)
        one = law.law(t.mass, t.diameter, t.velocity)
        if isinstance(one, StepBoundLaw):  # a law with memory, bound to the test's sampling (its radius does not depend on it)
            one = one.for_time_step(float(t.time[1] - t.time[0]))
        one = one.branch(one.initial_state()) if isinstance(one, HistoryLaw) else one  # its radius is its branch's
        over_bar.append(float(one.radius(alpha)) / bar_radius)
    return {"approach_over_diameter": [min(over_d), max(over_d)], "contact_radius_over_bar_radius": [min(over_bar), max(over_bar)]}


def identify_files(series, tests, law, approaches, closure, figures: bool = True, prefix: str = "", predictions=()) -> dict[str, bytes | str]:
    """law.json (with the predictive intervals, :func:`predictions_summary`; ``identified_on`` with the tests' projectiles
    and the approach and contact radius they reached, :func:`approach_record`), closure.csv,
    predictions.csv, approach-<test>.csv and (optionally) closure-forces.png, force-approach.png."""
    summary = law_summary(law, [t.name for t in tests], closure, str(series.path), projectile_record(tests))
    summary.setdefault("identified_on", {}).update(approach_record(tests, approaches, law, series.bar.diameter / 2))
    summary.update(predictions_summary(law, predictions))
    files = {
        prefix + "law.json": json_text(summary),
        prefix + "closure.csv": csv_text(closure_columns(tests, closure)),
    }
    if predictions:
        files[prefix + "predictions.csv"] = csv_text(prediction_columns(predictions))
    for a, t in zip(approaches, tests):
        files[prefix + f"approach-{t.name}.csv"] = csv_text(
            {
                "time_s": a.time,
                "force_N": a.force,
                "approach_m": a.approach,
                "approach_rate_m_s": a.rate,
                "impactor_velocity_m_s": a.impactor_velocity,
                "bar_end_displacement_m": a.end_displacement,
                "in_fit": a.main_pulse.astype(float),
            }
        )
    if figures:
        files[prefix + "closure-forces.png"] = figure_bytes(closure_figure(tests, closure, series.units))
        files[prefix + "force-approach.png"] = figure_bytes(force_approach_figure(tests, law, approaches, series.units))
    return files
