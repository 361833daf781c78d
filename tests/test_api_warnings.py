"""The Python API is not quieter than the command line: the same warnings, the same manifest, errors in the API's terms."""

import hashlib
import json
import os
import shutil
import warnings
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import softimpact as si
from softimpact.cli import main
from softimpact.errors import InputError, SoftimpactWarning

from _support.problems import IDENTIFIED_LAW, IDENTIFIED_ON_LONG_BEAM

LAW = IDENTIFIED_LAW

RUBBER_CASE = IDENTIFIED_ON_LONG_BEAM.format(material="silicone rubber", velocity="2000 in/s", duration="1000 us")


def _sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _rubber_on_the_long_beam(law):
    """The new user's call: the paper's long beam (paper-long-beam.toml) from objects, struck by the rubber ball."""
    beam = si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(200, 6))
    return si.impact(
        beam,
        at="3 in",
        impactor=si.Sphere("silicone rubber", "0.5 in", velocity="2000 in/s"),
        law=law,
        time_step="0.5 us",
        duration="1000 us",
        gauges={"g1": "2 in", "g2": "0.5 in"},
    )


@pytest.fixture(scope="module")
def rubber(tmp_path_factory):
    """The rubber case run three ways in one folder: the command line, si.impact from objects, si.run(si.load(file))."""
    here = tmp_path_factory.mktemp("rubber")
    shutil.copy(LAW, here / "law.json")
    (here / "rubber.toml").write_text(RUBBER_CASE)
    before = Path.cwd()
    os.chdir(here)  # relative paths, as the new user gave them (manifest.json lists inputs as given)
    try:
        done = CliRunner().invoke(main, ["impact", "rubber.toml", "--out", "cli", "--no-figures"], catch_exceptions=False)
        assert done.exit_code == 0, done.output
        cli = json.loads((here / "cli" / "manifest.json").read_text())
        with warnings.catch_warnings(record=True) as heard_impact:
            warnings.simplefilter("always")
            api = _rubber_on_the_long_beam("law.json")
        with warnings.catch_warnings(record=True) as heard_run:
            warnings.simplefilter("always")
            loaded = si.run(si.load("rubber.toml"), figures=False)
        api.write("api", figures=False)
        loaded.write("run", figures=False)
    finally:
        os.chdir(before)
    return {
        "here": here,
        "cli": cli,
        "api": api,
        "loaded": loaded,
        "heard_impact": heard_impact,
        "heard_run": heard_run,
        "api_manifest": json.loads((here / "api" / "manifest.json").read_text()),
        "run_manifest": json.loads((here / "run" / "manifest.json").read_text()),
    }


def _said(heard) -> list[str]:
    return [" ".join(str(w.message).split()) for w in heard if issubclass(w.category, SoftimpactWarning)]


def test_impact_warns_where_the_models_stop_holding(rubber):
    """si.impact warns of a contact radius past the ball's radius and a deflection past half the thickness exactly when the run's own histories pass them."""
    res = rubber["api"]
    said = _said(rubber["heard_impact"])
    radius_ratio = float(np.max(res.result.contact_radius)) / (0.5 * 0.0254 / 2)
    deflection_ratio = float(np.max(np.abs(res.result.target_displacement))) / (20 * 0.0055 * 0.0254)  # 20 T300/934 plies of 0.0055 in
    assert radius_ratio > 1.0 and deflection_ratio > 0.5  # the new user's case passes both limits
    assert any("contact radius" in s and f"{radius_ratio:.3g} times the projectile's radius" in s for s in said), said
    assert any("linear beam theory" in s and f"{deflection_ratio:.3g} times the thickness" in s for s in said), said


def test_impact_warns_as_the_command_line_at_the_users_line(rubber):
    """The SoftimpactWarnings of si.impact are the command line's warnings, in its order, each pointing at the user's call (this file)."""
    assert _said(rubber["heard_impact"]) == rubber["cli"]["warnings"]
    # the unchecked projectile of law.json, the contact radius (an old law.json: no approach record), the deflection, and the
    # quasi-static delamination criteria on this wave-controlled impact (issue 42)
    assert len(rubber["cli"]["warnings"]) == 4
    for w in rubber["heard_impact"]:
        if issubclass(w.category, SoftimpactWarning):
            assert Path(w.filename).resolve() == Path(__file__).resolve()


def test_run_of_a_loaded_case_warns_as_the_command_line(rubber):
    """si.run(si.load(file)) warns the command line's warnings, each once, at the user's line."""
    assert _said(rubber["heard_run"]) == rubber["cli"]["warnings"]
    assert all(Path(w.filename).resolve() == Path(__file__).resolve() for w in rubber["heard_run"] if issubclass(w.category, SoftimpactWarning))


def test_api_manifest_carries_the_commands_warnings_and_inputs(rubber):
    """manifest.json of res.write lists the command's warnings and law.json with its SHA-256 (hashed here independently)."""
    here, cli = rubber["here"], rubber["cli"]
    api, run = rubber["api_manifest"], rubber["run_manifest"]
    assert api["warnings"] == cli["warnings"] == run["warnings"]
    assert api["inputs"] == {"law.json": _sha256(here / "law.json")}
    assert run["inputs"] == cli["inputs"]
    assert cli["inputs"]["law.json"] == _sha256(here / "law.json")
    assert rubber["api"].warnings == tuple(cli["warnings"])


def test_api_and_command_agree_on_the_numbers(rubber):
    """The object-built rubber impact gives the peak force and impulse of the same case run from files by the command line."""
    cli_summary = json.loads((rubber["here"] / "cli" / "summary.json").read_text())
    assert rubber["api"].peak_force == pytest.approx(cli_summary["peak_force_N"], rel=1e-12)
    assert rubber["api"].impulse == pytest.approx(cli_summary["impulse_N_s"], rel=1e-12)


def test_a_quiet_run_warns_nothing():
    """A steel ball at 100 in/s on the long beam stays inside every model's envelope: its one SoftimpactWarning is that the
    damage block's quasi-static delamination criteria do not apply to its regime (M_i/M_p, computed here, between the
    stand-in bounds 0.25 and 2.5: intermediate), which the manifest lists alone (run for 700 µs: its third and last contact
    ends at 634 µs and the ball leaves; none is cut short, none to come)."""
    import math

    beam = si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(40, 4))
    with warnings.catch_warnings(record=True) as heard:
        warnings.simplefilter("always")
        res = si.impact(beam, at="3 in", impactor=si.Sphere("steel", "0.5 in", velocity="100 in/s"), time_step="1 us", duration="700 us")
    inch = 0.0254
    ratio = 7833.413032987483 * math.pi / 6 * (0.5 * inch) ** 3 / (1580.0 * 20 * 0.0055 * inch * 1 * inch * 6 * inch)  # steel ball over the beam
    assert 0.25 < ratio < 2.5
    (said,) = _said(heard)
    assert "quasi-static thresholds applied to an intermediate impact" in said
    assert res.warnings == (said,)


def test_negative_diameter_is_named_before_the_mass():
    """A negative diameter is refused naming the diameter (as the case file's impactor.diameter), not the mass it would give."""
    with pytest.raises(InputError, match="^diameter: must be positive"):
        si.Sphere("steel", "-0.5 in", velocity="100 in/s")
    with pytest.raises(InputError, match="^diameter: must be positive"):
        si.Sphere("steel", "0 in", velocity="100 in/s")


def test_writing_onto_a_file_names_write_not_out(tmp_path):
    """res.write(path) where path is a file is refused in the API's terms: `write: ...`, no `--out`."""
    beam = si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(40, 4))
    res = si.impact(beam, at="3 in", impactor=si.Sphere("steel", "0.5 in", velocity="100 in/s"), time_step="1 us", duration="50 us")
    afile = tmp_path / "afile"
    afile.write_text("x")
    with pytest.raises(InputError, match="^write: ") as exc:
        res.write(afile, figures=False)
    assert "--out" not in str(exc.value)


def test_foreign_files_name_the_force_argument(tmp_path):
    """A folder holding a file no run wrote is refused telling the API's force=True, not the command line's --force."""
    beam = si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(40, 4))
    res = si.impact(beam, at="3 in", impactor=si.Sphere("steel", "0.5 in", velocity="100 in/s"), time_step="1 us", duration="50 us")
    (tmp_path / "summary.json").write_text("{}")
    with pytest.raises(InputError, match="^write: ") as exc:
        res.write(tmp_path, figures=False)
    assert "force=True" in str(exc.value) and "--force" not in str(exc.value)
    res.write(tmp_path, figures=False, force=True)
    assert json.loads((tmp_path / "summary.json").read_text())["peak_force_N"] == res.peak_force


def test_beam_case_warns_and_records_as_the_command_line(tmp_path):
    """si.run(si.load("paper-short-beam")) warns the command's deflection flag at the user's line and lists it, and the case, in manifest.json."""
    done = CliRunner().invoke(main, ["beam", "paper-short-beam", "--out", str(tmp_path / "cli"), "--no-figures"], catch_exceptions=False)
    assert done.exit_code == 0, done.output
    cli = json.loads((tmp_path / "cli" / "manifest.json").read_text())
    with warnings.catch_warnings(record=True) as heard:
        warnings.simplefilter("always")
        res = si.run(si.load("paper-short-beam"), figures=False)
    res.write(tmp_path / "api", figures=False)
    api = json.loads((tmp_path / "api" / "manifest.json").read_text())
    assert cli["warnings"] and _said(heard) == cli["warnings"] == api["warnings"]
    assert api["inputs"] == cli["inputs"]
    w = float(np.max(np.abs(res.result.deflection))) / res.problem.beam.thickness
    assert w > 0.5 and any(f"{w:.3g} times the thickness" in s for s in _said(heard))
    assert all(Path(x.filename).resolve() == Path(__file__).resolve() for x in heard if issubclass(x.category, SoftimpactWarning))


def test_bar_impact_warns_of_a_contact_wider_than_the_bar(tmp_path):
    """The rubber ball at 2000 in/s on the 1/2-in bar: the contact radius (from the run's history) passes the bar's radius, and si.impact says so."""
    shutil.copy(LAW, tmp_path / "law.json")
    bar = si.Bar("Al 6061-T6", length="36 in", diameter="0.5 in")
    with warnings.catch_warnings(record=True) as heard:
        warnings.simplefilter("always")
        res = si.impact(
            bar, impactor=si.Sphere("silicone rubber", "0.5 in", velocity="2000 in/s"), law=tmp_path / "law.json", time_step="0.5 us", duration="600 us"
        )
    a = float(np.max(res.result.contact_radius))
    assert a > 0.25 * 0.0254
    assert any(f"contact radius {a:.4g} m exceeds the bar's radius" in s for s in _said(heard)), _said(heard)
    assert res.warnings == tuple(_said(heard))
    res.write(tmp_path / "out", figures=False)
    manifest = json.loads((tmp_path / "out" / "manifest.json").read_text())
    assert manifest["warnings"] == list(res.warnings)
    assert manifest["inputs"] == {str(tmp_path / "law.json"): _sha256(tmp_path / "law.json")}


def test_command_wrappers_warn_at_the_users_line(tmp_path):
    """si.predict past the constants' 1000-5000 in/s warns (a SoftimpactWarning at this line, as `softimpact predict` warns) and manifest.json keeps it."""
    with warnings.catch_warnings(record=True) as heard:
        warnings.simplefilter("always")
        res = si.predict(projectile="rubber-1/2in", velocity="6000 in/s", figures=False)
    said = _said(heard)
    assert len(said) == 1 and "outside the range of the constants" in said[0]
    assert all(Path(x.filename).resolve() == Path(__file__).resolve() for x in heard if issubclass(x.category, SoftimpactWarning))
    res.write(tmp_path / "out", figures=False)
    assert json.loads((tmp_path / "out" / "manifest.json").read_text())["warnings"] == said
    done = CliRunner().invoke(
        main, ["predict", "--projectile", "rubber-1/2in", "--velocity", "6000 in/s", "--out", str(tmp_path / "cli"), "--no-figures"], catch_exceptions=False
    )
    assert done.exit_code == 0, done.output
    assert json.loads((tmp_path / "cli" / "manifest.json").read_text())["warnings"] == said  # in the user's units, as the command says it
