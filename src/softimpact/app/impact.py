"""``softimpact impact``: a rigid impactor on a laminated beam or plate through a contact law (coupled)."""

from __future__ import annotations

import time

import numpy as np

from ..cases import KINDS
from ..cases.impact import with_identified_envelope
from ..cases.run import execute
from ..extras import require
from ..input.impact_case import load_impact_case
from ..input.sweep_spec import case_files
from ..input.toml import case_units
from ..models.validity import warn
from ..output.fields import field_files, kept_frames, select_kept
from ..output.impact import impact_files
from ..units import display
from . import Outcome, Progress, no_progress
from .options import display_system

__all__ = ["impact"]


def _damage_words(summary: dict, force) -> str:
    """The line's damage part (summary.json's ``damage``): the largest index, Davies–Zhang's ratio (the largest
    force of any contact over P_c: a later contact can press harder than the first, whose peak is F0), the
    response regime and Olsson's threshold F_d in the display unit ``force``, then the verdict."""
    d = summary.get("damage")
    if not d:
        return ""
    if "max_strain" not in d:  # a metal plate's: its dent, or its stresses against yield
        return f"; damage: {d['verdict']}"
    worst = max(("max_strain", "tsai_wu", "hashin", "interlaminar_index"), key=lambda k: d[k])
    words = f"; damage: {worst.replace('_', ' ')} {d[worst]:.2f}, F_max/P_c (Davies-Zhang) {d['delamination']:.2f}"
    if "regime" in d:
        words += f"; regime {d['regime']}"
    if "olsson_threshold_force_N" in d:
        words += f", F_d (Olsson) {d['olsson_threshold_force_N'] * force.factor:.1f} {force.label}"
    return words + f"; verdict: {d['verdict']}"


def impact(*, case: str, units: str | None = None, figures: bool = True, fields: bool = False, progress: Progress = no_progress) -> Outcome:
    """Run an impact case (file or built-in name) on a beam or plate target; ``fields``: also
    fields.xdmf/.h5, the target's displacement fields (:mod:`softimpact.output.fields`); ``units``: the display system of the line and figures (None: the case's)."""
    if fields:  # before any work: the extra's modules, or exit 2 with the install line
        require("fields", "--fields (fields.xdmf/.h5)")
    problem, inputs = load_impact_case(case)
    system = display_system(units, case_units(inputs[0]))
    KINDS["impact"].check(problem)  # the target's mesh and resources, the step against the contact's rise (exit 2)
    t0 = time.perf_counter()
    steps = problem.solver.steps
    run = execute(problem, figures=figures, fields=fields, progress=lambda k: progress(k, steps, "stepping"))
    run = with_identified_envelope(run, inputs[2] if len(inputs) > 2 else None)  # the law.json's identified envelope
    result, model = run.result, run.model
    files = impact_files(problem, select_kept(result, run.shown) if fields else result, figures, model=model, summary=run.summary, units=system)
    if fields:
        files.update(field_files(model, kept_frames(result, run.kept)))
    warn(run.warnings)
    fu, tu, su = (display(system, k) for k in ("force", "time", "strain"))
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
    line = (
        f"{problem.law_name}: F0 {result.peak_force * fu.factor:.1f} {fu.label} at {result.time_of_peak * tu.factor:.1f} {tu.label}, {T}, "
        f"{len(result.contacts)} contact(s){f'; peak strains {peaks}' if peaks else ''}{_damage_words(run.summary, fu)} "
        f"({model.size} DOF, {steps} steps, {time.perf_counter() - t0:.1f} s)"
    )
    return Outcome(files, line, case_files(inputs[0], inputs[1:]), unfinished)  # the case and every file it names: never removed
