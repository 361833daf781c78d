"""Scaling constants α1–α4 named on the command line (``--constants``): a preset, a scaling.json
of ``softimpact fit``, or the projectile's own preset; and the bar-model force history they give
at a velocity (eqs 4–6 with eq 15), the start of a calibration."""

from __future__ import annotations

from pathlib import Path

from .. import units
from ..errors import InputError
from ..formats.scaling_json import read_scaling_law
from ..models.empirical import PRESETS, PROJECTILES, ScalingLaw
from ..models.pulses import SkewedPulse

__all__ = ["scaling_law", "start_pulse"]


def scaling_law(constants: str | None, group: str, projectile) -> ScalingLaw:
    """The α's: a projectile's name (its preset: ``rubber-1/2in``), a preset's own name (``silicone-1/2in``, the
    deprecated spelling of the same constants), a scaling.json from `softimpact fit`, or the projectile's preset."""
    if constants is None:
        if projectile is None:
            raise InputError("--constants: needed with --mass/--diameter (a preset or a scaling.json)")
        return PRESETS[projectile.law]
    if constants in PROJECTILES:  # one name per ball: a projectile's name gives its own constants
        return PRESETS[PROJECTILES[constants].law]
    if constants in PRESETS:  # the presets' own names (silicone-1/2in): the older spelling, still accepted
        return PRESETS[constants]
    path = Path(constants)
    if not path.is_file():
        raise InputError(f"--constants: {constants!r} is neither a projectile's constants ({', '.join(PROJECTILES)}; formerly {', '.join(PRESETS)}) nor a file")
    return read_scaling_law(path, group)


def start_pulse(projectile: str, constants: str | None, velocity: float, system: str = "in-lbf-s") -> SkewedPulse:
    """The bar-model history at ``velocity`` [m/s]: eqs (4)–(6) with eq (15); refuses velocities out
    of the constants' range (the message in the display ``system``'s velocity unit)."""
    if projectile not in PROJECTILES:
        raise InputError(f"--projectile: unknown {projectile!r} (known: {', '.join(PROJECTILES)})")
    P = PROJECTILES[projectile]
    law = scaling_law(constants, "pooled", P)
    if not law.in_range(velocity):
        lo, hi = law.velocity_range
        vu = units.display(system, "velocity")
        raise InputError(
            f"velocity: {velocity * vu.factor:.0f} {vu.label} is outside the range of the bar model {law.name} "
            f"({lo * vu.factor:.0f}-{hi * vu.factor:.0f} {vu.label})"
        )
    return law.pulse(P.mass, P.diameter, velocity)
