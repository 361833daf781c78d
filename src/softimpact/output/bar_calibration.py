"""Outputs of ``softimpact calibrate-bar``: bar.toml (the bar file), calibration.json, shots.csv, and the figures
(each shot's echoes against the fitted model; every shot's constants against the pooled ones)."""

from __future__ import annotations

import math

import numpy as np

from ..formats._json import json_text
from ..formats.bar_file import bar_file_text
from ..gates import quality
from ..units import display
from .files import csv_text, figure_bytes
from .report import stem

__all__ = ["calibration_files", "calibration_summary", "CONSTANTS"]

# name in the result → (key in calibration.json and shots.csv, unit)
CONSTANTS = {
    "wave_speed": ("wave_speed_m_s", "m/s"),
    "youngs_modulus": ("youngs_modulus_Pa", "Pa"),
    "poisson_ratio": ("poisson_ratio", "-"),
    "radius": ("effective_radius_m", "m"),
    "gauge_position": ("gauge_position_m", "m"),
    "sensitivity": ("sensitivity", "-"),
}


def calibration_summary(cal, calfile, bridge) -> dict:
    """calibration.json: each constant (value, 95 % half-width, residual and what it is, each shot's), the gauge factor
    (nominal / S) when the records came through a bridge, the shots, the gates and flags."""
    out = {"calibration": str(calfile.path), "title": calfile.title, "synthetic": calfile.synthetic, "constants": {}}
    for name, (key, unit) in CONSTANTS.items():
        c = getattr(cal, name)
        if c is None:
            continue
        out["constants"][key] = {
            "value": c.value,
            "ci95_half_width": c.half_width,
            "unit": unit,
            "residual": c.residual,
            "residual_is": c.residual_meaning,
            "shots": [{"value": v, "ci95_half_width": h} for v, h in c.shots],
        }
    if cal.sensitivity is not None and bridge is not None:
        gf = bridge.gauge_factor / cal.sensitivity.value
        out["constants"]["gauge_factor"] = {
            "value": gf,
            "ci95_half_width": gf * cal.sensitivity.half_width / cal.sensitivity.value,
            "nominal": bridge.gauge_factor,
        }
    out["nominal"] = {"wave_speed_m_s": cal.geometry.wave_speed, "poisson_ratio": cal.geometry.poisson_ratio, "gauge_position_m": cal.geometry.gauge_position}
    out["shots"] = {
        s.name: {
            "fitted": s.echo is not None,
            "error": s.error,
            "arrival_record_time_s": s.arrival_time,
            "noise_strain": s.noise,
            "echoes_fitted": 0 if s.echo is None else len(s.echo.arrivals),
            "echo_residual_power_over_noise": math.nan if s.echo is None else s.echo.reduced_chi2,
            "impulse_strain_s": s.impulse,
            "sensitivity": s.sensitivity,
            "flags": list(s.flags),
        }
        for s in cal.shots
    }
    out["flags"] = list(cal.flags)
    out["quality"] = quality(cal.gates)
    return out


def _shots_csv(cal) -> str:
    cols = {"shot": [], "status": []}
    for key, _ in CONSTANTS.values():
        cols[key] = []
        cols[key + "_ci95"] = []
    cols["echo_residual_power_over_noise"] = []
    for s in cal.shots:
        cols["shot"].append(s.name)
        cols["status"].append("fitted" if s.echo is not None else ("error: " + s.error).replace(",", ";"))
        for name, (key, _) in CONSTANTS.items():
            v = h = math.nan
            if s.echo is not None and name in s.echo.names:
                v, h = s.echo.value(name), s.echo.half_width(name)
            elif name == "sensitivity" and math.isfinite(s.sensitivity):
                v, h = s.sensitivity, 1.959963984540054 * s.sensitivity_sd
            elif name == "youngs_modulus" and s.echo is not None:
                c = s.echo.value("wave_speed")
                v, h = cal.geometry.density * c * c, 2 * s.echo.half_width("wave_speed") / c * cal.geometry.density * c * c
            cols[key].append(v)
            cols[key + "_ci95"].append(h)
        cols["echo_residual_power_over_noise"].append(math.nan if s.echo is None else s.echo.reduced_chi2)
    return csv_text({k: np.array(v, dtype=object) for k, v in cols.items()})


def _echo_figure(shot, system: str):
    """A shot's record over the fitted windows, the model of each arrival (the incident wave moved) over it."""
    from .plots import _figure

    tu, su = display(system, "time"), display(system, "strain")
    fig, ax = _figure(7.5, 4.0)
    e = shot.echo
    ax.plot(e.time * tu.factor, e.data * su.factor, lw=0.8, color="0.4", label="record (fitted windows)")
    template = np.where(e.template != 0.0, e.template, np.nan)
    ax.plot(e.time * tu.factor, template * su.factor, lw=0.8, color="C0", label="incident wave (template, tapered)")
    ax.plot(e.time * tu.factor, e.model * su.factor, lw=1.0, ls="--", color="C3", label="echoes: template moved along the bar (fit)")
    ax.set_xlabel(f"record time [{tu.label}]")
    ax.set_ylabel(f"strain [{su.label}] (tension +)")
    ax.set_title(f"{shot.name}: c0 {e.value('wave_speed'):.1f} m/s, residual {math.sqrt(e.reduced_chi2):.2f}x noise")
    ax.legend(fontsize=8)
    return fig


def _constants_figure(cal):
    """Every shot's constants with their 95 % intervals, the pooled value and interval as a band."""
    import matplotlib.pyplot as plt

    names = [n for n in ("wave_speed", "poisson_ratio", "gauge_position", "sensitivity") if getattr(cal, n) is not None]
    fig, axes = plt.subplots(1, len(names), figsize=(3.0 * len(names), 3.2), layout="constrained", squeeze=False)
    for ax, name in zip(axes[0], names):
        c = getattr(cal, name)
        vals = np.array([v for v, _ in c.shots])
        half = np.array([h for _, h in c.shots])
        ax.errorbar(np.arange(vals.size), vals, yerr=half, fmt="o", capsize=3)
        ax.axhspan(c.value - c.half_width, c.value + c.half_width, color="C1", alpha=0.3, label="pooled, 95 %")
        ax.axhline(c.value, color="C1")
        ax.set_xticks(np.arange(vals.size))
        ax.set_xlabel("shot")
        ax.set_title(f"{CONSTANTS[name][0]}", fontsize=9)
        ax.ticklabel_format(useOffset=False, axis="y")
    axes[0][0].legend(fontsize=8)
    return fig


def calibration_files(cal, calfile, figures: bool = True) -> dict[str, bytes | str]:
    """bar.toml, calibration.json, shots.csv and, with figures, echoes-<shot>.png and calibration.png."""
    files: dict[str, bytes | str] = {
        "bar.toml": bar_file_text(
            cal, title=calfile.title, source=calfile.path.name, material_name=calfile.material_name, bridge=calfile.bridge, gauge_keys=calfile.gauge_keys
        ),
        "calibration.json": json_text(calibration_summary(cal, calfile, calfile.bridge)),
        "shots.csv": _shots_csv(cal),
    }
    if figures:
        for s in cal.shots:
            if s.echo is not None:
                files[f"echoes-{stem(s.name)}.png"] = figure_bytes(_echo_figure(s, calfile.units))
        files["calibration.png"] = figure_bytes(_constants_figure(cal))
    return files
