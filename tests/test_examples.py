"""The scripts of examples/ run and their one asserted number holds (scikit-fem's habit: examples cannot rot)."""

import runpy
import tempfile
from pathlib import Path

import matplotlib
import pytest

EXAMPLES = sorted((Path(__file__).parents[1] / "examples").glob("[0-9][0-9]_*.py"))


def test_every_task_has_an_example():
    """The six tasks of the gallery are there (bar test, reduce and fit, beam, own plate, calibration, sweep)."""
    assert len(EXAMPLES) == 6


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_example_runs_and_asserts_its_number(path, monkeypatch, tmp_path):
    """The example runs to its end: its assert against a closed form, the paper or a peer passed."""
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))  # the examples write into tempfile.mkdtemp()
    try:
        runpy.run_path(str(path), run_name="__main__")
    finally:
        plt.close("all")
