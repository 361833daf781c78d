"""Never silently wrong (issue 32): a sweep's fingerprint covers every file its runs read; bounds are labelled as bounds."""

import json

import pyarrow.parquet as pq
from click.testing import CliRunner

from softimpact.cli import main

from _support.problems import COARSE_LONG_BEAM, LONG_BEAM_IMPACT

SPEC = """
[sweep]
case = "impact.toml"
method = "grid"
outputs = ["peak_force_N"]
[[sweep.parameter]]
key = "impactor.velocity"
values = ["1000 in/s", "3000 in/s"]
"""


def _impact_on_local_beam(folder, layup="[90/0]5s"):
    """An impact case whose target is the beam case beam.toml beside it, and a velocity grid on it."""
    (folder / "beam.toml").write_text(COARSE_LONG_BEAM.replace("[90/0]5s", layup))
    case = LONG_BEAM_IMPACT.format(velocity="2000 in/s").replace('"paper-long-beam"', '"beam.toml"').replace('"300 us"', '"150 us"')
    (folder / "impact.toml").write_text(case)
    (folder / "spec.toml").write_text(SPEC)
    return folder / "spec.toml"


def _sweep(spec, out):
    r = CliRunner().invoke(main, ["sweep", str(spec), "--out", str(out), "--no-figures", "--workers", "0"])
    assert r.exit_code == 0, r.output
    return r.output, pq.read_table(out / "runs.parquet").to_pydict()["peak_force_N"], json.loads((out / "summary.json").read_text())


def test_a_sweep_resumed_after_its_target_case_was_edited_follows_the_edit_and_names_the_file(tmp_path):
    """Editing the impact case's target case between two sweeps into one --out: the second sweep's peak forces are those
    of a fresh sweep of the edited cases (computed independently into another --out), not the old checkpoints', and its
    warning names the edited file."""
    first = tmp_path / "a"
    first.mkdir()
    spec = _impact_on_local_beam(first)
    out = tmp_path / "out"
    _, before, _ = _sweep(spec, out)
    (first / "beam.toml").write_text(COARSE_LONG_BEAM.replace("[90/0]5s", "[90/0]10s"))  # twice as thick: stiffer, higher peak force
    text, after, summary = _sweep(spec, out)
    fresh = tmp_path / "b"
    fresh.mkdir()
    _, expected, _ = _sweep(_impact_on_local_beam(fresh, "[90/0]10s"), tmp_path / "fresh")
    assert after == expected
    assert all(a > b for a, b in zip(after, before))
    assert summary["from_checkpoints"] == 0
    assert "beam.toml (edited)" in text and "inputs changed" in text
    # unchanged inputs resume from the new checkpoints without a word about changes
    text, again, summary = _sweep(spec, out)
    assert again == after and summary["from_checkpoints"] == 2 and "inputs changed" not in text


def test_the_fingerprint_covers_the_law_json_of_an_identified_contact_law(tmp_path):
    """The law.json an impact case's identified contact law reads (``contact.law_file``) enters the spec's inputs:
    editing one of its numbers changes the fingerprint, so its checkpoints are not reused."""
    from softimpact.input.sweep_spec import load_sweep_spec

    from _support.problems import IDENTIFIED_LAW, IDENTIFIED_ON_LONG_BEAM

    (tmp_path / "law.json").write_text(IDENTIFIED_LAW.read_text())
    (tmp_path / "impact.toml").write_text(IDENTIFIED_ON_LONG_BEAM.format(material="steel", velocity="2000 in/s", duration="100 us"))
    (tmp_path / "spec.toml").write_text(SPEC)
    one = load_sweep_spec(str(tmp_path / "spec.toml"))
    assert str((tmp_path / "law.json").resolve()) in dict(one.inputs)
    law = json.loads(IDENTIFIED_LAW.read_text())
    law["edited"] = True
    (tmp_path / "law.json").write_text(json.dumps(law))
    assert load_sweep_spec(str(tmp_path / "spec.toml")).fingerprint != one.fingerprint
