"""Symmetry edges only where the laminate is orthotropic about the mirror plane (issue 23, item 2)."""

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact.cli import main
from softimpact.input.toml import locate
from softimpact.models.laminate import PLIES, Stack, parse_layup
from softimpact.models.plate_laminate import plate_section

QUARTER = {
    'x0 = "simply-supported"': 'x0 = "symmetry"',
    'y0 = "simply-supported"': 'y0 = "symmetry"',
    'position = ["4 in", "4 in"]': 'position = ["0 in", "0 in"]',
    'position = ["5 in", "4 in"]': 'position = ["1 in", "0 in"]',
    'position = ["4 in", "6 in"]': 'position = ["0 in", "2 in"]',
    "elements = [48, 48]": "elements = [8, 8]",
    'duration = "1000 us"': 'duration = "20 us"',
}


def _quarter_case(tmp_path, layup: str):
    text = locate("plate-ss-8in").read_text()
    for old, new in QUARTER.items():
        assert old in text
        text = text.replace(old, new)
    text = text.replace('layup = "[90/0]5s"', f'layup = "{layup}"')
    case = tmp_path / "quarter.toml"
    case.write_text(text)
    return case


def test_mirror_coupling_of_a_single_angle_stack_matches_the_closed_form():
    """[45]4s: D16/D11 = (Q11 − Q22)/(Q11 + Q22 + 2Q12 + 4Q66), from the classical rotation of the reduced stiffness."""
    ply = PLIES["T300/934"]
    d = 1.0 - ply.nu12**2 * ply.E2 / ply.E1
    Q11, Q22, Q66 = ply.E1 / d, ply.E2 / d, ply.G12
    Q12 = ply.nu12 * Q22
    expected = (Q11 - Q22) / (Q11 + Q22 + 2 * Q12 + 4 * Q66)
    found = plate_section(Stack(ply, parse_layup("[45]4s"))).mirror_coupling()
    assert found["D16"] == pytest.approx(expected, rel=1e-9)
    assert found["D26"] == pytest.approx(expected, rel=1e-9)


@pytest.mark.parametrize("layup", ["[90/0]5s", "[0/90]", "[0/90/0]"])
def test_cross_ply_stacks_carry_no_mirror_coupling(layup):
    """Plies at 0° and 90° only are orthotropic about both mirror planes: nothing to refuse."""
    assert plate_section(Stack(PLIES["T300/934"], parse_layup(layup))).mirror_coupling() == {}


@pytest.mark.parametrize("layup,term", [("[45]4s", "D16"), ("[45/0/-45/90]s", "D16"), ("[45/-45]s", "D26")])
def test_quarter_plate_of_a_coupled_laminate_is_refused(tmp_path, layup, term):
    """`softimpact plate` on a quarter model of a bending–twisting laminate: exit 2 naming the term, nothing written."""
    out = tmp_path / "out"
    r = CliRunner().invoke(main, ["plate", str(_quarter_case(tmp_path, layup)), "--out", str(out), "--no-figures"])
    assert r.exit_code == 2, r.output
    assert term in r.stderr and "symmetry" in r.stderr
    assert not out.exists()


def test_impact_on_a_coupled_quarter_plate_is_refused(tmp_path):
    """`softimpact impact` whose target is such a quarter plate: the same refusal, through the target case."""
    target = _quarter_case(tmp_path, "[45/0/-45/90]s")
    text = locate("plate-ss-8in-impact").read_text().replace('case = "plate-ss-8in"', f'case = "{target.name}"')
    case = tmp_path / "impact.toml"
    case.write_text(text)
    r = CliRunner().invoke(main, ["impact", str(case), "--out", str(tmp_path / "out"), "--no-figures"])
    assert r.exit_code == 2, r.output
    assert "D16" in r.stderr


def test_quarter_of_a_cross_ply_plate_still_runs(tmp_path):
    """The refusal does not touch what holds: the cross-ply quarter model runs (exit 0) with finite strains."""
    out = tmp_path / "out"
    r = CliRunner().invoke(main, ["plate", str(_quarter_case(tmp_path, "[90/0]5s")), "--out", str(out), "--no-figures"])
    assert r.exit_code == 0, r.output
    data = np.genfromtxt(out / "history.csv", delimiter=",", names=True)
    assert np.all(np.isfinite(data["strain_g1"]))
