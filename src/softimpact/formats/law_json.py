"""law.json: a projectile's contact law identified from bar tests, written and read in this one place
(``softimpact identify`` writes it; impact and bar cases read it through input/contact_law). Two families:
the soft projectile's visco-elastic law (``softimpact identify``, :class:`~softimpact.workflows.identification.IdentifiedLaw`)
and an ice sphere's crushing law (``softimpact identify --law crushing``,
:class:`~softimpact.workflows.identification.CrushingIdentifiedLaw`).

Layout of the soft law (SI): ``family`` (``"soft-projectile"``), ``form`` (the law in words),
``units``, ``d_ref_m``, ``parameters`` (``k_ref``, ``p``, ``c_ref``, ``q_k``,
``q_c``, ``q_p``, ``kappa_ref``, ``theta_ref``, ``q_kappa``, ``q_theta``, each with
``value`` and ``ci95_half_width``), ``fit`` (``cost`` and ``rms_over_F0`` per test), and,
when the closure was run, ``closure`` per test (measured and simulated F0, T, I, t_F0 and
their relative errors).

``identified_on`` holds the ranges of the tests: ``velocity_m_s``, ``diameter_m`` and ``projectile``
(``mass_kg``, ``diameter_m``, ``density_kg_m3``: what the law may be used for; files written before it
read without it, and a case using them is warned that the projectile cannot be checked), and the law's own
geometry on them, ``approach_over_diameter`` and ``contact_radius_over_bar_radius`` (the range of each test's
largest): the envelope a run's approach is checked against (an identified law is fitted to its balls' own
flattening, so Hertz's small-contact check does not apply to it). Each range must read [min, max].

Older files (the memoryless law, before the Maxwell arm; or before ``q_p``) lack the later
parameters: they read as 0, i.e. no arm and no size power, the law they were written for.

The crushing law's file has the same layout with ``family`` ``"crushing"``, ``parameters`` ``strength_ref``
(σ_ref [Pa], the strength at the reference rate) and ``rate_exponent`` (m_c, in [0, 1)), ``reference_rate_1_s``
(ε̇_ref, the geometric mean of the tests' V/d), ``coefficient_at_1_per_s_Pa`` (σ_ref·ε̇_ref^(−m_c), the catalogue's
form σ_c = A·(ε̇/1 s⁻¹)^m: written for the reader, checked against the parameters when read), and
``identified_on`` with ``strain_rate_1_s`` too (the tests' V/d: the strength law's measured range), and
``fit.contact_start_shift_s``, each test's fitted first contact after its reduced record's.
``d_ref_m`` (the largest tested diameter) means nothing to the law (it has no size scaling) and may be absent.
``method`` says how the strength was measured (absent: bar tests of spheres, ``softimpact identify``). A law
measured on the material itself, in two-bar (split Hopkinson) tests (``softimpact shpb``, method
"two-bar (split Hopkinson) tests ..."), has no impactor's velocity, diameter or mass in ``identified_on``: its
``strain_rate_1_s`` (the rates measured) and, when the specimens' density was given, ``projectile.density_kg_m3``;
its ``fit.rms_over_F0`` holds each test's residual ln(σ_test/σ_law) (a strength's, not a force history's).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..workflows.identification import CRUSHING_PARAMETERS, PARAMETERS, CrushingIdentifiedLaw, IdentifiedLaw
from ._json import check_si, json_text

__all__ = ["FAMILY", "CRUSHING_FAMILY", "projectile_record", "law_summary", "law_json", "read_law", "crushing_range_error"]

FAMILY = "soft-projectile"
CRUSHING_FAMILY = CrushingIdentifiedLaw.family  # "crushing"
CRUSHING_FORM = "F = A(s)*(sigma_ref*(sdot/d/rate_ref)^rate_exponent + rho*sdot^2), A = pi*s*(d - s) (models/crushing_law.py)"
CRUSHING_RANGES = "strength_ref > 0, 0 <= rate_exponent < 1"
COEFFICIENT_TOL = 1e-9  # relative: coefficient_at_1_per_s_Pa against strength_ref·reference_rate^(−rate_exponent)
MATERIAL_METHOD = "two-bar"  # a crushing law.json whose method starts so was measured on the material (softimpact shpb), not on spheres
FORM = (
    "F = (m*V^2/d)*[k*(alpha/d)^n*(1 + c*alpha_dot/V) + sigma] >= 0, k = k_ref*(d/d_ref)^q_k, c = c_ref*(d/d_ref)^q_c, "
    "n = p*(d/d_ref)^q_p; Maxwell arm d(sigma)/dt = kappa*d(max(alpha,0)/d)/dt - sigma*V/(theta*d), "
    "kappa = kappa_ref*(d/d_ref)^q_kappa, theta = theta_ref*(d/d_ref)^q_theta (kappa_ref = 0: no arm); "
    "contact radius a = sqrt(d*alpha)"
)
LATER = ("q_p", "kappa_ref", "theta_ref", "q_kappa", "q_theta")  # parameters older law.json files lack (read as 0)
# identified_on's record of the law's own geometry on its tests (output.identify.approach_record): the range of the
# tests' largest approach over diameter and of their largest contact radius over the bar's radius; older files lack it
GEOMETRY = ("approach_over_diameter", "contact_radius_over_bar_radius")


def projectile_record(tests) -> dict:
    """The projectiles a law was identified on (``identified_on.projectile`` of law.json): the ranges of
    mass [kg], diameter [m] and density [kg/m³] (m/(π d³/6), the material as the law sees it) of the
    bar tests (:class:`softimpact.workflows.identification.BarTest`)."""
    m = [float(t.mass) for t in tests]
    d = [float(t.diameter) for t in tests]
    rho = [mi / (math.pi / 6 * di**3) for mi, di in zip(m, d)]
    return {"mass_kg": [min(m), max(m)], "diameter_m": [min(d), max(d)], "density_kg_m3": [min(rho), max(rho)]}


def law_summary(law: IdentifiedLaw | CrushingIdentifiedLaw, test_names, closure=None, series: str = "", projectile: dict | None = None) -> dict:
    """The content of law.json (module docstring), of either family; ``projectile``: :func:`projectile_record` of the tests."""
    crushing = isinstance(law, CrushingIdentifiedLaw)
    out = {
        "family": CRUSHING_FAMILY if crushing else FAMILY,
        "form": CRUSHING_FORM if crushing else FORM,
        "units": "SI",
        "series": series,
        **({"d_ref_m": law.d_ref} if math.isfinite(law.d_ref) else {}),  # a law without a size (two-bar tests) has none
        "parameters": {n: {"value": float(v), "ci95_half_width": float(h)} for n, v, h in zip(law.names, law.values, law.half_widths)},
        "fit": {"cost": law.cost, "rms_over_F0": dict(zip(test_names, map(float, law.rms_per_test)))},
    }
    if crushing:
        out["reference_rate_1_s"] = float(law.reference_rate)
        out["coefficient_at_1_per_s_Pa"] = law.coefficient_at_1_per_s
        if law.start_shifts is not None:  # each test's fitted first contact after its record's (not read back: the tests', not the law's)
            out["fit"]["contact_start_shift_s"] = dict(zip(test_names, map(float, law.start_shifts)))
        out["method"] = law.method
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


def law_json(law: IdentifiedLaw | CrushingIdentifiedLaw, test_names, closure=None, series: str = "", projectile: dict | None = None) -> str:
    """The text of law.json."""
    return json_text(law_summary(law, test_names, closure, series, projectile))


def read_law(path, argument: str = "contact.law_file") -> IdentifiedLaw | CrushingIdentifiedLaw:
    """The identified law of a law.json, of either family (module docstring); anything else is an
    :class:`InputError` naming ``argument``."""
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
    except OSError as exc:
        where = "" if Path(path).is_absolute() else f", looked for at {Path(path).resolve()}"
        raise InputError(f"{argument}: cannot read {path} ({exc.strerror}{where})") from None
    except (ValueError, UnicodeDecodeError):
        raise InputError(f"{argument}: {path} is not JSON (expected a law.json from `softimpact identify`)") from None
    names = PARAMETERS
    check_si(data, path, argument)
    family = data.get("family") if isinstance(data, dict) else None
    if family == CRUSHING_FAMILY:
        return _read_crushing(data, path, argument)
    if isinstance(family, str) and family != FAMILY:  # outside the try below: InputError is a ValueError
        raise InputError(f"{argument}: {path} holds a {family!r} law; only {FAMILY!r} and {CRUSHING_FAMILY!r} laws are known")
    try:
        if data["family"] != FAMILY:
            raise KeyError("family")
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
            reached = {k: ranges[k] for k in GEOMETRY if k in ranges}  # absent from files written before they were recorded
            ranges = {k: [float(x) for x in ranges[k]] for k in ("velocity_m_s", "diameter_m")}
            ranges.update({k: [float(x) for x in v] for k, v in reached.items()})
            if proj is not None:
                ranges["projectile"] = {k: [float(x) for x in proj[k]] for k in ("mass_kg", "diameter_m", "density_kg_m3")}
    except (KeyError, TypeError, ValueError, AttributeError):
        raise InputError(
            f"{argument}: {path} is not a law.json (needs family, d_ref_m and parameters {', '.join(n for n in names if n not in LATER)})"
        ) from None
    if ranges is not None:
        _check_ranges(ranges, path, argument)
    arm_ok = values[6] == 0.0 or (values[6] > 0.0 and values[7] > 0.0)
    if not (np.all(np.isfinite(values)) and values[0] > 0 and values[1] > 0 and values[2] >= 0 and arm_ok and math.isfinite(d_ref) and d_ref > 0):
        raise InputError(f"{argument}: {path} has parameters out of range (k_ref > 0, p > 0, c_ref >= 0, kappa_ref >= 0 with theta_ref > 0, d_ref_m > 0)")
    return IdentifiedLaw(names, values, half, d_ref, rms, cost, ranges)


def _check_ranges(ranges: dict, path, argument: str, where: str = "identified_on.") -> None:
    """Each [min, max] of a law.json's ``identified_on`` (and of its ``projectile``) finite, positive and in order: a
    reversed or edited range would otherwise be reported as "outside 105-13 m/s" (InputError naming the key)."""
    for key, pair in ranges.items():
        if isinstance(pair, dict):
            _check_ranges(pair, path, argument, f"{where}{key}.")
            continue
        if not (isinstance(pair, (list, tuple)) and len(pair) == 2):
            raise InputError(f"{argument}: {path}: {where}{key} must be [min, max], got {pair!r}")
        lo, hi = pair
        if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo <= hi):
            raise InputError(f"{argument}: {path}: {where}{key} must be [min, max] with 0 < min <= max, got [{lo!r}, {hi!r}]")


def crushing_range_error(values) -> str | None:
    """What is out of range in a crushing law's (strength_ref, rate_exponent), or None (CRUSHING_RANGES)."""
    sigma, m = (float(v) for v in values)
    if not (math.isfinite(sigma) and sigma > 0.0):
        return f"strength_ref must be positive, got {sigma!r}"
    if not (0.0 <= m < 1.0):
        return f"rate_exponent must lie in [0, 1), got {m!r}"
    return None


def _read_crushing(data: dict, path, argument: str) -> CrushingIdentifiedLaw:
    """The crushing law of a law.json whose family is "crushing" (module docstring); a missing or bad key is an
    :class:`InputError` naming it."""

    def number(value, key: str) -> float:
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise InputError(f"{argument}: {path}: {key} must be a finite number, got {value!r}")
        return float(value)

    def table(parent: dict, key: str, where: str) -> dict:
        if key not in parent:
            raise InputError(f"{argument}: {path} is not a crushing law.json: no {where}{key}")
        if not isinstance(parent[key], dict):
            raise InputError(f"{argument}: {path}: {where}{key} must be a table, got {parent[key]!r}")
        return parent[key]

    def pair(value, key: str) -> list[float]:
        if not isinstance(value, list) or len(value) != 2:
            raise InputError(f"{argument}: {path}: {key} must be [min, max], got {value!r}")
        return [number(x, key) for x in value]

    pars = table(data, "parameters", "")
    values, half = [], []
    for n in CRUSHING_PARAMETERS:
        p = table(pars, n, "parameters.")
        if "value" not in p:
            raise InputError(f"{argument}: {path} is not a crushing law.json: no parameters.{n}.value")
        values.append(number(p["value"], f"parameters.{n}.value"))
        h = p.get("ci95_half_width", math.nan)
        half.append(math.nan if h is None else number(h, f"parameters.{n}.ci95_half_width"))
    problem = crushing_range_error(values)
    if problem:
        raise InputError(f"{argument}: {path} has parameters out of range: {problem}")
    if "reference_rate_1_s" not in data:
        raise InputError(f"{argument}: {path} is not a crushing law.json: no reference_rate_1_s")
    rate = number(data["reference_rate_1_s"], "reference_rate_1_s")
    if rate <= 0.0:
        raise InputError(f"{argument}: {path}: reference_rate_1_s must be positive, got {rate!r}")
    if "coefficient_at_1_per_s_Pa" in data:  # written for the reader: it must be the parameters' own
        a = number(data["coefficient_at_1_per_s_Pa"], "coefficient_at_1_per_s_Pa")
        with np.errstate(over="ignore"):
            expected = float(values[0] * np.float64(rate) ** (-values[1]))
        if not abs(a - expected) <= COEFFICIENT_TOL * expected:
            raise InputError(
                f"{argument}: {path}: coefficient_at_1_per_s_Pa = {a!r} is not strength_ref*reference_rate_1_s^(-rate_exponent) = {expected!r}: "
                "edit the parameters (the law uses them) and drop or correct coefficient_at_1_per_s_Pa"
            )
    d_ref = number(data["d_ref_m"], "d_ref_m") if "d_ref_m" in data else math.nan  # no size scaling: kept for the layout
    fit = data.get("fit", {})
    fit = fit if isinstance(fit, dict) else {}
    rms_table = fit.get("rms_over_F0", {})
    rms = np.array([number(v, "fit.rms_over_F0") for v in rms_table.values()]) if isinstance(rms_table, dict) else np.array([])
    cost = fit.get("cost")
    cost = math.nan if cost is None else number(cost, "fit.cost")
    ranges = None
    method = data.get("method", "bar tests (softimpact identify)")
    if not isinstance(method, str):
        raise InputError(f"{argument}: {path}: method must be text, got {method!r}")
    # a law measured on two-bar tests (softimpact shpb) is a material's: no impactor's velocity, diameter or mass
    sized = not method.startswith(MATERIAL_METHOD)
    if "identified_on" in data:
        on = table(data, "identified_on", "")
        ranges = {}
        for k in ("velocity_m_s", "diameter_m", "strain_rate_1_s"):  # the last: the strength law's measured range
            if k not in on:
                if k != "strain_rate_1_s" and not sized:
                    continue
                raise InputError(f"{argument}: {path} is not a crushing law.json: no identified_on.{k}")
            ranges[k] = pair(on[k], f"identified_on.{k}")
        for k in GEOMETRY:  # absent from files written before they were recorded
            if k in on:
                ranges[k] = pair(on[k], f"identified_on.{k}")
        if "projectile" in on:
            proj = table(on, "projectile", "identified_on.")
            ranges["projectile"] = {}
            for k in ("mass_kg", "diameter_m", "density_kg_m3"):
                if k not in proj:
                    if k != "density_kg_m3" and not sized:
                        continue
                    raise InputError(f"{argument}: {path} is not a crushing law.json: no identified_on.projectile.{k}")
                ranges["projectile"][k] = pair(proj[k], f"identified_on.projectile.{k}")
        _check_ranges(ranges, path, argument)
    return CrushingIdentifiedLaw(CRUSHING_PARAMETERS, np.array(values), np.array(half), rate, d_ref, rms, cost, ranges, method=method)
