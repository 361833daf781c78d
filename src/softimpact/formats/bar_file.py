"""The bar file ``softimpact calibrate-bar`` writes (read by :mod:`softimpact.input.bar_file`): TOML, SI quantities
written with their units, every number to the last digit.

- ``[bar]``: ``material`` (an inline table: E = ρ·c0² from the calibrated wave speed, ν calibrated when the
  dispersion gave it, else the nominal one, the density as given, and where they come from), ``length``, ``diameter``;
- ``[gauge]``: ``position`` (calibrated when the far-end echoes gave it), the bridge as given with its
  ``gauge_factor`` calibrated (the nominal one divided by the record's sensitivity S) when a known impact gave it;
- ``[calibration]`` (for people, not read): each constant's value, 95 % half-width, its fit's residual and what that
  residual is; the gates' outcome.
"""

from __future__ import annotations

import json
import math

from .. import __version__

__all__ = ["bar_file_text"]


def _q(value: float, unit: str) -> str:
    return json.dumps(f"{value!r} {unit}")


def _s(text: str) -> str:
    return json.dumps(text, ensure_ascii=False)


def _constant(name: str, c, unit: str) -> str:
    items = [f"value = {c.value!r}", f"ci95_half_width = {c.half_width!r}", f"unit = {_s(unit)}"]
    if math.isfinite(c.residual):
        items.append(f"residual = {c.residual!r}")
    items.append(f"residual_is = {_s(c.residual_meaning)}")
    return f"{name} = {{ {', '.join(items)} }}"


def _gauge_lines(position: float, bridge, gauge_keys: dict, gauge_factor: float | None) -> list[str]:
    lines = ["[gauge]", f"position = {_q(position, 'm')}"]
    if bridge is None:
        return lines
    polarity = -bridge.polarity  # the file's polarity is the sign tension reads; the Bridge's is NI's (input/series.py)
    lines += [
        f"bridge = {_s(bridge.configuration)}",
        f"gauge_factor = {(bridge.gauge_factor if gauge_factor is None else gauge_factor)!r}",
        f"excitation = {_q(bridge.excitation, 'V')}",
        f"gain = {bridge.gain!r}  # as the shunt calibration left it, if one was given",
        f"polarity = {polarity}",
        f"gauge_resistance_ohm = {bridge.gauge_resistance!r}",
        f"lead_resistance_ohm = {bridge.lead_resistance!r}",
    ]
    if bridge.poisson_ratio is not None and "poisson_ratio" in gauge_keys:
        lines.append(f"poisson_ratio = {bridge.poisson_ratio!r}")
    return lines


def bar_file_text(cal, *, title: str, source: str, material_name: str, bridge, gauge_keys: dict) -> str:
    """The bar file of a calibration (:class:`softimpact.workflows.bar_calibration.BarCalibration`); ``source`` names the
    calibration file, ``material_name`` the nominal material, ``bridge`` the nominal bridge (None: records in strain),
    ``gauge_keys`` the calibration file's own ``[gauge]`` keys."""
    g = cal.geometry
    nu = cal.poisson_ratio.value if cal.poisson_ratio is not None else g.poisson_ratio
    origin = f"softimpact calibrate-bar {__version__}, from {source}"
    nu_from = "from the dispersion" if cal.poisson_ratio is not None else "nominal"
    name = _s(material_name + " (calibrated)")
    why = _s(f"E = rho*c0^2 with c0 from the echoes; nu {nu_from}; {origin}")
    material = (
        f"{{ name = {name}, youngs_modulus = {_q(cal.youngs_modulus.value, 'Pa')}, poisson_ratio = {nu!r}, "
        f"density = {_q(g.density, 'kg/m^3')}, source = {why} }}"
    )
    position = cal.gauge_position.value if cal.gauge_position is not None else g.gauge_position
    gf = None
    if cal.sensitivity is not None and bridge is not None:
        gf = bridge.gauge_factor / cal.sensitivity.value
    lines = [
        f"# A bar file written by {origin}.",
        "# [bar] and [gauge] are read by the bar cases and series that name this file ([bar] file = ...); [calibration]",
        "# records each constant's 95 % interval and its fit's residual, for people: it is not read.",
        f"title = {_s(title)}",
        "",
        "[bar]",
        f"material = {material}",
        f"length = {_q(g.length, 'm')}",
        f"diameter = {_q(g.diameter, 'm')}",
        "",
        *_gauge_lines(position, bridge, gauge_keys, gf),
        "",
        "[calibration]",
        _constant("wave_speed_m_s", cal.wave_speed, "m/s"),
        _constant("youngs_modulus_Pa", cal.youngs_modulus, "Pa"),
    ]
    if cal.poisson_ratio is not None:
        lines.append(_constant("poisson_ratio", cal.poisson_ratio, "-"))
    if cal.radius is not None:
        lines.append(_constant("effective_radius_m", cal.radius, "m") + "  # the dispersion's radius (not written into [bar]: the area is the diameter's)")
    if cal.gauge_position is not None:
        lines.append(_constant("gauge_position_m", cal.gauge_position, "m"))
    if cal.sensitivity is not None:
        lines.append(_constant("sensitivity", cal.sensitivity, "strain per recorded strain"))
        if gf is not None:
            half = gf * cal.sensitivity.half_width / cal.sensitivity.value
            lines.append(f"gauge_factor = {{ value = {gf!r}, ci95_half_width = {half!r}, nominal = {bridge.gauge_factor!r} }}")
        else:
            lines.append("# records in strain: multiply them by the sensitivity (a bar series has no key for it; record volts to carry it in [gauge])")
    else:
        lines.append("# gauge factor not calibrated: no shot of a known impact")
    lines.append(f"shots = {json.dumps([s.name for s in cal.shots])}")
    lines.append(f"gates_passed = {str(all(gt.passed for gt in cal.gates)).lower()}")
    return "\n".join(lines) + "\n"
