"""``softimpact plate``: transverse impact of a laminated plate (FSDT, MITC9 or MITC4)."""

from __future__ import annotations

import time

import numpy as np

from ..input.plate_case import load_plate_case
from ..output.fields import field_files, kept_frames, sampled_steps, select_kept
from ..output.plate import plate_files, plate_validity, snapshot_steps
from ..units import display
from ..workflows.plate_impact import PlateModel
from . import Outcome, Progress, no_progress

__all__ = ["plate", "mirrored_loads"]


def plate(*, case: str, history: int | None = None, figures: bool = True, fields: bool = False, progress: Progress = no_progress) -> Outcome:
    """Run a plate case (file or built-in name), optionally with row ``history`` of its [[load.table]];
    ``fields``: also fields.xdmf/.h5, the displacement fields (:mod:`softimpact.output.fields`)."""
    problem, path = load_plate_case(case, history)
    t0 = time.perf_counter()
    model = PlateModel(problem)
    steps = problem.solver.steps
    shown = snapshot_steps(steps) if figures else ()
    kept = sampled_steps(steps) if fields else ()
    result = model.direct(progress=lambda k: progress(k, steps, "stepping"), snapshots=np.union1d(shown, kept).astype(int) if fields else shown)
    progress(steps, steps, "stepping")
    files = plate_files(model, select_kept(result, shown) if fields else result, figures)
    if fields:
        files.update(field_files(model, kept_frames(result, kept)))
    su, lu = display(problem.units, "strain"), display(problem.units, "length")
    peaks = "".join(f", {g.name} {eps[np.argmax(np.abs(eps))] * su.factor:.0f} {su.label}" for g, eps in zip(problem.gauges, result.strain))
    w = result.deflection[0]
    line = f"{model.fe.n} DOF, {steps} steps ({time.perf_counter() - t0:.1f} s); peak deflection {w[np.argmax(np.abs(w))] * lu.factor:.3g} {lu.label}{peaks}"
    return Outcome(files, line, (path,), mirrored_loads(problem) + plate_validity(result).flags)


def mirrored_loads(problem) -> tuple[str, ...]:
    """A warning per symmetry edge that misses the load point (:meth:`PlateProblem.mirrored_edges`)."""
    return tuple(
        f'plate.support.{edge} = "symmetry" does not pass through the load point: the model carries the load mirrored about it too'
        for edge in problem.mirrored_edges()
    )
