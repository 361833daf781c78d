"""Coupled impacts on a metal skin (workflows/plate with an elastic–plastic section): the energy balance with the plastic
work, the dent, the elastic run's yield flag, and the case keys of a metal plate."""

from __future__ import annotations

import pytest

from softimpact.errors import InputError

PLATE = """
title = "Quarter of a clamped 250 x 250 mm Al 2024-T3 panel, 2 mm"
units = "SI"
[plate]
length = "125 mm"
width = "125 mm"
elements = [6, 6]
support = { x0 = "symmetry", x1 = "clamped", y0 = "symmetry", y1 = "clamped" }
kinematics = "von-karman"
%s
[load]
position = ["0 mm", "0 mm"]
contact_radius = "10 mm"
history = { shape = "skewed", peak_force = "2 kN", time_of_peak = "50 us", duration = "300 us" }
[solver]
time_step = "2 us"
duration = "600 us"
"""
METAL = 'material = "Al 2024-T3"\nthickness = "2 mm"'
IMPACT = """
[target]
case = "plate.toml"
[impactor]
material = "steel"
diameter = "20 mm"
velocity = "%g m/s"
[contact]
law = "hertz"
[solver]
time_step = "2 us"
duration = "600 us"
"""


def _problem(folder, velocity: float, plate: str = METAL):
    """A 20-mm steel sphere (Hertz) at ``velocity`` on the centre of a quarter of a clamped 250-mm Al 2024-T3 skin, 2 mm,
    6 × 6 MITC9 (``plate``: the [plate] keys of its section), as the impact command reads it."""
    from softimpact.input.impact_case import load_impact_case

    (folder / "plate.toml").write_text(PLATE % plate)
    (folder / "impact.toml").write_text(IMPACT % velocity)
    return load_impact_case(str(folder / "impact.toml"))[0]


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """Four runs through the impact command's path: 25 m/s elastic-plastic and elastic, 1 m/s elastic-plastic and elastic."""
    from softimpact.cases import KINDS

    out = {}
    for v in (25.0, 1.0):
        for plastic in (None, False):
            plate = METAL + ("" if plastic is None else "\nplasticity = false")
            out[(v, plastic)] = KINDS["impact"].execute(_problem(tmp_path_factory.mktemp("run"), v, plate))
    return out


def test_energy_balances_with_the_plastic_work(runs):
    """Impactor KE + structure KE + elastic energy + plastic work + contact work = KE0 to 1e-3 of KE0 (summary.json's
    energy_balance_relative: the plastic work counted from the state, σ_{n+1}·Δεᵖ at each commit, not as a remainder);
    the plastic work positive and below the impact energy."""
    run = runs[(25.0, None)]
    ke0 = 0.5 * run.problem.impactor.mass * 25.0**2
    assert run.summary["energy_balance_relative"] <= 1e-3
    assert 0 < run.summary["damage"]["plastic_work_J"] < ke0


def test_a_hard_impact_dents_and_a_gentle_one_does_not(runs):
    """25 m/s leaves a dent (positive, into the plate) and a plastic zone; at 1 m/s the skin stays elastic: no plastic work,
    no zone and a rest shape flat to 1e-6 of the thickness."""
    hard, gentle = runs[(25.0, None)].summary["damage"], runs[(1.0, None)].summary["damage"]
    assert hard["dent_depth_m"] > 0 and hard["plastic_zone_area_m2"] > 0
    assert gentle["plastic_work_J"] == 0 and gentle["plastic_zone_area_m2"] == 0
    assert abs(gentle["dent_depth_m"]) < 1e-6 * 2e-3


def test_an_elastic_skin_past_yield_is_flagged(runs):
    """Run elastically (plasticity = false), the 25 m/s impact's von Mises stress passes yield and the run carries the
    elastic_past_yield flag; at 1 m/s the stress stays below yield, unflagged — consistent with the elastic–plastic runs,
    which yield at 25 m/s and not at 1 m/s."""
    hard, gentle = runs[(25.0, False)], runs[(1.0, False)]
    assert hard.summary["damage"]["max_von_mises_over_yield"] > 1
    assert "elastic_past_yield" in hard.warnings.names
    assert gentle.summary["damage"]["max_von_mises_over_yield"] < 1
    assert "elastic_past_yield" not in gentle.warnings.names


@pytest.mark.slow
def test_a_perfectly_plastic_skin_dents_deeper_than_a_hardening_one(runs, tmp_path):
    """Of the same impact, an inline metal with the catalogue 2024-T3's elastic constants and yield but no hardening
    (perfectly plastic) keeps a deeper dent than the catalogue's (hardening 0.8 GPa)."""
    from softimpact.cases import KINDS

    perfect = 'material = { youngs_modulus = "73 GPa", poisson_ratio = 0.33, density = "2780 kg/m^3", yield_stress = "345 MPa" }\nthickness = "2 mm"'
    soft = KINDS["impact"].execute(_problem(tmp_path, 25.0, perfect)).summary["damage"]["dent_depth_m"]
    assert soft > runs[(25.0, None)].summary["damage"]["dent_depth_m"]


@pytest.mark.parametrize(
    "plate, message",
    [
        ('material = "Al 2024-T3"', "thickness"),
        ('material = "unobtainium"\nthickness = "2 mm"', "unknown metal"),
        ('material = "Al 2024-T3"\nthickness = "2 mm"\n[plate.laminate]\nply = "T300/934"\nlayup = "[0]4"', "not both"),
        ('plasticity = true\n[plate.laminate]\nply = "T300/934"\nlayup = "[0]4"', "metal"),
        (
            'material = { youngs_modulus = "70 GPa", poisson_ratio = 0.33, density = "2700 kg/m^3", yield_stress = "900 GPa" }\nthickness = "2 mm"',
            "yield stress",
        ),
    ],
)
def test_metal_plate_keys_are_checked(tmp_path, plate, message):
    """A metal plate needs its thickness, a known metal, no laminate beside it; a laminate takes no plasticity; an inline
    metal's yield stress must lie below its modulus: each a one-line InputError naming the key."""
    from softimpact.input.plate_case import load_plate_case

    (tmp_path / "plate.toml").write_text(PLATE % plate)
    with pytest.raises(InputError, match=message):
        load_plate_case(str(tmp_path / "plate.toml"))
