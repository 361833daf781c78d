"""Stand-ins, for the Python API until it runs cases through :func:`softimpact.cases.run.execute`.

The damage indices of a coupled impact no longer ride along as pseudo-gauges: a target's model carries
them as its ``"damage"`` output group (:meth:`~softimpact.models.protocols.Target.damage_gauges`), a run's
result keeps that group apart from the user's gauges (``CoupledResult.groups``), and the run path computes
the indices (:func:`softimpact.workflows.damage.coupled_damage`). Delete this module once ``api.py`` calls
``execute`` (its ``_run`` and ``ImpactResult``).
"""

from __future__ import annotations

__all__ = ["damage_problem", "split_damage"]


def damage_problem(problem):
    """The problem unchanged: the damage outputs are the target model's own group now."""
    return problem


def split_damage(problem, result):
    """(problem, result, the result's ``"damage"`` group by name): its gauges are already only the user's."""
    groups = result.groups or {}
    names, rows = groups.get("damage", ((), ()))
    return problem, result, dict(zip(names, rows))
