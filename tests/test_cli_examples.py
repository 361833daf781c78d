"""Every command's --help ends with an example, and the example runs as written (a temporary --out)."""

import shlex

import pytest
from click.testing import CliRunner

from softimpact.cli import EXAMPLES, main

# Examples that take more than a few seconds on 2 shared cores: executed in the slow tier only.
# Measured one at a time (2 cores, loaded): bar 1.9 s, beam 0.7 s, impact 0.9 s; converge 2 s, sweep 4 s, reduce 6 s,
# fit 10 s, calibrate 16 s, plate 18 s, identify 58 s.
SLOW = {
    "converge",
    "sweep",
    "reduce",
    "fit",
    "calibrate",
    "plate",
    "identify",
    "calibrate-bar",
    "shpb",
}  # the last two: run in tests/test_cli_calibrate_bar.py and test_cli_shpb.py
NOT_RUN = {"paper": "the whole paper takes minutes; run by the lead at merge"}


def _help(name):
    return CliRunner().invoke(main, [name, "--help"]).output


@pytest.mark.parametrize("name", sorted(main.commands))
def test_every_command_shows_an_example(name):
    """``softimpact NAME --help`` ends with an Example block holding the command line of EXAMPLES, as typed."""
    assert name in EXAMPLES, f"softimpact {name} has no example in cli.EXAMPLES"
    text = _help(name)
    assert "Example" in text and EXAMPLES[name][1] in text
    assert EXAMPLES[name][1].startswith(f"softimpact {name}")


def _run_example(name, tmp_path, monkeypatch):
    needs, line = EXAMPLES[name]
    monkeypatch.chdir(tmp_path)
    if needs is not None:
        head, *body = needs
        (tmp_path / head.split(":")[0]).write_text("\n".join(body) + "\n")
    args = shlex.split(line)[1:]
    if "--out" in args:
        args[args.index("--out") + 1] = str(tmp_path / "out")
    run = CliRunner().invoke(main, args)
    assert run.exit_code == 0, run.output
    if "--out" in args:
        import json

        manifest = json.loads((tmp_path / "out" / "manifest.json").read_text())
        assert manifest["status"] == "passed"
    else:
        assert run.output.strip()


def _cases(slow):
    return [pytest.param(n, marks=pytest.mark.slow) if n in SLOW else n for n in sorted(EXAMPLES) if (n in SLOW) == slow and n not in NOT_RUN]


@pytest.mark.parametrize("name", _cases(False))
def test_quick_example_runs(name, tmp_path, monkeypatch):
    """A quick command's help example exits 0 and writes into --out a manifest whose quality checks passed (or prints its listing)."""
    _run_example(name, tmp_path, monkeypatch)


@pytest.mark.parametrize("name", _cases(True))
def test_slow_example_runs(name, tmp_path, monkeypatch):
    """A slower command's help example exits 0 and writes into --out a manifest whose quality checks passed."""
    _run_example(name, tmp_path, monkeypatch)
