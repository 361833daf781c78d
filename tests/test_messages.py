"""Messages name the real cause: the key and the value a user gave, and what was expected instead."""

import re

import numpy as np
import pytest
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


def test_converge_with_two_levels_says_the_order_is_assumed(tmp_path):
    """With two levels no order can be observed (three are needed): the result line says "assumed order 2", not "observed order 2.00"."""
    r = invoke("converge", "paper-calibration", "--levels", "2", "--out", tmp_path / "o", "--no-figures")
    assert r.exit_code == 0, r.output
    assert "assumed order 2" in r.output and "observed order" not in r.output


def _study(status: str, order: float, errors):
    from types import SimpleNamespace

    import numpy as np

    out = SimpleNamespace(
        name="strain_g1_history", kind="history", status=status, order=order, errors=np.asarray(errors, float), gci_fine=np.nan, safety_factor=np.nan
    )
    return SimpleNamespace(outputs=[out], levels=[0, 1, 2], ratio=2.0)


def test_a_diverging_output_shows_a_dash_and_its_reason_not_nan_percent():
    """A convergence table row without errors (a diverging output, as the short beam's zero crossings): a dash and "not converging", never "nan %"."""
    from softimpact.output.converge import converge_section

    sizes = [{"elements": [10], "time_step_s": 1e-6}] * 3
    section = converge_section(_study("diverging", float("nan"), [np.nan] * 3), sizes, "t", "", False)
    row = section.tables[0][2][0]
    text = " ".join(map(str, row))
    assert "nan" not in text.lower() and "not converging" in text and "–" in text


def test_output_labels_are_words_with_display_units():
    """Legends read "g1: strain history [µε]" and "peak deflection under load [in]", not raw variable names."""
    from softimpact.output.converge import output_label

    assert output_label("strain_g1_history", "in-lbf-s") == "g1: strain history [µε]"
    assert output_label("peak_deflection_under_load_m", "in-lbf-s") == "peak deflection under load [in]"
    assert output_label("peak_force_N", "SI") == "peak force [N]"
    assert output_label("impulse_N_s", "in-lbf-s") == "impulse [lbf·s]"


def test_the_error_figure_labels_at_least_two_decades():
    """Errors spanning less than a decade (0.2–0.6 %) still get two labelled decades on the log axis."""
    import matplotlib

    matplotlib.use("Agg")
    from softimpact.output.converge import _error_figure

    fig = _error_figure(_study("monotone", 1.6, [0.006, 0.004, 0.002]), "t", 0, "SI")
    fig.canvas.draw()
    ax = fig.axes[0]
    lo, hi = ax.get_ylim()
    labelled = [t for t in ax.get_yticklabels() if t.get_text() and lo <= t.get_position()[1] <= hi]
    assert len(labelled) >= 2, [t.get_text() for t in ax.get_yticklabels()]


def test_converge_refused_at_its_default_levels_names_the_levels_that_fit(tmp_path):
    """``converge plate-ss-8in`` (the README's) refused at 3 levels names the largest --levels that fits and the level that does not."""
    line = error_line(invoke("converge", "plate-ss-8in", "--out", tmp_path / "o", "--no-figures"))
    m = re.search(r"--levels (\d+) \(×1 … ×(\d+)\) is the most that fits", line)
    assert m and int(m.group(1)) < 3 and int(m.group(2)) == 2 ** (int(m.group(1)) - 1), line
    assert "level 3 of 3 (×4)" in line and "--ignore-limits" in line
    assert not (tmp_path / "o").exists()


@pytest.mark.slow  # seconds: the slow tier (make test-slow)
def test_calibrates_result_line_says_how_the_fit_ended_in_plain_words(tmp_path):
    """calibrate's result line says "converged after N model runs" in our words, never scipy's termination text."""
    from importlib import resources

    record = resources.files("softimpact") / "data" / "series" / "paper-long-calibration" / "long-V1166.csv"
    r = invoke("calibrate", "paper-long-beam", "--measured", record, "--velocity", "1166 in/s", "--no-figures", "--out", tmp_path / "o")
    assert r.exit_code == 0, r.output
    assert re.search(r"converged after \d+ model runs", r.output), r.output
    for scipy_text in ("`ftol`", "`xtol`", "`gtol`", "termination condition", "satisfied"):
        assert scipy_text not in r.output


def test_the_error_figure_gives_each_of_many_outputs_its_own_colour():
    """Thirteen outputs (more than the ten-colour cycle): thirteen distinct curve colours on the error figure."""
    from types import SimpleNamespace

    import matplotlib
    from matplotlib.colors import to_rgba

    matplotlib.use("Agg")
    from softimpact.output.converge import _error_figure

    outs = [
        SimpleNamespace(name=f"strain_g{i}_peak_magnitude", kind="scalar", status="monotone", order=2.0, errors=np.array([0.01, 0.0025, 0.0006]) * (1 + i))
        for i in range(13)
    ]
    fig = _error_figure(SimpleNamespace(outputs=outs, levels=[0, 1, 2], ratio=2.0), "t", 0, "SI")
    colors = {to_rgba(line.get_color()) for line in fig.axes[0].get_lines() if not line.get_label().startswith("slope")}
    assert len(colors) == 13


@pytest.mark.parametrize(
    "command, case, given, expected",
    [
        ("plate", "paper-long-beam", "a beam case", "a plate case"),
        ("bar", "plate-ss-8in-impact", "an impact case", "a bar case"),
        ("impact", "plate-ss-8in", "a plate case", "an impact case"),
        ("beam", "paper-calibration", "a bar case", "a beam case"),
    ],
)
def test_a_case_of_another_kind_names_what_was_given_and_what_is_expected(tmp_path, command, case, given, expected):
    """Every case command given a case of another kind: one line naming both kinds, never "<table>: missing"."""
    line = error_line(invoke(command, case, "--out", tmp_path / "o", "--no-figures"))
    assert f"is {given}: {expected}" in line and "missing" not in line


@pytest.mark.parametrize(
    ("written", "expected", "key"), [('layup = "', 'lay_up = "', "plate.laminate.layup"), ("support = {", "supports = {", "plate.support")]
)
def test_a_misspelt_required_key_is_named_with_the_key_written(tmp_path, written, expected, key):
    """A required key written misspelt ('lay_up', 'supports') is reported once, naming the key expected and the one
    written (not as 'missing' with no hint, nor with its key printed twice), and nothing is written."""
    text = locate("plate-ss-8in").read_text().replace("elements = [48, 48]", "elements = [8, 8]")
    assert written in text
    (tmp_path / "plate.toml").write_text(text.replace(written, expected, 1))
    line = error_line(invoke("plate", tmp_path / "plate.toml", "--out", tmp_path / "out", "--no-figures"))
    assert line.count(key) == 1 and "missing (required)" in line and repr(expected.split(" ")[0]) in line
    assert not (tmp_path / "out").exists()
