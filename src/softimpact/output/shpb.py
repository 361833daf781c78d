"""Outputs of ``softimpact shpb``: tests.csv, curve-<test>.csv, summary.json's tests and rate law, and the figures
(stress–strain at rate, the equilibrium check, the rate law)."""

from __future__ import annotations

import math

import numpy as np

from ..units import display
from .files import csv_text, figure_bytes
from .report import stem

__all__ = ["shpb_files", "test_summary", "rate_law_summary", "CURVE_COLUMNS"]

CURVE_COLUMNS = {  # curve-<test>.csv: column → the result's array
    "incident_strain": "incident",
    "reflected_strain": "reflected",
    "transmitted_strain": "transmitted",
    "front_force_N": "front_force",
    "back_force_N": "back_force",
    "stress_one_wave_Pa": "stress_one",
    "stress_two_wave_Pa": "stress_two",
    "stress_three_wave_Pa": "stress_three",
    "strain_rate_one_wave_1_s": "strain_rate_one",
    "strain_rate_three_wave_1_s": "strain_rate_three",
    "strain_one_wave": "strain_one",
    "strain_three_wave": "strain_three",
    "equilibrium_ratio": "equilibrium_ratio",
}


def test_summary(r, specimen) -> dict:
    """One test's scalars (SI), as summary.json and tests.csv give them."""
    return {
        "specimen_length_m": specimen.length,
        "specimen_diameter_m": specimen.diameter,
        "strength_Pa": r.strength,
        "strain_rate_1_s": r.strain_rate,
        "modulus_Pa": r.modulus,
        "modulus_se_Pa": r.modulus_se,
        "peak_stress_Pa": float(np.max(r.stress_three)),
        "equilibrium_start_s": r.equilibrium_window[0],
        "equilibrium_end_s": r.equilibrium_window[1],
        "equilibrium_at_strength": r.equilibrium_at_strength,
        "equilibrium_in_rise": r.equilibrium_in_rise,
        "flags": list(r.flags),
        "notes": list(r.notes),
    }


def rate_law_summary(law) -> dict:
    """The rate law's numbers (SI): σ_ref and m with their 95 % half-widths, ε̇_ref, A = σ_ref·ε̇_ref^(−m), the rates measured."""
    return {
        "form": "sigma = strength_ref*(rate/reference_rate)^rate_exponent",
        "strength_ref_Pa": law.strength_ref,
        "strength_ref_ci95_half_width_Pa": law.strength_ref_half_width,
        "rate_exponent": law.exponent,
        "rate_exponent_ci95_half_width": law.exponent_half_width,
        "reference_rate_1_s": law.reference_rate,
        "coefficient_at_1_per_s_Pa": law.coefficient_at_1_per_s,
        "strain_rate_range_1_s": list(law.rate_range),
        "residual_rms_log_strength": law.residual,
        "tests": list(law.names),
    }


def _tests_csv(results, series) -> str:
    rows = [(t.name, test_summary(r, t.specimen)) for t, r in zip(series.tests, results) if r is not None]
    cols = {"test": [n for n, _ in rows]}
    for key in rows[0][1] if rows else ():
        cols[key] = [("; ".join(s[key]).replace(",", ";") if key in ("flags", "notes") else s[key]) for _, s in rows]
    return csv_text({k: np.array(v, dtype=object) for k, v in cols.items()})


def _stress_strain(r, system: str):
    """One-, two- and three-wave stress against the three-wave strain; the equilibrium window bold."""
    from .plots import _figure

    su = display(system, "stress")
    fig, ax = _figure()
    e = r.strain_three
    inside = np.zeros(e.size, bool)
    if math.isfinite(r.equilibrium_window[0]):
        inside = (r.time >= r.equilibrium_window[0]) & (r.time <= r.equilibrium_window[1])
    for arr, label, style in (
        (r.stress_one, "one-wave (back face)", ":"),
        (r.stress_two, "two-wave (front face)", "--"),
        (r.stress_three, "three-wave (mean)", "-"),
    ):
        ax.plot(e, arr * su.factor, ls=style, lw=1.0, label=label)
    ax.plot(e[inside], r.stress_three[inside] * su.factor, lw=2.5, color="k", alpha=0.35, label="in equilibrium")
    ax.set_xlabel("engineering strain (three-wave), compression +")
    ax.set_ylabel(f"engineering stress [{su.label}], compression +")
    ax.set_title(f"{r.name}: strength {r.strength * su.factor:.4g} {su.label} at {r.strain_rate:.4g} /s")
    ax.legend(fontsize=8)
    return fig


def _equilibrium(r, system: str):
    """The faces' forces against time, and R = 2(F1 − F2)/(F1 + F2) with the tolerance and the window."""
    from .plots import _figure

    tu, fu = display(system, "time"), display(system, "force")
    fig, ax = _figure()
    ax.plot(r.time * tu.factor, r.front_force * fu.factor, label="front face (incident + reflected)")
    ax.plot(r.time * tu.factor, r.back_force * fu.factor, ls="--", label="back face (transmitted)")
    ax.set_xlabel(f"time from the incident wave's arrival at the specimen [{tu.label}]")
    ax.set_ylabel(f"force [{fu.label}], compression +")
    twin = ax.twinx()
    twin.plot(r.time * tu.factor, r.equilibrium_ratio, color="C2", lw=0.8, label="R = 2(F1 - F2)/(F1 + F2)")
    twin.axhline(0.05, color="C2", ls=":", lw=0.8)
    twin.axhline(-0.05, color="C2", ls=":", lw=0.8)
    twin.set_ylim(-0.3, 0.3)
    twin.set_ylabel("equilibrium ratio R")
    if math.isfinite(r.equilibrium_window[0]):
        ax.axvspan(r.equilibrium_window[0] * tu.factor, r.equilibrium_window[1] * tu.factor, color="C2", alpha=0.1, label="|R| <= 5 %")
    ax.legend(fontsize=8, loc="upper left")
    ax.set_title(f"{r.name}: dynamic equilibrium")
    return fig


def _rate_law(law, system: str):
    """Each test's strength against its strain rate (log-log), the fitted law and the range it was measured on."""
    from .plots import _figure

    su = display(system, "stress")
    fig, ax = _figure()
    pts = np.array(law.points)
    ax.loglog(pts[:, 0], pts[:, 1] * su.factor, "o", label="tests (plateau stress, its strain rate)")
    rates = np.geomspace(law.rate_range[0], law.rate_range[1], 50)
    ax.loglog(
        rates, law(rates) * su.factor, "-", label=f"sigma = {law.strength_ref * su.factor:.4g} {su.label} (rate/{law.reference_rate:.4g} /s)^{law.exponent:.3f}"
    )
    ax.set_xlabel("strain rate [1/s]")
    ax.set_ylabel(f"strength [{su.label}]")
    ax.set_title("Rate-dependent strength (its validity envelope: the rates measured)")
    ax.legend(fontsize=8)
    return fig


def shpb_files(results, series, law, figures: bool = True) -> dict[str, bytes | str]:
    """tests.csv, curve-<test>.csv per analysed test and, with figures, stress-strain-<test>.png, equilibrium-<test>.png
    and (with a rate law) rate-law.png."""
    files: dict[str, bytes | str] = {"tests.csv": _tests_csv(results, series)}
    for r in results:
        if r is None:
            continue
        files[f"curve-{stem(r.name)}.csv"] = csv_text({"time_s": r.time, **{k: getattr(r, v) for k, v in CURVE_COLUMNS.items()}})
        if figures:
            files[f"stress-strain-{stem(r.name)}.png"] = figure_bytes(_stress_strain(r, series.units))
            files[f"equilibrium-{stem(r.name)}.png"] = figure_bytes(_equilibrium(r, series.units))
    if figures and law is not None:
        files["rate-law.png"] = figure_bytes(_rate_law(law, series.units))
    return files
