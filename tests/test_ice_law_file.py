"""A crushing law.json (``softimpact identify --law crushing``) read back by a case's ``law = "identified"``:
the same law as the crushing law built from its strength, the same run as ``law = "crushing"`` with that
strength, and a clear InputError for a corrupt file."""

import json
import warnings

import numpy as np
import pytest

from softimpact.errors import InputError, SoftimpactWarning
from softimpact.formats.law_json import law_json, read_law
from softimpact.input.bar_case import load_bar_case
from softimpact.input.toml import locate
from softimpact.models.crushing_law import CrushingLaw
from softimpact.models.projectiles import PowerLawStrength
from softimpact.workflows.identification import CRUSHING_PARAMETERS, CrushingIdentifiedLaw

SIGMA_REF, EXPONENT, RATE_REF = 14.0e6, 0.21, 900.0  # Pa, -, 1/s: a law of the size the fit gives (not the catalogue's)
RANGES = {"velocity_m_s": [13.0, 105.0], "diameter_m": [0.0318, 0.0508], "strain_rate_1_s": [13.0 / 0.0508, 105.0 / 0.0318]}
PROJECTILE = {"mass_kg": [0.0154, 0.0627], "diameter_m": [0.0318, 0.0508], "density_kg_m3": [916.7, 916.7]}


def _law(sigma=SIGMA_REF, exponent=EXPONENT, ranges=None) -> CrushingIdentifiedLaw:
    ranges = dict(RANGES, projectile=PROJECTILE) if ranges is None else ranges
    return CrushingIdentifiedLaw(
        CRUSHING_PARAMETERS, np.array([sigma, exponent]), np.array([0.3e6, 0.02]), RATE_REF, 0.0508, np.array([0.01, 0.02]), 0.1, ranges
    )


def _write(tmp_path, law=None, edit=None):
    """law.json of ``law`` (written by the one writer), its parsed content changed by ``edit`` if given."""
    text = law_json(law or _law(), ["a", "b"])
    if edit is not None:
        data = json.loads(text)
        edit(data)
        text = json.dumps(data)
    path = tmp_path / "law.json"
    path.write_text(text)
    return path


def test_a_crushing_law_json_reads_back_to_the_crushing_law_of_its_strength(tmp_path):
    """Read back, the law's force at several (α, α̇) is that of a CrushingLaw built from σ_c = A·(ε̇/1 s⁻¹)^m, A = σ_ref·ε̇_ref^(−m), to 1e-12."""
    back = read_law(_write(tmp_path))
    assert isinstance(back, CrushingIdentifiedLaw) and back.names == CRUSHING_PARAMETERS
    assert back.identified_on["projectile"] == PROJECTILE
    m, d = 0.0627, 0.0508
    direct = CrushingLaw(m, d, PowerLawStrength(SIGMA_REF * RATE_REF**-EXPONENT, EXPONENT, (0.1, 10.0), 1.0))
    law = back.law(m, d, 61.0)
    for alpha, rate in [(1e-4, 61.0), (2e-3, 40.0), (0.01, 20.0), (0.02, 3.0), (0.024, 0.001)]:
        f, g = law.response(alpha, rate)[0], direct.response(alpha, rate)[0]
        assert f > 0 and f == pytest.approx(g, rel=1e-12)


def test_the_law_json_names_the_crushing_family_and_its_catalogue_coefficient(tmp_path):
    """The written file says family "crushing", its reference rate and A = σ_ref·ε̇_ref^(−m) (computed here)."""
    data = json.loads(_write(tmp_path).read_text())
    assert data["family"] == "crushing" and set(data["parameters"]) == set(CRUSHING_PARAMETERS)
    assert data["reference_rate_1_s"] == RATE_REF
    assert data["coefficient_at_1_per_s_Pa"] == pytest.approx(SIGMA_REF * RATE_REF**-EXPONENT, rel=1e-14)


def _case(tmp_path, contact: str):
    """The built-in hail-bar-50mm case (50.8 mm at 61 m/s on the 2-in bar) with ``contact`` as its [contact] table, 600 us long."""
    text = locate("hail-bar-50mm").read_text()
    text = text.replace('[contact]\nlaw = "crushing"', "[contact]\n" + contact).replace('duration = "1200 us"', 'duration = "600 us"')
    path = tmp_path / f"case-{abs(hash(contact))}.toml"
    path.write_text(text)
    return path


def test_a_bar_case_with_the_identified_crushing_law_is_the_crushing_run_of_its_strength(tmp_path):
    """The hail bar case through law = "identified" runs, and its peak force and impulse equal the case with law = "crushing" and
    strength_coefficient = σ_ref·ε̇_ref^(−m), strength_exponent = m (computed here) to 1e-9."""
    from softimpact.cases.run import execute

    _write(tmp_path)
    with warnings.catch_warnings():
        warnings.simplefilter("error", SoftimpactWarning)  # 61 m/s and 50.8 mm lie within what the law was identified on
        identified, _ = load_bar_case(str(_case(tmp_path, 'law = "identified"\nlaw_file = "law.json"')))
    a = SIGMA_REF * RATE_REF**-EXPONENT
    direct, _ = load_bar_case(str(_case(tmp_path, f'law = "crushing"\nstrength_coefficient = "{a!r} Pa"\nstrength_exponent = {EXPONENT!r}')))
    assert isinstance(identified.law, CrushingLaw)
    r1, r2 = execute(identified).result, execute(direct).result
    p = identified.projectile
    assert r1.peak_force > 0 and r1.impulse == pytest.approx(p.mass * p.velocity, rel=0.15)  # the ball's momentum is brought to rest
    assert r1.peak_force == pytest.approx(r2.peak_force, rel=1e-9)
    assert r1.impulse == pytest.approx(r2.impulse, rel=1e-9)


def test_a_case_outside_the_identified_ranges_is_warned(tmp_path):
    """A sphere faster than every test the crushing law was identified on is warned as an extrapolation."""
    slow = {"velocity_m_s": [13.0, 30.0], "diameter_m": [0.0318, 0.0508], "strain_rate_1_s": [13.0 / 0.0508, 30.0 / 0.0318], "projectile": PROJECTILE}
    _write(tmp_path, _law(ranges=slow))
    with pytest.warns(SoftimpactWarning, match="velocity"):
        load_bar_case(str(_case(tmp_path, 'law = "identified"\nlaw_file = "law.json"')))


def test_the_case_parameters_replace_the_crushing_law_values(tmp_path):
    """contact.parameters sets a crushing law's strength_ref and rate_exponent; out of range they are refused naming the key."""
    _write(tmp_path)
    p, _ = load_bar_case(str(_case(tmp_path, 'law = "identified"\nlaw_file = "law.json"\nparameters = { strength_ref = 2e7, rate_exponent = 0.1 }')))
    assert p.law.strength(RATE_REF)[0] == pytest.approx(2e7, rel=1e-12) and p.law.strength.exponent == 0.1
    for bad in ("rate_exponent = 1.0", "strength_ref = 0.0", "rate_exponent = -0.1"):
        with pytest.raises(InputError, match=r"contact\.parameters.*" + bad.split(" ")[0]):
            load_bar_case(str(_case(tmp_path, f'law = "identified"\nlaw_file = "law.json"\nparameters = {{ {bad} }}')))


def _drop(*keys):
    def edit(data):
        table = data
        for k in keys[:-1]:
            table = table[k]
        del table[keys[-1]]

    return edit


def _set(value, *keys):
    def edit(data):
        table = data
        for k in keys[:-1]:
            table = table[k]
        table[keys[-1]] = value

    return edit


@pytest.mark.parametrize(
    "edit, key",
    [
        (_drop("parameters", "strength_ref"), "parameters.strength_ref"),
        (_drop("parameters", "rate_exponent", "value"), "parameters.rate_exponent.value"),
        (_drop("parameters"), "parameters"),
        (_drop("reference_rate_1_s"), "reference_rate_1_s"),
        (_drop("identified_on", "strain_rate_1_s"), "identified_on.strain_rate_1_s"),
        (_set(0.0, "parameters", "strength_ref", "value"), "strength_ref"),
        (_set(-1e6, "parameters", "strength_ref", "value"), "strength_ref"),
        (_set(1.0, "parameters", "rate_exponent", "value"), "rate_exponent"),
        (_set(-0.05, "parameters", "rate_exponent", "value"), "rate_exponent"),
        (_set("fast", "parameters", "rate_exponent", "value"), "rate_exponent"),
        (_set(0.0, "reference_rate_1_s"), "reference_rate_1_s"),
        (_set(1e7, "coefficient_at_1_per_s_Pa"), "coefficient_at_1_per_s_Pa"),
        (_set([1.0], "identified_on", "velocity_m_s"), "identified_on.velocity_m_s"),
    ],
)
def test_a_corrupt_crushing_law_json_is_an_input_error_naming_the_key(tmp_path, edit, key):
    """A crushing law.json with a key missing or out of range is one InputError line naming the argument and the key."""
    path = _write(tmp_path, edit=edit)
    with pytest.raises(InputError, match=key) as info:
        read_law(path, "contact.law_file")
    assert "contact.law_file" in str(info.value) and "\n" not in str(info.value)


def test_a_corrupt_crushing_law_json_stops_the_case(tmp_path):
    """A case whose crushing law_file has a negative strength is refused before any run, naming contact.law_file."""
    _write(tmp_path, edit=_set(-1.0, "parameters", "strength_ref", "value"))
    with pytest.raises(InputError, match=r"contact\.law_file.*strength_ref"):
        load_bar_case(str(_case(tmp_path, 'law = "identified"\nlaw_file = "law.json"')))


def test_an_unknown_family_names_both_known_ones(tmp_path):
    """A law.json of another family is refused, naming the soft-projectile and crushing families."""
    path = _write(tmp_path, edit=_set("rubber", "family"))
    with pytest.raises(InputError, match="soft-projectile.*crushing"):
        read_law(path)


@pytest.mark.parametrize("rate,flagged", [(100.0, True), (1000.0, False), (5000.0, True)])
def test_the_identified_strength_is_valid_over_the_tests_strain_rates_only(rate, flagged):
    """An identified crushing law's strength is measured over its tests' V/d (255-3302 1/s here), not down to the fit's 0.1 1/s floor: a crush at 100 or 5000 1/s is flagged as an extrapolation, at 1000 1/s not."""
    from softimpact.models.validity import ice_strength_validity

    strength = _law().strength
    assert strength.rate_range == pytest.approx(tuple(RANGES["strain_rate_1_s"]), rel=1e-12)
    diameter = 0.0381
    v = ice_strength_validity(diameter, rate * diameter, strength)  # a crush at V/d = rate
    assert bool(v.flags) is flagged


def test_the_identified_strength_keeps_the_fits_ramp_below_the_tests():
    """Below the tests' rates the identified strength is its power law down to the fit's floor (0.1 1/s), then a ramp to zero: the same force the fit used."""
    from softimpact.workflows._identification_crushing import RATE_FLOOR

    strength = _law().strength
    for rate in (1.0, 50.0):
        assert strength(rate)[0] == pytest.approx(SIGMA_REF * (rate / RATE_REF) ** EXPONENT, rel=1e-12)
    floor = SIGMA_REF * (RATE_FLOOR / RATE_REF) ** EXPONENT
    assert strength(0.5 * RATE_FLOOR)[0] == pytest.approx(0.5 * floor, rel=1e-12)


def test_a_missing_law_file_says_where_it_was_looked_for(tmp_path, monkeypatch):
    """A relative law file that is not there is an InputError naming the key and the folder it was looked for in."""
    monkeypatch.chdir(tmp_path)
    with pytest.raises(InputError, match="contact.law_file: cannot read nosuch.json") as err:
        read_law("nosuch.json")
    assert str(tmp_path.resolve() / "nosuch.json") in str(err.value)
