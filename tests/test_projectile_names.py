"""One name per ball: ``--constants rubber-1/2in`` names the same constants as ``--projectile rubber-1/2in``; the old preset names stay accepted aliases."""

import json

import pytest
from click.testing import CliRunner

from softimpact.cli import main
from softimpact.errors import InputError
from softimpact.input.scaling_constants import scaling_law

# Table I of the paper (longitudinal bar tests): alpha1, alpha2, alpha4 of each ball (alpha3 of the 1/2-in ball is
# missing in Table I; both balls use 0.25).
TABLE_I = {"rubber-1/2in": (4.25, 0.93, 0.66), "rubber-3/8in": (4.00, 1.03, 0.74)}
OLD_NAMES = {"rubber-1/2in": "silicone-1/2in", "rubber-3/8in": "silicone-3/8in"}


@pytest.mark.parametrize("name", TABLE_I)
def test_projectile_name_gives_its_table_i_constants(name):
    """``--constants rubber-1/2in`` gives that ball's alpha1, alpha2, alpha4 of Table I."""
    law = scaling_law(name, "pooled", None)
    assert (law.alpha1, law.alpha2, law.alpha4) == pytest.approx(TABLE_I[name], abs=1e-12)


@pytest.mark.parametrize("name", TABLE_I)
def test_old_name_is_an_alias(name):
    """The old preset name (silicone-1/2in) gives exactly the constants of the new one."""
    assert scaling_law(OLD_NAMES[name], "pooled", None) == scaling_law(name, "pooled", None)


def test_unknown_name_lists_the_names():
    """An unknown name is refused, the message listing the projectiles' names and the old ones."""
    with pytest.raises(InputError) as err:
        scaling_law("rubber-1in", "pooled", None)
    assert "rubber-1/2in" in str(err.value) and "silicone-1/2in" in str(err.value)


@pytest.mark.parametrize("command", ["predict", "calibrate"])
def test_help_names_the_alias_as_deprecated(command):
    """The --constants help names the projectiles' names and marks the old ones deprecated."""
    text = " ".join(CliRunner().invoke(main, [command, "--help"]).output.split())
    assert "rubber-1/2in" in text and "silicone-1/2in" in text and "deprecated" in text


@pytest.mark.parametrize("name", ["rubber-1/2in", "silicone-1/2in"])
def test_predict_under_either_name(tmp_path, name):
    """``softimpact predict --constants NAME`` under the new and the old name gives eq (4)'s F0 = alpha1·m·V²/(2d) with Table I's alpha1 = 4.25 of the 1/2-in ball (1.1 g)."""
    args = ["predict", "--projectile", "rubber-1/2in", "--constants", name, "--velocity", "2000 in/s", "--no-figures", "--out", str(tmp_path)]
    run = CliRunner().invoke(main, args)
    assert run.exit_code == 0, run.output
    summary = json.loads((tmp_path / "summary.json").read_text())
    V, d = 2000 * 0.0254, 0.5 * 0.0254
    assert summary["peak_force_N"] == pytest.approx(4.25 * 1.1e-3 * V**2 / (2 * d), rel=1e-9)
