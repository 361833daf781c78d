"""law.json: a soft projectile's contact law identified from bar tests, written and read in this one place
(``softimpact identify`` writes it; impact and bar cases read it through input/contact_law).

Layout (SI): ``family`` (``"soft-projectile"``), ``form`` (the law in words),
``units``, ``d_ref_m``, ``parameters`` (``k_ref``, ``p``, ``c_ref``, ``q_k``,
``q_c``, ``q_p``, ``kappa_ref``, ``theta_ref``, ``q_kappa``, ``q_theta``, each with
``value`` and ``ci95_half_width``), ``fit`` (``cost`` and ``rms_over_F0`` per test), and,
when the closure was run, ``closure`` per test (measured and simulated F0, T, I, t_F0 and
their relative errors).

``identified_on`` holds the ranges of the tests: ``velocity_m_s``, ``diameter_m`` and ``projectile``
(``mass_kg``, ``diameter_m``, ``density_kg_m3``: what the law may be used for; files written before it
read without it, and a case using them is warned that the projectile cannot be checked).

Older files (the memoryless law, before the Maxwell arm; or before ``q_p``) lack the later
parameters: they read as 0, i.e. no arm and no size power, the law they were written for.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..workflows.identification import PARAMETERS, IdentifiedLaw
from ._json import check_si, json_text

__all__ = ["FAMILY", "projectile_record", "law_summary", "law_json", "read_law"]

FAMILY = "soft-projectile"
FORM = (
    "F = (m*V^2/d)*[k*(alpha/d)^n*(1 + c*alpha_dot/V) + sigma] >= 0, k = k_ref*(d/d_ref)^q_k, c = c_ref*(d/d_ref)^q_c, "
    "n = p*(d/d_ref)^q_p; Maxwell arm d(sigma)/dt = kappa*d(max(alpha,0)/d)/dt - sigma*V/(theta*d), "
    "kappa = kappa_ref*(d/d_ref)^q_kappa, theta = theta_ref*(d/d_ref)^q_theta (kappa_ref = 0: no arm); "
    "contact radius a = sqrt(d*alpha)"
)
LATER = ("q_p", "kappa_ref", "theta_ref", "q_kappa", "q_theta")  # parameters older law.json files lack (read as 0)


def projectile_record(tests) -> dict:
    """The projectiles a law was identified on (``identified_on.projectile`` of law.json): the ranges of
    mass [kg], diameter [m] and density [kg/m³] (m/(π d³/6), the material as the law sees it) of the
    bar tests (:class:`softimpact.workflows.identification.BarTest`)."""
    m = [float(t.mass) for t in tests]
    d = [float(t.diameter) for t in tests]
    rho = [mi / (math.pi / 6 * di**3) for mi, di in zip(m, d)]
    return {"mass_kg": [min(m), max(m)], "diameter_m": [min(d), max(d)], "density_kg_m3": [min(rho), max(rho)]}


def law_summary(law: IdentifiedLaw, test_names, closure=None, series: str = "", projectile: dict | None = None) -> dict:
    """The content of law.json (module docstring); ``projectile``: :func:`projectile_record` of the tests."""
    out = {
        "family": FAMILY,
        "form": FORM,
        "units": "SI",
        "series": series,
        "d_ref_m": law.d_ref,
        "parameters": {n: {"value": float(v), "ci95_half_width": float(h)} for n, v, h in zip(law.names, law.values, law.half_widths)},
        "fit": {"cost": law.cost, "rms_over_F0": dict(zip(test_names, map(float, law.rms_per_test)))},
    }
    if law.identified_on is not None:
        out["identified_on"] = dict(law.identified_on)
    if projectile is not None:
        out.setdefault("identified_on", {})["projectile"] = projectile
    if closure is not None:
        keys = ("peak_force_N", "duration_s", "impulse_N_s")
        out["closure"] = {
            name: {
                "measured": dict(zip(keys, map(float, m))),
                "simulated": dict(zip(keys, map(float, s))),
                "relative_error": dict(zip(("peak_force", "duration", "impulse"), map(float, e))),
            }
            for name, m, s, e in zip(closure.names, closure.measured, closure.simulated, closure.errors)
        }
        if closure.peak_times is not None:
            for name, (m, s), e in zip(closure.names, closure.peak_times, closure.peak_time_errors):
                c = out["closure"][name]
                c["measured"]["time_of_peak_s"], c["simulated"]["time_of_peak_s"] = float(m), float(s)
                c["relative_error"]["time_of_peak"] = float(e)
    return out


def law_json(law: IdentifiedLaw, test_names, closure=None, series: str = "", projectile: dict | None = None) -> str:
    """The text of law.json."""
    return json_text(law_summary(law, test_names, closure, series, projectile))


def read_law(path, argument: str = "contact.law_file") -> IdentifiedLaw:
    """The identified law of a law.json; anything else is an :class:`InputError` naming ``argument``."""
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
    except OSError as exc:
        raise InputError(f"{argument}: cannot read {path} ({exc.strerror})") from None
    except (ValueError, UnicodeDecodeError):
        raise InputError(f"{argument}: {path} is not JSON (expected a law.json from `softimpact identify`)") from None
    names = PARAMETERS
    check_si(data, path, argument)
    try:
        if data["family"] != FAMILY:
            raise InputError(f"{argument}: {path} holds a {data['family']!r} law; only {FAMILY!r} laws are known")
        pars = data["parameters"]
        values = np.array([float(pars[n]["value"]) if n in pars or n not in LATER else 0.0 for n in names])
        half = np.array([float(pars[n].get("ci95_half_width", math.nan)) if n in pars else 0.0 for n in names])
        d_ref = float(data["d_ref_m"])
        fit = data.get("fit", {})
        rms = np.array([float(v) for v in fit.get("rms_over_F0", {}).values()])
        cost = float(fit.get("cost", math.nan))
        ranges = data.get("identified_on")  # absent from files written before it was recorded
        if ranges is not None:
            proj = ranges.get("projectile")  # absent from files written before it was recorded
            ranges = {k: [float(x) for x in ranges[k]] for k in ("velocity_m_s", "diameter_m")}
            if proj is not None:
                ranges["projectile"] = {k: [float(x) for x in proj[k]] for k in ("mass_kg", "diameter_m", "density_kg_m3")}
    except (KeyError, TypeError, ValueError, AttributeError):
        raise InputError(
            f"{argument}: {path} is not a law.json (needs family, d_ref_m and parameters {', '.join(n for n in names if n not in LATER)})"
        ) from None
    arm_ok = values[6] == 0.0 or (values[6] > 0.0 and values[7] > 0.0)
    if not (np.all(np.isfinite(values)) and values[0] > 0 and values[1] > 0 and values[2] >= 0 and arm_ok and math.isfinite(d_ref) and d_ref > 0):
        raise InputError(f"{argument}: {path} has parameters out of range (k_ref > 0, p > 0, c_ref >= 0, kappa_ref >= 0 with theta_ref > 0, d_ref_m > 0)")
    return IdentifiedLaw(names, values, half, d_ref, rms, cost, ranges)
