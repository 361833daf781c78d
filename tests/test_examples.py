"""The scripts of examples/ and the code of the Python page run and their numbers hold (scikit-fem's habit: examples cannot rot)."""

import re
import runpy
import tempfile
from pathlib import Path

import matplotlib
import pytest

ROOT = Path(__file__).parents[1]
EXAMPLES = sorted((ROOT / "examples").glob("[0-9][0-9]_*.py"))
PYTHON_PAGE = ROOT / "docs" / "python.md"
GETTING_STARTED = ROOT / "docs" / "getting-started.md"


def test_every_task_has_an_example():
    """The twelve tasks of the gallery are there (bar test, reduce and fit, beam, own plate, calibration, sweep, hail and bird, large deflection,
    a lab's own bars, the delamination benchmarks, the C-scan of a struck plate, a dent in a metal skin)."""
    assert len(EXAMPLES) == 12


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_example_speaks_the_notebook_api(path):
    """Each example runs through `import softimpact as si`, not through the command line's click runner."""
    text = path.read_text()
    assert "import softimpact as si" in text
    assert "CliRunner" not in text and "softimpact.cli" not in text


SLOW_EXAMPLES = {
    "05_calibrate_force_history",
    "09_your_own_bars",
    "10_delamination_benchmarks",
    "11_delamination_cscan",
    "12_dent_in_a_metal_skin",
}  # 16 s, 6 s, 6 s, about 3 min and 25 s of one core: run in the slow tier (the quick one keeps 3 minutes)


@pytest.mark.parametrize("path", [pytest.param(p, marks=pytest.mark.slow) if p.stem in SLOW_EXAMPLES else p for p in EXAMPLES], ids=lambda p: p.stem)
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


def python_blocks(text: str) -> list[str]:
    """The ```python fences of a MyST page (``{code-block} python`` fences are shown, not run)."""
    return re.findall(r"^```python\n(.*?)^```", text, flags=re.MULTILINE | re.DOTALL)


def test_python_page_runs(monkeypatch, tmp_path):
    """The ```python blocks of docs/python.md run in order in one namespace; their asserts (the file run equals the object run, to the bit) pass."""
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    blocks = python_blocks(PYTHON_PAGE.read_text())
    assert len(blocks) >= 5, "the page lost its runnable blocks"
    monkeypatch.chdir(tmp_path)
    namespace: dict = {"__name__": "__main__"}
    try:
        for i, block in enumerate(blocks):
            exec(compile(block, f"{PYTHON_PAGE.name}[block {i + 1}]", "exec"), namespace)
    finally:
        plt.close("all")
    assert (tmp_path / "out" / "impact" / "manifest.json").is_file()
    assert (tmp_path / "out" / "impact" / "fields.xdmf").is_file()


def test_getting_started_python_runs(monkeypatch, tmp_path):
    """The ```python block of docs/getting-started.md runs: the paper's bar case by name and the issue's beam from objects, written to out/bar."""
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    (block,) = python_blocks(GETTING_STARTED.read_text())
    monkeypatch.chdir(tmp_path)
    namespace: dict = {"__name__": "__main__"}
    try:
        exec(compile(block, GETTING_STARTED.name, "exec"), namespace)
    finally:
        plt.close("all")
    assert (tmp_path / "out" / "bar" / "summary.json").is_file()
    assert namespace["hit"].peak_force > 0
