"""The sphere of a bar case's ``[projectile]`` and an impact case's ``[impactor]``: material, diameter, velocity,
mass, given directly or as a threat.

Directly: ``material`` (a catalogue name or an inline table), ``diameter``, ``velocity``, optional ``mass``
(default: a solid sphere of the material). As a threat, ``threat = { hail = "38.1 mm" }``: a hailstone of that
diameter, of the catalogue's ice, falling at its terminal velocity
(:func:`softimpact.models.threats.hail_terminal_velocity`), or, with ``airspeed``, met by a structure flying
level at that speed (:func:`softimpact.models.threats.flight_hail_velocity`); the table's ``velocity`` (the
velocity toward the target, e.g. its normal component on an inclined skin) and ``mass`` (natural hail is
lighter than ice) may still be given and replace the threat's. ``material`` and ``diameter`` may not: the threat
sets them.

A bird, ``threat = { bird = "1.8 kg" }`` (or ``"4 lb"``): a bird of that mass as its gelatin substitute
(:func:`softimpact.models.threats.substitute_bird`), a hemispherical-ended cylinder of L/D = 2 and density 950 kg/m³
(``density`` in the threat table replaces it), striking nose first. A bird has no speed of its own: the table's
``velocity`` is required (the rule's speed, e.g. V_C at sea level), and ``material``, ``diameter`` and ``mass`` are the
threat's. The sphere read keeps the bird's mass and takes the cylinder's diameter; its ``length`` reaches the
hydrodynamic law (:class:`softimpact.models.hydrodynamic_law.HydrodynamicCapsuleLaw`), whose force acts on the
cylinder's section for the time L/V the bird takes to flow.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import InputError
from ..models.materials import CATALOGUE, Material, sphere_mass
from ..models.threats import BIRD_SUBSTITUTE_DENSITY, SubstituteBird, flight_hail_velocity, hail_terminal_velocity, substitute_bird
from .toml import Table, read_material

__all__ = ["Sphere", "read_sphere", "check_mass", "MASS_DENSITY_FACTOR"]

# A sphere's mass over that of a solid sphere of its material of its diameter may lie between 1/F and F: natural hail is
# lighter than solid ice, a ball may be hollow or filled; a sphere twice or half as dense as its material is not of it
# (another material, or a mass given in the wrong unit: a "1.1 kg" rubber ball is a thousand times a 1.1 g one).
MASS_DENSITY_FACTOR = 2.0


@dataclass(frozen=True)
class Sphere:
    """A projectile sphere as read: ``material``, ``diameter`` [m], ``velocity`` [m/s] toward the target,
    ``mass`` [kg]; a bird threat's ``length`` [m] (its hemispherical-ended cylinder's; None: a sphere) and its
    ``threat`` (:class:`~softimpact.models.threats.SubstituteBird`)."""

    material: Material
    diameter: float
    velocity: float
    mass: float
    length: float | None = None
    threat: SubstituteBird | None = None


def read_sphere(tbl: Table) -> Sphere:
    """The sphere of ``tbl`` (``[projectile]`` or ``[impactor]``), directly or by ``threat`` (module docstring);
    the table's other keys are left to the caller (it calls ``tbl.done()``). ``striker = true``: a drop weight's
    hemispherical striker (tup) of ``diameter`` on a carriage of ``mass`` (required; no solid-sphere check), which may
    be dropped with an ``energy`` in place of its ``velocity`` (v = sqrt(2E/m), ASTM D7136's way of naming an impact)."""
    threat = tbl.table("threat", optional=True)
    striker = tbl.raw("striker", False)
    if not isinstance(striker, bool):
        raise InputError(f"{tbl.key('striker')}: expected true or false, got {striker!r}")
    if striker:
        if threat is not None:
            raise InputError(f"{tbl.key('striker')}: a drop weight's striker is not a threat ({tbl.key('threat')}): give one or the other")
        material = read_material(tbl)
        diameter = tbl.quantity("diameter", "length")
        mass = tbl.quantity("mass", "mass")
        if ("velocity" in tbl) == ("energy" in tbl):
            raise InputError(f"{tbl.key('velocity')}: a striker needs its velocity or its energy ({tbl.key('energy')}), one of them")
        velocity = tbl.quantity("velocity", "velocity") if "velocity" in tbl else math.sqrt(2 * tbl.quantity("energy", "energy") / mass)
        return Sphere(material, diameter, velocity, mass)
    if threat is None:
        material = read_material(tbl)
        diameter = tbl.quantity("diameter", "length")
        velocity = tbl.quantity("velocity", "velocity")
    else:
        for key in ("material", "diameter"):
            if key in tbl:
                raise InputError(f"{tbl.key(key)}: the threat ({tbl.key('threat')}) sets it: give one or the other")
        if ("hail" in threat) == ("bird" in threat):
            raise InputError(f"{tbl.key('threat')}: a hailstone ({threat.key('hail')}) or a bird ({threat.key('bird')}), one of them")
        if "bird" in threat:
            threat.read_with({"airspeed": f"{threat.key('hail')} (a hailstone)"})
            return _bird(tbl, threat)
        threat.read_with({"density": f"{threat.key('bird')} (a bird)"})
        material = CATALOGUE["ice"]
        diameter = threat.quantity("hail", "length")
        airspeed = threat.quantity("airspeed", "velocity", default=None)
        threat.done()
        fall = hail_terminal_velocity(diameter) if airspeed is None else flight_hail_velocity(airspeed, diameter)
        velocity = tbl.quantity("velocity", "velocity", default=fall)
    mass = tbl.quantity("mass", "mass", default=None)
    if mass is not None:
        check_mass(material, diameter, mass, tbl.key("mass"), tbl.raw("mass"))
    return Sphere(material, diameter, velocity, sphere_mass(material, diameter) if mass is None else mass)


def _bird(tbl: Table, threat: Table) -> Sphere:
    """The substitute bird of ``threat = { bird = ... }`` at the table's required ``velocity`` (module docstring)."""
    if "mass" in tbl:
        raise InputError(f"{tbl.key('mass')}: the bird threat ({threat.key('bird')}) is the mass: give one or the other")
    bird = substitute_bird(threat.quantity("bird", "mass"), threat.quantity("density", "density", default=BIRD_SUBSTITUTE_DENSITY))
    threat.done()
    if "velocity" not in tbl:
        raise InputError(
            f"{tbl.key('velocity')}: required with a bird threat ({threat.key('bird')}): a bird has no speed of its own; "
            "give the impact speed toward the target (e.g. the rule's V_C at sea level)"
        )
    return Sphere(CATALOGUE["gelatin"], bird.diameter, tbl.quantity("velocity", "velocity"), bird.mass, bird.length, bird)


def check_mass(material: Material, diameter: float, mass: float, key: str, given) -> None:
    """Refuse a sphere's ``mass`` [kg] (``given`` as written, at ``key``) more than :data:`MASS_DENSITY_FACTOR` times
    above or below that of a solid sphere of ``material`` of ``diameter`` [m]: its density m/(π·d³/6) is then not the
    material's (InputError naming the key, the density it implies and the material's)."""
    solid = sphere_mass(material, diameter)
    ratio = mass / solid
    if not 1.0 / MASS_DENSITY_FACTOR <= ratio <= MASS_DENSITY_FACTOR:
        density = mass / (math.pi / 6.0 * diameter**3)
        raise InputError(
            f"{key}: {given!r} is {ratio:.3g} times the mass of a solid {diameter * 1e3:.4g}-mm sphere of {material.name} ({solid * 1e3:.4g} g): "
            f"a density of {density:.4g} kg/m^3 against the material's {material.density:.4g} (it must lie within a factor {MASS_DENSITY_FACTOR:g} of it): "
            "check the mass's unit, or give the sphere's own material"
        )
