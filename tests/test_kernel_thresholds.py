"""Thresholds on contact kernels (issue 21): the impact velocity at which a response reaches a set value,
found by bisection over kernel runs, equals the one found by bisection over direct coupled stepping."""

from dataclasses import replace

import numpy as np
import pytest

from softimpact.fem.newmark import SolverSpec
from softimpact.input.impact_case import load_impact_case
from softimpact.workflows.coupled import impact_kernels, impact_model, run_impact

INCH = 0.0254


@pytest.fixture(scope="module")
def beam():
    """The long-beam impact case on a coarse mesh (60 × 4, 400 µs of 1 µs), its model and its kernels, built once."""
    problem, _ = load_impact_case("paper-long-beam-impact")
    t = problem.target
    t = replace(t, beam=replace(t.beam, nx=60, nz=4), solver=SolverSpec(1.0e-6, 400e-6, problem.solver.newmark))
    problem = replace(problem, target=t)
    model = impact_model(problem)
    return problem, model, impact_kernels(problem, model)


def _peak(beam, velocity: float, method: str, what: str) -> float:
    problem, model, kernels = beam
    p = replace(problem, impactor=replace(problem.impactor, velocity=velocity))
    _, r = run_impact(p, model, energy=False, method=method, kernels=kernels if method == "kernels" else None)
    return r.peak_force if what == "force" else float(np.max(np.abs(r.strain[0])))


def _threshold(f, level: float, lo: float, hi: float, rtol: float = 1e-5) -> float:
    """The root of f(V) = level in [lo, hi] by bisection (f increasing there)."""
    assert f(lo) < level < f(hi)
    while hi - lo > rtol * lo:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) < level else (lo, mid)
    return 0.5 * (lo + hi)


@pytest.mark.parametrize(("what", "level"), [("force", 250.0), ("strain", 2.0e-4)])
def test_threshold_velocity_by_kernels_equals_the_direct_one(beam, what, level):
    """The velocity at which the peak contact force (250 N) or the first gauge's peak strain (2e-4) is reached,
    bisected over kernel runs, is within 0.5 % of the one bisected over direct coupled stepping."""
    lo, hi = 20 * INCH, 400 * INCH
    fast = _threshold(lambda v: _peak(beam, v, "kernels", what), level, lo, hi)
    direct = _threshold(lambda v: _peak(beam, v, "direct", what), level, lo, hi)
    assert fast == pytest.approx(direct, rel=5e-3)
    assert lo < fast < hi


def test_run_impact_methods(beam):
    """ "auto" runs on the kernels it is given (no structure energies: NaN) and steps directly when
    energies are asked for; "kernels" with energies, or an unknown method, is bad input."""
    from softimpact.errors import InputError

    problem, model, kernels = beam
    _, fast = run_impact(problem, model, energy=False, method="auto", kernels=kernels)
    _, direct = run_impact(problem, model, energy=True, method="auto", kernels=kernels)
    assert np.all(np.isnan(fast.energies.kinetic)) and np.all(np.isfinite(direct.energies.kinetic))
    assert fast.peak_force == pytest.approx(direct.peak_force, rel=1e-9)
    with pytest.raises(InputError, match="energy=False"):
        run_impact(problem, model, energy=True, method="kernels", kernels=kernels)
    with pytest.raises(InputError, match="method"):
        run_impact(problem, model, method="modal")
