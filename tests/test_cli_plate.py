"""The plate command: contract files, quasi-static check against the Navier series, --history,
bad input refused with exit 2 and nothing written."""

import csv
import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact.cli import main
from softimpact.input.toml import locate
from softimpact.models.laminate import PLIES, Stack, parse_layup
from softimpact.models.plate_laminate import plate_section

from _support import plate_navier as nav
from _support.constants import INCH, LBF

BASE = locate("plate-ss-8in").read_text()
# 12 × 12 MITC4 elements for speed; MITC9 (`softimpact plate`'s default) on 6 × 6 has the same nodes.
SMALL = BASE.replace("elements = [48, 48]", 'elements = [12, 12]\nelement = "mitc4"').replace('duration = "1000 us"', 'duration = "100 us"')
SMALL9 = BASE.replace("elements = [48, 48]", "elements = [6, 6]").replace('duration = "1000 us"', 'duration = "100 us"')


def _run(tmp_path, text, *extra):
    case = tmp_path / "plate.toml"
    case.write_text(text)
    out = tmp_path / "out"
    return CliRunner().invoke(main, ["plate", str(case), "--out", str(out), *extra]), out


def _history(out):
    with open(out / "history.csv") as fh:
        rows = list(csv.reader(fh))
    return rows[0], np.array(rows[1:], float)


def test_contract_files_and_force_column(tmp_path):
    """history.csv has the contract's columns, the force column is eq 15 at the sampled times, the
    impulse is 2·F0·T/π, energy balances, and the figures are written."""
    result, out = _run(tmp_path, SMALL9.replace('duration = "100 us"', 'duration = "300 us"'))
    assert result.exit_code == 0, result.output
    header, data = _history(out)
    assert header == ["time_s", "force_N", "deflection_m", "strain_g1", "strain_g2"]
    t, F = data[:, 0], data[:, 1]
    F0, tp, T = 100 * LBF, 20e-6, 250e-6
    expected = np.where(t < tp, F0 * np.sin(np.pi * t / (2 * tp)), np.where(t < T, F0 * np.cos(np.pi * (t - tp) / (2 * (T - tp))), 0.0))
    assert np.max(np.abs(F - expected)) < 1e-9 * F0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["impulse_N_s"] == pytest.approx(2 * F0 * T / math.pi, rel=1e-4)
    assert summary["element"] == "mitc9"  # softimpact plate's default
    assert summary["energy_balance_relative"] < 1e-9
    assert summary["peak_deflection_at_load_m"] < 0  # pushed down
    assert {p.name for p in out.iterdir()} == {"history.csv", "summary.json", "plate-mesh.png", "deflection.png", "histories.png", "manifest.json"}


def test_slow_load_gives_the_navier_static_deflection(tmp_path):
    """A half-sine 400 ms long (fundamental ~300 Hz: the free vibration its start excites is ~0.4 % of
    the static deflection) loads the plate quasi-statically: at the peak the centre deflection is F0
    times the FSDT Navier static series (written here) within 2 % on 8 × 8 MITC9 (the default element)."""
    text = (
        SMALL9.replace("elements = [6, 6]", "elements = [8, 8]")
        .replace('time_of_peak = "20 us", duration = "250 us"', 'time_of_peak = "200 ms", duration = "400 ms"')
        .replace('time_step = "1 us"', 'time_step = "200 us"')
        .replace('duration = "100 us"', 'duration = "200 ms"')
        .replace('contact_radius = "0.25 in"', 'contact_radius = "0.5 in"')
    )
    result, out = _run(tmp_path, text, "--no-figures")
    assert result.exit_code == 0, result.output
    _, data = _history(out)
    sec = plate_section(Stack(PLIES["T300/934"], parse_layup("[90/0]5s")))
    a = 8 * INCH
    m = np.arange(1, 200, 2)
    al, be = np.meshgrid(m * math.pi / a, m * math.pi / a, indexing="ij")
    q = nav.cosine_patch_coefficients(a, a, a / 2, a / 2, 0.5 * INCH, m, m)
    K, _ = nav.mode_matrices(sec.D, sec.S, sec.I0, sec.I2, al, be)
    rhs = np.zeros(al.shape + (3, 1))
    rhs[..., 0, 0] = -q * 100 * LBF
    W = np.linalg.solve(K, rhs)[..., 0, 0]
    w_static = np.einsum("mn,m,n->", W, np.sin(m * math.pi / 2), np.sin(m * math.pi / 2))
    assert data[-1, 2] == pytest.approx(w_static, rel=0.02)


def test_history_row_and_no_figures(tmp_path):
    """--history 2 runs the second [[load.table]] row; --no-figures writes only the numbers."""
    rows = '[[load.table]]\npeak_force = "50 lbf"\ntime_of_peak = "20 us"\nduration = "250 us"\n\n'
    rows += '[[load.table]]\npeak_force = "80 lbf"\ntime_of_peak = "25 us"\nduration = "200 us"\n\n'
    result, out = _run(tmp_path, SMALL.replace("[solver]", rows + "[solver]", 1), "--history", "2", "--no-figures")
    assert result.exit_code == 0, result.output
    summary = json.loads((out / "summary.json").read_text())
    assert summary["peak_force_N"] == pytest.approx(80 * LBF, rel=1e-3)
    assert {p.name for p in out.iterdir()} == {"history.csv", "summary.json", "manifest.json"}


@pytest.mark.parametrize(
    "old, new, key",
    [
        ('position = ["5 in", "4 in"]', 'position = ["8.5 in", "4 in"]', "gauge g1"),
        ('position = ["4 in", "4 in"]', 'position = ["0.1 in", "4 in"]', "load position"),
        ('x0 = "simply-supported"', 'x0 = "hinged"', "plate.support.x0"),
        ("elements = [12, 12]", "elements = [1, 12]", "plate.elements"),
        (
            'support = { x0 = "simply-supported", x1 = "simply-supported", y0 = "simply-supported", y1 = "simply-supported" }',
            'support = { x0 = "free", x1 = "free", y0 = "simply-supported", y1 = "free" }',
            "mechanism",
        ),
        ('model = "fsdt"', 'model = "solid"', "not implemented"),
        ('direction = "x"', 'direction = "z"', "direction"),
        ('time_step = "1 us"', 'time_step = "10 us"', "time_step"),
    ],
    ids=["gauge off plate", "load off plate", "unknown support", "too few elements", "mechanism", "solid", "direction", "time step"],
)
def test_bad_input(tmp_path, old, new, key):
    """Each bad value: exit 2, one line naming it, nothing written."""
    assert old in SMALL
    result, out = _run(tmp_path, SMALL.replace(old, new, 1))
    assert result.exit_code == 2, result.output
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert len(lines) == 1 and key in lines[0], lines
    assert not out.exists() or not any(out.iterdir())


def test_bad_history_row(tmp_path):
    """--history beyond the [[load.table]] rows: exit 2."""
    result, out = _run(tmp_path, SMALL, "--history", "3")
    assert result.exit_code == 2 and "load.table" in result.output
    assert not out.exists()


def test_quarter_case_with_symmetry_edges_equals_the_full_case(tmp_path):
    """The contract case on 12 × 12 and its quarter (x, y ≥ 4 in, symmetry on x0 and y0, load at the
    corner) on 6 × 6 write the same history.csv deflection and strains to round-off."""
    full, out_full = _run(tmp_path, SMALL, "--no-figures")
    quarter_text = (
        SMALL.replace('length = "8 in"', 'length = "4 in"')
        .replace('width = "8 in"', 'width = "4 in"')
        .replace("elements = [12, 12]", "elements = [6, 6]")
        .replace('x0 = "simply-supported"', 'x0 = "symmetry"')
        .replace('y0 = "simply-supported"', 'y0 = "symmetry"')
        .replace('position = ["4 in", "4 in"]', 'position = ["0 in", "0 in"]')
        .replace('position = ["5 in", "4 in"]', 'position = ["1 in", "0 in"]')
        .replace('position = ["4 in", "6 in"]', 'position = ["0 in", "2 in"]')
    )
    case = tmp_path / "quarter.toml"
    case.write_text(quarter_text)
    out_q = tmp_path / "outq"
    quarter = CliRunner().invoke(main, ["plate", str(case), "--out", str(out_q), "--no-figures"])
    assert full.exit_code == 0 and quarter.exit_code == 0, quarter.output
    (_, a), (_, b) = _history(out_full), _history(out_q)
    assert np.max(np.abs(a[:, 2:] - b[:, 2:]) / np.max(np.abs(a[:, 2:]), axis=0)) < 1e-9


def test_a_symmetry_edge_that_misses_the_load_is_warned_of(tmp_path):
    """A symmetry edge away from the load models the load mirrored about it (two loads): the run goes on
    with a warning naming the edge; the same edge through the load (a half model) draws none."""
    text = SMALL9.replace('y1 = "simply-supported"', 'y1 = "symmetry"')
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    r, _ = _run(tmp_path / "a", text, "--no-figures")
    assert r.exit_code == 0 and "warning: plate.support.y1" in r.output and "mirrored" in r.output
    half = text.replace('width = "8 in"', 'width = "4 in"').replace('position = ["4 in", "6 in"]', 'position = ["4 in", "2 in"]')
    r, _ = _run(tmp_path / "b", half, "--no-figures")
    assert r.exit_code == 0 and "mirrored" not in r.output
