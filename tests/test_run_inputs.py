"""A run's inputs are never inside what it may delete (issue 42): a file an earlier softimpact run wrote into --out
and that this run reads (a law.json, a scaling.json, a force table) survives this run, unchanged, whatever the
earlier run's manifest says; a second run of the same command then reads it again."""

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from softimpact.cli import main
from softimpact.output.files import MANIFEST, write_outputs

from _support.problems import COARSE_LONG_BEAM, IDENTIFIED_LAW
from _support.small_cases import BEAM

IMPACT_ON_LAW = """units = "in-lbf-s"
[target]
case = "beam.toml"
[impactor]
material = "silicone rubber"
diameter = "0.5 in"
velocity = "2000 in/s"
[contact]
law = "identified"
law_file = "out/law.json"
[solver]
time_step = "1 us"
duration = "60 us"
"""


def _earlier_run(out: Path, name: str, content: str) -> Path:
    """``out/name`` written as an earlier softimpact run writes it: listed, with its hash, in a manifest it signed."""
    write_outputs(out, {name: content}, manifest={"command": "earlier run"})
    return out / name


def _impact(folder: Path) -> list[str]:
    (folder / "beam.toml").write_text(COARSE_LONG_BEAM)
    (folder / "case.toml").write_text(IMPACT_ON_LAW)
    _earlier_run(folder / "out", "law.json", IDENTIFIED_LAW.read_text())
    return ["impact", folder / "case.toml", "--no-figures"], "law.json"


def _predict(folder: Path) -> list[str]:
    scaling = (Path(__file__).parent / "data" / "scaling-v-main.json").read_text()
    _earlier_run(folder / "out", "scaling.json", scaling)
    return ["predict", "--constants", folder / "out" / "scaling.json", "--mass", "1.1 g", "--diameter", "0.5 in", "--velocity", "1500 in/s"], "scaling.json"


def _beam_table(folder: Path) -> list[str]:
    _earlier_run(folder / "out", "force.csv", "time_s,force_N\n0,0\n1e-4,100\n2e-4,0\n3e-4,0\n")
    case = BEAM.replace(
        'history = { shape = "skewed", peak_force = "44 lbf", time_of_peak = "30 us", duration = "355 us" }',
        'history = { shape = "table", file = "out/force.csv" }',
    )
    (folder / "beam.toml").write_text(case.replace('duration = "450 us"', 'duration = "300 us"'))
    return ["beam", folder / "beam.toml", "--no-figures"], "force.csv"


def _sweep(folder: Path) -> list[str]:
    _impact(folder)
    (folder / "spec.toml").write_text(
        '[sweep]\ncase = "case.toml"\nmethod = "grid"\noutputs = ["peak_force_N"]\n'
        '[[sweep.parameter]]\nkey = "impactor.velocity"\nvalues = ["1500 in/s", "2000 in/s"]\n'
    )
    return ["sweep", folder / "spec.toml", "--no-figures", "--workers", "0"], "law.json"


@pytest.mark.parametrize(
    "setup", [_impact, _predict, _beam_table, _sweep], ids=["impact-law.json", "predict-scaling.json", "beam-force-table", "sweep-law.json"]
)
def test_a_file_the_run_reads_survives_an_out_that_holds_it(tmp_path, setup):
    """--out at the folder holding a file the run reads, which an earlier softimpact run wrote there: the run exits 0
    leaving the file byte for byte, lists it among its manifest's inputs, and the same command run again exits 0."""
    args, name = setup(tmp_path)
    out = tmp_path / "out"
    before = (out / name).read_bytes()
    for _ in range(2):
        r = CliRunner().invoke(main, [str(a) for a in args] + ["--out", str(out)])
        assert r.exit_code == 0, r.output
        assert (out / name).read_bytes() == before
    manifest = json.loads((out / MANIFEST).read_text())
    assert str((out / name).resolve()) in {str(Path(p).resolve()) for p in manifest["inputs"]}
    assert name not in manifest["files"]
