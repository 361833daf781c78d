"""`softimpact converge`: the estimated discretisation error against the error measured on a much finer run."""

import csv
import json
from dataclasses import replace

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact.cases import KINDS
from softimpact.cli import main
from softimpact.fem.newmark import SolverSpec
from softimpact.input.bar_case import load_bar_case
from softimpact.input.toml import locate
from softimpact.workflows.bar_impact import simulate_impact
from softimpact.workflows.convergence import study_case
from softimpact.workflows.refinement import coarsen_beam, refine_bar

# A coarse, short beam: the levels ×1, ×2, ×4 run in a few seconds.
SMALL_BEAM = (
    locate("paper-short-beam")
    .read_text()
    .replace("elements = [200, 6]", "elements = [40, 2]")
    .replace('duration = "1000 us"', 'duration = "200 us"')
    .replace('time_step = "1 us"', 'time_step = "2 us"')
)


def _bar_short():
    problem, _ = load_bar_case("paper-calibration")
    return replace(problem, solver=SolverSpec(0.5e-6, 100e-6, problem.solver.newmark))


def test_bar_estimate_bounds_the_true_error():
    """Bar (39 elements, 0.5 µs; ×2, ×4): the observed order of the peak force and the force history
    is near the formal 2, and the error estimated for the case's own level agrees (within a factor 1.5)
    with its error against an independent run 16 times finer."""
    problem = _bar_short()
    result, sizes = study_case(KINDS["bar"], problem, 3, 2)
    fine = simulate_impact(refine_bar(problem, 16))
    assert [s["factor"] for s in sizes] == [1, 2, 4]
    for name in ("peak_force_N", "contact_force_history_N"):
        o = result[name]
        assert o.status == "asymptotic" and 1.6 < o.order < 2.4, (name, o.order)
    true_peak = abs(result["peak_force_N"].values[0] - fine.peak_force) / fine.peak_force
    assert result["peak_force_N"].errors[0] == pytest.approx(true_peak, rel=0.5)
    ref = fine.force[::16]
    coarse = result["contact_force_history_N"].values[0]
    true_hist = np.sqrt(np.mean((coarse - ref) ** 2)) / np.sqrt(np.mean(ref**2))
    assert result["contact_force_history_N"].errors[0] == pytest.approx(true_hist, rel=0.5)
    # The GCI of the finest level is a bound of its true error (Roache's safety factor 1.25).
    fine3 = result["peak_force_N"].values[-1]
    assert abs(fine3 - fine.peak_force) / fine.peak_force < result["peak_force_N"].gci_fine


def test_cli_beam_contract(tmp_path):
    """`converge` on a beam case: convergence.csv (one row per output), summary.json, figures; orders near 2."""
    case = tmp_path / "beam.toml"
    case.write_text(SMALL_BEAM)
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["converge", str(case), "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert "from converged" in result.output
    rows = list(csv.DictReader((out / "convergence.csv").open()))
    names = {r["output"] for r in rows}
    assert {"strain_g1_history", "strain_g2_history", "strain_g1_peak_magnitude", "peak_deflection_under_load_m"} <= names
    assert set(rows[0]) >= {"status", "observed_order", "extrapolated", "relative_error_level_1", "relative_error_level_3", "gci_fine"}
    hist = next(r for r in rows if r["output"] == "strain_g1_history")
    assert float(hist["relative_error_level_1"]) > float(hist["relative_error_level_2"]) > float(hist["relative_error_level_3"])
    summary = json.loads((out / "summary.json").read_text())
    assert [lv["elements"] for lv in summary["levels"]] == [[40, 2], [80, 4], [160, 8]]
    assert [lv["time_step_s"] for lv in summary["levels"]] == pytest.approx([2e-6, 1e-6, 0.5e-6])
    assert (out / "convergence.png").stat().st_size > 10_000 and (out / "histories.png").exists()


@pytest.mark.parametrize(
    "args, needle",
    [
        (["--levels", "1"], "--levels"),
        (["--levels", "9"], "--levels"),
        (["--ratio", "1"], "--ratio"),
    ],
)
def test_cli_bad_options(tmp_path, args, needle):
    """Bad options: one line, exit 2, nothing written."""
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["converge", "paper-calibration", "--out", str(out), *args])
    assert result.exit_code == 2 and needle in result.output and len(result.output.strip().splitlines()) == 1
    assert not out.exists()


def test_cli_refuses_a_study_too_big_for_the_machine(tmp_path):
    """Five levels at ratio 4 make the finest beam 3200 × 96 over 16 000 steps: refused before
    the first level runs, with the estimate, exit 2, nothing written."""
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["converge", "paper-long-beam", "--levels", "5", "--ratio", "4", "--out", str(out)])
    assert result.exit_code == 2 and "3200 x 96" in result.output and "memory" in result.output
    assert not out.exists()


def test_cli_refuses_a_plate_study_too_big_for_the_machine(tmp_path):
    """The built-in 48 × 48 MITC9 plate at three levels of ratio 4 (192 × 192 over 4000 steps, then
    768 × 768 over 16 000): refused before the first level runs, as `softimpact plate` refuses those
    meshes, with the estimate and the way past the guard; exit 2."""
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["converge", "plate-ss-8in", "--levels", "3", "--ratio", "4", "--out", str(out)])
    assert result.exit_code == 2 and "MITC9 plate" in result.output and "--ignore-limits" in result.output
    assert not out.exists()


def test_cli_refuses_series_and_bar_history(tmp_path):
    """A series is not a case; a bar case has no --history: one line, exit 2."""
    r1 = CliRunner().invoke(main, ["converge", "paper-rubber-series", "--out", str(tmp_path / "a")])
    assert r1.exit_code == 2 and "series" in r1.output
    r2 = CliRunner().invoke(main, ["converge", "paper-calibration", "--history", "2", "--out", str(tmp_path / "b")])
    assert r2.exit_code == 2 and "history" in r2.output


def test_coarsen_beam_checks_divisibility():
    """Coarsening needs element counts divisible by the factor; it scales dt up by it."""
    from softimpact.errors import InputError
    from softimpact.input.beam_case import load_beam_case

    problem, _ = load_beam_case("paper-long-beam")
    coarse = coarsen_beam(problem, 2)
    assert (coarse.beam.nx, coarse.beam.nz, coarse.solver.time_step) == (100, 3, pytest.approx(2e-6))
    with pytest.raises(InputError, match="divide"):
        coarsen_beam(problem, 4)


def test_cli_plate_errors_fall_with_refinement(tmp_path):
    """`converge` on a plate case (12 × 12, ×2, ×4): the deflection history's error against the
    extrapolation falls at every level, and the summary lists the plate's element counts."""
    case = tmp_path / "plate.toml"
    text = locate("plate-ss-8in").read_text().replace("elements = [48, 48]", 'elements = [12, 12]\nelement = "mitc4"')
    case.write_text(text.replace('duration = "1000 us"', 'duration = "300 us"'))
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["converge", str(case), "--out", str(out), "--no-figures"])
    assert result.exit_code == 0, result.output
    rows = {r["output"]: r for r in csv.DictReader((out / "convergence.csv").open())}
    e = [float(rows["deflection_at_load_history_m"][f"relative_error_level_{k}"]) for k in (1, 2, 3)]
    assert e[0] > e[1] > e[2]
    summary = json.loads((out / "summary.json").read_text())
    assert [lv["elements"] for lv in summary["levels"]] == [[12, 12], [24, 24], [48, 48]]


def test_cli_bar_reports_the_hermite_rods_true_dof_count(tmp_path):
    """`converge paper-calibration` reports the DOFs of the rod that ran: Hermite elements carry an axial
    displacement and a strain per node, so 39 elements (40 nodes) are 80 DOFs, ×2 refined 158, ×4 314."""
    r = CliRunner().invoke(main, ["converge", "paper-calibration", "--out", str(tmp_path / "out"), "--no-figures"])
    assert r.exit_code == 0, r.output
    levels = json.loads((tmp_path / "out" / "summary.json").read_text())["levels"]
    for level, factor in zip(levels, (1, 2, 4)):
        nodes = 39 * factor + 1
        assert level["elements"] == [39 * factor] and level["dofs"] == 2 * nodes


@pytest.mark.slow
def test_cli_impact_case_peak_force_converges_at_second_order(tmp_path):
    """`converge` on a coupled impact case (steel ball on the long beam, Hertz): the first contact's peak
    force converges monotonically at an observed order near 2 (average-acceleration Newmark and
    linear elements are both second order), its two finest levels within 0.1 %, and the levels
    report the beam model's DOFs: 2 per node of the nx × nz Q4 mesh, less the nz + 1 nodes held
    at the clamped end (the long beam is clamped-free)."""
    case = tmp_path / "impact.toml"
    case.write_text(
        'units = "in-lbf-s"\n[target]\ncase = "paper-long-beam"\n[impactor]\nmaterial = "steel"\ndiameter = "0.5 in"\nvelocity = "100 in/s"\n'
        '[contact]\nlaw = "hertz"\ntarget_modulus = "7.9 GPa"\n[solver]\ntime_step = "1 us"\nduration = "150 us"\n'
    )
    r = CliRunner().invoke(main, ["converge", str(case), "--out", str(tmp_path / "out"), "--no-figures"])
    assert r.exit_code == 0, r.output
    s = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert s["kind"] == "impact"
    peak = s["outputs"]["peak_force_N"]
    assert peak["status"] == "asymptotic" and 1.5 < peak["observed_order"] < 2.5, peak
    v = peak["values"]
    assert abs(v[2] - v[1]) / abs(v[2]) < 1e-3
    for level in s["levels"]:
        nx, nz = level["elements"]
        assert level["dofs"] == 2 * (nx + 1) * (nz + 1) - 2 * (nz + 1)


def test_cases_lists_each_builtin_with_its_kind():
    """`softimpact cases` names each built-in's kind from the one registry: the bar calibration case, the
    paper's beams, the plate, the impact cases and the series (told by their [[test]] tables)."""
    r = CliRunner().invoke(main, ["cases"])
    assert r.exit_code == 0, r.output
    kinds = {line.split()[0]: line.split()[1] for line in r.output.strip().splitlines()}
    assert kinds["paper-calibration"] == "bar" and kinds["paper-long-beam"] == "beam" and kinds["plate-ss-8in"] == "plate"
    assert kinds["paper-long-beam-impact"] == kinds["plate-ss-8in-impact"] == "impact" and kinds["paper-rubber-series"] == "series"
