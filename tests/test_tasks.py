"""The report's task runner (softimpact.studies.tasks): forked tasks give what one process gives, a memoised value is
computed once and handed to the tasks after it, an error in a task is raised again in the parent with its type, and a
task's warnings come back with it."""

from __future__ import annotations

import math
import warnings

import pytest

from softimpact.errors import InputError, SoftimpactWarning
from softimpact.studies import tasks as T
from softimpact.studies.tasks import Task, once, run_tasks, usable_workers

pytestmark = pytest.mark.skipif(usable_workers(2) < 2, reason="processes cannot be forked here")


@once
def _series_sum(n: int, power: int = 2, log: str = "") -> float:
    """Σ k^power for k = 1..n; each computation appended to the file ``log`` (the test counts them across processes)."""
    if log:
        with open(log, "a") as fh:
            fh.write(f"{n}\n")
    return float(sum(k**power for k in range(1, n + 1)))


def _tasks(log: str) -> list[Task]:
    return [
        Task("a", lambda: _series_sum(100, 2, log), cost=2.0),
        Task("b", lambda: _series_sum(100, 2, log) + _series_sum(10, 2, log), after=("a",)),
        Task("c", lambda: _series_sum(100, 2, log) * 2, after=("a",)),
        Task("d", lambda: _series_sum(20, 3, log)),
    ]


@pytest.mark.parametrize("workers", [1, 2])
def test_tasks_give_the_closed_forms_and_compute_a_shared_value_once(tmp_path, workers):
    """Σk² = n(n+1)(2n+1)/6 and Σk³ = (n(n+1)/2)² from the tasks, on one process or two; the value 'a' memoised is
    computed once and reused by 'b' and 'c', which come after it (each computation logged to a file)."""
    log = str(tmp_path / "log")
    T._MEMO.clear()
    done = run_tasks(_tasks(log), workers)
    T._MEMO.clear()
    sq = lambda n: n * (n + 1) * (2 * n + 1) / 6  # noqa: E731
    assert done["a"].value == sq(100)
    assert done["b"].value == sq(100) + sq(10)
    assert done["c"].value == 2 * sq(100)
    assert done["d"].value == (20 * 21 / 2) ** 2
    computed = open(log).read().split()
    assert sorted(computed) == ["10", "100", "20"]  # 100 once, though three tasks use it
    assert all(d.cpu >= 0 and d.wall >= 0 for d in done.values())


def test_memo_fills_defaults_so_one_value_has_one_key():
    """f(n) and f(n, power=2) are one memoised value: the second call does not recompute (nor log) it."""
    T._MEMO.clear()
    first = _series_sum(7)
    assert _series_sum(7, 2) is first and _series_sum(n=7, power=2, log="") is first
    assert len(T._MEMO) == 1
    T._MEMO.clear()


def _fails():
    raise InputError("bad key: got 3 mm", "key")


def _warns():
    warnings.warn(SoftimpactWarning("a caveat of the run"), stacklevel=2)
    return math.pi


@pytest.mark.parametrize("workers", [1, 2])
def test_an_error_in_a_task_is_raised_in_the_parent_with_its_type(workers):
    """An InputError raised in a (forked) task reaches the caller as an InputError with its message (exit 2 at the CLI)."""
    with pytest.raises(InputError, match="bad key: got 3 mm"):
        run_tasks([Task("ok", lambda: 1), Task("bad", _fails, after=("ok",))], workers)


@pytest.mark.parametrize("workers", [1, 2])
def test_a_tasks_warnings_come_back_with_its_value(workers):
    """A SoftimpactWarning raised in a task is held and returned as one line beside the task's value."""
    done = run_tasks([Task("w", _warns)], workers)
    assert done["w"].value == math.pi and done["w"].warnings == ["a caveat of the run"]


def test_unknown_dependency_is_refused():
    """A task coming after a task that is not in the list is refused before anything runs."""
    with pytest.raises(ValueError, match="unknown"):
        run_tasks([Task("a", lambda: 1, after=("nowhere",))], 2)
