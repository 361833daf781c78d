"""Calibration of the transverse force history against measured strains (Tables II, III)."""

from dataclasses import replace

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact.cli import main
from softimpact.errors import InputError
from softimpact.fem.newmark import SolverSpec as BeamSolver
from softimpact.input.beam_case import load_beam_case
from softimpact.models.empirical import PRESETS, PROJECTILES
from softimpact.models.pulses import SkewedPulse
from softimpact.workflows.beam_impact import BeamModel
from softimpact.workflows.calibration import Measured, calibrate
from softimpact.workflows.synthetic import beam_measurement

from _support.constants import INCH

TRUE = SkewedPulse(44 * 4.4482216152605, 30e-6, 355e-6)  # Table II, history 1
V = 1166 * INCH


@pytest.fixture(scope="module")
def setup():
    """Strains from a finer model (300 × 8, 0.5 µs) with 1.5 % noise and offsets; the paper's model (200 × 6, 1 µs) to calibrate."""
    problem, _ = load_beam_case("paper-long-beam", 1)
    fine = BeamModel(replace(problem, beam=replace(problem.beam, nx=300, nz=8), solver=BeamSolver(0.5e-6, 1000e-6)))
    t, strains = beam_measurement(fine, TRUE, pre_trigger=100e-6, noise=0.015, offsets=[25e-6, -40e-6], rng=np.random.default_rng(11), sample_interval=1e-6)
    model = BeamModel(problem, patch_radius=1.5 * problem.load.contact_radius)
    P = PROJECTILES["rubber-1/2in"]
    start = PRESETS[P.law].pulse(P.mass, P.diameter, V)
    return model, Measured("synthetic", t + 7.5, strains), start  # an arbitrary record clock


def test_least_squares_recovers_history(setup):
    """Model mismatch, noise and offsets: F0 and T within 3 %, t_F0 within 10 %."""
    model, measured, start = setup
    c = calibrate(model, measured, start, "least-squares")
    assert c.peak_force == pytest.approx(TRUE.peak_force, rel=0.03)
    assert c.duration == pytest.approx(TRUE.duration, rel=0.03)
    assert c.time_of_peak == pytest.approx(TRUE.time_of_peak, rel=0.10)
    assert abs(c.prepared.contact_time - (7.5 + 100e-6)) < 2e-6


def test_paper_method_recovers_history(setup):
    """The paper's procedure, from the bar model (eqs 4-5) with the table's t_F0/T: F0 and T within 5 %."""
    model, measured, start = setup
    start = SkewedPulse(start.peak_force, TRUE.time_of_peak / TRUE.duration * start.duration, start.duration)
    c = calibrate(model, measured, start, "paper")
    assert c.converged and c.iterations > 1
    assert c.peak_force == pytest.approx(TRUE.peak_force, rel=0.05)
    assert c.duration == pytest.approx(TRUE.duration, rel=0.05)


def test_deconvolved_force_peaks_at_F0(setup):
    """The non-negative, GCV-regularised deconvolution peaks within 5 % of F0 and is causal."""
    model, measured, start = setup
    c = calibrate(model, measured, start, "deconvolve")
    assert c.peak_force == pytest.approx(TRUE.peak_force, rel=0.05)
    assert np.all(c.pulse.force >= 0) and c.pulse.force[0] == 0.0


def test_standard_errors_are_honest():
    """Over 30 noise draws on the calibration model's own strains, the true F0 lies within 2 SE in ≥ 90 % of them."""
    problem, _ = load_beam_case("paper-long-beam", 1)
    problem = replace(problem, solver=BeamSolver(1e-6, 600e-6))
    model = BeamModel(problem)
    clean = model.respond(TRUE)
    t = np.arange(-100e-6, 600e-6, 1e-6)
    rng = np.random.default_rng(3)
    start = SkewedPulse(0.8 * TRUE.peak_force, 40e-6, 420e-6)
    hits = 0
    for _ in range(30):
        strains = {
            g.name: np.interp(t, clean.time, s, left=0.0) + 0.015 * np.max(np.abs(s)) * rng.standard_normal(t.size)
            for g, s in zip(problem.gauges, clean.strain)
        }
        c = calibrate(model, Measured("draw", t, strains), start, "least-squares", contact_time=-1e-12, fit_origin=False)
        hits += abs(c.peak_force - TRUE.peak_force) <= 2 * c.standard_errors["peak_force"]
    assert hits >= 27


def test_unknown_gauge_and_short_record(setup):
    """A gauge the case lacks, or a record shorter than the pulse, is refused with a clear message."""
    model, measured, start = setup
    with pytest.raises(InputError, match="g9.*not in the case"):
        calibrate(model, Measured("m", measured.time, {**measured.strains, "g9": measured.strains["g1"]}), start)
    short = measured.time < 7.5 + 250e-6
    with pytest.raises(InputError, match="shorter than the pulse"):
        calibrate(model, Measured("m", measured.time[short], {k: v[short] for k, v in measured.strains.items()}), start)


def _write(tmp_path, measured, nan=False):
    path = tmp_path / "measured.csv"
    y1 = measured.strains["g1"].copy()
    if nan:
        y1[300] = np.nan
    rows = ["time_s,strain_g1,strain_g2"] + [f"{float(a)!r},{float(b)!r},{float(c)!r}" for a, b, c in zip(measured.time, y1, measured.strains["g2"])]
    path.write_text("\n".join(rows) + "\n")
    return path


@pytest.mark.parametrize(
    "nan, velocity, message",
    [(True, "1166 in/s", "NaN"), (False, "9000 in/s", "outside the range")],
    ids=["NaN", "velocity out of range"],
)
def test_cli_bad_input_writes_nothing(tmp_path, setup, nan, velocity, message):
    """calibrate: NaN in the record or a velocity beyond the bar model: exit 2, a message, nothing written."""
    _, measured, _ = setup
    path = _write(tmp_path, measured, nan)
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["calibrate", "paper-long-beam", "--measured", str(path), "--velocity", velocity, "--out", str(out)])
    assert result.exit_code == 2 and message in result.output
    assert not out.exists() or not any(out.iterdir())


def test_cli_single_test_contract(tmp_path, setup):
    """calibrate with --measured writes calibration.json (F0, its SE, residuals) and history.csv."""
    import json

    _, measured, _ = setup
    path = _write(tmp_path, measured)
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["calibrate", "paper-long-beam", "--measured", str(path), "--velocity", "1166 in/s", "--out", str(out), "--no-figures"])
    assert result.exit_code == 0, result.output
    test = json.loads((out / "calibration.json").read_text())["tests"][0]
    for key in ("peak_force_N", "time_of_peak_s", "duration_s", "contact_radius_m", "peak_force_se_N", "method", "iterations", "residual_rms"):
        assert key in test
    assert test["peak_force_N"] == pytest.approx(TRUE.peak_force, rel=0.03)
    header = (out / "history.csv").read_text().splitlines()[0].split(",")
    assert header[:2] == ["time_s", "force_N"] and "measured_g1" in header and "computed_g2" in header
