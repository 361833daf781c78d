"""``softimpact plate`` on static pressure cases (von Kármán and linear) against independent solutions, on a
force history with von Kármán kinematics (small-load limit, energy, quasi-static limit), the plate summaries'
``kinematics``, and the von Kármán keys' errors (exit 2, the key named)."""

import json

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact.cli import main
from softimpact.input.toml import locate

from _support import plate_vk_ritz as ritz

PSI = 6894.757293168  # Pa (exact: lbf/in² with the international inch and pound)
INCH = 0.0254  # m
# The built-in case's plate (data/cases/plate-ss-pressure-vk.toml): a = 10 in, h = 0.1 in, E = 10 Msi, ν = 0.3, 20 psi.
A, H, E, NU, Q = 10 * INCH, 0.1 * INCH, 10e6 * PSI, 0.3, 20 * PSI
STATIC = locate("plate-ss-pressure-vk").read_text()
DYNAMIC = locate("plate-ss-8in").read_text().replace("elements = [48, 48]", "elements = [4, 4]").replace('duration = "1000 us"', 'duration = "20 us"')


def _run(tmp_path, text, *extra):
    tmp_path.mkdir(parents=True, exist_ok=True)
    case = tmp_path / "plate.toml"
    case.write_text(text)
    out = tmp_path / "out"
    return CliRunner().invoke(main, ["plate", str(case), "--out", str(out), *extra]), out


def test_builtin_large_deflection_case_matches_the_ritz_series(tmp_path):
    """The built-in von Kármán case run by the command: w0/h within 2 % of the independent Ritz series, Newton converged in every load step."""
    result = CliRunner().invoke(main, ["plate", "plate-ss-pressure-vk", "--out", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    s = json.loads((tmp_path / "out" / "summary.json").read_text())
    w_ritz = ritz.centre_deflections(np.array([0.5, 1.0]) * Q, a=A, h=H, E=E, nu=NU, clamped=False, n_w=5, n_u=8, n_quad=32)[-1]
    assert w_ritz / H > 1.5  # the large-deflection regime: the linear plate would be far off
    assert s["max_deflection_m"] == pytest.approx(w_ritz, rel=0.02)
    assert s["kinematics"] == "von-karman" and s["in_plane"] == "immovable"
    newton = s["newton"]
    assert newton["converged"] and len(newton["iterations"]) == 10
    assert max(newton["iterations"]) <= 8  # full Newton from the previous load step converges quadratically
    assert s["validity"]["flags"] == []  # von Kármán is the model past w/h = 0.5: no linear-theory flag


def test_linear_static_case_gives_navier_and_flags_the_envelope(tmp_path):
    """kinematics = "linear" on the same case: the Navier deflection 0.00406 q a⁴/D (Timoshenko & Woinowsky-Krieger §30) within 1 %, and the linear envelope's flag."""
    result, out = _run(tmp_path, STATIC.replace('kinematics = "von-karman"', 'kinematics = "linear"'))
    assert result.exit_code == 0, result.output
    s = json.loads((out / "summary.json").read_text())
    D = E * H**3 / (12 * (1 - NU**2))
    assert s["kinematics"] == "linear"
    assert s["max_deflection_m"] == pytest.approx(0.00406 * Q * A**4 / D, rel=0.01)
    assert s["newton"]["converged"]
    assert any("linear plate theory" in f for f in s["validity"]["flags"])


def test_movable_edges_deflect_more_than_immovable(tmp_path):
    """in_plane = "movable" lets the edges draw in: less membrane stiffening, a larger deflection (still below the linear one)."""
    result, out = _run(tmp_path, STATIC.replace('in_plane = "immovable"', 'in_plane = "movable"'))
    assert result.exit_code == 0, result.output
    movable = json.loads((out / "summary.json").read_text())["max_deflection_m"]
    w_ritz = ritz.centre_deflections(np.array([0.5, 1.0]) * Q, a=A, h=H, E=E, nu=NU, clamped=False, n_w=3, n_u=6, n_quad=32)[-1]
    D = E * H**3 / (12 * (1 - NU**2))
    assert 1.05 * w_ritz < movable < 0.00406 * Q * A**4 / D


def test_dynamic_plate_summary_states_linear_kinematics(tmp_path):
    """A dynamic plate run (no kinematics key) states kinematics "linear" in summary.json."""
    result, out = _run(tmp_path, DYNAMIC, "--no-figures")
    assert result.exit_code == 0, result.output
    assert json.loads((out / "summary.json").read_text())["kinematics"] == "linear"


@pytest.mark.parametrize(
    "text,key",
    [
        (STATIC.replace('kinematics = "von-karman"', 'kinematics = "vonkarman"'), "plate.kinematics"),
        (STATIC.replace('in_plane = "immovable"', 'in_plane = "fixed"'), "plate.in_plane"),
        (STATIC.replace('analysis = "static"', 'analysis = "steady"'), "solver.analysis"),
        (STATIC.replace('analysis = "static"\n', ""), "load.pressure"),
        (STATIC.replace('pressure = "20 psi"', 'pressure = "-2 psi"'), "load.pressure"),
        (STATIC.replace("load_steps = 10", "load_steps = 0"), "solver.load_steps"),
        (STATIC.replace('pressure = "20 psi"', 'position = ["1 in", "1 in"]'), "load.pressure"),
        (DYNAMIC.replace('duration = "20 us"', 'duration = "20 us"\nload_steps = 3'), "solver.load_steps"),
    ],
)
def test_bad_large_deflection_keys_are_refused(tmp_path, text, key):
    """A wrong or misplaced kinematics, in_plane, analysis, pressure or load_steps exits 2 naming the key, and writes nothing."""
    result, out = _run(tmp_path, text)
    assert result.exit_code == 2, result.output
    assert key in result.output
    assert not out.exists() or not any(out.iterdir())


def test_converge_refuses_a_static_plate_case(tmp_path):
    """softimpact converge on the static von Kármán case exits 2 with a reason naming the keys it needs (only linear dynamic plates are wired there)."""
    result = CliRunner().invoke(main, ["converge", "plate-ss-pressure-vk", "--out", str(tmp_path / "out"), "--no-figures"])
    assert result.exit_code == 2, result.output
    assert "solver.analysis" in result.output


H8 = 0.110 * INCH  # plate-ss-8in's thickness [m]
VK_DYNAMIC = DYNAMIC.replace('model = "fsdt"', 'model = "fsdt"\nkinematics = "von-karman"')


def _deflection(out):
    import csv

    with open(out / "history.csv") as fh:
        rows = list(csv.reader(fh))
    return np.array([float(r[rows[0].index("deflection_m")]) for r in rows[1:]])


@pytest.mark.parametrize("scale,tol,balance", [(0.1, 1e-3, 1e-6), (60.0, None, 1e-3)])
def test_dynamic_von_karman_plate_against_the_linear_plate(tmp_path, scale, tol, balance):
    """Under a tenth of the built-in pulse (w/h ~ 0.01) the von Kármán plate's deflection history is the linear plate's to 1e-3 and
    its energy balances to 1e-6 of the work; 60 times the force (w/h > 1) stiffens it (peak > 10 % below the linear one)
    and the balance holds to 1e-3 (average acceleration conserves energy exactly for linear forces only: with von Kármán
    its error is O(dt²), tests/test_plate_vk.py)."""
    out = {}
    for kin, text in (("linear", DYNAMIC), ("von-karman", VK_DYNAMIC)):
        text = text.replace('peak_force = "100 lbf"', f'peak_force = "{100 * scale:g} lbf"').replace('duration = "20 us"', 'duration = "150 us"')
        result, o = _run(tmp_path / kin, text, "--no-figures")
        assert result.exit_code == 0, result.output
        out[kin] = (_deflection(o), json.loads((o / "summary.json").read_text()))
    (w_lin, s_lin), (w_vk, s_vk) = out["linear"], out["von-karman"]
    assert s_lin["kinematics"] == "linear"
    assert s_vk["kinematics"] == "von-karman" and s_vk["energy_balance_relative"] < balance
    peak_lin, peak_vk = np.abs(w_lin).max(), np.abs(w_vk).max()
    if tol is not None:
        assert np.abs(w_vk - w_lin).max() <= tol * peak_lin
    else:
        assert peak_vk / H8 > 1 and peak_vk < 0.9 * peak_lin
        assert not any("linear plate theory" in f for f in s_vk["validity"]["flags"])
