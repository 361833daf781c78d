"""The ``[contact]`` table of impact and bar cases: a contact law and its keys.

``law`` = ``hertz`` | ``hertz-unloading`` (``critical_indentation``, default
0.08 mm, Yang & Sun's graphite/epoxy value) | ``hunt-crossley`` (``restitution``
required, ``form`` lankarani-nikravesh | hunt-crossley) | ``identified``
(``law_file``: a law.json of ``softimpact identify``, relative to the case file).
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
        identified = read_law(path, c.key("law_file"))
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
