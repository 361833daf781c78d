"""Results → files: CSV histories, JSON summaries, figures, and the HTML report.

Each ``*_files`` function returns ``{relative name: content}`` for
:func:`softimpact.io.write_outputs`; nothing here touches the disk.
"""

from __future__ import annotations

import html
import math
from dataclasses import dataclass, field

import numpy as np

from . import __version__
from .io import csv_text, figure_bytes, json_text
from .units import display

__all__ = ["Section", "bar_files", "bar_summary", "inferred_force", "render_report"]


@dataclass
class Section:
    """A part of the HTML report: text, tables (header, rows) and figure paths."""

    title: str
    paragraphs: list[str] = field(default_factory=list)
    tables: list[tuple[str, list[str], list[list[str]]]] = field(default_factory=list)
    figures: list[tuple[str, str]] = field(default_factory=list)  # (path, caption)


def inferred_force(result, gauge_index: int = 0):
    """F(t) = −EA·ε(t + x/c): the force at the struck end read from a gauge (paper, Fig 5).

    Returns (time, force) on the result's grid, NaN where t + x/c is past the record.
    """
    bar = result.problem.bar
    rod = bar.rod()
    x = result.problem.gauges[gauge_index].position
    t = result.time
    shifted = np.interp(t + x / rod.wave_speed, t, result.gauge_strain[gauge_index], right=np.nan)
    return t, -rod.axial_stiffness * shifted


def bar_summary(result) -> dict:
    """The scalars of a bar run, SI with unit-suffixed keys, and the resolved case."""
    p = result.problem
    gauges = {}
    for g, eps in zip(p.gauges, result.gauge_strain):
        kc, kt = int(np.argmin(eps)), int(np.argmax(eps))
        gauges[g.name] = {
            "position_m": g.position,
            "peak_compressive_strain": float(eps[kc]),
            "time_of_peak_compressive_strain_s": float(result.time[kc]),
            "peak_tensile_strain": float(eps[kt]),
            "time_of_peak_tensile_strain_s": float(result.time[kt]),
        }
    e = result.energies.total
    return {
        "title": p.title,
        "peak_force_N": result.peak_force,
        "time_of_peak_s": result.time_of_peak,
        "contact_duration_s": result.contact_duration,
        "impulse_N_s": result.impulse,
        "rebound_velocity_m_s": result.rebound_velocity,
        "rebound_velocity_note": "impactor velocity after separation, positive toward the bar (negative = bounced back)",
        "contact_intervals": result.contacts,
        "projectile_mass_kg": p.projectile.mass,
        "end_cap_mass_kg": 0.0 if p.bar.end_cap is None else p.bar.end_cap.mass,
        "hertz_constant_N_per_m1_5": p.contact_law().K,
        "bar_wave_speed_m_s": p.bar.rod().wave_speed,
        "energy_drift_relative": float((e.max() - e.min()) / e[0]),
        "newton_iterations": result.newton_iterations,
        "gauges": gauges,
        "case_SI": p,
    }


def bar_files(result, plain=None, figures: bool = True, prefix: str = "") -> dict[str, bytes | str]:
    """history.csv, summary.json and (optionally) Figs 4–6 of a bar run."""
    from . import plots

    p = result.problem
    cols = {
        "time_s": result.time,
        "contact_force_N": result.contact_force,
        "impactor_velocity_m_s": result.impactor_velocity,
        "impactor_displacement_m": result.impactor_displacement,
        "approach_m": result.approach,
    }
    for g, eps in zip(p.gauges, result.gauge_strain):
        cols[f"strain_{g.name}"] = eps
    cols["energy_total_J"] = result.energies.total
    summary = bar_summary(result)
    if plain is not None:
        summary["without_end_cap"] = {
            "peak_force_N": plain.peak_force,
            "time_of_peak_s": plain.time_of_peak,
            "contact_duration_s": plain.contact_duration,
        }
    files = {prefix + "history.csv": csv_text(cols), prefix + "summary.json": json_text(summary)}
    if figures:
        system = p.units
        files[prefix + "fig04-gauge-strain.png"] = figure_bytes(plots.bar_gauge_strain(result, system))
        inferred = None
        if p.gauges:
            t, f = inferred_force(result, 0)
            inferred = (t, f, p.gauges[0].name)
        files[prefix + "fig05-contact-force.png"] = figure_bytes(plots.bar_contact_force(result, plain, inferred, system))
        L_over_c = p.bar.length / p.bar.rod().wave_speed
        span = min(result.time[-1], 2.0 * L_over_c)
        instants = np.linspace(0.0, span, 7)[1:]
        files[prefix + "fig06-strain-along-bar.png"] = figure_bytes(plots.bar_strain_profiles(result, instants, system))
        files[prefix + "energy.png"] = figure_bytes(plots.bar_energy(result))
    return files


def bar_section(result, plain, prefix: str) -> Section:
    """The report section of the calibration test."""
    p = result.problem
    sysname = p.units
    fu, tu, su = display(sysname, "force"), display(sysname, "time"), display(sysname, "strain")
    rows = [
        ["peak contact force", f"{result.peak_force * fu.factor:.1f} {fu.label}"],
        ["time of peak", f"{result.time_of_peak * tu.factor:.1f} {tu.label}"],
        ["contact duration", f"{result.contact_duration * tu.factor:.1f} {tu.label}"],
        ["impulse", f"{result.impulse:.4g} N·s"],
        ["rebound velocity (toward bar +)", f"{result.rebound_velocity:.3f} m/s"],
    ]
    if plain is not None:
        rows.append(["peak force without end cap", f"{plain.peak_force * fu.factor:.1f} {fu.label}"])
        rows.append(["contact duration without end cap", f"{plain.contact_duration * tu.factor:.1f} {tu.label}"])
    for g, eps in zip(p.gauges, result.gauge_strain):
        k = int(np.argmin(eps))
        rows.append([f"peak compressive strain at {g.name}", f"{eps[k] * su.factor:.1f} {su.label} at {result.time[k] * tu.factor:.1f} {tu.label}"])
    return Section(
        p.title or "Bar impact",
        [
            "Hermite rod elements (u, du/dx per node), Hertz contact (eq 3) to a lumped impactor mass, "
            "Newmark average acceleration with Newton iterations on the contact. The end cap is lumped mass at the struck end. "
            "The force read from the gauge, F = EA·ε(t + x/c), follows the FE contact force until the reflection returns."
        ],
        [("Calibration test results", ["quantity", "value"], rows)],
        [
            (prefix + "fig04-gauge-strain.png", "Fig 4: strain history at the gauge"),
            (prefix + "fig05-contact-force.png", "Fig 5: contact force with and without end cap, and as read from the gauge"),
            (prefix + "fig06-strain-along-bar.png", "Fig 6: strain along the bar; the compressive pulse returns from the free end as tension"),
            (prefix + "energy.png", "Energy balance (the total stays flat)"),
        ],
    )


def render_report(title: str, sections: list[Section], notes: list[str] = ()) -> str:
    """A self-contained HTML page (figures linked by relative path)."""
    esc = html.escape
    out = [
        "<!doctype html><html><head><meta charset='utf-8'>",
        f"<title>{esc(title)}</title>",
        "<style>body{font-family:sans-serif;max-width:1000px;margin:auto;padding:1em;line-height:1.4}"
        "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #bbb;padding:2px 8px;text-align:left}"
        "th{background:#eee}figure{margin:1em 0}img{max-width:100%}figcaption{font-size:90%;color:#444}</style>",
        "</head><body>",
        f"<h1>{esc(title)}</h1>",
        f"<p>softimpact {esc(__version__)}</p>",
    ]
    for s in sections:
        out.append(f"<h2>{esc(s.title)}</h2>")
        out += [f"<p>{esc(p)}</p>" for p in s.paragraphs]
        for caption, header, rows in s.tables:
            out.append(f"<table><caption>{esc(caption)}</caption><tr>" + "".join(f"<th>{esc(h)}</th>" for h in header) + "</tr>")
            out += ["<tr>" + "".join(f"<td>{esc(str(c))}</td>" for c in row) + "</tr>" for row in rows]
            out.append("</table>")
        for path, caption in s.figures:
            out.append(f"<figure><img src='{esc(path)}' alt='{esc(caption)}'><figcaption>{esc(caption)}</figcaption></figure>")
    if notes:
        out.append("<h2>Assumptions and errata</h2><ul>" + "".join(f"<li>{esc(n)}</li>" for n in notes) + "</ul>")
    out.append("</body></html>")
    return "\n".join(out)


def fmt(x: float, digits: int = 4) -> str:
    return "—" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.{digits}g}"
