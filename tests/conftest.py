"""Test-session settings and the fixtures shared across test files (helpers and shared problems: tests/_support)."""

import os
import tempfile

import pytest

from _support.paper import PaperReport, shared_paper

os.environ.setdefault("MPLBACKEND", "Agg")
# The unit-factor cache of softimpact.units goes to a folder of this test session,
# not the user's ~/.cache (subprocesses of the CLI tests inherit it).
os.environ["SOFTIMPACT_CACHE_DIR"] = tempfile.mkdtemp(prefix="softimpact-cache-")


@pytest.fixture(scope="session")
def paper_report(tmp_path_factory, worker_id) -> PaperReport:
    """`softimpact paper` run once per test run (across xdist workers, under a file lock) and read from disk."""
    return shared_paper(tmp_path_factory, worker_id)
