"""Messages name the real cause: the key and the value a user gave, and what was expected instead."""

import re

from click.testing import CliRunner

from softimpact.cli import main
from softimpact.input.toml import locate


def invoke(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def error_line(result) -> str:
    """The one ``softimpact: error:`` line of a run that exited 2."""
    assert result.exit_code == 2, result.output
    lines = [line for line in result.stderr.splitlines() if line.startswith("softimpact: error:")]
    assert len(lines) == 1 and "Traceback" not in result.output, result.output
    return lines[0]


def _plate(tmp_path, direction: str):
    text = locate("plate-ss-8in").read_text().replace("elements = [48, 48]", "elements = [8, 8]")
    text = text.replace('direction = "x"', f"direction = {direction}", 1)
    (tmp_path / "plate.toml").write_text(text)
    return tmp_path / "plate.toml"


def test_a_nan_gauge_direction_names_the_key_and_the_value(tmp_path):
    """A NaN gauge direction (TOML ``nan``) is refused as not a finite angle, naming the key, not as a gauge off the plate."""
    line = error_line(invoke("plate", _plate(tmp_path, "nan"), "--out", tmp_path / "out", "--no-figures"))
    assert "gauges[0].direction" in line and "nan" in line and "finite angle" in line
    assert "off the plate" not in line
    assert not (tmp_path / "out").exists()


def test_an_infinite_gauge_direction_is_refused_too(tmp_path):
    """An infinite direction is no angle either: the same one-line refusal."""
    line = error_line(invoke("plate", _plate(tmp_path, "inf"), "--out", tmp_path / "out", "--no-figures"))
    assert "gauges[0].direction" in line and "finite angle" in line


def _measured(tmp_path):
    (tmp_path / "m.csv").write_text("time_s,strain_g1\n0,0\n1e-6,1e-6\n2e-6,2e-6\n")
    return tmp_path / "m.csv"


def test_calibrate_given_a_bar_case_says_a_beam_case_is_expected(tmp_path):
    """``calibrate`` on a bar case names what it was given (a bar case) and what it expects (a beam case), not "beam: missing"."""
    line = error_line(invoke("calibrate", "paper-calibration", "--measured", _measured(tmp_path), "--velocity", "1166 in/s", "--out", tmp_path / "o"))
    assert "a bar case" in line and "a beam case" in line and "missing" not in line


def test_calibrate_and_beam_given_a_plate_or_impact_case_name_its_kind(tmp_path):
    """A plate case or an impact case where a beam case is expected: each named by its kind, with the right article."""
    line = error_line(invoke("beam", "plate-ss-8in", "--out", tmp_path / "o"))
    assert "a plate case" in line and "a beam case" in line
    line = error_line(invoke("calibrate", "plate-ss-8in-impact", "--measured", _measured(tmp_path), "--velocity", "1166 in/s", "--out", tmp_path / "o"))
    assert "an impact case" in line and "a impact" not in line


def test_impact_given_a_bar_target_is_one_line_naming_the_bar_case(tmp_path):
    """``softimpact impact`` whose target is a bar case: one line saying it is a bar case and what impact strikes."""
    (tmp_path / "case.toml").write_text(
        'units = "in-lbf-s"\n[target]\ncase = "paper-calibration"\n[impactor]\nmaterial = "steel"\ndiameter = "0.5 in"\n'
        'velocity = "100 in/s"\n[contact]\nlaw = "hertz"\n[solver]\ntime_step = "0.5 us"\nduration = "100 us"\n'
    )
    line = error_line(invoke("impact", tmp_path / "case.toml", "--out", tmp_path / "o", "--no-figures"))
    assert "a bar case" in line and "beams and plates" in line and "missing" not in line


def test_a_beam_sweep_asking_damage_of_a_ply_without_strengths_names_the_missing_keys(tmp_path):
    """A beam sweep asking damage outputs of an inline ply without strengths: exit 2 naming the strengths to give, not "not an output"."""
    from softimpact.models.laminate import PLIES

    p = PLIES["T300/934"]
    rows = ['name = "mine"'] + [f'{k} = "{getattr(p, k)!r} Pa"' for k in ("E1", "E2", "E3", "G12", "G13", "G23")]
    rows += [f"{k} = {getattr(p, k)!r}" for k in ("nu12", "nu13", "nu23")]
    rows += [f'density = "{p.density!r} kg/m^3"', f'thickness = "{p.thickness!r} m"']
    beam = locate("paper-long-beam").read_text().replace('ply = "T300/934"\n', "")
    beam = beam.replace("[beam.laminate]\n", "[beam.laminate.ply]\n" + "\n".join(rows) + "\n\n[beam.laminate]\n")
    (tmp_path / "beam.toml").write_text(beam)
    (tmp_path / "spec.toml").write_text(
        '[sweep]\ncase = "beam.toml"\nmethod = "grid"\noutputs = ["damage.tsai_wu"]\n'
        '[[sweep.parameter]]\nkey = "load.contact_radius"\nvalues = ["0.2 in", "0.3 in"]\n'
    )
    line = error_line(invoke("sweep", tmp_path / "spec.toml", "--out", tmp_path / "out", "--workers", "0", "--no-figures"))
    assert "not an output" not in line and "beam.laminate.ply" in line
    assert all(k in line for k in ("Xt", "Yc", "G_IIc"))


def test_no_message_in_the_sources_puts_a_before_a_vowel_kind():
    """Kind names that start with a vowel (impact) get "an": no "a impact"/"a {kind}" before a kind that may be one."""
    import pathlib

    import softimpact

    root = pathlib.Path(softimpact.__file__).parent
    bad = [f"{p.name}: {m.group(0)}" for p in root.rglob("*.py") for m in re.finditer(r"\ba (impact|identified|isotropic|inline|orthotropic)\b", p.read_text())]
    assert not bad, bad


def test_an_impact_sweep_asking_an_unknown_output_says_an_impact_case(tmp_path):
    """A sweep of an impact case asking an output it has not: "not an output of an impact case" (the article follows the kind)."""
    (tmp_path / "spec.toml").write_text(
        '[sweep]\ncase = "plate-ss-8in-impact"\nmethod = "grid"\noutputs = ["no_such_output"]\n'
        '[[sweep.parameter]]\nkey = "impactor.velocity"\nvalues = ["50 in/s", "150 in/s"]\n'
    )
    line = error_line(invoke("sweep", tmp_path / "spec.toml", "--out", tmp_path / "out", "--workers", "0", "--no-figures"))
    assert "no_such_output" in line and "an impact case" in line and "a impact" not in line


def test_a_unitless_energy_or_impulse_gets_an():
    """A number without its unit where an energy is expected: "(expected an energy, ...)", the article by the kind's first letter."""
    import pytest

    from softimpact import units
    from softimpact.errors import InputError

    with pytest.raises(InputError, match=r"expected an energy"):
        units.parse(3.0, "energy", "x")
    with pytest.raises(InputError, match=r"expected an impulse"):
        units.parse(3.0, "impulse", "x")
    with pytest.raises(InputError, match=r"expected a length"):
        units.parse(3.0, "length", "x")
