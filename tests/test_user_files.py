"""A user's files are never replaced or deleted: softimpact trusts only a manifest it signed, every
writer holds the folder's lock, and the fields writer leaves an existing .xdmf/.h5 pair alone."""

import json

import numpy as np
import pytest
from click.testing import CliRunner
from filelock import FileLock

from softimpact.cli import main
from softimpact.errors import InputError
from softimpact.output.files import LOCK, MANIFEST, signature, write_outputs

PREDICT = ["predict", "--projectile", "rubber-1/2in", "--velocity", "1166 in/s", "--no-figures"]


def invoke(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_another_tools_manifest_is_not_trusted(tmp_path):
    """A manifest.json of another tool listing the user's data.csv: predict exits 2 naming it, and
    neither data.csv nor that manifest is touched."""
    out = tmp_path / "out"
    out.mkdir()
    (out / "data.csv").write_text("t,x\n0,1\n")
    theirs = json.dumps({"tool": "labview-export", "files": {"data.csv": "0" * 64}})
    (out / MANIFEST).write_text(theirs)
    result = invoke(*PREDICT, "--out", out)
    assert result.exit_code == 2, result.output
    assert MANIFEST in result.output
    assert (out / "data.csv").read_text() == "t,x\n0,1\n"
    assert (out / MANIFEST).read_text() == theirs


def test_an_edited_manifest_loses_its_signature(tmp_path):
    """A softimpact manifest whose file list was edited by hand (a user file added to it) no longer
    matches its signature: the listed user file survives the next run, which exits 2."""
    out = tmp_path / "out"
    assert invoke(*PREDICT, "--out", out).exit_code == 0
    data = json.loads((out / MANIFEST).read_text())
    (out / "mine.csv").write_text("precious\n")
    data["files"]["mine.csv"] = "0" * 64
    (out / MANIFEST).write_text(json.dumps(data))
    assert invoke(*PREDICT, "--out", out).exit_code == 2
    assert (out / "mine.csv").read_text() == "precious\n"


def test_own_manifest_is_signed_over_its_files(tmp_path):
    """softimpact's manifest carries its generator and the signature of exactly the files it lists, so a
    rerun into the folder proceeds (the same command twice, exit 0 both times)."""
    out = tmp_path / "out"
    assert invoke(*PREDICT, "--out", out).exit_code == 0
    data = json.loads((out / MANIFEST).read_text())
    assert data["generator"] == "softimpact" and data["signature"] == signature(data["files"])
    assert invoke(*PREDICT, "--out", out).exit_code == 0


def test_python_write_over_a_users_manifest_is_refused(tmp_path):
    """The writer behind every ``.write()``: a user's own manifest.json in the folder stops it, unchanged."""
    (tmp_path / MANIFEST).write_text('{"mine": true}')
    with pytest.raises(InputError, match="manifest.json"):
        write_outputs(tmp_path, {"summary.json": "{}"}, manifest={"command": "test"})
    assert (tmp_path / MANIFEST).read_text() == '{"mine": true}'
    assert not (tmp_path / "summary.json").exists()


def test_python_write_respects_a_running_commands_lock(tmp_path):
    """A folder whose lock another run holds (as a running command does): a Python write is refused at
    once, nothing written."""
    held = FileLock(str(tmp_path / LOCK), timeout=0)
    held.acquire()
    try:
        # filelock locks per open file: a second lock object in this process stands for the other run
        with pytest.raises(InputError, match="another softimpact run"):
            write_outputs(tmp_path, {"summary.json": "{}"}, manifest={"command": "test"})
    finally:
        held.release()
    assert not (tmp_path / "summary.json").exists()


@pytest.fixture(scope="module")
def beam_model():
    import softimpact as si

    beam = si.Beam(length="2 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]s"), elements=(16, 4))
    res = si.impact(beam, at="1 in", impactor=si.Sphere("steel", "0.25 in", velocity="10 in/s"), time_step="1 us", duration="20 us")
    return res


def test_fields_never_replace_a_users_companion_h5(tmp_path, beam_model):
    """write_fields("shot12.xdmf") beside the user's shot12.h5: refused naming it, the .h5 unchanged."""
    (tmp_path / "shot12.h5").write_bytes(b"user data")
    with pytest.raises(InputError, match="shot12.h5"):
        beam_model.write_fields(tmp_path / "shot12.xdmf")
    assert (tmp_path / "shot12.h5").read_bytes() == b"user data"
    assert not (tmp_path / "shot12.xdmf").exists()


def test_fields_need_an_xdmf_path(tmp_path, beam_model):
    """write_fields("fields.h5") would write an unreadable pair: refused before writing."""
    with pytest.raises(InputError, match="xdmf"):
        beam_model.write_fields(tmp_path / "fields.h5")
    assert list(tmp_path.iterdir()) == []


def test_fields_written_as_a_pair_read_back(tmp_path, beam_model):
    """A fresh path gets both files, and meshio reads back as many frames as steps written."""
    meshio = pytest.importorskip("meshio")
    steps = beam_model.write_fields(tmp_path / "f.xdmf", frames=5)
    assert (tmp_path / "f.h5").exists()
    with meshio.xdmf.TimeSeriesReader(str(tmp_path / "f.xdmf")) as reader:
        reader.read_points_cells()
        assert reader.num_steps == len(np.asarray(steps))
