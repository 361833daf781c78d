"""``softimpact converge``: a case on refined meshes and time steps, and its discretisation error.

Levels are the case's own discretisation refined by a constant integer ratio r
(mesh and time step together: h, h/r, h/r², …). Each level's outputs (scalars
and histories on the coarsest level's time grid) go to the Richardson analysis of
:mod:`softimpact.workflows.convergence`; the error of the first level is the case's
own distance from converged. Any kind of case joins through its case kind
(:mod:`softimpact.cases`: load, refine, check, study): bar, beam, plate and impact.
"""

from __future__ import annotations

import time

from ..cases import case_kind
from ..errors import InputError
from ..input.toml import case_units
from ..output.converge import converge_files, order_phrase
from ..workflows.convergence import study_case
from . import Outcome, Progress, no_progress
from .options import display_system

__all__ = ["converge", "MAX_LEVELS"]

MAX_LEVELS = 5


def converge(
    *, case: str, levels: int = 3, ratio: int = 2, history: int | None = None, units: str | None = None, figures: bool = True, progress: Progress = no_progress
) -> Outcome:
    """Run CASE at ``levels`` discretisations refined by ``ratio`` and write the Richardson table and figures, in display
    ``units`` (None: the case's)."""
    if isinstance(levels, bool) or not isinstance(levels, int) or not 2 <= levels <= MAX_LEVELS:
        raise InputError(f"--levels: need 2 to {MAX_LEVELS} levels, got {levels!r}")
    if isinstance(ratio, bool) or not isinstance(ratio, int) or ratio < 2:
        raise InputError(f"--ratio: the refinement ratio must be an integer ≥ 2, got {ratio!r}")
    kind, _ = case_kind(case)
    problem, inputs = kind.load(case, history)
    why = kind.refusal(problem, "converge")
    if why is not None:
        raise InputError(why)
    t0 = time.perf_counter()
    result, sizes = study_case(kind, problem, levels, ratio, progress)
    files = converge_files(result, sizes, problem, kind.name, figures, units=display_system(units, case_units(case)))
    first = [o for o in result.outputs if o.kind == "history"]
    worst = max(first, key=lambda o: o.errors[0]) if first else max(result.outputs, key=lambda o: o.errors[0])
    unreliable = [o.name for o in result.outputs if not o.reliable]
    line = (
        f"{levels} levels (×1 … ×{ratio ** (levels - 1)}, {time.perf_counter() - t0:.1f} s); the case's own discretisation is "
        f"{100 * worst.errors[0]:.2g} % from converged on {worst.name} ({order_phrase(worst)})"
    )
    warnings = ()
    if unreliable:
        warnings = (f"extrapolation not reliable for {', '.join(unreliable)} (see status in convergence.csv)",)
    return Outcome(files, line, tuple(inputs), warnings)
