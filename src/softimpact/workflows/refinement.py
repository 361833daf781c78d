"""Refined copies of a problem for a convergence study (see ``convergence``).

Duck-typed on the problem's attributes so that this module imports no other
workflow: a bar problem has ``bar.elements`` and ``solver.time_step``; a beam
problem has ``beam.nx``, ``beam.nz`` and ``solver.time_step``; a plate problem
``plate.elements`` (nx, ny) and ``solver.time_step``. Only the
discretisation changes; the physics, the run's duration and its outputs do not.
"""

from __future__ import annotations

from dataclasses import replace

from ..errors import InputError

__all__ = ["refine_bar", "refine_beam", "refine_plate", "refine_solver", "coarsen_beam"]


def _check(factor) -> int:
    if isinstance(factor, bool) or not isinstance(factor, int) or factor < 1:
        raise InputError(f"refinement factor must be a positive integer, got {factor!r}")
    return factor


def refine_solver(solver, factor: int):
    """The solver with time step dt/factor and the same duration (so the coarse
    time grid is every factor-th sample of the fine one)."""
    return replace(solver, time_step=solver.time_step / _check(factor))


def refine_bar(problem, factor: int, *, space: bool = True, time: bool = True):
    """A bar impact problem with factor × the elements and/or dt/factor."""
    factor = _check(factor)
    out = problem
    if space:
        out = replace(out, bar=replace(out.bar, elements=out.bar.elements * factor))
    if time:
        out = replace(out, solver=refine_solver(out.solver, factor))
    return out


def refine_beam(problem, factor: int, *, space: bool = True, time: bool = True):
    """A beam problem with factor × the elements along and through the thickness
    and/or dt/factor (the contact patch, gauges and load are unchanged)."""
    factor = _check(factor)
    out = problem
    if space:
        out = replace(out, beam=replace(out.beam, nx=out.beam.nx * factor, nz=out.beam.nz * factor))
    if time:
        out = replace(out, solver=refine_solver(out.solver, factor))
    return out


def refine_plate(problem, factor: int, *, space: bool = True, time: bool = True):
    """A plate problem with factor × the elements along x and y and/or dt/factor
    (the load patch, gauges and points are unchanged)."""
    factor = _check(factor)
    out = problem
    if space:
        nx, ny = out.plate.elements
        out = replace(out, plate=replace(out.plate, elements=(nx * factor, ny * factor)))
    if time:
        out = replace(out, solver=refine_solver(out.solver, factor))
    return out


def coarsen_beam(problem, factor: int):
    """The beam problem with nx/factor × nz/factor elements and dt·factor: the level
    below a case's own, so that a study (factor, 1, 1/factor) brackets the case's
    discretisation. The element counts must divide by ``factor``; the duration must
    stay a whole number of the coarser steps."""
    factor = _check(factor)
    b, s = problem.beam, problem.solver
    if b.nx % factor or b.nz % factor:
        raise InputError(f"cannot coarsen a {b.nx} × {b.nz} mesh by {factor}: the element counts must divide by it")
    steps = s.duration / (s.time_step * factor)
    if abs(steps - round(steps)) > 1e-9 * steps:
        raise InputError(f"cannot coarsen dt = {s.time_step!r} s by {factor}: the duration is not a whole number of the coarser steps")
    return replace(problem, beam=replace(b, nx=b.nx // factor, nz=b.nz // factor), solver=replace(s, time_step=s.time_step * factor))
