"""One name per thing: one sphere class, a pulse's time of peak declared by every pulse, the display system
at the edges only, and a bar driven by a prescribed force through the one run path."""

import json
import math
from dataclasses import replace

import numpy as np
import pytest

from softimpact.cases.run import execute
from softimpact.errors import InputError
from softimpact.input.bar_case import load_bar_case
from softimpact.models.materials import lookup
from softimpact.models.pulses import SkewedPulse, TabulatedPulse, TailedPulse
from softimpact.models.specimens import Impactor
from softimpact.workflows.bar_impact import without_end_cap

STEEL = lookup("steel")


def test_solid_sphere_mass_is_density_times_volume():
    """Impactor.solid: mass = ρ·π·d³/6 (the sphere's volume, written here), its material kept; a rigid impactor has none."""
    d = 0.0127
    ball = Impactor.solid(STEEL, d, 2.54)
    assert ball.mass == pytest.approx(STEEL.density * math.pi * d**3 / 6.0, rel=1e-12)
    assert ball.material is STEEL and Impactor(0.0084, d, 2.54).material is None
    with pytest.raises(InputError, match="impactor.velocity"):
        Impactor(0.0084, d, 0.0)


@pytest.mark.parametrize(
    "pulse",
    [
        SkewedPulse(1000.0, 30e-6, 200e-6),
        TailedPulse(SkewedPulse(1000.0, 30e-6, 200e-6), 0.3, 50e-6),
        TabulatedPulse(np.array([0.0, 1e-5, 4e-5, 9e-5]), np.array([0.0, 5.0, 9.0, 2.0])),
    ],
    ids=["skewed", "tailed", "table"],
)
def test_time_of_peak_is_where_the_sampled_force_is_largest(pulse):
    """Every pulse's time_of_peak is the time of its largest value, found by sampling F(t) on a fine grid (step 1 ns)."""
    t = np.arange(0.0, pulse.duration, 1e-9)
    assert pulse.time_of_peak == pytest.approx(t[np.argmax(pulse(t))], abs=2e-9)


def test_bar_under_a_prescribed_force_carries_the_incident_wave():
    """``execute(bar, force=F)``: before the far end's reflection returns, the gauge reads the 1-D incident wave
    ε(t) = −F(t − x/c)/(E·A) (d'Alembert; c = √(E/ρ)), to 2 % of its peak."""
    problem = without_end_cap(load_bar_case("paper-calibration")[0])
    bar, gauge = problem.bar, problem.gauges[0]
    pulse = SkewedPulse(1000.0, 40e-6, 100e-6)
    run = execute(problem, force=pulse)
    E, rho = bar.material.youngs_modulus, bar.material.density
    c = math.sqrt(E / rho)
    t = run.result.time
    before = t < (2 * bar.length - gauge.position) / c  # the reflection from the free far end has not come back
    expected = -pulse(t - gauge.position / c) / (E * bar.area)
    measured = run.result.strain[0]
    assert np.max(np.abs(measured[before] - expected[before])) < 0.02 * np.max(np.abs(expected))
    assert run.summary == {}  # a prescribed force has no contact: no summary of its own


def test_display_system_is_the_cases_not_the_problems(tmp_path):
    """A bar case read with units = "SI" and with "in-lbf-s": the same problem, summary.json's numbers equal, and
    its case_SI.units the case's (the display choice written at the edge)."""
    import softimpact as si

    base = load_bar_case("paper-calibration")[1].read_text()
    lines = [ln for ln in base.splitlines() if not ln.startswith("units")]
    out = {}
    for system in ("SI", "in-lbf-s"):
        case = tmp_path / f"{system}.toml"
        case.write_text(f'units = "{system}"\n' + "\n".join(lines) + "\n")
        loaded = si.load(case)
        assert loaded.units == system
        res = si.run(loaded, figures=False)
        out[system] = (loaded.problem, json.loads(res.files(figures=False)["summary.json"]))
    (p_si, s_si), (p_us, s_us) = out["SI"], out["in-lbf-s"]
    assert p_si == p_us
    assert s_si["case_SI"]["units"] == "SI" and s_us["case_SI"]["units"] == "in-lbf-s"
    assert s_si["peak_force_N"] == s_us["peak_force_N"] and s_si["contact_duration_s"] == s_us["contact_duration_s"]


def test_replaced_force_history_is_the_one_that_steps():
    """``execute(beam, force=F)``: the force the beam carries is F at every step (F evaluated here), not the case's own history."""
    from softimpact.input.beam_case import load_beam_case

    problem = load_beam_case("paper-long-beam")[0]
    problem = replace(problem, solver=replace(problem.solver, duration=100e-6))
    pulse = SkewedPulse(200.0, 20e-6, 80e-6)
    r = execute(problem, force=pulse, energy=False, summary=False).result
    assert np.array_equal(r.force, pulse(r.time)) and not np.array_equal(r.force, problem.load.history(r.time))
