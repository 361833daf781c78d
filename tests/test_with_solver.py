"""Every problem kind swaps its time step through `with_solver` (the one-factor refinement of `converge`), no probing of its fields."""

from dataclasses import replace

import pytest

import softimpact as si
from softimpact.fem.newmark import SolverSpec

from _support.small_cases import BEAM, PLATE


def _problems(tmp_path):
    (tmp_path / "beam.toml").write_text(BEAM)
    (tmp_path / "plate.toml").write_text(PLATE)
    (tmp_path / "impact.toml").write_text(
        '[target]\ncase = "beam.toml"\n[impactor]\nmaterial = "steel"\ndiameter = "0.5 in"\nvelocity = "100 in/s"\n'
        '[contact]\nlaw = "hertz"\n[solver]\ntime_step = "1 us"\nduration = "300 us"\n'
    )
    return {
        "bar": si.load("paper-calibration").problem,
        "beam": si.load(tmp_path / "beam.toml").problem,
        "plate": si.load(tmp_path / "plate.toml").problem,
        "impact": si.load(tmp_path / "impact.toml").problem,
    }


@pytest.mark.parametrize("kind", ["bar", "beam", "plate", "impact"])
def test_with_solver_swaps_the_time_step_and_keeps_the_rest(tmp_path, kind):
    """`with_solver(s)` steps the problem by s (a coupled problem: its target, which steps the coupled run); every other input is the problem's."""
    problem = _problems(tmp_path)[kind]
    s = SolverSpec(problem.solver.time_step / 2, problem.solver.duration)
    swapped = problem.with_solver(s)
    assert swapped.solver == s and swapped.solver.steps == 2 * problem.solver.steps
    if kind == "impact":
        assert swapped.target.solver == s and swapped == replace(problem, target=replace(problem.target, solver=s))
    else:
        assert swapped == replace(problem, solver=s)
