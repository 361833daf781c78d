"""The damage indices of a coupled impact need strains the user did not ask for: the load point's
faces and the face opposite each gauge (a beam), the in-plane strain tensor under the load and at
each gauge (a plate). They ride along as pseudo-gauges named ``_damage.*`` — added to the problem
before the run (:func:`damage_problem`) and split off the result after it (:func:`split_damage`) —
for every path that runs an impact: the command, the notebook API, sweeps and threshold maps.

A study (one level above workflows): it composes the beam and the plate workflows' gauges.
"""

from __future__ import annotations

import dataclasses

__all__ = ["DAMAGE_PREFIX", "damage_problem", "split_damage"]


DAMAGE_PREFIX = "_damage"  # names of the pseudo-gauges that feed the damage indices


def _opposite(surface: str) -> str:
    return "top" if surface == "bottom" else "bottom"


def damage_problem(problem):
    """The impact problem with the pseudo-gauges its damage indices need, when its target is a
    layup whose ply has strengths (else unchanged): on a beam the load point's two faces and the
    face opposite each gauge (axial strain over the gauge length); on a plate point strains in x, y
    and 45° on both faces under the load and at each gauge's centre (the in-plane strain tensor,
    :func:`softimpact.workflows.damage.strain_tensor`)."""
    if _bar(problem):
        return problem
    target = problem.target
    stack = target.plate.stack if problem.on_plate else target.beam.stack
    if stack is None or not hasattr(stack, "angles") or stack.ply.strength is None:
        return problem
    if problem.on_plate:
        from ..workflows.plate_impact import PlateGauge

        spots = {"at_load": tuple(target.load.position), **{f"at_{g.name}": tuple(g.position) for g in target.gauges}}
        extra = tuple(
            PlateGauge(f"{DAMAGE_PREFIX}.{n}.{face}.{d}", xy, face, d, 0.0) for n, xy in spots.items() for face in ("top", "bottom") for d in ("x", "y", 45.0)
        )
    else:
        from ..workflows.beam_impact import BeamGauge

        x = target.load.position
        extra = (BeamGauge(f"{DAMAGE_PREFIX}.at_load.top", x, "top"), BeamGauge(f"{DAMAGE_PREFIX}.at_load.bottom", x, "bottom"))
        extra += tuple(BeamGauge(f"{DAMAGE_PREFIX}.at_{g.name}.{_opposite(g.surface)}", g.position, _opposite(g.surface), g.length) for g in target.gauges)
    return dataclasses.replace(problem, target=dataclasses.replace(target, gauges=target.gauges + extra))


def _bar(problem) -> bool:
    return not hasattr(problem, "target")


def split_damage(problem, result):
    """(problem, result) without the damage pseudo-gauges, and those gauges' strains by name."""
    keep = [i for i, n in enumerate(result.strain_names) if not n.startswith(DAMAGE_PREFIX + ".")]
    if len(keep) == len(result.strain_names):
        return problem, result, {}
    pseudo = {n: result.strain[i] for i, n in enumerate(result.strain_names) if i not in keep}
    result = dataclasses.replace(result, strain=result.strain[keep], strain_names=tuple(result.strain_names[i] for i in keep))
    target = problem.target
    problem = dataclasses.replace(
        problem, target=dataclasses.replace(target, gauges=tuple(g for g in target.gauges if not g.name.startswith(DAMAGE_PREFIX + ".")))
    )
    return problem, result, pseudo
