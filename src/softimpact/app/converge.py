"""``softimpact converge``: a case on refined meshes and time steps, and its discretisation error.

Levels are the case's own discretisation refined by a constant integer ratio r
(mesh and time step together: h, h/r, h/r², …). Each level's outputs (scalars
and histories on the coarsest level's time grid) go to the Richardson analysis of
:mod:`softimpact.workflows.convergence`; the error of the first level is the case's
own distance from converged. A structure joins by a :class:`Study`: how to load
the case, refine it and read its outputs.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..input.toml import case_kind
from ..models.features import first_lobe_peak, first_zero_crossing
from ..output.converge import converge_files
from ..workflows.convergence import ConvergenceStudy, convergence_study
from ..workflows.refinement import refine_bar, refine_beam, refine_plate
from . import Outcome, Progress, no_progress

__all__ = ["Study", "STUDIES", "converge", "study_case", "bar_outputs", "beam_outputs", "plate_outputs"]

MAX_LEVELS = 5


def bar_outputs(problem, stride: int, progress: Callable[[int], None] | None = None) -> tuple[dict, dict]:
    """Scalars and histories of a bar impact run (histories every ``stride``-th sample) and its size."""
    from ..workflows.bar_impact import simulate_impact

    r = simulate_impact(problem)
    out = {
        "peak_force_N": r.peak_force,
        "time_of_peak_s": r.time_of_peak,
        "contact_duration_s": r.contact_duration,
        "impulse_N_s": r.total_impulse,
        "contact_force_history_N": r.force[::stride],
    }
    for g, eps in zip(problem.gauges, r.strain):
        out[f"strain_{g.name}_peak_magnitude"] = float(np.max(np.abs(eps)))  # unsigned: the signed extreme jumps when two peaks of opposite sign are close
        out[f"strain_{g.name}_history"] = eps[::stride]
    return out, {"elements": [problem.bar.elements], "time_step_s": problem.solver.time_step, "dofs": problem.bar.elements + 1}


def beam_outputs(problem, stride: int, progress: Callable[[int], None] | None = None) -> tuple[dict, dict]:
    """Gauge peaks, first-lobe peaks, first zero crossings and histories of a beam run; its size."""
    from ..workflows.beam_impact import BeamModel

    model = BeamModel(problem)
    r = model.direct(progress=progress, energy=False, displacement=False)
    out = {"peak_deflection_under_load_m": float(r.deflection[np.argmax(np.abs(r.deflection))])}
    for g, eps in zip(problem.gauges, r.strain):
        out[f"strain_{g.name}_peak_magnitude"] = float(np.max(np.abs(eps)))  # unsigned: the signed extreme jumps when two peaks of opposite sign are close
        out[f"strain_{g.name}_first_lobe_peak"] = first_lobe_peak(r.time, eps)
        out[f"strain_{g.name}_first_zero_crossing_s"] = first_zero_crossing(r.time, eps)
        out[f"strain_{g.name}_history"] = eps[::stride]
    return out, {"elements": [problem.beam.nx, problem.beam.nz], "time_step_s": problem.solver.time_step, "dofs": model.plane.n}


def plate_outputs(problem, stride: int, progress: Callable[[int], None] | None = None) -> tuple[dict, dict]:
    """Peak deflection under the load, gauge peaks and histories of a plate run; its size."""
    from ..workflows.plate_impact import PlateModel

    model = PlateModel(problem)
    r = model.direct(progress=progress, energy=False, snapshots=[])
    w = r.deflection[0]
    out = {"peak_deflection_under_load_m": float(w[np.argmax(np.abs(w))]), "deflection_under_load_history_m": w[::stride]}
    for g, eps in zip(problem.gauges, r.strain):
        out[f"strain_{g.name}_peak_magnitude"] = float(np.max(np.abs(eps)))  # unsigned: the signed extreme jumps when two peaks of opposite sign are close
        out[f"strain_{g.name}_history"] = eps[::stride]
    return out, {"elements": list(problem.plate.elements), "time_step_s": problem.solver.time_step, "dofs": int(model.fe.n)}


@dataclass(frozen=True)
class Study:
    """How to study one kind of case: ``load(case, history) -> (problem, path)``,
    ``refine(problem, factor)``, ``outputs(problem, stride, progress) -> (values, size)``,
    and ``check(problem)``, the kind's resource guard (None: the kind has none), applied
    to every level before the first is run."""

    load: Callable
    refine: Callable
    outputs: Callable
    check: Callable | None = None


def _load_bar(case, history):
    from ..input.bar_case import load_bar_case

    if history is not None:
        raise InputError("--history: a bar case has no table of histories", "history")
    return load_bar_case(case)


def _load_beam(case, history):
    from ..input.beam_case import load_beam_case

    return load_beam_case(case, history)


def _load_plate(case, history):
    from ..input.plate_case import load_plate_case

    return load_plate_case(case, history)


def _check_bar(problem):
    from ..workflows.bar_impact import check_problem

    check_problem(problem)


def _check_beam(problem):
    from ..workflows.beam_impact import check_problem

    check_problem(problem)


def _check_plate(problem):
    from ..workflows.plate_impact import check_problem

    check_problem(problem)


STUDIES = {
    "bar": Study(_load_bar, refine_bar, bar_outputs, _check_bar),
    "beam": Study(_load_beam, refine_beam, beam_outputs, _check_beam),
    "plate": Study(_load_plate, refine_plate, plate_outputs, _check_plate),
}


def study_case(study: Study, problem, levels: int, ratio: int, progress: Progress = no_progress, case_level: int = 0) -> tuple[ConvergenceStudy, list[dict]]:
    """Run ``levels`` refinements of ``problem`` (factors 1, r, r², …) and analyse them.

    ``case_level``: the index of the user's own discretisation among the levels; the levels
    below it are coarsenings the study chose (the paper report's ½), so the warnings of their
    checks (a mesh below the advised resolution) are not the user's and are not shown.
    """
    import warnings

    from ..errors import SoftimpactWarning

    factors = [ratio**k for k in range(levels)]
    problems = [study.refine(problem, f) for f in factors]
    if study.check is not None:  # the finest level decides whether the study fits the machine
        for k, p in enumerate(problems):
            with warnings.catch_warnings():
                if k < case_level:
                    warnings.simplefilter("ignore", SoftimpactWarning)
                study.check(p)
    work = [p.solver.steps for p in problems]
    total = sum(work)
    sizes = []

    def run(k):
        done = sum(work[:k])
        label = f"level {k + 1}/{levels} (×{factors[k]})"
        progress(done, total, label)
        t0 = time.perf_counter()
        values, size = study.outputs(problems[k], factors[k], lambda i: progress(done + i, total, label))
        sizes.append({"factor": factors[k], **size, "run_time_s": time.perf_counter() - t0})
        return values

    result = convergence_study(run, range(levels), float(ratio), formal_order=2.0)
    progress(total, total, "done")
    return result, sizes


def converge(case: str, levels: int = 3, ratio: int = 2, history: int | None = None, figures: bool = True, progress: Progress = no_progress) -> Outcome:
    """Run CASE at ``levels`` discretisations refined by ``ratio`` and write the Richardson table and figures."""
    if isinstance(levels, bool) or not isinstance(levels, int) or not 2 <= levels <= MAX_LEVELS:
        raise InputError(f"--levels: need 2 to {MAX_LEVELS} levels, got {levels!r}")
    if isinstance(ratio, bool) or not isinstance(ratio, int) or ratio < 2:
        raise InputError(f"--ratio: the refinement ratio must be an integer ≥ 2, got {ratio!r}")
    kind, _ = case_kind(case)
    if kind not in STUDIES:
        raise InputError(f"CASE: converge studies {', '.join(STUDIES)} cases; {case!r} is a {kind} case")
    study = STUDIES[kind]
    problem, path = study.load(case, history)
    t0 = time.perf_counter()
    result, sizes = study_case(study, problem, levels, ratio, progress)
    files = converge_files(result, sizes, problem, kind, figures)
    first = [o for o in result.outputs if o.kind == "history"]
    worst = max(first, key=lambda o: o.errors[0]) if first else max(result.outputs, key=lambda o: o.errors[0])
    unreliable = [o.name for o in result.outputs if not o.reliable]
    line = (
        f"{levels} levels (×1 … ×{ratio ** (levels - 1)}, {time.perf_counter() - t0:.1f} s); the case's own discretisation is "
        f"{100 * worst.errors[0]:.2g} % from converged on {worst.name} (observed order {worst.order:.2f})"
    )
    warnings = ()
    if unreliable:
        warnings = (f"extrapolation not reliable for {', '.join(unreliable)} (see status in convergence.csv)",)
    return Outcome(files, line, (path,), warnings)
