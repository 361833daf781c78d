"""``softimpact calibrate-bar``: a lab's bar calibrated from its records into a bar file (bar.toml) that bar cases and
series read (:mod:`softimpact.input.bar_file`).

The calibration file names the bar as the lab knows it (nominal material, measured length, diameter, density, each
with its uncertainty), the gauge (nominal position, the bridge with its nominal gauge factor) and the shots
(:mod:`softimpact.input.bar_calibration`); :func:`softimpact.workflows.bar_calibration.calibrate_bar` fits each
record's echoes and known impact and pools the shots. A gate fails (exit 3) when the echoes are not a uniform
bar's or when the shots disagree beyond their intervals.
"""

from __future__ import annotations

from dataclasses import replace

from ..input.bar_calibration import load_calibration_file
from ..output.bar_calibration import calibration_files
from ..workflows.bar_calibration import calibrate_bar as calibrate
from . import Outcome, Progress, no_progress
from .options import display_system

__all__ = ["calibrate_bar"]


def calibrate_bar(*, calibration: str, units: str | None = None, figures: bool = True, progress: Progress = no_progress) -> Outcome:
    """Calibrate the bar of a calibration file (path or built-in name); ``units``: the figures' display system (None: the file's)."""
    calfile = load_calibration_file(calibration)
    calfile = replace(calfile, units=display_system(units, calfile.units))
    progress(0, 1, "calibrating")
    cal = calibrate(calfile.shots, calfile.geometry)
    progress(1, 1, "calibrating")
    files = calibration_files(cal, calfile, figures)
    c = cal.wave_speed
    parts = [f"c0 {c.value:.1f} +/- {c.half_width:.1f} m/s"]
    if cal.poisson_ratio is not None:
        parts.append(f"nu {cal.poisson_ratio.value:.3f} +/- {cal.poisson_ratio.half_width:.3f}")
    if cal.sensitivity is not None and calfile.bridge is not None:
        gf = calfile.bridge.gauge_factor / cal.sensitivity.value
        parts.append(f"gauge factor {gf:.4f} +/- {gf * cal.sensitivity.half_width / cal.sensitivity.value:.4f}")
    elif cal.sensitivity is not None:
        parts.append(f"strain scale {cal.sensitivity.value:.4f} +/- {cal.sensitivity.half_width:.4f}")
    warnings = tuple(cal.flags)
    return Outcome(files, "; ".join(parts) + "; bar.toml", (calfile.path, *calfile.records), warnings, cal.gates)
