"""A user's files in ``--out`` are never lost, and every ``--out`` problem is found before any computing."""

import os

import pytest
from click.testing import CliRunner
from filelock import FileLock

from softimpact.cli import main
from softimpact.errors import InputError
from softimpact.output.files import LOCK, write_outputs


def invoke(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def error_line(result) -> str:
    """The one ``softimpact: error:`` line of a run that exited 2."""
    assert result.exit_code == 2, result.output
    lines = [line for line in result.stderr.splitlines() if line.startswith("softimpact: error:")]
    assert len(lines) == 1 and "Traceback" not in result.output, result.output
    return lines[0]


def test_users_file_with_an_outputs_name_stops_the_run_before_computing(tmp_path):
    """A measured history.csv of the user's in --out: exit 2 naming it, the file untouched, nothing written."""
    out = tmp_path / "out"
    out.mkdir()
    mine = out / "history.csv"
    mine.write_text("time_s,strain\n0,0\n")
    line = error_line(invoke("bar", "paper-calibration", "--out", out))
    assert "history.csv" in line and "--force" in line
    assert mine.read_text() == "time_s,strain\n0,0\n"
    assert sorted(p.name for p in out.iterdir()) == ["history.csv"]


def test_force_lets_the_run_replace_the_users_file(tmp_path):
    """``softimpact --force`` proceeds and lists the replaced file in its manifest."""
    out = tmp_path / "out"
    out.mkdir()
    (out / "history.csv").write_text("mine\n")
    result = invoke("--force", "bar", "paper-calibration", "--out", out, "--no-figures")
    assert result.exit_code == 0, result.output
    assert (out / "history.csv").read_text().startswith("time_s,")


def test_a_second_run_replaces_only_what_the_first_wrote(tmp_path):
    """A rerun into its own folder needs no --force; a file of the user's beside the outputs stays."""
    out = tmp_path / "out"
    assert invoke("bar", "paper-calibration", "--out", out, "--no-figures").exit_code == 0
    (out / "notes.md").write_text("mine")
    assert invoke("bar", "paper-calibration", "--out", out, "--no-figures").exit_code == 0
    assert (out / "notes.md").read_text() == "mine"


def test_an_edited_output_the_run_would_rewrite_is_kept(tmp_path):
    """An output the user edited since the run wrote it is not replaced by a run that writes it again."""
    out = tmp_path / "out"
    assert invoke("bar", "paper-calibration", "--out", out, "--no-figures").exit_code == 0
    (out / "summary.json").write_text("{}\n")
    line = error_line(invoke("bar", "paper-calibration", "--out", out, "--no-figures"))
    assert "summary.json" in line
    assert (out / "summary.json").read_text() == "{}\n"


def test_empty_out_is_refused(tmp_path, monkeypatch):
    """``--out ""`` would write into the working folder: exit 2, nothing written there."""
    monkeypatch.chdir(tmp_path)
    line = error_line(invoke("bar", "paper-calibration", "--out", ""))
    assert "--out" in line
    assert list(tmp_path.iterdir()) == []


def test_dangling_symlink_out_is_refused(tmp_path):
    """A symlink pointing nowhere as --out: exit 2 naming its target, nothing created."""
    link = tmp_path / "link"
    os.symlink(tmp_path / "missing" / "deeper", link)
    line = error_line(invoke("bar", "paper-calibration", "--out", link))
    assert "does not exist" in line
    assert not (tmp_path / "missing").exists()


def test_busy_folder_is_refused_at_once(tmp_path):
    """A folder another run holds (its lock taken): exit 2 saying so, the other run's lock left alone."""
    out = tmp_path / "out"
    out.mkdir()
    with FileLock(str(out / LOCK)):
        line = error_line(invoke("bar", "paper-calibration", "--out", out, "--no-figures"))
        assert "another softimpact run" in line
        assert not (out / "summary.json").exists()


def test_failed_run_leaves_no_folder_behind(tmp_path):
    """A run refused for bad input does not leave the folder it would have created (nor its lock)."""
    out = tmp_path / "new"
    error_line(invoke("bar", "no-such-case", "--out", out))
    assert not out.exists()


def test_write_outputs_refuses_a_foreign_target(tmp_path):
    """write_outputs itself (the Python edge) never replaces a file no manifest lists, unless forced."""
    (tmp_path / "a.csv").write_text("mine\n")
    with pytest.raises(InputError, match="a.csv"):
        write_outputs(tmp_path, {"a.csv": "x\n1\n"}, manifest={"status": "passed"})
    assert (tmp_path / "a.csv").read_text() == "mine\n"
    write_outputs(tmp_path, {"a.csv": "x\n1\n"}, manifest={"status": "passed"}, force=True)
    assert (tmp_path / "a.csv").read_text() == "x\n1\n"
