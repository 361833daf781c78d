"""A coupled run tells its progress as it steps (a long run's progress bar): the steps reported rise, every
PROGRESS_STRIDE steps, and never pass the run's length; a run without a callback is the same run."""

import numpy as np

from softimpact.cases import KINDS
from softimpact.fem.stepping import CoupledStepper
from softimpact.input.impact_case import load_impact_case


def test_the_steps_reported_rise_to_the_run_and_change_nothing():
    problem, _ = load_impact_case("paper-long-beam-impact")
    calls = []
    told = KINDS["impact"].execute(problem, figures=False, progress=calls.append)
    quiet = KINDS["impact"].execute(problem, figures=False)
    steps = problem.solver.steps
    reported = calls[1:]  # the first call, 0, is the command's before the run
    assert calls[0] == 0 and len(reported) >= 2
    assert all(b >= a for a, b in zip(reported, reported[1:])) and reported[-1] == steps
    assert all((k % CoupledStepper.PROGRESS_STRIDE == 0 or k == steps) and 0 < k <= steps for k in reported)
    assert np.array_equal(told.result.force, quiet.result.force)
