"""studies/calibration.py (the calibration on a ladder of models, moved down from app/calibrate.py):
the scaling fit of calibrated histories against a closed form, and the quality gates of a calibration."""

from types import SimpleNamespace

import numpy as np
import pytest

from softimpact.input.scaling_constants import start_pulse
from softimpact.models.empirical import PROJECTILES
from softimpact.studies.calibration import MAX_RESIDUAL_TO_NOISE, CalibratedTest, calibration_gates, series_fits

INCH = 0.0254  # m, by definition


def _calibrated(name, V, alphas, projectile="rubber-1/2in"):
    """A calibrated test whose F0, tF0, T follow eqs (4)-(6) exactly with α1, α2, α3."""
    P = PROJECTILES[projectile]
    a1, a2, a3 = alphas
    T = a2 * P.diameter / V
    cal = SimpleNamespace(peak_force=a1 * P.mass * V**2 / (2 * P.diameter), time_of_peak=a3 * T, duration=T)
    return CalibratedTest(SimpleNamespace(name=name, velocity=V), cal)


def test_series_fits_recover_the_alphas_of_exact_histories():
    """Calibrated histories made from eqs (4)-(6) with chosen α's fit back to them; eq 15's impulse 2F0T/π gives α4 = α1·α2/(2π)."""
    alphas = (3.2, 1.4, 0.08)
    items = [_calibrated(f"V{v}", v * INCH, alphas) for v in (1166, 1932, 3058, 4026)]
    items.append(CalibratedTest(SimpleNamespace(name="failed", velocity=2000 * INCH), None, error="unreadable"))
    fit = next(iter(series_fits(SimpleNamespace(projectile="rubber-1/2in"), items).values()))
    got = [fit.origin[f"alpha{i}"].slope for i in (1, 2, 3, 4)]
    assert got == pytest.approx([*alphas, alphas[0] * alphas[1] / (2 * np.pi)], rel=1e-9)


def test_series_fits_need_two_calibrated_tests():
    """One calibrated history determines no scaling fit (None)."""
    assert series_fits(SimpleNamespace(projectile="rubber-1/2in"), [_calibrated("V1", 30.0, (4, 1, 0.1))]) is None


def _gate_item(residual_to_noise=1.0, time_of_peak=10e-6, duration=100e-6, converged=True, at_bounds=()):
    cal = SimpleNamespace(
        residual_rms=np.array([0.5, residual_to_noise]) * 1e-6,
        prepared=SimpleNamespace(noise=np.array([1e-6, 1e-6])),
        time_of_peak=time_of_peak,
        duration=duration,
        converged=converged,
        method="least-squares",
        message="ok" if converged else "max evaluations",
        at_bounds=at_bounds,
    )
    return CalibratedTest(SimpleNamespace(name="h1"), cal)


@pytest.mark.parametrize(
    ("item", "failing"),
    [
        (_gate_item(), set()),
        (_gate_item(residual_to_noise=1.5 * MAX_RESIDUAL_TO_NOISE), {"residual[h1]"}),
        (_gate_item(time_of_peak=99e-6), {"pulse-skew[h1]"}),
        (_gate_item(converged=False), {"optimiser[h1]"}),
        (_gate_item(at_bounds=("time_of_peak",)), {"bounds[h1]"}),
    ],
)
def test_calibration_gates(item, failing):
    """Each calibrated test is held to its worst gauge's residual against the noise, a non-degenerate pulse, the optimiser's status
    and no parameter on a bound."""
    gates = calibration_gates([item, CalibratedTest(SimpleNamespace(name="h2"), None, error="no fit")])
    assert {g.name for g in gates} == {"residual[h1]", "pulse-skew[h1]", "optimiser[h1]", "bounds[h1]"}
    assert {g.name for g in gates if not g.passed} == failing


def test_start_pulse_is_table_I_at_the_velocity():
    """The calibration's start at 1166 in/s is eqs (4)-(6) with Table I (1/2 in: α1 4.25, α2 0.93, α3 0.25) for the 1.1-g, 1/2-in ball."""
    m, d, V = 1.1e-3, 0.5 * INCH, 1166 * INCH
    pulse = start_pulse("rubber-1/2in", None, V)
    assert pulse.peak_force == pytest.approx(4.25 * m * V**2 / (2 * d), rel=1e-3)
    assert pulse.duration == pytest.approx(0.93 * d / V, rel=1e-3)
    assert pulse.time_of_peak == pytest.approx(0.25 * pulse.duration, rel=1e-3)


def test_start_pulse_refuses_a_velocity_outside_the_constants():
    """Table I holds for 1000-5000 in/s: 6000 in/s is refused, naming the range in the display units."""
    from softimpact.errors import InputError

    with pytest.raises(InputError, match="outside the range of the bar model .*1000-5000 in/s"):
        start_pulse("rubber-1/2in", None, 6000 * INCH)


def test_model_ladder_levels_refine_the_papers_mesh():
    """The ladder's level 0 is the paper's calibration model (200 × 6 elements at 1 µs, docs/modelling-notes.md); level k
    multiplies both element counts by 2^k and divides the step by 2^k, level -1 coarsens; the budget picks a level from 0 to 3."""
    from softimpact.input.beam_case import load_beam_case
    from softimpact.studies.calibration import ModelLadder

    problem, _ = load_beam_case("paper-long-beam")
    ladder = ModelLadder(problem, [0.25 * INCH, 0.35 * INCH])
    assert ladder.describe(0) == {"level": 0, "factor": 1, "elements": [200, 6], "time_step_s": pytest.approx(1e-6)}
    assert ladder.describe(1) == {"level": 1, "factor": 2, "elements": [400, 12], "time_step_s": pytest.approx(0.5e-6)}
    assert ladder.describe(-1)["elements"] == [100, 3]
    assert ladder.reach == pytest.approx(0.35 * INCH)
    assert ladder.affordable(0.0) == 0 and ladder.affordable(1e12) == 3
    assert ladder.finest() is ladder(1)
