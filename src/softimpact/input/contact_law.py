"""The ``[contact]`` table of impact and bar cases: a contact law and its keys.

``law`` = ``hertz`` | ``hertz-unloading`` (``critical_indentation``, default
0.08 mm, Yang & Sun's graphite/epoxy value) | ``hunt-crossley`` (``restitution``
required, ``form`` lankarani-nikravesh | hunt-crossley) | ``identified``
(``law_file``: a law.json of ``softimpact identify``, relative to the case file; optional
``parameters``, a table of the law's parameters by name replacing the file's values: a sweep's
draws from the law's covariance, :class:`softimpact.input.sweep_spec.LawDraw`).
The Hertz constant comes from the caller (a laminate, a flat, the bar's end).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from ..errors import InputError
from ..formats.law_json import read_law
from ..models.contact_laws import CONTACT_LAWS, HertzLaw, HuntCrossleyLaw, YangSunLaw
from .toml import Table

__all__ = ["CONTACT_LAWS", "CRITICAL_INDENTATION", "HUNT_CROSSLEY_FORMS", "read_contact_law"]

CRITICAL_INDENTATION = 0.08e-3  # m: Yang & Sun (1982), graphite/epoxy struck by a 12.7 mm steel ball
HUNT_CROSSLEY_FORMS = ("lankarani-nikravesh", "hunt-crossley")


def read_contact_law(c: Table, name: str, hertz: Callable[[], HertzLaw], mass: float, diameter: float, velocity: float, base: Path):
    """The law ``name`` of table ``c`` for an impactor (mass [kg], diameter [m], velocity [m/s]);
    ``hertz()`` gives the pair's Hertz law. Returns (law, the law file read or None)."""
    if name == "identified":
        file = c.string("law_file")
        path = Path(file) if Path(file).is_absolute() else base / file
        identified = _with_parameters(read_law(path, c.key("law_file")), c)
        _warn_outside(identified.identified_on, velocity, diameter, path)
        return identified.law(mass, diameter, velocity), path
    h = hertz()
    if name == "hertz":
        return h, None
    if name == "hertz-unloading":
        return YangSunLaw(h, c.quantity("critical_indentation", "length", default=CRITICAL_INDENTATION)), None
    restitution = c.number("restitution")
    if not 0.0 < restitution <= 1.0:
        raise InputError(f"{c.key('restitution')}: must be in (0, 1], got {restitution!r}")
    form = c.string("form", HUNT_CROSSLEY_FORMS[0], choices=HUNT_CROSSLEY_FORMS)
    return HuntCrossleyLaw(h.K, h.R, restitution, velocity, h.exponent, form), None


def _with_parameters(law, c: Table):
    """``law`` with the values of table ``contact.parameters`` (by name) in place of the file's, checked
    as the file's are (k_ref > 0, p > 0, c_ref >= 0, kappa_ref >= 0, theta_ref > 0)."""
    import dataclasses
    import math

    given = c.raw("parameters", None)
    if given is None:
        return law
    if not isinstance(given, dict):
        raise InputError(f"{c.key('parameters')}: expected a table of the law's parameters, got {given!r}")
    values = law.values.copy()
    for name, v in given.items():
        if name not in law.names:
            raise InputError(f"{c.key('parameters')}.{name}: not a parameter of the law (known: {', '.join(law.names)})")
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise InputError(f"{c.key('parameters')}.{name}: expected a finite number, got {v!r}")
        values[law.names.index(name)] = float(v)
    k, p, cr, ka, th = (values[law.names.index(n)] for n in ("k_ref", "p", "c_ref", "kappa_ref", "theta_ref"))
    if not (k > 0 and p > 0 and cr >= 0 and ka >= 0 and (ka == 0 or th > 0)):
        raise InputError(f"{c.key('parameters')}: out of range (k_ref > 0, p > 0, c_ref >= 0, kappa_ref >= 0 with theta_ref > 0), got {given!r}")
    return dataclasses.replace(law, values=values)


def _warn_outside(ranges: dict | None, velocity: float, diameter: float, path: Path) -> None:
    """A warning when the impactor's velocity or diameter lies outside those the law was identified
    on (more than 10 % beyond the range): the law is then an extrapolation."""
    import warnings

    from ..errors import SoftimpactWarning

    if ranges is None:  # a law.json written before the ranges were recorded
        return
    for what, key, value, unit in (("velocity", "velocity_m_s", velocity, "m/s"), ("diameter", "diameter_m", diameter, "m")):
        lo, hi = ranges[key]
        if not 0.9 * lo <= value <= 1.1 * hi:
            warnings.warn(
                f"the impactor's {what} {value:.4g} {unit} lies outside the {lo:.4g}-{hi:.4g} {unit} the law of {path.name} was "
                "identified on: its force is an extrapolation",
                SoftimpactWarning,
                stacklevel=2,
            )
