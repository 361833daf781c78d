"""Test-side helpers: the paper's long beam model and its ContactStructure (fem.plane_contact)."""

from dataclasses import replace

from softimpact.app.impact import beam_contact_structure as beam_structure  # noqa: F401 (re-exported for the tests)
from softimpact.fem.newmark import SolverSpec
from softimpact.input.beam_case import load_beam_case
from softimpact.workflows.beam_impact import BeamModel

INCH = 0.0254


def long_beam_model(time_step=0.5e-6, duration=600e-6, nx=200, nz=6):
    """BeamModel of the paper's long beam (paper-long-beam case) with the given step and mesh."""
    problem, _ = load_beam_case("paper-long-beam")
    beam = replace(problem.beam, nx=nx, nz=nz)
    solver = SolverSpec(time_step, duration, problem.solver.newmark)
    return BeamModel(replace(problem, beam=beam, solver=solver))
