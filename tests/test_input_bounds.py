"""Every numeric input has finite, physical bounds, and a refusal names the key or argument the user wrote and echoes the
value as written, with its unit (issue 42 and issue 43's Python messages)."""

import math

import pytest

import softimpact as si
from softimpact.errors import InputError
from softimpact.input.bar_case import bar_problem
from softimpact.input.impact_case import impact_problem
from softimpact.input.toml import PHYSICAL_RANGES, load_toml, locate

HAIL_BAR = locate("hail-bar-50mm").read_text()
GELATIN_BAR = HAIL_BAR.replace('material = "ice"', 'material = "gelatin"').replace('law = "crushing"', 'law = "hydrodynamic"')


def _bar(text):
    import tomllib

    return bar_problem(tomllib.loads(text))


@pytest.mark.parametrize(
    "text, old, new, key, echo",
    [
        (GELATIN_BAR, 'law = "hydrodynamic"', 'law = "hydrodynamic"\nhugoniot_slope = inf', "contact.hugoniot_slope", "inf"),
        (GELATIN_BAR, 'law = "hydrodynamic"', 'law = "hydrodynamic"\nhugoniot_slope = nan', "contact.hugoniot_slope", "nan"),
        (HAIL_BAR, 'law = "crushing"', 'law = "crushing"\nstrength_coefficient = "1e300 Pa"', "contact.strength_coefficient", "1e300 Pa"),
        (HAIL_BAR, 'law = "crushing"', 'law = "crushing"\nstrength_exponent = nan', "contact.strength_exponent", "nan"),
        (HAIL_BAR, 'length = "36 in"', 'length = "1e300 in"', "bar.length", "1e300 in"),
        (HAIL_BAR, 'velocity = "61 m/s"', 'velocity = "1e300 m/s"', "projectile.velocity", "1e300 m/s"),
        (HAIL_BAR, 'diameter = "50.8 mm"', 'threat = { hail = "1e300 mm" }', "projectile.threat.hail", "1e300 mm"),
        (HAIL_BAR, 'velocity = "61 m/s"', 'velocity = "61 m/s"\nmass = "63 kg"', "projectile.mass", "63 kg"),
        (HAIL_BAR, "elements = 39", 'elements = 39\n[bar.end_cap]\nmaterial = "steel"\ndiameter = "-2 in"\nlength = "0.2 in"', "bar.end_cap.diameter", "-2 in"),
    ],
    ids=[
        "inf Hugoniot slope",
        "NaN Hugoniot slope",
        "1e300 strength",
        "NaN strength exponent",
        "1e300 length",
        "1e300 velocity",
        "1e300 hail",
        "1000x mass",
        "negative end cap",
    ],
)
def test_an_unphysical_number_is_refused_naming_its_key_and_value(text, old, new, key, echo):
    """An infinite, NaN, overflowing (1e300) or negative value of a case key, or a projectile a thousand times too heavy
    for its size and material: one InputError line naming the key and the value as written."""
    assert old in text
    edited = text.replace(old, new, 1)
    if "threat" in new:  # a threat sets the material and diameter: drop them
        edited = edited.replace('material = "ice"\n', "", 1)
    with pytest.raises(InputError) as info:
        _bar(edited)
    message = str(info.value)
    assert key in message and echo in message and "\n" not in message, message


def test_the_physical_ranges_hold_the_built_in_cases():
    """Every built-in case (each read as its command reads it) lies inside the physical ranges: the bounds refuse slips,
    not the paper's problems."""
    import softimpact.cases as cases

    for name in ("paper-calibration", "paper-long-beam", "plate-ss-8in", "paper-long-beam-impact", "hail-bar-50mm", "gelatin-plate", "hail-plate-38mm"):
        kind, path = cases.case_kind(name)
        kind.load(str(path))
    assert all(lo < hi for lo, hi, _ in PHYSICAL_RANGES.values())


@pytest.mark.parametrize(
    "make, argument, echo",
    [
        (lambda: si.Plate(length="-250 mm", width="250 mm", laminate=si.Laminate("T300/934", "[90/0]5s")), "length", "-250 mm"),
        (lambda: si.Beam(length="6 in", width="0 in", laminate=si.Laminate("T300/934", "[90/0]5s")), "width", "0 in"),
        (
            lambda: si.Bar("Al 6061-T6", length="36 in", diameter="2 in", end_cap={"material": "steel", "diameter": "-1 in", "length": "0.1 in"}),
            "end_cap.diameter",
            "-1 in",
        ),
        (lambda: si.Sphere("steel", "1e300 m", velocity="1 m/s"), "diameter", "1e300 m"),
        (lambda: si.Sphere("steel", "0.5 in", velocity="1e300 m/s"), "velocity", "1e300 m/s"),
        (lambda: si.Sphere("steel", "0.5 in", velocity="1 m/s", mass="8 kg"), "mass", "8 kg"),
    ],
    ids=["negative plate length", "zero beam width", "negative end cap", "1e300 diameter", "1e300 velocity", "1000x mass"],
)
def test_the_api_names_the_users_argument_and_echoes_its_value(make, argument, echo):
    """si.Plate, si.Beam, si.Bar and si.Sphere refuse a non-positive, overflowing or too heavy value with the argument's own
    name and the value as written, its unit with it (``length: ... '-250 mm'``, never ``length_x ... -0.25``)."""
    with pytest.raises(InputError) as info:
        make()
    message = str(info.value)
    assert message.startswith(f"{argument}:") and repr(echo) in message, message
    assert "length_x" not in message and "-0.25" not in message


@pytest.mark.parametrize("mass, ok", [("8.4 g", True), ("4.3 g", True), ("16.7 g", True), ("4.1 g", False), ("17 g", False), ("8.4 kg", False)])
def test_a_spheres_mass_lies_within_a_factor_two_of_its_materials(mass, ok):
    """A 1/2-in steel ball (8.40 g solid: 7833 kg/m^3 × π/6 × (12.7 mm)^3, by hand) takes a mass from half to twice that,
    and refuses one outside (a density its material cannot have)."""
    solid = 7833.413032987483 * math.pi / 6 * 0.0127**3
    assert solid == pytest.approx(8.40e-3, rel=1e-3)
    make = lambda: si.Sphere("steel", "0.5 in", velocity="1 m/s", mass=mass)  # noqa: E731
    if ok:
        assert make().mass == pytest.approx(float(mass.split()[0]) * 1e-3, rel=1e-12)
    else:
        with pytest.raises(InputError, match="^mass:"):
            make()


@pytest.mark.parametrize(
    "call, keyword, meant",
    [
        (lambda: si.Plate(lenght="8 in", width="8 in", laminate=None), "lenght", "length"),
        (lambda: si.Beam(length="6 in", widht="1 in"), "widht", "width"),
        (lambda: si.Sphere("steel", "0.5 in", velocty="1 m/s"), "velocty", "velocity"),
        (lambda: si.impact(None, impactor=None, time_step="1 us", duraton="1 us"), "duraton", "duration"),
        (lambda: si.converge("paper-calibration", level=2), "level", "levels"),
        (lambda: si.load("paper-calibration", histroy=1), "histroy", "history"),
    ],
)
def test_a_misspelt_keyword_names_it_and_suggests_the_one_meant(call, keyword, meant):
    """A misspelt keyword of the API is an InputError (and a TypeError, as Python's own) naming it and the nearest keyword
    the function takes, raised before anything runs."""
    with pytest.raises(TypeError) as info:
        call()
    assert isinstance(info.value, InputError)
    assert str(info.value).startswith(f"{keyword}:") and repr(meant) in str(info.value)


def test_an_unknown_display_system_is_refused_before_the_run(monkeypatch):
    """si.impact(units="metric") is refused naming units before anything is built (the run would fail only at .write())."""
    monkeypatch.setattr("softimpact.api.commands._run", lambda *a, **k: pytest.fail("ran"))
    beam = si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(20, 4))
    with pytest.raises(InputError, match="^units: 'metric'"):
        si.impact(beam, at="3 in", impactor=si.Sphere("steel", "0.5 in", velocity="100 in/s"), time_step="1 us", duration="20 us", units="metric")


def test_an_empty_sweep_folder_is_refused(tmp_path, monkeypatch):
    """si.sweep(out="") is refused as the command line's --out "" is, and nothing is written in the working folder."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "spec.toml").write_text(
        '[sweep]\ncase = "paper-calibration"\nmethod = "grid"\noutputs = ["peak_force_N"]\n[[sweep.parameter]]\nkey = "projectile.velocity"\nvalues = ["40 in/s"]\n'
    )
    with pytest.raises(InputError, match="^out: give a folder"):
        si.sweep(tmp_path / "spec.toml", out="", workers=0)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["spec.toml"]


def test_cohesive_keys_are_bounded():
    """A cohesive interface's penalty of 1e300 N/m^3 or a NaN Benzeggagh–Kenane exponent: refused naming the damage key."""
    target = locate("plate-ss-8in-quarter").read_text().replace("elements = [24, 24]", "elements = [4, 4]")
    data = load_toml(locate("plate-ss-8in-impact-cohesive"))
    import tempfile
    from pathlib import Path

    folder = Path(tempfile.mkdtemp())
    (folder / "quarter.toml").write_text(target)
    data["target"]["case"] = "quarter.toml"
    for key, value, words in (("penalty", "1e300 N/m^3", "damage.penalty"), ("bk_exponent", float("nan"), "damage.bk_exponent")):
        bad = {**data, "damage": {**data["damage"], key: value}}
        with pytest.raises(InputError, match=words):
            impact_problem(bad, folder)
