"""Bird threats: ``threat = { bird = ... }`` builds the gelatin substitute (a hemispherical-ended cylinder, L/D = 2),
its hydrodynamic law acts on the cylinder's section for L/V, and the edges (case files, si.bird, summary.json) carry
it; each number checked against an independent computation or a closed form."""

import json
import math

import pytest
from click.testing import CliRunner
from scipy.integrate import quad
from scipy.optimize import brentq

import softimpact as si
from softimpact.cli import main
from softimpact.errors import InputError
from softimpact.input.impact_case import impact_problem, load_impact_case
from softimpact.input.toml import load_toml, locate
from softimpact.models.capsule import capsule_advance, capsule_crushed_volume, capsule_depth, capsule_section, capsule_volume
from softimpact.models.crushing_law import centre_of_mass_advance, rigid_target_pulse
from softimpact.models.hydrodynamic_law import HydrodynamicCapsuleLaw, HydrodynamicLaw
from softimpact.models.threats import substitute_bird

POUND = 0.45359237  # kg, the international avoirdupois pound (exact by definition)
RHO = 950.0  # kg/m^3, Wilbeck's gelatin as the project cites it (models/threats.py)


def _diameter_by_root(mass: float, density: float, aspect: float = 2.0) -> float:
    """D solving m/ρ = (cylinder of length (λ − 1)·D) + (sphere of D), by root finding: independent of the code's
    closed form."""
    return brentq(lambda d: math.pi * d * d / 4 * (aspect - 1) * d + math.pi * d**3 / 6 - mass / density, 1e-4, 10.0, xtol=1e-15)


def _case(**impactor) -> dict:
    """The gelatin-plate case (the quasi-isotropic plate) with ``impactor`` as its [impactor] table."""
    data = load_toml(locate("gelatin-plate"))
    data["impactor"] = impactor
    return data


@pytest.mark.parametrize("mass", [1.0, 1.8, 4 * POUND, 8 * POUND])
def test_diameter_from_mass_matches_the_volume_solved_independently(mass):
    """D = (12·m/(5·π·ρ))^(1/3) of an L/D = 2 capsule matches the diameter whose cylinder-plus-sphere volume holds m."""
    bird = substitute_bird(mass)
    assert bird.diameter == pytest.approx(_diameter_by_root(mass, RHO), rel=1e-12)
    assert bird.length == pytest.approx(2 * bird.diameter, rel=1e-15)
    assert RHO * capsule_volume(bird.diameter, bird.length) == pytest.approx(mass, rel=1e-12)


def test_four_pounds_read_as_1814_grams():
    """``bird = "4 lb"`` is 4 × 0.45359237 kg = 1.814 kg, the 4-lb bird of the rules."""
    problem, _ = impact_problem(_case(threat={"bird": "4 lb"}, velocity="150 m/s"), locate("gelatin-plate").parent)
    assert problem.impactor.mass == pytest.approx(4 * POUND, rel=1e-12)
    assert round(problem.impactor.mass, 3) == 1.814
    assert problem.threat.mass == problem.impactor.mass


def test_density_key_changes_the_diameter():
    """A substitute of 938 kg/m³ (``threat.density``) is wider, by the independent root of its own volume."""
    problem, _ = impact_problem(_case(threat={"bird": "1.8 kg", "density": "938 kg/m^3"}, velocity="150 m/s"), locate("gelatin-plate").parent)
    assert problem.impactor.diameter == pytest.approx(_diameter_by_root(1.8, 938.0), rel=1e-12)
    assert problem.law.density == pytest.approx(938.0, rel=1e-12)


@pytest.mark.parametrize(
    "impactor, key",
    [
        ({"threat": {"bird": "1.8 kg"}}, "impactor.velocity"),  # a bird has no speed of its own
        ({"threat": {"bird": "1.8 kg"}, "velocity": "150 m/s", "diameter": "100 mm"}, "impactor.diameter"),
        ({"threat": {"bird": "1.8 kg"}, "velocity": "150 m/s", "mass": "2 kg"}, "impactor.mass"),
        ({"threat": {"bird": "1.8 kg"}, "velocity": "150 m/s", "material": "ice"}, "impactor.material"),
        ({"threat": {"bird": "1.8 kg", "hail": "50 mm"}, "velocity": "150 m/s"}, "impactor.threat"),
        ({"threat": {"bird": "1.8 kg", "airspeed": "100 m/s"}, "velocity": "150 m/s"}, "airspeed"),
        ({"threat": {"bird": "-1 kg"}, "velocity": "150 m/s"}, "bird"),
    ],
)
def test_bird_threat_refusals_name_the_key(impactor, key):
    """A bird without velocity, or with a diameter, mass, material, hailstone or airspeed beside it, is refused naming the key."""
    with pytest.raises(InputError, match=key.replace(".", r"\.")):
        impact_problem(_case(**impactor), locate("gelatin-plate").parent)


def test_capsule_geometry_against_quadrature():
    """The crushed volume is the integral of the section, X(s) that of the remaining fraction, X(L) = L/2, and the
    inversion of X returns the depth (an L/D = 2 capsule)."""
    d, L = 0.1, 0.2
    kinks = [d / 2, L - d / 2]
    V = quad(lambda s: capsule_section(s, d, L)[0], 0, L, points=kinks)[0]
    assert V == pytest.approx(5 * math.pi * d**3 / 12, rel=1e-12)
    for s in (0.01, 0.05, 0.11, 0.17, 0.199):
        assert capsule_crushed_volume(s, d, L) == pytest.approx(
            quad(lambda z: capsule_section(z, d, L)[0], 0, s, points=[k for k in kinks if k < s])[0], rel=1e-10
        )
        X = quad(lambda z: capsule_advance(z, d, L)[1], 0, s, points=[k for k in kinks if k < s])[0]
        assert capsule_advance(s, d, L)[0] == pytest.approx(X, rel=1e-10)
        assert capsule_depth(X, d, L) == pytest.approx(s, rel=1e-10)
    assert capsule_advance(L, d, L)[0] == pytest.approx(L / 2, rel=1e-14)


@pytest.mark.parametrize("u", [0.05, 0.3, 0.5, 0.8])
def test_capsule_of_length_d_is_the_sphere(u):
    """At L = d the capsule's advance is the sphere's X/d = u − u³ + u⁴/2 (models/crushing_law.py)."""
    assert capsule_advance(u * 0.1, 0.1, 0.1)[0] / 0.1 == pytest.approx(centre_of_mass_advance(u), rel=1e-12)


def test_capsule_law_on_a_rigid_target():
    """On a rigid target the substitute's force history brings m·V to rest (momentum), lasts about L/V, and its
    plateau is Wilbeck's steady force ρ·(π·D²/4)·V² while the cylinder flows."""
    import numpy as np

    bird, V = substitute_bird(1.8), 150.0
    law = HydrodynamicLaw.of("gelatin", bird.diameter, bird.mass, V, length=bird.length)
    assert isinstance(law, HydrodynamicCapsuleLaw)
    pulse = rigid_target_pulse(law, bird.mass, V)
    t, f = np.asarray(pulse.time), np.asarray(pulse.force)
    impulse = float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(t)))
    assert impulse == pytest.approx(bird.mass * V, rel=2e-3)
    # consumed when the remainder, at most V, has flowed L; the run stops at X = (1 - 1e-9)·L/2 (crushing_law.CONSUMED),
    # a tail of (L/2 - X)^(1/4)-scale depth short of L, about 0.2 % here
    assert 0.99 * bird.length / V <= t[-1] <= 1.3 * bird.length / V
    steady = RHO * math.pi * bird.diameter**2 / 4 * V**2
    early = f[(t > 0.3 * bird.diameter / V) & (t < 0.5 * bird.diameter / V)]  # the cylinder's front, the remainder still near V
    assert early.max() == pytest.approx(steady, rel=0.05)


def test_builtin_bird_cases_load():
    """bird-al-skin and bird-plate-qi load as a 1.8-kg substitute (D by the independent root, L = 2D) at 150 m/s with
    the capsule's hydrodynamic law."""
    for name in ("bird-al-skin", "bird-plate-qi"):
        problem, _ = load_impact_case(name)
        assert problem.impactor.mass == 1.8 and problem.impactor.velocity == 150.0
        assert problem.impactor.diameter == pytest.approx(_diameter_by_root(1.8, RHO), rel=1e-12)
        assert isinstance(problem.law, HydrodynamicCapsuleLaw) and problem.law.length == pytest.approx(2 * problem.impactor.diameter)
        assert problem.threat.summary()["bird_mass_kg"] == 1.8


def test_si_bird_is_the_case_files_bird():
    """si.bird builds the same substitute and law as the case file's threat."""
    b = si.bird("4 lb", velocity="150 m/s")
    problem, _ = impact_problem(_case(threat={"bird": "4 lb"}, velocity="150 m/s"), locate("gelatin-plate").parent)
    assert (b.mass, b.diameter, b.velocity) == (problem.impactor.mass, problem.impactor.diameter, problem.impactor.velocity)
    assert b.law("hydrodynamic") == problem.law
    with pytest.raises(TypeError):
        si.bird("4 lb")  # velocity is required


def _toml(data: dict, head: str = "") -> str:
    lines, subs = [], []
    for k, v in data.items():
        if isinstance(v, dict) and not (head == "impactor." or k == "threat"):
            subs.append(f"\n[{head}{k}]\n" + _toml(v, f"{head}{k}."))
        elif isinstance(v, dict):
            lines.append(f"{k} = {{ " + ", ".join(f"{a} = {json.dumps(b)}" for a, b in v.items()) + " }")
        else:
            lines.append(f"{k} = {json.dumps(v)}")
    return "\n".join(lines) + "\n" + "".join(subs)


def test_short_coupled_run_keeps_momentum_and_says_the_threat(tmp_path):
    """A bird's first 300 us on the quasi-isotropic plate: the impulse given stays within m·V (momentum), and
    summary.json says the threat (mass, the substitute's density, shape and diameter)."""
    data = _case(threat={"bird": "1.8 kg"}, velocity="150 m/s")
    data["target"]["case"] = "hail-plate-qi"
    data["solver"] = {"time_step": "2 us", "duration": "300 us"}
    case = tmp_path / "bird.toml"
    case.write_text(_toml(data))
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["impact", str(case), "--out", str(out), "--no-figures"])
    assert result.exit_code == 0, result.output
    s = json.loads((out / "summary.json").read_text())
    assert 0 < s["total_impulse_N_s"] <= 1.8 * 150.0
    threat = s["threat"]
    assert threat["bird_mass_kg"] == 1.8 and threat["substitute_density_kg_m3"] == RHO
    assert threat["substitute_diameter_m"] == pytest.approx(_diameter_by_root(1.8, RHO), rel=1e-12)
    assert "L/D = 2" in threat["substitute_shape"]
