"""Optional extras checked before any work: a command that needs a module of an extra that is not installed stops
at once with exit 2 and the extra's install line, and writes nothing (no output folder, no checkpoints/).

A missing module is simulated by ``sys.modules[name] = None`` (what Python's import machinery reads as "cannot be
imported"), so the tests run where the extras are installed.
"""

from __future__ import annotations

import sys

import pytest
from click.testing import CliRunner

from softimpact.cli import main
from softimpact.extras import EXTRAS, MissingExtra, missing, require

SPEC = """[sweep]
case = "paper-long-beam"
method = "grid"
outputs = ["peak_force_N"]
[[sweep.parameter]]
key = "load.history"
value = { shape = "empirical", projectile = "rubber-1/2in", velocity = "1000 in/s" }
[[sweep.parameter]]
key = "load.history.velocity"
values = ["1000 in/s", "3000 in/s"]
"""

SERIES = """[bar]
material = "Al 6061-T6"
length = "36 in"
diameter = "0.5 in"
[gauge]
position = "18 in"
[[test]]
name = "shot"
record = "{record}"
velocity = "2000 in/s"
diameter = "0.5 in"
mass = "1.1 g"
"""

# a record file of each optional format: (name, first bytes that make the reader's format detection pick it)
RECORDS = {
    "tdms": ("shot.tdms", b"TDSm" + bytes(60)),
    "hdf5": ("shot.h5", b"\x89HDF\r\n\x1a\n" + bytes(60)),
    "scope": ("shot.isf", b":WFMPRE:BYT_NR 2;" + bytes(60)),
}


def _block(monkeypatch, *modules):
    """Make ``modules`` unimportable for the test (and its CliRunner call, in this process)."""
    for m in modules:
        monkeypatch.setitem(sys.modules, m, None)


def _exit_2_nothing_written(result, out, extra):
    """The command stopped with exit 2, one line naming the extra's install line, and no output folder."""
    assert result.exit_code == 2, result.output
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and f"pip install 'softimpact[{extra}]'" in lines[0], result.output
    assert not out.exists()


@pytest.mark.parametrize("blocked", ["pyarrow", "dask", "distributed"])
def test_sweep_without_its_extra_stops_before_any_run(tmp_path, monkeypatch, blocked):
    """A sweep on Dask workers without pyarrow or Dask: exit 2 with the install line, no checkpoints/ left behind."""
    spec = tmp_path / "spec.toml"
    spec.write_text(SPEC)
    _block(monkeypatch, blocked)
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["sweep", str(spec), "--workers", "2", "--no-figures", "--out", str(out)])
    _exit_2_nothing_written(result, out, "sweep")
    assert blocked in result.output


def test_sweep_in_a_plain_loop_needs_pyarrow_only():
    """A plain-loop sweep (--workers 0) asks for pyarrow (runs.parquet) but not for Dask."""
    assert "pyarrow" in EXTRAS["sweep"] and "dask" in EXTRAS["sweep"]
    with pytest.MonkeyPatch.context() as mp:
        _block(mp, "dask", "distributed")
        require("sweep", "softimpact sweep", ("pyarrow",))  # no error: Dask is not asked for
        with pytest.raises(MissingExtra, match="dask, distributed"):
            require("sweep", "softimpact sweep")


@pytest.mark.parametrize("command, case", [("beam", "paper-long-beam"), ("plate", "plate-ss-8in"), ("impact", "paper-long-beam-impact")])
@pytest.mark.parametrize("blocked", ["meshio", "h5py"])
def test_fields_without_its_extra_stops_before_the_run(tmp_path, monkeypatch, command, case, blocked):
    """--fields without meshio or h5py: exit 2 with the fields extra's install line, before the case is run."""
    _block(monkeypatch, blocked)
    out = tmp_path / "out"
    result = CliRunner().invoke(main, [command, case, "--fields", "--no-figures", "--out", str(out)])
    _exit_2_nothing_written(result, out, "fields")


@pytest.mark.parametrize("fmt, extra, blocked", [("tdms", "lab", "nptdms"), ("hdf5", "lab", "h5py"), ("scope", "scope", "RigolWFM")])
@pytest.mark.parametrize("command", ["reduce", "identify"])
def test_lab_record_without_its_reader_stops_before_reading(tmp_path, monkeypatch, fmt, extra, blocked, command):
    """A series with a lab record whose reader is not installed: exit 2 naming the file and the extra's install line."""
    name, head = RECORDS[fmt]
    (tmp_path / name).write_bytes(head)
    series = tmp_path / "series.toml"
    series.write_text(SERIES.format(record=name))
    _block(monkeypatch, blocked)
    out = tmp_path / "out"
    result = CliRunner().invoke(main, [command, str(series), "--no-figures", "--out", str(out)])
    _exit_2_nothing_written(result, out, extra)
    assert name in result.output


def test_missing_names_only_the_absent_modules(monkeypatch):
    """missing() lists the blocked module of an extra and not the installed ones; a MissingExtra is an ImportError too."""
    _block(monkeypatch, "h5py")
    assert missing("fields", ("h5py",)) == ["h5py"]
    assert missing("fields", ("sys",)) == []
    with pytest.raises(ImportError):
        require("fields", "write_fields", ("h5py",))
