"""Field output for ParaView (--fields, res.write_fields): XDMF time series read back with meshio against the model's own outputs."""

import json

import numpy as np
import pytest
from click.testing import CliRunner

import softimpact as si
from softimpact.cli import main
from softimpact.output.fields import FRAMES, beam_cell_strain, sampled_steps

from _support.small_cases import BEAM, PLATE


def _read(path):
    """(points, cells, [(t, point_data, cell_data)]) of an XDMF time series."""
    TimeSeriesReader = pytest.importorskip("meshio.xdmf").TimeSeriesReader  # the fields extra
    reader = TimeSeriesReader(str(path))
    points, cells = reader.read_points_cells()
    frames = [reader.read_data(k) for k in range(reader.num_steps)]
    return points, cells, frames


def _node(points, x, y):
    k = int(np.argmin((points[:, 0] - x) ** 2 + (points[:, 1] - y) ** 2))
    assert np.hypot(points[k, 0] - x, points[k, 1] - y) < 1e-12
    return k


def _cli(args, out):
    pytest.importorskip("meshio")  # the fields extra
    result = CliRunner().invoke(main, [*args, "--out", str(out), "--no-figures", "--fields"], catch_exceptions=False)
    assert result.exit_code == 0, result.output


def test_sampled_steps_keep_at_most_frames_evenly():
    """The sampled steps start at 0, are evenly spaced by ceil((n + 1)/frames) and number at most `frames`."""
    for steps in (10, 199, 200, 1000, 4001):
        s = sampled_steps(steps)
        k = -(-(steps + 1) // FRAMES)
        assert s[0] == 0 and len(s) <= FRAMES and np.all(np.diff(s) == k) and s[-1] <= steps < s[-1] + k


def test_cell_strain_of_a_linear_field_is_exact():
    """For u_x = a·x + b·z, u_z = c·x + d·z the centre strains are a, d and b + c on any rectangle (closed form)."""
    points = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 0.5], [0.0, 0.5], [3.5, 0.0], [3.5, 0.5]])
    cells = np.array([[0, 1, 2, 3], [1, 4, 5, 2]])
    a, b, c, d = 1e-3, -2e-4, 3e-4, 5e-5
    ux = (a * points[:, 0] + b * points[:, 1])[:, None]
    uz = (c * points[:, 0] + d * points[:, 1])[:, None]
    e = beam_cell_strain(points, cells, ux, uz)
    np.testing.assert_allclose(e["strain_xx"], a, rtol=1e-12)
    np.testing.assert_allclose(e["strain_zz"], d, rtol=1e-12)
    np.testing.assert_allclose(e["shear_strain_xz"], b + c, rtol=1e-12)


def test_beam_fields_from_the_command_match_the_deflection_output(tmp_path):
    """`softimpact beam --fields` writes fields.xdmf/.h5 (in the manifest); the top-face vertical displacement under the load read back equals the model's deflection output at the sampled steps."""
    case = tmp_path / "beam.toml"
    case.write_text(BEAM)
    out = tmp_path / "out"
    _cli(["beam", str(case)], out)
    manifest = json.loads((out / "manifest.json").read_text())
    names = {f["name"] if isinstance(f, dict) else f for f in manifest["files"]}
    assert {"fields.xdmf", "fields.h5"} <= names
    points, cells, frames = _read(out / "fields.xdmf")
    res = si.run(si.load(case))
    steps = sampled_steps(res.problem.solver.steps)
    assert len(frames) == len(steps) <= FRAMES
    h = res.problem.beam.thickness
    k = _node(points, 3 * 0.0254, h)
    scale = np.max(np.abs(res.result.deflection))
    for i in (1, len(steps) // 3, len(steps) - 1):
        t, pd, cd = frames[i]
        assert t == pytest.approx(res.time[steps[i]], rel=1e-12)
        assert pd["displacement"][k, 1] == pytest.approx(res.result.deflection[steps[i]], abs=1e-12 * scale)
        assert set(cd) == {"strain_xx", "strain_zz", "shear_strain_xz"}


def test_plate_fields_from_the_command_match_the_deflection_output(tmp_path):
    """`softimpact plate --fields`: w read back at the load point equals the model's deflection output at the sampled steps."""
    case = tmp_path / "plate.toml"
    case.write_text(PLATE)
    out = tmp_path / "out"
    _cli(["plate", str(case)], out)
    points, cells, frames = _read(out / "fields.xdmf")
    res = si.run(si.load(case), figures=False)
    steps = sampled_steps(res.problem.solver.steps)
    k = _node(points, 4 * 0.0254, 4 * 0.0254)
    w = res.result.deflection[0]
    for i in (2, len(steps) // 2, len(steps) - 1):
        t, pd, _ = frames[i]
        assert t == pytest.approx(res.time[steps[i]], rel=1e-12)
        assert pd["displacement"][k, 2] == pytest.approx(w[steps[i]], abs=1e-12 * np.max(np.abs(w)))


def test_impact_fields_match_the_coupled_deflection(tmp_path):
    """`res.write_fields` of a coupled beam impact: the mid-surface displacement under the impact point read back is minus the stepper's deflection (into the target +), and `softimpact impact --fields` writes the same file."""
    pytest.importorskip("meshio")  # the fields extra
    beam = si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(40, 4))
    res = si.impact(beam, at="3 in", impactor=si.Sphere("steel", "0.5 in", velocity="100 in/s"), time_step="1 us", duration="300 us")
    steps = res.write_fields(tmp_path / "api" / "fields.xdmf")
    points, _, frames = _read(tmp_path / "api" / "fields.xdmf")
    k = _node(points, 3 * 0.0254, res.problem.target.beam.thickness / 2)
    scale = np.max(np.abs(res.result.target_displacement))
    for i in (1, len(steps) // 2, len(steps) - 1):
        t, pd, _ = frames[i]
        assert t == pytest.approx(res.time[steps[i]], rel=1e-12)
        assert -pd["displacement"][k, 1] == pytest.approx(res.result.target_displacement[steps[i]], abs=1e-12 * scale)
    (tmp_path / "beam.toml").write_text(BEAM)
    (tmp_path / "impact.toml").write_text(
        '[target]\ncase = "beam.toml"\n[impactor]\nmaterial = "steel"\ndiameter = "0.5 in"\nvelocity = "100 in/s"\n'
        '[contact]\nlaw = "hertz"\n[solver]\ntime_step = "1 us"\nduration = "300 us"\n'
    )
    _cli(["impact", str(tmp_path / "impact.toml")], tmp_path / "cli")
    cli_points, _, cli_frames = _read(tmp_path / "cli" / "fields.xdmf")
    np.testing.assert_array_equal(cli_points, points)
    for (t1, a, _), (t2, b, _) in zip(cli_frames, frames):
        assert t1 == t2
        np.testing.assert_allclose(a["displacement"], b["displacement"], rtol=0, atol=1e-12 * scale)


@pytest.mark.parametrize("kind, text", [("beam", BEAM), ("plate", PLATE)])
def test_write_fields_writes_the_frames_of_the_command(tmp_path, kind, text):
    """`res.write_fields` of a run that kept no fields (figures=False) writes the mesh, times and fields `softimpact KIND --fields` writes for the same case."""
    case = tmp_path / f"{kind}.toml"
    case.write_text(text)
    _cli([kind, str(case)], tmp_path / "cli")
    res = si.run(si.load(case), figures=False)
    steps = res.write_fields(tmp_path / "api" / "fields.xdmf")
    api_points, api_cells, api_frames = _read(tmp_path / "api" / "fields.xdmf")
    cli_points, cli_cells, cli_frames = _read(tmp_path / "cli" / "fields.xdmf")
    np.testing.assert_array_equal(api_points, cli_points)
    assert len(api_frames) == len(cli_frames) == len(steps)
    for (t1, a, _), (t2, b, _) in zip(api_frames, cli_frames):
        assert t1 == t2
        np.testing.assert_array_equal(a["displacement"], b["displacement"])


def test_write_fields_frames_are_a_sampled_subset_of_the_command_s(tmp_path):
    """`write_fields(frames=n)` writes at most n frames, every ceil((steps + 1)/n)-th step from 0, each equal to the command's frame at the same time."""
    case = tmp_path / "plate.toml"
    case.write_text(PLATE)
    _cli(["plate", str(case)], tmp_path / "cli")
    res = si.run(si.load(case), figures=False)
    n_steps = res.problem.solver.steps
    n = 7
    steps = res.write_fields(tmp_path / "api" / "fields.xdmf", frames=n)
    k = -(-(n_steps + 1) // n)  # ceil, written independently of sampled_steps
    np.testing.assert_array_equal(steps, np.arange(0, n_steps + 1, k))
    _, _, api_frames = _read(tmp_path / "api" / "fields.xdmf")
    _, _, cli_frames = _read(tmp_path / "cli" / "fields.xdmf")
    assert len(api_frames) == len(steps) <= n
    cli_at = {t: pd for t, pd, _ in cli_frames}
    common = [(t, pd) for t, pd, _ in api_frames if t in cli_at]
    assert len(common) >= 2
    for t, pd in common:
        np.testing.assert_array_equal(pd["displacement"], cli_at[t]["displacement"])
