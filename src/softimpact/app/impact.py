"""``softimpact impact``: a rigid impactor on a laminated beam or plate through a contact law (coupled)."""

from __future__ import annotations

import time

import numpy as np

from ..input.impact_case import load_impact_case
from ..output.fields import field_files, sampled_steps, select_kept
from ..output.impact import impact_files, snapshot_steps
from ..units import display
from ..workflows.coupled import impact_model, run_impact
from . import Outcome, Progress, no_progress

__all__ = ["impact"]


def impact(*, case: str, figures: bool = True, fields: bool = False, progress: Progress = no_progress) -> Outcome:
    """Run an impact case (file or built-in name) on a beam or plate target; ``fields``: also
    fields.xdmf/.h5, the target's displacement fields (:mod:`softimpact.output.fields`)."""
    problem, inputs = load_impact_case(case)
    t0 = time.perf_counter()
    steps = problem.solver.steps
    model = impact_model(problem)
    progress(0, steps, "stepping")
    snaps = snapshot_steps(steps) if figures and problem.on_plate else ()
    kept = sampled_steps(steps) if fields else ()
    model, result = run_impact(problem, model, snapshots=np.union1d(snaps, kept).astype(int) if fields else snaps)
    progress(steps, steps, "stepping")
    files = impact_files(problem, select_kept(result, snaps) if fields else result, figures, model=model)
    if fields:
        at = {int(k): i for i, k in enumerate(result.kept)}
        files.update(field_files(model, (kept, result.time[kept], result.displacement[:, [at[int(k)] for k in kept]])))
    fu, tu, su = (display(problem.units, k) for k in ("force", "time", "strain"))
    peaks = ", ".join(f"{n} {eps[np.argmax(np.abs(eps))] * su.factor:.0f} {su.label}" for n, eps in zip(result.strain_names, result.strain))
    T = "not separated" if not np.isfinite(result.contact_duration) else f"T {result.contact_duration * tu.factor:.1f} {tu.label}"
    unfinished = (
        ()
        if np.isfinite(result.contact_duration)
        else (
            f"the first contact has not ended by the end of the run ({problem.solver.duration * tu.factor:.4g} {tu.label}): "
            "its duration and the rebound velocity are unknown (null in summary.json) and its peak may be later; lengthen solver.duration",
        )
    )
    dofs = model.size
    line = (
        f"{problem.law_name}: F0 {result.peak_force * fu.factor:.1f} {fu.label} at {result.time_of_peak * tu.factor:.1f} {tu.label}, {T}, "
        f"{len(result.contacts)} contact(s); peak strains {peaks} ({dofs} DOF, {steps} steps, {time.perf_counter() - t0:.1f} s)"
    )
    return Outcome(files, line, inputs, unfinished)
