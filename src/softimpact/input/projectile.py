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
"""

from __future__ import annotations

from dataclasses import dataclass

from ..errors import InputError
from ..models.materials import CATALOGUE, Material, sphere_mass
from ..models.threats import flight_hail_velocity, hail_terminal_velocity
from .toml import Table, read_material

__all__ = ["Sphere", "read_sphere"]


@dataclass(frozen=True)
class Sphere:
    """A projectile sphere as read: ``material``, ``diameter`` [m], ``velocity`` [m/s] toward the target,
    ``mass`` [kg]."""

    material: Material
    diameter: float
    velocity: float
    mass: float


def read_sphere(tbl: Table) -> Sphere:
    """The sphere of ``tbl`` (``[projectile]`` or ``[impactor]``), directly or by ``threat`` (module docstring);
    the table's other keys are left to the caller (it calls ``tbl.done()``)."""
    threat = tbl.table("threat", optional=True)
    if threat is None:
        material = read_material(tbl)
        diameter = tbl.quantity("diameter", "length")
        velocity = tbl.quantity("velocity", "velocity")
    else:
        for key in ("material", "diameter"):
            if key in tbl:
                raise InputError(f"{tbl.key(key)}: the threat ({tbl.key('threat')}) sets it: give one or the other")
        material = CATALOGUE["ice"]
        diameter = threat.quantity("hail", "length")
        airspeed = threat.quantity("airspeed", "velocity", default=None)
        threat.done()
        fall = hail_terminal_velocity(diameter) if airspeed is None else flight_hail_velocity(airspeed, diameter)
        velocity = tbl.quantity("velocity", "velocity", default=fall)
    mass = tbl.quantity("mass", "mass", default=None)
    return Sphere(material, diameter, velocity, sphere_mass(material, diameter) if mass is None else mass)
