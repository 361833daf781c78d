"""Ice and gelatin wired through the edges: [contact] laws "crushing" and "hydrodynamic", hail threats, the built-in
hail cases, si.Sphere and ``predict --model crushing|hydrodynamic``, each checked against an independent number."""

import json
import math

import pytest
from click.testing import CliRunner

import softimpact as si
from softimpact.cli import main
from softimpact.errors import InputError
from softimpact.input.bar_case import bar_problem, load_bar_case
from softimpact.input.impact_case import load_impact_case
from softimpact.input.toml import load_toml, locate
from softimpact.models.contact_laws import CONTACT_LAWS, law_name, law_validity

# The published bar tests of ice spheres on a rigid target ("Experiments on an ice ball impacting onto a rigid
# target", abstract at discovery.researcher.life): 31.8-50.8 mm, 13-105 m/s, impulse over momentum 0.8-1.12.
IMPULSE_BAND = (0.8, 1.12)
ICE_DENSITY = 916.7  # kg/m^3, the catalogue's ice at 0 C (models/materials.py)
G, RHO_AIR, CD = 9.80665, 1.225, 0.5  # ISA gravity and sea-level air, a sphere's drag coefficient (models/threats.py)


def _bar_data(material: str, law: str | None, **contact) -> dict:
    """The paper's calibration bar case, 2 in wide without end cap, struck by a 38.1-mm sphere of ``material``
    at 30 m/s, run for a short time (keys and numbers, not the paper)."""
    data = load_toml(locate("paper-calibration"))
    data["bar"]["diameter"] = "2 in"
    data["bar"].pop("end_cap", None)
    data["projectile"] = {"material": material, "diameter": "38.1 mm", "velocity": "30 m/s"}
    data["contact"] = {"law": law or "hertz", **contact}
    data["solver"] = {"time_step": "1 us", "duration": "300 us"}
    data.pop("output", None)
    return data


def _toml(data: dict, head: str = "") -> str:
    """A small TOML writer for the case tables of :func:`_bar_data` (strings, numbers, tables, arrays of tables)."""
    lines, subs = [], []
    for k, v in data.items():
        if isinstance(v, dict):
            subs.append(f"\n[{head}{k}]\n" + _toml(v, f"{head}{k}."))
        elif isinstance(v, list):
            subs += [f"\n[[{head}{k}]]\n" + _toml(row, f"{head}{k}.") for row in v]
        else:
            lines.append(f"{k} = {json.dumps(v)}")
    return "\n".join(lines) + "\n" + "".join(subs)


def _summary_keys(tmp_path, name, data) -> tuple[set, dict]:
    case = tmp_path / f"{name}.toml"
    case.write_text(_toml(data))
    out = tmp_path / name
    result = CliRunner().invoke(main, ["bar", str(case), "--out", str(out), "--no-figures"])
    assert result.exit_code == 0, result.output
    summary = json.loads((out / "summary.json").read_text())
    return set(summary), summary


def test_bar_with_ice_or_gelatin_writes_the_summary_keys_of_steel(tmp_path):
    """`softimpact bar` with an ice (crushing) or gelatin (hydrodynamic) sphere writes the same summary.json keys as with a steel (Hertz) one, and its validity adds the law's own ratios."""
    steel, s = _summary_keys(tmp_path, "steel", _bar_data("steel", None))
    for material, law in (("ice", "crushing"), ("gelatin", "hydrodynamic")):
        keys, summary = _summary_keys(tmp_path, material, _bar_data(material, law))
        assert keys == steel
        assert summary["case_SI"]["contact"] == law
        assert set(s["validity"]) <= set(summary["validity"])


@pytest.mark.parametrize("law, own", [("crushing", "strain_rate_over_fitted_max"), ("hydrodynamic", "release_depth_over_diameter")])
def test_the_laws_envelope_is_raised_by_a_bar_run(law, own):
    """A bar run with the crushing (hydrodynamic) law reports the law's own envelope: the strain rate V/d against Jones's 10 1/s, the release depth V²/(4 U_s²) against d."""
    from softimpact.cases.run import execute

    material = "ice" if law == "crushing" else "gelatin"
    problem = bar_problem(_bar_data(material, law))
    run = execute(problem)
    V, d = 30.0, 0.0381
    expected = V / d / 10.0 if law == "crushing" else V**2 / (4 * (1482.9 + 2.0 * V) ** 2)  # Jones's top rate; Wilbeck's c0, k
    assert run.warnings.values[own] == pytest.approx(expected, rel=1e-9)
    assert ("extrapolated_strain_rate" in run.warnings.names) == (law == "crushing")


def test_crushing_overrides_replace_the_catalogue_strength():
    """`strength_coefficient`, `strength_exponent` in [contact] give F = A(s)·[A·(ṡ/d)^m + ρ·ṡ²] with the case's A and m (computed here from the sphere's geometry)."""
    problem = bar_problem(_bar_data("ice", "crushing", strength_coefficient="20 MPa", strength_exponent=0.3))
    law = problem.law
    d = 0.0381
    m = ICE_DENSITY * math.pi / 6 * d**3
    u = 0.2  # crushed depth s = u·d; the centre of mass has advanced X = d·(u − u³ + u⁴/2), its rate φ·ṡ
    phi = (1 - u) ** 2 * (1 + 2 * u)
    sdot = 25.0
    alpha, rate = d * (u - u**3 + u**4 / 2), phi * sdot
    area = math.pi * u * d * (d - u * d)
    expected = area * (20e6 * (sdot / d) ** 0.3 + m / (math.pi / 6 * d**3) * sdot**2)
    assert law.force(alpha, rate) == pytest.approx(expected, rel=1e-8)
    assert law_name(law) == "crushing"


def test_hydrodynamic_overrides_replace_the_catalogue_hugoniot():
    """`sound_speed`, `hugoniot_slope` in [contact] give the Hugoniot pressure ρ·(c0 + k·V)·V with the case's c0 and k."""
    law = bar_problem(_bar_data("gelatin", "hydrodynamic", sound_speed="1600 m/s", hugoniot_slope=1.5)).law
    rho = law.mass / (math.pi / 6 * law.diameter**3)
    assert law.hugoniot_pressure == pytest.approx(rho * (1600.0 + 1.5 * 30.0) * 30.0, rel=1e-12)
    assert law_name(law) == "hydrodynamic"


@pytest.mark.parametrize("material, law", [("steel", "crushing"), ("ice", "hydrodynamic"), ("gelatin", "crushing")])
def test_a_law_of_another_material_is_refused_naming_the_keys(material, law):
    """The crushing law of a steel (or gelatin) sphere, the hydrodynamic law of an ice one: an InputError naming contact.law and projectile.material."""
    with pytest.raises(InputError) as exc:
        bar_problem(_bar_data(material, law))
    assert "contact.law" in str(exc.value) and "projectile.material" in str(exc.value)


def test_hail_threat_gives_the_ice_sphere_at_its_terminal_velocity():
    """`threat = { hail = "38.1 mm" }`: an ice sphere of 38.1 mm, its mass ρ·π·d³/6 and V_t = sqrt(4ρgD/(3·C_d·ρ_air)) (computed here); with `airspeed` the hypotenuse."""
    problem, _ = load_impact_case("hail-plate-38mm")
    d = 0.0381
    vt = math.sqrt(4 * ICE_DENSITY * G * d / (3 * CD * RHO_AIR))
    assert problem.impactor.diameter == d
    assert problem.impactor.mass == pytest.approx(ICE_DENSITY * math.pi / 6 * d**3, rel=1e-12)
    assert problem.impactor.velocity == pytest.approx(vt, rel=1e-12)
    assert 27.0 < vt < 27.6  # the number the case's comment gives
    data = _bar_data("ice", "crushing")
    data["projectile"] = {"threat": {"hail": "38.1 mm", "airspeed": "100 m/s"}}
    assert bar_problem(data).projectile.velocity == pytest.approx(math.hypot(100.0, vt), rel=1e-12)


def test_a_threat_and_a_diameter_are_refused_together():
    """A threat sets the sphere's material and diameter: giving either as well is an InputError naming it."""
    data = _bar_data("ice", "crushing")
    data["projectile"] = {"threat": {"hail": "38.1 mm"}, "diameter": "40 mm"}
    with pytest.raises(InputError, match="projectile.diameter"):
        bar_problem(data)


def test_builtin_ice_bar_case_impulse_is_in_the_published_band():
    """The built-in hail-bar-50mm (50.8 mm at 61 m/s): impulse over m·V within the published 0.8-1.12, no rebound, the strain-rate extrapolation flagged."""
    from softimpact.cases.run import execute

    problem, _ = load_bar_case("hail-bar-50mm")
    run = execute(problem)
    p = problem.projectile
    assert IMPULSE_BAND[0] <= run.result.impulse / (p.mass * p.velocity) <= IMPULSE_BAND[1]
    assert run.result.rebound_velocity >= -1e-3 * p.velocity
    assert "extrapolated_strain_rate" in run.warnings.names


def test_sphere_api_builds_the_materials_law_and_impacts_a_bar():
    """si.Sphere("ice").law("crushing") is the crushing law of its mass and diameter; si.impact on a bar with law="crushing" carries the momentum m·V within the published band."""
    ball = si.Sphere("ice", "38.1 mm", velocity="30 m/s")
    law = ball.law("crushing")
    assert type(law) is CONTACT_LAWS["crushing"] and law.mass == ball.mass and law.diameter == ball.diameter
    with pytest.raises(InputError):
        ball.law("hertz")
    bar = si.Bar("Al 6061-T6", length="36 in", diameter="2 in")
    with pytest.warns(Warning):  # the strength law's extrapolation
        res = si.impact(bar, impactor=ball, law="crushing", time_step="1 us", duration="1500 us")
    assert IMPULSE_BAND[0] <= res.result.impulse / (ball.mass * ball.velocity) <= IMPULSE_BAND[1]
    assert law_validity(law, ball.velocity).values["strain_rate_over_fitted_max"] == pytest.approx(30.0 / 0.0381 / 10.0)


@pytest.mark.parametrize("material, model", [("ice", "crushing"), ("gelatin", "hydrodynamic")])
def test_predict_material_model_impulse_is_the_momentum(tmp_path, material, model):
    """`predict --material ice --model crushing` (gelatin, hydrodynamic): on a rigid target the whole momentum is brought to rest, impulse m·V within 1 %."""
    m, V = 0.02, 30.0
    result = CliRunner().invoke(
        main,
        [
            "predict",
            "--material",
            material,
            "--model",
            model,
            "--mass",
            f"{m * 1e3} g",
            "--diameter",
            "35 mm",
            "--velocity",
            f"{V} m/s",
            "--out",
            str(tmp_path),
            "--no-figures",
        ],
    )
    assert result.exit_code == 0, result.output
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["impulse_N_s"] == pytest.approx(m * V, rel=0.01)
