"""The API's wrappers of the commands, its plate impact and lab records: the same files and numbers as the command line."""

import json

import numpy as np
import pytest
from click.testing import CliRunner

import softimpact as si
from softimpact.cli import main

from _support.small_cases import BEAM, PLATE  # the small beam and plate cases


def _cli(args, out):
    result = CliRunner().invoke(main, [*args, "--out", str(out), "--no-figures"], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    return out


@pytest.mark.slow  # about 10 s: fits the whole rubber series (the fit itself is in the quick tier through test_cli_series)
def test_fit_wrapper_gives_the_commands_scaling_json(tmp_path):
    """si.fit returns the scaling.json of `softimpact fit` on the same series, byte for byte, and writes it with a manifest."""
    res = si.fit("paper-rubber-series", figures=False)
    out = _cli(["fit", "paper-rubber-series"], tmp_path / "cli")
    assert res.outcome.files["scaling.json"] == (out / "scaling.json").read_text()
    res.write(tmp_path / "api", figures=False)
    manifest = json.loads((tmp_path / "api" / "manifest.json").read_text())
    assert manifest["command"].startswith("softimpact fit")
    assert (tmp_path / "api" / "scaling.json").read_text() == (out / "scaling.json").read_text()
    assert list(res.table("tests.csv").columns)


def test_plate_impact_from_objects_equals_the_command(tmp_path):
    """A si.Plate struck by a si.Sphere gives the peak force of `softimpact impact` on the same plate written as a case."""
    (tmp_path / "plate.toml").write_text(PLATE)
    (tmp_path / "impact.toml").write_text(
        '[target]\ncase = "plate.toml"\n[impactor]\nmaterial = "steel"\ndiameter = "0.5 in"\nvelocity = "100 in/s"\n'
        '[contact]\nlaw = "hertz"\n[solver]\ntime_step = "1 us"\nduration = "300 us"\n'
    )
    cli = json.loads((_cli(["impact", str(tmp_path / "impact.toml")], tmp_path / "out") / "summary.json").read_text())
    plate = si.Plate(length="8 in", width="8 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(8, 8))
    res = si.impact(plate, at=("4 in", "4 in"), impactor=si.Sphere("steel", "0.5 in", velocity="100 in/s"), time_step="1 us", duration="300 us")
    assert res.peak_force == pytest.approx(cli["peak_force_N"], rel=1e-12)
    assert res.time_of_peak == pytest.approx(cli["time_of_peak_s"], rel=1e-12)


def test_isotropic_beam_takes_material_and_thickness():
    """An isotropic si.Beam carries its catalogue material and thickness in SI (0.1 in = 2.54 mm)."""
    beam = si.Beam(length="6 in", width="1 in", material="Al 6061-T6", thickness="0.1 in", elements=(60, 4))
    assert beam.spec.thickness == pytest.approx(2.54e-3, rel=1e-15)
    assert beam.spec.material.name.startswith("Al")


def test_run_of_a_beam_case_equals_the_command(tmp_path):
    """si.run of a beam case gives the command's summary.json numbers and history.csv."""
    (tmp_path / "beam.toml").write_text(BEAM)
    out = _cli(["beam", str(tmp_path / "beam.toml")], tmp_path / "out")
    res = si.run(si.load(tmp_path / "beam.toml"))
    files = res.files(figures=False)
    assert files["history.csv"] == (out / "history.csv").read_text()
    ours, theirs = res.summary(), json.loads((out / "summary.json").read_text())
    assert ours["gauges"] == theirs["gauges"]


def test_read_record_converts_time_and_millivolts(tmp_path):
    """si.read_record reads a scope CSV: time in µs becomes seconds and mV becomes V (factors 1e-6 and 1e-3, exact by definition)."""
    t_us = np.arange(0.0, 50.0, 0.5)
    mv = 3.0 * t_us - 20.0
    path = tmp_path / "scope.csv"
    path.write_text("Time (us),CH1 (mV)\n" + "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(t_us, mv)))
    rec = si.read_record(path, channel="CH1")
    assert rec.unit == "V"
    np.testing.assert_allclose(rec.time, t_us * 1e-6, rtol=1e-12)
    np.testing.assert_allclose(rec.signal, mv * 1e-3, rtol=1e-12, atol=1e-15)
    df = rec.to_frame()
    assert df.attrs["units"]["signal"] == "V" and df.index.name == "time_s"


def test_law_json_path_equals_the_identified_law_of_a_case(tmp_path):
    """law= the path of a law.json runs the identified law as `softimpact impact` does with contact.law = "identified"."""
    from pathlib import Path

    law = Path(__file__).parent / "data" / "law-v-main.json"
    (tmp_path / "beam.toml").write_text(BEAM)
    (tmp_path / "impact.toml").write_text(
        '[target]\ncase = "beam.toml"\n[impactor]\nmaterial = "silicone rubber"\ndiameter = "0.5 in"\nvelocity = "1500 in/s"\n'
        f'[contact]\nlaw = "identified"\nlaw_file = "{law}"\n[solver]\ntime_step = "1 us"\nduration = "300 us"\n'
    )
    cli = json.loads((_cli(["impact", str(tmp_path / "impact.toml")], tmp_path / "out") / "summary.json").read_text())
    beam = si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(40, 4))
    ball = si.Sphere("silicone rubber", "0.5 in", velocity="1500 in/s")
    res = si.impact(beam, at="3 in", impactor=ball, law=law, time_step="1 us", duration="300 us", gauges={"g1": "2 in"})
    assert res.problem.law_name == "identified"
    assert res.peak_force == pytest.approx(cli["peak_force_N"], rel=1e-12)
