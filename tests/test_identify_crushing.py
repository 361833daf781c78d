"""identify with the crushing family: an ice sphere's strength law recovered from synthetic bar records.

The records are made here, independently of the fit: the coupled bar simulation (the FE rod struck by a
sphere under a crushing law of KNOWN strength, σ_c = 12 MPa·(ε̇/1 s⁻¹)^0.2, not the catalogue's) at the
published bar tests' sizes and velocities (31.8–50.8 mm, 13–105 m/s: "Experiments on an ice ball impacting
onto a rigid target", abstract at discovery.researcher.life), with white noise of 2 % of each test's peak.
"""

import math

import numpy as np
import pytest

from softimpact.fem.bar import Rod, assemble_rod
from softimpact.fem.contact import rod_contact_structure
from softimpact.fem.impact import integrate_impact
from softimpact.models.crushing_law import CrushingLaw, sphere_crush_depth, sphere_crush_depths
from softimpact.models.projectiles import PowerLawStrength
from softimpact.units import INCH
from softimpact.workflows.identification import BarTest, identify_crushing, identify_series

TRUE = PowerLawStrength(12e6, 0.2, (0.1, 10.0), 1.0, "the synthetic records' truth")
ICE_DENSITY = 917.0  # kg/m³ (the records' spheres; the fit takes each test's m and d)
DIAMETERS = (0.0318, 0.0381, 0.0508)  # m: the published tests' range
VELOCITIES = (13.0, 30.0, 60.0, 105.0)  # m/s: the published tests' range
NOISE = 0.02  # white noise, a fraction of each test's peak force
ROD = Rod(36 * INCH, math.pi / 4 * (2 * INCH) ** 2, 68.9e9, 2700.0, 39)  # the hail-bar case's 2-in Al bar, no cap


def _records(noise: float, seed: int = 3, every: int = 1):
    """Bar tests simulated at every ``every``-th (d, V) of the grid, white noise of ``noise`` × each peak."""
    structure = rod_contact_structure(assemble_rod(ROD))
    rng = np.random.default_rng(seed)
    out = []
    for d, V in [(d, V) for d in DIAMETERS for V in VELOCITIES][::every]:
        m = ICE_DENSITY * math.pi / 6 * d**3
        T = d / V
        dt = T / 400
        h = integrate_impact(structure, CrushingLaw(m, d, TRUE), m, V, dt, int(2.5 * T / dt), energy=False, stop_after=0.2 * T)
        F = h.force + noise * h.force.max() * rng.standard_normal(h.force.size)
        out.append(BarTest(f"d{d * 1e3:.1f}-V{V:g}", h.time - h.time[0], F, m, d, V))
    return out


@pytest.fixture(scope="module")
def noisy():
    return identify_crushing(_records(NOISE), ROD)


def _truth_at(law) -> np.ndarray:
    """The true (σ_ref, m_c) at the fit's reference rate: σ_ref = 12 MPa·ε̇_ref^0.2."""
    return np.array([TRUE.coefficient * (law.reference_rate / TRUE.reference_rate) ** TRUE.exponent, TRUE.exponent])


@pytest.mark.slow  # seconds: the slow tier (make test-slow)
def test_the_intervals_contain_the_true_strength_law(noisy):
    """From noisy synthetic records the identified σ_ref and m_c lie within their stated 95 % intervals of the truth."""
    law, _ = noisy
    assert np.all(np.abs(law.values - _truth_at(law)) <= law.half_widths)


@pytest.mark.slow  # seconds: the slow tier (make test-slow)
def test_the_intervals_are_informative(noisy):
    """The intervals are narrow enough to mean something: σ_ref within ±3 %, m_c within ±0.03 (on 0.2)."""
    law, _ = noisy
    assert law.half_widths[0] < 0.03 * law.values[0]
    assert law.half_widths[1] < 0.03
    assert not law.at_bounds and not law.unfixed_parameters


def test_noise_free_records_give_the_parameters_exactly():
    """Without noise the reconstructed approach is the simulation's own, so the fit returns the truth to 1e-6 and each
    record's first contact (its time zero) to 1 ns."""
    law, _ = identify_crushing(_records(0.0, every=5), ROD)
    np.testing.assert_allclose(law.values, _truth_at(law), rtol=1e-6)
    assert np.all(np.abs(law.start_shifts) < 1e-9)


def test_the_identified_law_is_the_catalogue_form(noisy):
    """The law's coefficient at 1 s⁻¹ is σ_ref·ε̇_ref^(−m_c), and its CrushingLaw carries that strength."""
    law, _ = noisy
    sigma, m = law.values
    assert law.coefficient_at_1_per_s == pytest.approx(sigma * law.reference_rate ** (-m), rel=1e-12)
    c = law.law(0.02, 0.0381, 50.0)
    assert isinstance(c, CrushingLaw)
    assert c.strength(law.reference_rate)[0] == pytest.approx(sigma, rel=1e-12)


@pytest.mark.parametrize("x", [0.0, 1e-9, 0.01, 0.2, 0.4999, 0.5, 0.7, -0.1])
def test_the_vectorised_crush_depth_is_the_scalar_one(x):
    """The array inversion of X(s) agrees with the scalar one to 1e-12."""
    assert sphere_crush_depths(np.array([x]))[0] == pytest.approx(sphere_crush_depth(x), abs=1e-12)


def test_an_unknown_family_is_refused():
    """identify_series names the allowed families when given another."""
    from softimpact.errors import InputError

    with pytest.raises(InputError, match="soft, crushing"):
        identify_series(ROD, [], family="rubber")


def test_the_command_and_the_api_take_the_law_family():
    """`softimpact identify --law crushing` and si.identify(law=...) exist, with the families as the choices."""
    from click.testing import CliRunner

    import softimpact as si
    from softimpact.cli import main

    res = CliRunner().invoke(main, ["identify", "--help"])
    assert res.exit_code == 0 and "--law" in res.output and "crushing" in res.output
    assert "law" in si.identify.__doc__
    res = CliRunner().invoke(main, ["identify", "paper-rubber-series", "--law", "rubber"])
    assert res.exit_code == 2 and "rubber" in res.output


def test_law_json_of_a_crushing_law_names_its_family_and_reference_rate(noisy):
    """law.json of a crushing identification says family "crushing", its reference rate and the coefficient at 1 s⁻¹."""
    import json

    from softimpact.formats.law_json import law_json

    law, _ = noisy
    out = json.loads(law_json(law, [f"t{i}" for i in range(len(law.rms_per_test))]))
    assert out["family"] == "crushing" and set(out["parameters"]) == {"strength_ref", "rate_exponent"}
    assert out["reference_rate_1_s"] == pytest.approx(law.reference_rate)
    assert out["coefficient_at_1_per_s_Pa"] == pytest.approx(law.values[0] * law.reference_rate ** (-law.values[1]))


# The built-in hail-ice-series (tools/make_ice_series.py): synthetic records of the catalogue's ice crushing by Jones
# 1997's freshwater strength, σ_c = 8.9 MPa·(ε̇/1 s⁻¹)^0.15 (J. Phys. Chem. B 101:6099, as models/projectiles.py cites it).
JONES_1997 = (8.9e6, 0.15)


def test_the_builtin_ice_series_holds_the_published_tests_sizes_and_velocities():
    """hail-ice-series is a built-in series of 12 synthetic records: 31.8, 38.1, 50.8 mm at 13, 30, 60, 105 m/s, ice's mass m = 916.7·π·d³/6."""
    from softimpact.input.series import load_series
    from softimpact.input.toml import builtin_cases

    assert "hail-ice-series" in builtin_cases()
    s = load_series("hail-ice-series")
    assert "SYNTHETIC" in s.title
    assert sorted({round(t.diameter * 1e3, 1) for t in s.tests}) == [31.8, 38.1, 50.8]
    assert sorted({t.velocity for t in s.tests}) == [13.0, 30.0, 60.0, 105.0] and len(s.tests) == 12
    for t in s.tests:
        assert t.mass == pytest.approx(916.7 * math.pi / 6 * t.diameter**3, rel=1e-5)


@pytest.mark.slow  # ~20 s: reduces 12 records and identifies with the jackknife and the closure runs
def test_identify_on_the_builtin_ice_series_recovers_jones_1997(tmp_path):
    """`softimpact identify hail-ice-series --law crushing` writes a crushing law.json whose σ_ref and m_c contain the records' truth
    (Jones 1997) within their 95 % intervals, fits each record to its noise (rms under 2 % of F0 for 1 % gauge noise), and prints the strength."""
    from click.testing import CliRunner

    from softimpact.cli import main
    from softimpact.formats.law_json import read_law

    out = tmp_path / "id"
    r = CliRunner().invoke(main, ["identify", "hail-ice-series", "--law", "crushing", "--out", str(out), "--no-figures"])
    assert r.exit_code == 0, r.output
    law = read_law(out / "law.json")
    assert law.family == "crushing"
    truth = np.array([JONES_1997[0] * law.reference_rate ** JONES_1997[1], JONES_1997[1]])
    assert np.all(np.abs(law.values - truth) <= law.half_widths)
    assert law.coefficient_at_1_per_s == pytest.approx(JONES_1997[0], rel=0.01)
    assert np.all(law.rms_per_test < 0.02)
    assert f"crushing strength {law.values[0] / 1e6:.4g} MPa" in r.output  # the line says the law, not the soft law's d_ref
