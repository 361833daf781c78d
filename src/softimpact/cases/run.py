"""One run path: :func:`execute` runs a problem of any kind (bar, beam, plate, impact) and returns a :class:`Run`.

The command line (``softimpact bar|beam|plate|impact``), the Python API (:func:`softimpact.run`), sweeps,
``converge`` and the paper all run a case through it, so what a run computes is decided here once, by the
kind of its problem (:func:`softimpact.cases.kind_for`, each kind's ``execute``):

- the damage indices of an impact, from the target's ``"damage"`` output group (a layup with strengths;
  ``damage=False`` leaves them out: a sweep that asks for none);
- the snapshots of the structure's displacement (``figures``: a plate's deflected shapes; ``fields``: the
  frames of fields.xdmf, at most ``frames`` of them, :func:`softimpact.output.fields.sampled_steps`);
- how an impact is stepped (``method``: "direct", or "kernels" on contact kernels built once; ``energy``);
- a prescribed force instead of the case's (``force``: a bar's struck end driven by a pulse, ``softimpact
  predict --bar``; a beam's or plate's force history replaced) and whether summary.json's content is made
  (``summary``: sweeps and ``converge`` keep the run alone).

A :class:`Run` carries the result, the model that ran, summary.json's content and the run's
:class:`~softimpact.models.validity.Validity` (its warnings, as objects: the caller warns or lists them).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..models.validity import Validity

__all__ = ["Run", "execute", "impact_validity"]


@dataclass(frozen=True)
class Run:
    """One run of a case: ``result`` (the kind's: CoupledResult, BeamResult, PlateResult, the bar's
    result), ``model`` that ran (None for a bar), ``summary`` (the command's summary.json content, SI),
    ``warnings`` (the run's :class:`~softimpact.models.validity.Validity`: ratios and flags, in the
    command's order), ``problem`` as run; ``shown`` the step indices of the deflected-shape figure and
    ``kept`` those of the fields (both among the result's snapshots); a bar's ``plain`` (the same run
    without the end cap, None without one) and ``inferred`` ((time, force, gauge name) read from the
    first gauge, None without a gauge)."""

    result: object
    model: object
    summary: dict
    warnings: Validity
    problem: object = None
    shown: np.ndarray | tuple = ()
    kept: np.ndarray | tuple = ()
    plain: object = None
    inferred: tuple | None = None


def execute(
    problem,
    *,
    figures: bool = False,
    fields: bool = False,
    frames: int | None = None,
    damage: bool = True,
    method: str = "direct",
    kernels=None,
    model=None,
    energy: bool = True,
    stop_after: float | None = None,
    progress: Callable[[int], None] | None = None,
    force=None,
    summary: bool = True,
) -> Run:
    """Run ``problem`` (a BarImpactProblem, BeamProblem, PlateProblem or ImpactProblem) through its kind.

    ``figures``: keep what the figures draw (a plate's deflected shapes); ``fields``: keep the frames of the
    displacement fields, at most ``frames`` of them (default :data:`softimpact.output.fields.FRAMES`, evenly
    sampled: :func:`~softimpact.output.fields.sampled_steps`); ``damage``: an impact's damage indices (when its target's laminate allows them);
    ``method``, ``kernels``, ``energy``, ``stop_after``: how an impact is stepped
    (:func:`softimpact.workflows.coupled.run_impact`); ``model``: a model of the same structure and step to
    reuse; ``progress(k)``: called with the step index while stepping a beam or plate directly.

    ``force``: a prescribed force history F(t) [N] (a pulse) on a bar's struck end (the bar's response, no
    contact: a :class:`~softimpact.workflows.bar_impact.BarForceResult`, no summary) or in place of a beam's or
    plate's load history; ``summary``: False leaves the Run's summary empty (a plate: no natural frequencies;
    a bar with an end cap: no run without it, summary.json's ``without_end_cap``), for sweeps and
    ``converge``, which keep scalars of their own. An impact takes neither."""
    from . import kind_for

    own = {}  # the options only bars, beams and plates have (an impact's execute takes neither)
    if force is not None:
        own["force"] = force
    if not summary:
        own["summary"] = False
    return kind_for(problem).execute(
        problem,
        figures=figures,
        fields=fields,
        frames=frames,
        damage=damage,
        method=method,
        kernels=kernels,
        model=model,
        energy=energy,
        stop_after=stop_after,
        progress=progress,
        **own,
    )


def impact_validity(problem, result, damage: dict | None = None) -> Validity:
    """The envelopes of a coupled run (:func:`softimpact.models.validity.coupled_validity`): the contact law's approach and
    contact radius against the impactor's size, the law's own envelope, the target's deflection against its thickness (its theory,
    :meth:`~softimpact.models.protocols.Target.validity`), and with ``damage`` (summary.json's) the strains
    against the ply allowables (none when ``damage`` holds no indices: a cohesive run's growth alone, without the damage group),
    a metal target's yield or tearing, and on a plate target the plate's thickness against its span
    (:func:`softimpact.cases.plate.geometry_validity`)."""
    from ..models.validity import coupled_validity, front_step_validity, tearing_flags, yield_flags
    from ..workflows.plate.cohesive import CohesivePlateProblem
    from ..workflows.plate_impact import PlateProblem

    v = coupled_validity(problem, result, None if damage is None else damage.get("max_strain"))
    if damage is not None and "max_von_mises_over_yield" in damage:  # an elastic metal target
        v += yield_flags("the target (elastic metal)", damage["max_von_mises_over_yield"])
    if damage is not None and "max_equivalent_plastic_strain" in damage:  # an elastic-plastic metal target
        v += tearing_flags("the target (elastic-plastic metal)", damage["max_equivalent_plastic_strain"], problem.target.material.elongation)
    if isinstance(problem.target, PlateProblem):  # plate theory's geometry (cases.plate.geometry_validity), on every plate target
        from .plate import geometry_validity

        v += geometry_validity(problem.target)
    if isinstance(problem.target, CohesivePlateProblem):  # the delamination fronts against the step
        v += front_step_validity(_interface_areas(result), result.time, problem.target.node_spacing())
    return v


def _interface_areas(result) -> dict:
    """The delaminated area per interface per time [m²] of a cohesive run's "columns" group (name → history)."""
    names, rows = result.groups["columns"]
    prefix = "delaminated_area_m2_"
    return {n[len(prefix) :]: r for n, r in zip(names, rows) if n.startswith(prefix)}
