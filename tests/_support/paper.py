"""The paper report, computed once per test run and shared by every test (and xdist worker) that reads it.

The pattern of pytest-xdist's documentation ("Making session-scoped fixtures execute only once"): the
first worker to take the file lock in the run's shared temporary folder runs ``softimpact paper`` into
it; the others wait on the lock and read the finished folder from disk. Without xdist the report goes
to the session's own temporary folder.
"""

from __future__ import annotations

from dataclasses import dataclass
from html.parser import HTMLParser
from pathlib import Path

DONE = "paper.done"  # written last: the folder holds a finished report


@dataclass(frozen=True)
class PaperReport:
    """The folder ``softimpact paper --out`` wrote, and its report.html."""

    out: Path
    html: str

    def tables(self) -> dict[str, tuple[list[str], list[list[str]]]]:
        """The report's tables by caption: (header, rows), each cell the text as displayed."""
        parser = _Tables()
        parser.feed(self.html)
        return parser.tables


def shared_paper(tmp_path_factory, worker_id: str) -> PaperReport:
    """``softimpact paper --out DIR`` (the CLI, as a user runs it) once per test run; DIR and its report.html."""
    if worker_id == "master":  # no xdist: this session is the whole run
        return _read(_run(tmp_path_factory.mktemp("paper")))
    from filelock import FileLock

    shared = tmp_path_factory.getbasetemp().parent  # the run's folder, parent of every worker's basetemp
    out = shared / "paper"
    failed = shared / "paper.failed"  # a failed run is not repeated by the next worker: it reads why instead
    with FileLock(str(shared / "paper.lock")):
        if failed.is_file():
            raise AssertionError(failed.read_text())
        if not (shared / DONE).is_file():
            try:
                _run(out)
            except Exception as e:
                failed.write_text(f"softimpact paper failed in another worker: {e}")
                raise
            (shared / DONE).write_text("ok\n")
    return _read(out)


def _run(out: Path) -> Path:
    from click.testing import CliRunner

    from softimpact.cli import main

    result = CliRunner().invoke(main, ["paper", "--out", str(out)])
    assert result.exit_code == 0, result.output
    return out


def _read(out: Path) -> PaperReport:
    return PaperReport(out, (out / "report.html").read_text(encoding="utf-8"))


class _Tables(HTMLParser):
    """Collects ``<table><caption>…</caption><tr><th>…</th></tr><tr><td>…</td></tr></table>`` as written by output/report.py."""

    def __init__(self):
        super().__init__()
        self.tables: dict[str, tuple[list[str], list[list[str]]]] = {}
        self._caption = self._cell = None
        self._rows: list[list[str]] = []

    def handle_starttag(self, tag, attrs):
        if tag == "table":
            self._rows = []
        elif tag == "caption":
            self._caption = ""
        elif tag == "tr":
            self._rows.append([])
        elif tag in ("th", "td"):
            self._cell = ""

    def handle_endtag(self, tag):
        if tag in ("th", "td"):
            self._rows[-1].append(self._cell)
            self._cell = None
        elif tag == "caption":
            self._title, self._caption = self._caption, None
        elif tag == "table":
            self.tables[self._title] = (self._rows[0], self._rows[1:])

    def handle_data(self, data):
        if self._cell is not None:
            self._cell += data
        elif self._caption is not None:
            self._caption += data
