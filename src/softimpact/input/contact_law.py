"""The ``[contact]`` table of impact and bar cases: a contact law and its keys.

``law`` = ``hertz`` | ``hertz-unloading`` (``critical_indentation``, default
0.08 mm, Yang & Sun's graphite/epoxy value) | ``hunt-crossley`` (``restitution``
required, ``form`` lankarani-nikravesh | hunt-crossley) | ``identified``
(``law_file``: a law.json of ``softimpact identify``, relative to the case file, of either family: a soft
projectile's law, or with ``--law crushing`` an ice sphere's crushing law, run as its
:class:`~softimpact.models.crushing_law.CrushingLaw`; optional ``parameters``, a table of the law's parameters by
name replacing the file's values: a sweep's draws from the law's covariance,
:class:`softimpact.input.sweep_spec.LawDraw`) | ``crushing`` (an
ice sphere, :class:`~softimpact.models.crushing_law.CrushingLaw`; optional ``strength_coefficient`` A and
``strength_exponent`` m of σ_c = A·(ε̇/1 s⁻¹)^m in place of the material's, Jones 1997 for the catalogue's
ice) | ``hydrodynamic`` (a gelatin sphere, :class:`~softimpact.models.hydrodynamic_law.HydrodynamicLaw`;
optional ``sound_speed`` c0 and ``hugoniot_slope`` k of U_s = c0 + k·u_p in place of the material's,
Wilbeck's for the catalogue's gelatin). The crushing and hydrodynamic laws are the projectile's material's:
it must be ice or gelatin (:data:`softimpact.models.projectiles.PROJECTILES`).
The Hertz constant comes from the caller (a laminate, a flat, the bar's end).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from ..errors import InputError
from ..formats.law_json import CRUSHING_FAMILY, CRUSHING_RANGES, crushing_range_error, read_law
from ..models.contact_laws import CONTACT_LAWS, MATERIAL_LAWS, HertzLaw, HuntCrossleyLaw, YangSunLaw
from ..models.materials import Material
from ..models.projectiles import LinearHugoniot, PowerLawStrength, projectile_material
from .toml import Table

__all__ = ["CONTACT_LAWS", "CRITICAL_INDENTATION", "HUNT_CROSSLEY_FORMS", "LAW_KEYS", "note_law_keys", "read_contact_law", "check_family", "warn_outside"]

CRITICAL_INDENTATION = 0.08e-3  # m: Yang & Sun (1982), graphite/epoxy struck by a 12.7 mm steel ball
HUNT_CROSSLEY_FORMS = ("lankarani-nikravesh", "hunt-crossley")
# the keys each law reads besides ``law``: given with another law, the error names the law that reads them
LAW_KEYS = {
    "hertz-unloading": ("critical_indentation",),
    "hunt-crossley": ("restitution", "form"),
    "identified": ("law_file", "parameters"),
    "crushing": ("strength_coefficient", "strength_exponent"),
    "hydrodynamic": ("sound_speed", "hugoniot_slope"),
}


def read_contact_law(
    c: Table,
    name: str,
    hertz: Callable[[], HertzLaw],
    mass: float,
    diameter: float,
    velocity: float,
    base: Path,
    material: Material | None = None,
    where: str = "material",
    length: float | None = None,
):
    """The law ``name`` of table ``c`` for an impactor (mass [kg], diameter [m], velocity [m/s], ``material``
    the projectile's, read from the key ``where``; ``length`` [m] a bird substitute's, None for a sphere);
    ``hertz()`` gives the pair's Hertz law. Returns (law, the law file read or None)."""
    note_law_keys(c)
    if name in MATERIAL_LAWS:
        return _flow_law(c, name, material, mass, diameter, velocity, where, length), None
    if name == "identified":
        file = c.string("law_file")
        path = Path(file) if Path(file).is_absolute() else base / file
        given = c.raw("parameters", None)  # read before the file, so a case's keys are all known even when the file is not
        identified = _with_parameters(read_law(path, c.key("law_file")), c, given)
        check_family(identified, material, mass, diameter, f"{c.key('law_file')} ({path.name})", where)
        warn_outside(identified.identified_on, velocity, diameter, path, mass)
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


def note_law_keys(c: Table) -> None:
    """Tell table ``c`` which law reads each of :data:`LAW_KEYS`: one given beside another law is then refused naming it."""
    c.read_with({k: f'{c.key("law")} = "{law}"' for law, keys in LAW_KEYS.items() for k in keys})


def _flow_law(c: Table, name: str, material: Material | None, mass: float, diameter: float, velocity: float, where: str, length: float | None = None):
    """The crushing (ice) or hydrodynamic (gelatin) law of the projectile's ``material``, its strength law's or
    Hugoniot's constants replaced by the table's optional keys."""
    import dataclasses

    try:
        record = projectile_material(material if material is not None else "")
        law = CONTACT_LAWS[name].of(record, diameter, mass, velocity, **({} if length is None else {"length": length}))
    except InputError as exc:
        raise InputError(f"{c.key('law')} = {name!r} with {where}: {exc}") from None
    if name == "crushing":
        sc = law.strength
        coefficient = c.quantity("strength_coefficient", "stress", default=sc.coefficient)
        exponent = c.number("strength_exponent", sc.exponent)
        if not 0.0 <= exponent < 1.0:
            raise InputError(f"{c.key('strength_exponent')}: must lie in [0, 1), got {exponent!r}")
        if (coefficient, exponent) != (sc.coefficient, sc.exponent):
            source = f"{c.key('strength_coefficient')}, {c.key('strength_exponent')} of the case"
            law = dataclasses.replace(law, strength=PowerLawStrength(coefficient, exponent, sc.rate_range, sc.reference_rate, source))
        return law
    h = law.hugoniot
    c0 = c.quantity("sound_speed", "velocity", default=h.c0)
    k = c.number("hugoniot_slope", h.k)
    if not k >= 0.0:
        raise InputError(f"{c.key('hugoniot_slope')}: must be non-negative, got {k!r}")
    return law if (c0, k) == (h.c0, h.k) else dataclasses.replace(law, hugoniot=LinearHugoniot(c0, k))


def _with_parameters(law, c: Table, given):
    """``law`` with the values of table ``contact.parameters`` (by name) in place of the file's, checked
    as the file's are (a soft law: k_ref > 0, p > 0, c_ref >= 0, kappa_ref >= 0, theta_ref > 0; a crushing law:
    strength_ref > 0, 0 <= rate_exponent < 1)."""
    import dataclasses
    import math

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
    if getattr(law, "family", None) == CRUSHING_FAMILY:
        problem = crushing_range_error(values)
        if problem:
            raise InputError(f"{c.key('parameters')}: out of range ({CRUSHING_RANGES}): {problem}")
        return dataclasses.replace(law, values=values)
    k, p, cr, ka, th = (values[law.names.index(n)] for n in ("k_ref", "p", "c_ref", "kappa_ref", "theta_ref"))
    if not (k > 0 and p > 0 and cr >= 0 and ka >= 0 and (ka == 0 or th > 0)):
        raise InputError(f"{c.key('parameters')}: out of range (k_ref > 0, p > 0, c_ref >= 0, kappa_ref >= 0 with theta_ref > 0), got {given!r}")
    return dataclasses.replace(law, values=values)


def check_family(identified, material: Material | None, mass: float, diameter: float, law_key: str, material_key: str = "material") -> None:
    """Refuse an identified law on a projectile of another family than the one it was identified on: a crushing law
    (law.json's ``family`` "crushing", an ice sphere's) on a projectile whose material does not crush (no crushing
    strength: rubber, steel), a soft projectile's law on one that does (ice); and a projectile whose density
    m/(π·d³/6) lies more than :data:`~softimpact.input.projectile.MASS_DENSITY_FACTOR` times outside the identified
    projectiles' (law.json's ``identified_on.projectile``): another material (a steel ball under a rubber ball's law).
    Within that factor a density off by more than 20 % is an extrapolation, warned (:func:`warn_outside`)."""
    import math

    from ..models.projectiles import PROJECTILES
    from .projectile import MASS_DENSITY_FACTOR

    crushing = getattr(identified, "family", None) == CRUSHING_FAMILY
    if material is not None:
        record = next((r for k, r in PROJECTILES.items() if k.lower() == material.name.lower()), None)
        crushes = record is not None and record.strength is not None
        if crushing and not crushes:
            raise InputError(
                f"{law_key}: holds a crushing law (family {CRUSHING_FAMILY!r}, an ice sphere's) and the impactor is {material.name} "
                f"({material_key}): a law identified on one projectile family does not drive another; give an ice impactor, or the law of its own material"
            )
        if not crushing and crushes:
            raise InputError(
                f"{law_key}: holds a soft projectile's law (rubber, gel) and the impactor is {material.name} ({material_key}), which crushes: "
                "give its crushing law (law = 'crushing', or a law.json of `softimpact identify --law crushing`)"
            )
    proj = (identified.identified_on or {}).get("projectile")
    if proj is not None and diameter > 0:
        density = mass / (math.pi / 6.0 * diameter**3)
        lo, hi = proj["density_kg_m3"]
        if not lo / MASS_DENSITY_FACTOR <= density <= hi * MASS_DENSITY_FACTOR:
            raise InputError(
                f"{law_key}: identified on projectiles of {lo:.4g}-{hi:.4g} kg/m^3, and the impactor's density is {density:.4g} kg/m^3 "
                f"(more than {MASS_DENSITY_FACTOR:g} times outside: another material, {material_key}): a law identified on one projectile does not drive another"
            )


def warn_outside(ranges: dict | None, velocity: float, diameter: float, path: Path, mass: float | None = None) -> None:
    """Warnings when the impactor lies outside what the law was identified on (more than 10 % beyond the
    velocities, diameters or masses of its tests, or 20 % off their projectiles' density m/(π d³/6):
    another material; :mod:`softimpact.models.validity`): the law is then an extrapolation. A law.json
    without the record (written before it was kept) is warned as unchecked."""
    import warnings

    from ..errors import SoftimpactWarning
    from ..models.validity import identified_range_validity, warn

    what = f"the law of {path.name}"
    if ranges is None:  # a law.json written before the ranges were recorded
        warnings.warn(
            f"{what} does not record the tests it was identified on: the impactor's velocity, size and material cannot be checked",
            SoftimpactWarning,
            stacklevel=3,
        )
        return
    if ranges.get("projectile") is None:
        warnings.warn(
            f"{what} does not record the projectile it was identified on (mass, density): the impactor's mass and material cannot be checked",
            SoftimpactWarning,
            stacklevel=3,
        )
    warn(identified_range_validity(ranges, velocity, diameter, mass, what))
