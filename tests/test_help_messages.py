"""Help and messages (issue 43, item 4): every list of choices in --help comes from its table, the top-level help ends
with examples, no result line has an empty field, a misspelt sweep key gets the nearest name, and the case-file
reference says which keys are required one or the other and offers no choice that is not implemented."""

import importlib.util
import re
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from softimpact.cli import EXAMPLES, MAIN_EXAMPLES, main
from softimpact.input.toml import locate

from _support.problems import COARSE_LONG_BEAM

ROOT = Path(__file__).resolve().parent.parent


def _help(*args) -> str:
    text = CliRunner().invoke(main, [*args, "--help"], terminal_width=200).output
    return " ".join(text.split())  # click wraps the lines: compare the words


def _tables():
    from softimpact.models.contact_laws import CONTACT_LAWS
    from softimpact.models.empirical import PRESETS, PROJECTILES
    from softimpact.models.materials import CATALOGUE

    return {"contact_laws": CONTACT_LAWS, "projectiles": PROJECTILES, "presets": PRESETS, "materials": CATALOGUE}


@pytest.mark.parametrize(
    "command, table",
    [("impact", "contact_laws"), ("predict", "projectiles"), ("predict", "materials"), ("predict", "presets"), ("calibrate", "projectiles")],
)
def test_every_list_of_choices_in_help_is_its_table(command, table):
    """`softimpact COMMAND --help` names every row of the table its text lists (impact: every contact law, crushing and
    hydrodynamic among them; predict: every projectile, preset and material), read from the tables themselves."""
    text = _help(command)
    missing = [name for name in _tables()[table] if name not in text]
    assert not missing, f"{command} --help lacks {missing}"
    assert "{" + table not in text  # no placeholder left unfilled


def test_the_top_level_help_ends_with_examples_that_are_the_commands():
    """`softimpact --help` ends with an Examples block whose lines are commands' own examples (each run by test_cli_examples)."""
    text = CliRunner().invoke(main, ["--help"]).output
    assert "Examples:" in text
    tail = text.split("Examples:")[1]
    for name in MAIN_EXAMPLES:
        assert EXAMPLES[name][1] in tail


def test_an_impact_without_gauges_has_no_empty_field_in_its_line(tmp_path):
    """An impact on a beam without gauges prints no "peak strains" field at all (it printed "peak strains ;"), and no
    field of the line is empty."""
    beam = "\n".join(COARSE_LONG_BEAM.split("[[gauges]]")[0].splitlines()) + "\n"
    (tmp_path / "beam.toml").write_text(beam)
    (tmp_path / "case.toml").write_text(
        'units = "in-lbf-s"\n[target]\ncase = "beam.toml"\n[impactor]\nmaterial = "steel"\ndiameter = "0.5 in"\nvelocity = "100 in/s"\n'
        '[contact]\nlaw = "hertz"\n[solver]\ntime_step = "1 us"\nduration = "40 us"\n'
    )
    r = CliRunner().invoke(main, ["impact", str(tmp_path / "case.toml"), "--out", str(tmp_path / "o"), "--no-figures"])
    assert r.exit_code == 0, r.output
    line = r.stdout.strip().splitlines()[-1]
    assert "peak strains" not in line
    assert not re.search(r";\s*;|:\s*;|,\s*;|;\s*$", line), line


def test_a_misspelt_sweep_key_and_output_get_the_nearest_name(tmp_path):
    """A sweep varying impactor.velocty, or asking peak_forc_N: exit 2 naming it and suggesting velocity / peak_force_N."""
    spec = (
        '[sweep]\ncase = "paper-long-beam-impact"\nmethod = "grid"\noutputs = ["{out}"]\n[[sweep.parameter]]\nkey = "{key}"\nvalues = ["50 in/s", "60 in/s"]\n'
    )
    for key, out, words in (
        ("impactor.velocty", "peak_force_N", "misspelling of 'velocity'"),
        ("impactor.velocity", "peak_forc_N", "did you mean 'peak_force_N'"),
    ):
        (tmp_path / "spec.toml").write_text(spec.format(key=key, out=out))
        r = CliRunner().invoke(main, ["sweep", str(tmp_path / "spec.toml"), "--out", str(tmp_path / "o"), "--no-figures", "--workers", "0"])
        assert r.exit_code == 2 and words in r.output, r.output


def _reference() -> str:
    spec = importlib.util.spec_from_file_location("casekeys", ROOT / "docs" / "_ext" / "casekeys.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules["casekeys"] = module  # dataclasses look their module up
    spec.loader.exec_module(module)
    return module.markdown(module.record())


def test_the_case_reference_says_either_or_and_offers_no_unimplemented_choice():
    """The generated case-file reference: the plate's load.pressure and load.history are each required only with or
    without a static analysis (not both "required"), plate.model offers fsdt alone (the solid model is not implemented),
    and plate.support takes one kind for all edges."""
    text = _reference()
    plate = text.split("## Plate case")[1].split("## ")[0]
    rows = {m.group(1): m.group(0) for m in re.finditer(r"^\| `([^`]+)` \|.*$", plate, re.M)}
    for key in ("load.pressure", "load.history"):
        assert "| required |" not in rows[key] and 'analysis = "static"' in rows[key], rows[key]
    assert "`fsdt`" in rows["plate.model"] and "solid" not in rows["plate.model"]
    assert "all four edges" in rows["plate.support"]


def test_a_plate_model_named_solid_says_it_is_not_implemented(tmp_path):
    """plate.model = "solid" (no longer a choice) is refused saying it is not implemented, not merely "not one of"."""
    text = locate("plate-ss-8in").read_text().replace('model = "fsdt"', 'model = "solid"')
    (tmp_path / "p.toml").write_text(text)
    r = CliRunner().invoke(main, ["plate", str(tmp_path / "p.toml"), "--out", str(tmp_path / "o")])
    assert r.exit_code == 2 and "not implemented" in r.output


def test_a_misspelt_catalogue_table_gets_the_nearest_name():
    """si.catalogue().to_frame("material") (an AttributeError before) is an InputError suggesting "materials"."""
    import softimpact as si
    from softimpact.errors import InputError

    with pytest.raises(InputError, match="did you mean 'materials'"):
        si.catalogue().to_frame("material")
