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
def paper_report(tmp_path_factory, request) -> PaperReport:
    """`softimpact paper` run once per test run (across xdist workers, under a file lock) and read from disk."""
    worker = getattr(request.config, "workerinput", {}).get("workerid", "master")  # xdist's worker_id, also without xdist
    return shared_paper(tmp_path_factory, worker)


def pytest_collection_modifyitems(config, items):
    """Files in the order of their longest path: the files reading the shared paper first, then files with slow
    tests, then the rest (each file's own order kept). With ``--dist loadfile --no-loadscope-reorder`` (make test)
    the paper starts at once on one worker while the other takes the remaining files one by one."""

    def rank(item) -> int:
        return 0 if "paper_report" in item.fixturenames else 1 if item.get_closest_marker("slow") else 2

    files: dict = {}
    for item in items:
        files.setdefault(item.path, []).append(item)
    first = {path: min(rank(i) for i in group) for path, group in files.items()}
    items[:] = [item for path in sorted(files, key=first.__getitem__) for item in files[path]]
