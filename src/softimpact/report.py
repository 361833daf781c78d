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
    L_over_c = p.bar.length / p.bar.rod().wave_speed
    chosen = [t for t in p.snapshots if t <= result.time[-1]]
    instants = np.array(chosen) if chosen else np.linspace(0.0, min(result.time[-1], 2.0 * L_over_c), 7)[1:]
    dt = result.time[1] - result.time[0]
    along = {"x_m": result.bar_x}
    for t in instants:
        k = int(round(t / dt))
        along[f"strain_t{result.time[k] * 1e6:.1f}us"] = result.bar_strain[:, k]
    files[prefix + "strain-along-bar.csv"] = csv_text(along)
    if figures:
        system = p.units
        files[prefix + "fig04-gauge-strain.png"] = figure_bytes(plots.bar_gauge_strain(result, system))
        inferred = None
        if p.gauges:
            t, f = inferred_force(result, 0)
            inferred = (t, f, p.gauges[0].name)
        files[prefix + "fig05-contact-force.png"] = figure_bytes(plots.bar_contact_force(result, plain, inferred, system))
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


def _stem(name: str) -> str:
    return "".join(ch if ch.isalnum() or ch in "-_." else "_" for ch in name)


def reduction_files(series, reduced, figures: bool = True, prefix: str = "") -> dict[str, bytes | str]:
    """tests.csv, history-<test>.csv per test, Fig 7 per test."""
    from . import plots

    cols = {k: [] for k in (
        "record", "velocity_m_s", "mass_kg", "diameter_m", "peak_force_N", "time_of_peak_s", "duration_s", "impulse_N_s",
        "valid_until_s", "flags", "duration_threshold_s", "time_of_max_s", "impulse_uncertainty_N_s", "direct_until_s",
        "fit_peak_force_N", "fit_rms_N", "first_contact_record_time_s",
    )}
    files: dict[str, bytes | str] = {}
    for item in reduced:
        t, r = item.test, item.reduction
        cols["record"].append(str(t.record.name))
        cols["velocity_m_s"].append(t.velocity)
        cols["mass_kg"].append(t.mass)
        cols["diameter_m"].append(t.diameter)
        if r is None:
            for k in list(cols)[4:]:
                cols[k].append("error: " + item.error.replace(",", ";") if k == "flags" else math.nan)
            continue
        for k, v in (
            ("peak_force_N", r.peak_force), ("time_of_peak_s", r.time_of_peak), ("duration_s", r.duration), ("impulse_N_s", r.impulse),
            ("valid_until_s", r.valid_until), ("flags", "; ".join(r.flags).replace(",", ";")), ("duration_threshold_s", r.duration_threshold),
            ("time_of_max_s", r.time_of_max), ("impulse_uncertainty_N_s", r.impulse_uncertainty), ("direct_until_s", r.direct_until),
            ("fit_peak_force_N", r.fit.peak_force), ("fit_rms_N", r.fit_rms), ("first_contact_record_time_s", r.first_contact_record_time),
        ):
            cols[k].append(v)
        files[f"{prefix}history-{_stem(t.name)}.csv"] = csv_text({"time_s": r.time, "force_N": r.force})
        if figures:
            files[f"{prefix}fig07-force-{_stem(t.name)}.png"] = figure_bytes(plots.force_history(r, series.units))
    files[prefix + "tests.csv"] = csv_text({k: np.array(v, dtype=object) for k, v in cols.items()})
    return files


def scaling_summary(fits) -> dict:
    """scaling.json: per group and pooled, α1–α4 with their 95 % intervals, R², residuals, affine fits."""

    def line(f):
        return {"value": f.slope, "ci95": list(f.slope_ci), "r2": f.r2, "residuals": f.residuals}

    def affine(f):
        return {"slope": f.slope, "slope_ci95": list(f.slope_ci), "intercept": f.intercept, "intercept_ci95": list(f.intercept_ci), "r2": f.r2}

    def group(g):
        d = {name: line(f) for name, f in g.origin.items()}
        d["tests"] = [p.name for p in g.points]
        d["affine"] = {name: affine(f) for name, f in g.affine.items()}
        return d

    return {
        "groups": {label: group(g) for label, g in fits.items() if label != "pooled"},
        "pooled": group(fits["pooled"]) if "pooled" in fits else group(next(iter(fits.values()))),
        "regressors": {"alpha1": "F0 = alpha1*m*V^2/(2d)", "alpha2": "T = alpha2*d/V", "alpha3": "tF0 = alpha3*T", "alpha4": "I = alpha4*2*m*V"},
    }


def scaling_files(fits, system: str, figures: bool = True, prefix: str = "") -> dict[str, bytes | str]:
    from . import plots

    files: dict[str, bytes | str] = {prefix + "scaling.json": json_text(scaling_summary(fits))}
    if figures:
        files[prefix + "fig08-peak-force.png"] = figure_bytes(plots.scaling_peak_force(fits, system))
        files[prefix + "fig09-inverse-duration.png"] = figure_bytes(plots.scaling_duration(fits, system))
        files[prefix + "fig10-skewness.png"] = figure_bytes(plots.scaling_skewness(fits, system))
        files[prefix + "fig11-impulse.png"] = figure_bytes(plots.scaling_impulse(fits, system))
    return files


TABLE_I = {"0.375 in": (4.00, 1.03, 0.25, 0.74), "0.5 in": (4.25, 0.93, None, 0.66)}


def scaling_section(fits, series, reduced, prefix: str, figures: bool) -> Section:
    """Report section: the series, its reductions and Table I beside the fitted constants."""
    rows = []
    for label, g in fits.items():
        paper = TABLE_I.get(label)
        for i, name in enumerate(("alpha1", "alpha2", "alpha3", "alpha4")):
            f = g.origin[name]
            ref = "—" if paper is None or paper[i] is None else f"{paper[i]:.3g}"
            rows.append([label, name, f"{f.slope:.3f}", f"[{f.slope_ci[0]:.3f}, {f.slope_ci[1]:.3f}]", f"{f.r2:.4f}", ref])
    fu, tu = display(series.units, "force"), display(series.units, "time")
    vu = display(series.units, "velocity")
    trows = []
    for item in reduced:
        r = item.reduction
        if r is None:
            trows.append([item.test.name, f"{item.test.velocity * vu.factor:.0f}", "—", "—", "—", "—", item.error])
        else:
            trows.append([
                item.test.name, f"{item.test.velocity * vu.factor:.0f}", f"{r.peak_force * fu.factor:.1f}", f"{r.time_of_peak * tu.factor:.1f}",
                f"{r.duration * tu.factor:.1f}", f"{r.impulse:.4g}", "; ".join(r.flags),
            ])
    figs = [(prefix + n, c) for n, c in (
        ("fig08-peak-force.png", "Figs 8 and 12: F0 against mV²/(2d)"),
        ("fig09-inverse-duration.png", "Figs 9 and 13: 1/T against V"),
        ("fig10-skewness.png", "Figs 10 and 14: tF0/T against V"),
        ("fig11-impulse.png", "Figs 11 and 15: I against 2mV, with I = 2mV"),
    )]
    first = next((i for i in reduced if i.reduction is not None), None)
    if first is not None:
        figs.insert(0, (f"{prefix}fig07-force-{_stem(first.test.name)}.png", f"Fig 7: force history of {first.test.name}, with F0, tF0 and T"))
    paragraphs = [
        "Each record is reduced to the contact force at the struck end by separating the incident wave from its reflections "
        "(d'Alembert, exact for the non-dispersive bar), so pulses longer than the reflection return time 2(L−x)/c are handled. "
        "T comes from a least-squares fit of eq (15) to the main pulse; I integrates the whole history, tail included.",
    ]
    if series.synthetic:
        paragraphs.insert(0, "SYNTHETIC DATA: " + series.synthetic + ". The paper's own figure data are not available.")
    return Section(
        series.title,
        paragraphs,
        [
            (f"Reduced tests ({fu.label}, {tu.label}, N·s)", ["test", f"V [{vu.label}]", "F0", "tF0", "T", "I [N·s]", "flags"], trows),
            ("Table I: scaling constants fitted through the origin, with 95 % intervals, beside the paper's", ["group", "constant", "fitted", "95 % interval", "R²", "paper (Table I)"], rows),
        ],
        figs if figures else [],
    )


def beam_summary(model, result) -> dict:
    from .workflows.calibration import first_zero_crossing

    p = result.problem
    gauges = {}
    for g, eps, bend in zip(p.gauges, result.strain, result.bending):
        kmax, kmin = int(np.argmax(eps)), int(np.argmin(eps))
        zero = first_zero_crossing(result.time, bend)
        gauges[g.name] = {
            "position_m": g.position, "surface": g.surface,
            "peak_tensile_strain": float(eps[kmax]), "time_of_peak_tensile_strain_s": float(result.time[kmax]),
            "peak_compressive_strain": float(eps[kmin]), "time_of_peak_compressive_strain_s": float(result.time[kmin]),
            "first_zero_crossing_of_bending_strain_s": zero,
        }
    out = {
        "title": p.title,
        "dofs": model.plane.n,
        "elements": [p.beam.nx, p.beam.nz],
        "effective_moduli_Pa": model.moduli(),
        "peak_force_N": float(result.force.max()),
        "impulse_N_s": float(np.trapezoid(result.force, result.time)),
        "peak_deflection_under_load_m": float(result.deflection[np.argmax(np.abs(result.deflection))]),
        "gauges": gauges,
        "case_SI": p,
    }
    if result.energy:
        e = result.energy
        out["energy_balance_relative"] = float(np.max(np.abs(e["kinetic"] + e["strain"] - e["work"])) / max(np.max(np.abs(e["work"])), 1e-300))
    return out


def beam_files(model, result, figures: bool = True, prefix: str = "") -> dict[str, bytes | str]:
    """history.csv, summary.json and Figs 18, 20–22 and the deformed beam."""
    from . import plots

    p = result.problem
    cols = {"time_s": result.time, "force_N": result.force}
    for g, eps, bend in zip(p.gauges, result.strain, result.bending):
        cols[f"strain_{g.name}"] = eps
    for g, bend in zip(p.gauges, result.bending):
        cols[f"bending_strain_{g.name}"] = bend
    cols["deflection_under_load_m"] = result.deflection
    files = {prefix + "history.csv": csv_text(cols), prefix + "summary.json": json_text(beam_summary(model, result))}
    if figures:
        system = p.units
        files[prefix + "fig21-22-gauge-strains.png"] = figure_bytes(plots.beam_gauge_strains(result, system))
        tp = getattr(p.load.history, "time_of_peak", result.time[np.argmax(result.force)])
        T = getattr(p.load.history, "duration", result.time[-1] / 2)
        files[prefix + "fig20-load-distribution.png"] = figure_bytes(plots.beam_load_distribution(model, result, system, [tp / 3, tp, (tp + T) / 2, 0.9 * T]))
        files[prefix + "fig18-mesh.png"] = figure_bytes(plots.beam_mesh(model, system, 4 * p.load.contact_radius))
        if result.displacement is not None:
            files[prefix + "deformed.png"] = figure_bytes(plots.beam_deformed(model, result, system, np.linspace(0, result.time[-1], 6)[1:]))
    return files


def beam_section(model, result, prefix: str) -> Section:
    p = result.problem
    su, tu = display(p.units, "strain"), display(p.units, "time")
    summary = beam_summary(model, result)
    bs = summary["effective_moduli_Pa"].get("bending_stiffness_per_width_N_m", {})
    moduli = summary["effective_moduli_Pa"]
    rows = [[k, f"{moduli[k] / 1e9:.2f} GPa" if k[0] in "EG" else f"{moduli[k]:.3f}"] for k in ("E1", "E2", "E3", "G12", "G13", "G23", "nu12", "nu13", "nu23") if k in moduli]
    if bs:
        rows.append(["bending stiffness per width, smeared (E·h³/12)", f"{bs['smeared_EI_per_width']:.1f} N·m"])
        if "clt_D11" in bs:
            rows.append(["bending stiffness per width, real stacking (CLT D11)", f"{bs['clt_D11']:.1f} N·m"])
    grows = []
    for g, d in summary["gauges"].items():
        z = d["first_zero_crossing_of_bending_strain_s"]
        grows.append([g, f"{d['position_m'] / 0.0254:.3g} in, {d['surface']}", f"{d['peak_tensile_strain'] * su.factor:.0f}", f"{d['peak_compressive_strain'] * su.factor:.0f}", "—" if z is None or z != z else f"{z * tu.factor:.0f}"])
    return Section(
        p.title,
        [
            f"Plane-strain four-node elements, {p.beam.nx} × {p.beam.nz} ({model.plane.n} DOF), {p.beam.model} laminate, "
            f"{p.beam.support}; force history F0 = {result.force.max() / 4.4482216152605:.0f} lbf, "
            f"T = {getattr(p.load.history, 'duration', float('nan')) * 1e6:.0f} µs, r0 = {p.load.contact_radius / 0.0254:.2f} in. "
            f"Energy balance (work − kinetic − strain): {summary.get('energy_balance_relative', float('nan')):.1e} relative.",
        ],
        [
            ("Effective (smeared) moduli of the laminate", ["quantity", "value"], rows),
            (f"Gauge strains ({su.label}, {tu.label})", ["gauge", "where", "peak tension", "peak compression", "first zero crossing of bending strain"], grows),
        ],
        [
            (prefix + "fig21-22-gauge-strains.png", "Figs 21-22: strain at the gauges"),
            (prefix + "fig20-load-distribution.png", "Fig 20: nodal forces of the contact patch at several instants"),
            (prefix + "fig18-mesh.png", "Fig 18: the mesh near the impact point"),
            (prefix + "deformed.png", "The beam's deflection at several instants"),
        ],
    )


def calibration_entry(item, gauges) -> dict:
    """One test of calibration.json."""
    t, c = item.test, item.calibration
    entry = {"name": t.name, "measured": str(t.measured.name), "velocity_m_s": t.velocity}
    if c is None:
        entry["error"] = item.error
        return entry
    se = c.standard_errors
    entry.update({
        "method": c.method,
        "peak_force_N": c.peak_force,
        "time_of_peak_s": c.time_of_peak,
        "duration_s": c.duration,
        "contact_radius_m": c.contact_radius,
        "peak_force_se_N": se.get("peak_force"),
        "time_of_peak_se_s": se.get("time_of_peak"),
        "duration_se_s": se.get("duration"),
        "contact_radius_se_m": se.get("contact_radius"),
        "time_origin_se_s": se.get("time_origin"),
        "iterations": c.iterations,
        "converged": c.converged,
        "message": str(c.message),
        "residual_rms": {g: float(v) for g, v in zip(gauges, c.residual_rms)},
        "first_contact_record_time_s": c.prepared.contact_time,
        "offsets_removed": [float(v) for v in c.prepared.offsets],
        "start_bar_model": {"peak_force_N": c.start.peak_force, "time_of_peak_s": c.start.time_of_peak, "duration_s": c.start.duration},
    })
    if c.method == "paper":
        entry["paper_iterations"] = [{"peak_force_N": a, "time_of_peak_s": b, "duration_s": d} for a, b, d in c.history]
    if item.deconvolved is not None:
        d = item.deconvolved
        entry["deconvolved"] = {"peak_force_N": d.peak_force, "eq15_fit_time_of_peak_s": d.time_of_peak, "eq15_fit_duration_s": d.duration, "message": str(d.message)}
    return entry


def calibration_files(model, items, figures: bool, prefix: str = "", truths=None, single: bool = False) -> dict[str, bytes | str]:
    """calibration.json, a history CSV per test (history.csv for a single test), figures."""
    from . import plots

    system = model.problem.units
    gauges = [g.name for g in model.problem.gauges]
    files: dict[str, bytes | str] = {}
    tm = model.problem.solver.times()
    for k, item in enumerate(items):
        c = item.calibration
        if c is None:
            continue
        cols = {"time_s": tm, "force_N": c.pulse(tm)}
        if item.deconvolved is not None:
            cols["deconvolved_force_N"] = item.deconvolved.pulse(tm)
        for g, y, comp in zip(gauges, c.prepared.strains, c.computed):
            cols[f"measured_{g}"] = np.interp(tm, c.prepared.time, y, left=np.nan, right=np.nan)
            cols[f"computed_{g}"] = comp
        name = "history.csv" if single else f"history-{_stem(item.test.name)}.csv"
        files[prefix + name] = csv_text(cols)
        if figures:
            stem = "" if single else f"-{_stem(item.test.name)}"
            files[f"{prefix}strains{stem}.png"] = figure_bytes(plots.calibration_strains(c, model, system, f"{item.test.name}: measured and computed strains"))
            truth = None if truths is None else truths[k]
            files[f"{prefix}force{stem}.png"] = figure_bytes(plots.calibration_forces(c, item.deconvolved, system, f"{item.test.name}: calibrated force history", truth))
    data = {"case": model.problem.title, "gauges": gauges, "tests": [calibration_entry(i, gauges) for i in items]}
    files[prefix + "calibration.json"] = json_text(data)
    return files


def tables_rows(items):
    """(V, F0, tF0, T, r0) of each calibrated test, SI."""
    return [(i.test.velocity, i.calibration.peak_force, i.calibration.time_of_peak, i.calibration.duration, i.calibration.contact_radius) for i in items if i.calibration is not None]


def series_calibration_files(model, series, items, figures: bool, prefix: str = "", truths=None) -> dict[str, bytes | str]:
    """Per-test files, the Tables II/III layout, the scaling fit of the calibrated histories, Figs 23–25."""
    from . import plots
    from .models.empirical import PROJECTILES
    from .workflows.scaling import TestPoint, fit_groups

    files = calibration_files(model, items, figures, prefix, truths)
    rows = tables_rows(items)
    cols = {k: [] for k in ("test", "velocity_m_s", "peak_force_N", "time_of_peak_s", "duration_s", "contact_radius_m")}
    for item in items:
        if item.calibration is None:
            continue
        c = item.calibration
        for k, v in zip(cols, (item.test.name, item.test.velocity, c.peak_force, c.time_of_peak, c.duration, c.contact_radius)):
            cols[k].append(v)
    files[prefix + "tables.csv"] = csv_text({k: np.array(v, dtype=object) for k, v in cols.items()})
    P = PROJECTILES[series.projectile]
    points = [TestPoint(n, V, P.mass, P.diameter, F0, tp, T, 2 * F0 * T / math.pi) for n, (V, F0, tp, T, _) in zip(cols["test"], rows)]
    if len(points) >= 2:
        fits = fit_groups(points)
        files[prefix + "scaling.json"] = json_text(scaling_summary(fits))
    if figures and rows:
        groups = {"calibrated": [r[:4] for r in rows]}
        if series.reference:
            groups["Table II/III (paper)"] = [r[:4] for r in series.reference]
        files[prefix + "fig23-25-force-scaling.png"] = figure_bytes(plots.beam_force_scaling(groups, model.problem.units))
    return files


def calibration_section(model, series, items, prefix: str, figures: bool, paper_method=None) -> Section:
    """Tables II/III: the paper's histories beside ours, with the bar model and the scaling of both."""
    from .models.empirical import PRESETS, PROJECTILES
    from .workflows.scaling import TestPoint, fit_groups

    LBF, US, IN = 4.4482216152605, 1e-6, 0.0254
    P = PROJECTILES[series.projectile]
    law = PRESETS[P.law]
    ref = {round(r[0], 6): r for r in series.reference}
    rows = []
    for k, item in enumerate(items, 1):
        V = item.test.velocity
        r = ref.get(round(V, 6))
        c = item.calibration
        bar = law.parameters(P.mass, P.diameter, V)
        strains = ""
        if r is not None:
            from .models.pulses import SkewedPulse

            res = model.respond(SkewedPulse(r[1], r[2], r[3]), r[4])
            strains = " / ".join(f"{np.max(np.abs(s)) * 1e6:.0f}" for s in res.strain)
        if c is None:
            rows.append([k, f"{V / IN:.0f}", *(["—"] * 8), item.error])
            continue
        se = c.standard_errors
        def pm(v, key, unit):
            e = se.get(key)
            return f"{v / unit:.3g}" + (f" ± {e / unit:.2g}" if e else "")
        rows.append([
            k, f"{V / IN:.0f}",
            "—" if r is None else f"{r[1] / LBF:.0f}", "—" if r is None else f"{r[2] / US:.0f}", "—" if r is None else f"{r[3] / US:.0f}",
            "—" if r is None else f"{r[4] / IN:.2f}",
            pm(c.peak_force, "peak_force", LBF), pm(c.time_of_peak, "time_of_peak", US), pm(c.duration, "duration", US),
            f"{bar.peak_force / LBF:.0f} / {bar.duration / US:.0f}", strains,
        ])
    header = ["#", "V [in/s]", "paper F0 [lbf]", "paper tF0 [µs]", "paper T [µs]", "r0 [in]", "calibrated F0 [lbf]", "calibrated tF0 [µs]",
              "calibrated T [µs]", "bar model eqs 4-5: F0 [lbf] / T [µs]", "peak |strain| with the paper's history, g1 / g2 [µε]"]
    tables = [(f"{series.title}: force histories, the paper's beside ours", header, rows)]
    fit_rows = []
    for label, pts in (
        ("paper's table", [TestPoint(str(i), r[0], P.mass, P.diameter, r[1], r[2], r[3], 2 * r[1] * r[3] / math.pi) for i, r in enumerate(series.reference)]),
        ("calibrated", [TestPoint(i.test.name, i.test.velocity, P.mass, P.diameter, i.calibration.peak_force, i.calibration.time_of_peak, i.calibration.duration, 2 * i.calibration.peak_force * i.calibration.duration / math.pi) for i in items if i.calibration is not None]),
    ):
        if len(pts) >= 2:
            g = next(iter(fit_groups(pts).values()))
            fit_rows.append([label] + [f"{g.origin[a].slope:.3f} [{g.origin[a].slope_ci[0]:.3f}, {g.origin[a].slope_ci[1]:.3f}]" for a in ("alpha1", "alpha2", "alpha3")])
    fit_rows.append(["bar, Table I (1/2 in)", f"{law.alpha1:.3f}", f"{law.alpha2:.3f}", f"{law.alpha3:.3f} (assumed)"])
    tables.append(("Scaling of the transverse histories (eqs 4-6 refitted, 1/2-in, 1.1-g ball)", ["source", "α1", "α2", "α3 = tF0/T"], fit_rows))
    paragraphs = [
        "SYNTHETIC MEASUREMENTS: " + series.synthetic + ". Calibration by least squares on all of both gauge records "
        "(F0, tF0, T and the time origin); ± are standard errors from the noise (they do not cover model error: "
        "rise times of a few time steps, 10-15 µs here, come out biased high).",
    ]
    if paper_method is not None:
        c = paper_method
        paragraphs.append(
            f"The paper's own procedure (scale F0 by the peak-strain ratio, T by the zero-crossing ratio, keeping tF0/T), "
            f"automated, on test 1 starting from the bar model with tF0/T = {c.start.time_of_peak / c.start.duration:.3f}: "
            f"F0 = {c.peak_force / LBF:.1f} lbf, T = {c.duration / US:.0f} µs, {c.message}. It keeps the start's tF0/T and its "
            "T rests on a zero crossing that moves little with T, so it is less accurate than least squares."
        )
    figs = []
    if figures:
        figs.append((prefix + "fig23-25-force-scaling.png", "Figs 23-25: F0 against V², 1/T against V, tF0/T against V, calibrated and the paper's"))
        first = next((i for i in items if i.calibration is not None), None)
        if first is not None:
            stem = _stem(first.test.name)
            figs.append((f"{prefix}strains-{stem}.png", f"Figs 21-22 (calibrated): measured and computed strains, {first.test.name}"))
            figs.append((f"{prefix}force-{stem}.png", f"The calibrated, deconvolved and starting force histories, {first.test.name}"))
    return Section(series.title, paragraphs, tables, figs)
