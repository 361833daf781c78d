"""A multi-part study on the machine's cores: its parts as tasks, what several parts share computed once.

- :func:`once` memoises a function of hashable arguments in the process (as ``functools.lru_cache``), in one table
  that a task's process hands back to its parent: what a part computed for others (the contact law identified from
  the rubber series, a threshold map) is computed once per run, wherever it first ran.
- :func:`run_tasks` runs :class:`Task` s, each when the tasks it comes after are done, at most ``workers`` at a time,
  the costliest ready task first. Each runs in a process forked from this one at its start (so it holds every value
  the parent has by then: its dependencies' results and memoised values) and sends back its value, the
  :class:`~softimpact.errors.SoftimpactWarning` s it raised, its CPU and wall time, and the values it memoised. Where
  ``fork`` is not available (Windows, macOS's default) or ``workers`` is 1, the tasks run one after the other here.

The tasks' values and memoised values must pickle (a value that does not stays in its task's process, and its
users recompute it). An exception in a task is raised again in the parent (its type kept when it pickles).
"""

from __future__ import annotations

import functools
import inspect
import multiprocessing
import os
import pickle
import threading
import time
import traceback
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

from ..errors import HeldWarnings

__all__ = ["Task", "Done", "once", "run_tasks", "usable_workers"]

_MEMO: dict = {}  # (module, qualified name, arguments) → value: the memo of every function decorated with once()


def once(fn):
    """``fn`` memoised per arguments (hashable; defaults filled in) in this process's table (:data:`_MEMO`), which a task
    hands back to its parent."""

    signature = inspect.signature(fn)

    @functools.wraps(fn)
    def memoised(*args, **kwargs):
        bound = signature.bind(*args, **kwargs)
        bound.apply_defaults()  # f(x) and f(x, default) are one value
        key = (fn.__module__, fn.__qualname__, tuple(bound.arguments.values()))
        if key not in _MEMO:
            _MEMO[key] = fn(*args, **kwargs)
        return _MEMO[key]

    memoised.cache_clear = lambda: [_MEMO.pop(k) for k in list(_MEMO) if k[:2] == (fn.__module__, fn.__qualname__)]
    return memoised


@dataclass(frozen=True)
class Task:
    """One part of a study: ``fn()`` its work (its value is the task's), run when the tasks named in ``after`` are
    done; ``cost`` [s] its expected CPU time, so that the costliest ready task starts first."""

    name: str
    fn: Callable[[], object]
    after: tuple[str, ...] = ()
    cost: float = 1.0


@dataclass
class Done:
    """A finished task: its ``value``, the warnings it raised (one line each), its CPU time and wall time [s]."""

    value: object
    warnings: list[str] = field(default_factory=list)
    cpu: float = 0.0
    wall: float = 0.0


def usable_workers(workers: int | None = None) -> int:
    """The processes :func:`run_tasks` may use: ``workers``, or the cores this process may run on (None); 1 where
    processes cannot be forked, or where this process runs other threads (forking a threaded process can leave a
    child waiting on a lock another thread held)."""
    if "fork" not in multiprocessing.get_all_start_methods() or threading.active_count() > 1:
        return 1  # no fork, or other threads alive (a notebook's, a test runner's): a forked child could inherit a held lock
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1
    return max(1, cores if workers is None else workers)


def _run_here(task: Task) -> Done:
    """The task run in this process, its warnings held (one line each), its CPU and wall time measured."""
    c0, t0 = time.process_time(), time.perf_counter()
    with HeldWarnings() as held:
        value = task.fn()
    return Done(value, [" ".join(str(w.message).split()) for w in held.held], time.process_time() - c0, time.perf_counter() - t0)


def _picklable(memo: dict) -> dict:
    """The entries of ``memo`` that pickle (the others stay in the task's process)."""
    out = {}
    for k, v in memo.items():
        try:
            pickle.dumps(v, protocol=pickle.HIGHEST_PROTOCOL)
        except Exception:  # an object holding a closure or an open resource: its users recompute it
            continue
        out[k] = v
    return out


def _child(task: Task, conn) -> None:
    """A forked task's body: run it with one BLAS thread and send (status, Done or error, new memo entries) back."""
    from threadpoolctl import threadpool_limits

    before = set(_MEMO)
    try:
        with threadpool_limits(1, user_api="blas"):
            done = _run_here(task)
        new = _picklable({k: v for k, v in _MEMO.items() if k not in before})
        try:
            data = pickle.dumps(("ok", done, new), protocol=pickle.HIGHEST_PROTOCOL)
        except Exception as exc:
            data = pickle.dumps(("error", RuntimeError(f"task {task.name}: its value does not pickle ({exc})"), ""))
    except BaseException as exc:  # sent to the parent, which raises it again
        text = traceback.format_exc()
        try:
            data = pickle.dumps(("error", exc, text), protocol=pickle.HIGHEST_PROTOCOL)
        except Exception:
            data = pickle.dumps(("error", RuntimeError(f"{type(exc).__name__}: {exc}"), text))
    try:
        conn.send_bytes(data)
    finally:
        conn.close()
        os._exit(0)  # no atexit handlers or buffers of the parent's run twice


def _ready(tasks: Sequence[Task], done: dict, running: set) -> list[Task]:
    """The tasks whose dependencies are done and that are neither done nor running, costliest first."""
    ready = [t for t in tasks if t.name not in done and t.name not in running and all(a in done for a in t.after)]
    return sorted(ready, key=lambda t: -t.cost)


def run_tasks(tasks: Sequence[Task], workers: int = 1, progress: Callable[[int, int, str], None] | None = None) -> dict[str, Done]:
    """Run ``tasks`` (module docstring), at most ``workers`` processes at a time: {name: :class:`Done`}.
    ``progress(done, total, label)`` is called as each task ends."""
    names = [t.name for t in tasks]
    unknown = {a for t in tasks for a in t.after} - set(names)
    if len(set(names)) != len(names) or unknown:
        raise ValueError(f"tasks: names must be unique and every 'after' a task's name (unknown: {sorted(unknown)})")
    progress = progress or (lambda done, total, label: None)
    done: dict[str, Done] = {}
    if usable_workers(workers) <= 1:
        while len(done) < len(tasks):
            task = next(t for t in tasks if t.name not in done and all(a in done for a in t.after))
            done[task.name] = _run_here(task)
            progress(len(done), len(tasks), task.name)
        return done
    return _run_forked(tasks, usable_workers(workers), progress, done)


def _run_forked(tasks: Sequence[Task], workers: int, progress, done: dict) -> dict[str, Done]:
    """:func:`run_tasks` on forked processes: each started when a slot frees, its result read as soon as it is sent."""
    from multiprocessing.connection import wait

    ctx = multiprocessing.get_context("fork")
    running: dict = {}  # connection → (task, process)
    try:
        while len(done) < len(tasks):
            for task in _ready(tasks, done, {t.name for t, _ in running.values()})[: workers - len(running)]:
                parent, child = ctx.Pipe(duplex=False)
                process = ctx.Process(target=_child, args=(task, child), name=f"softimpact-{task.name}", daemon=True)
                process.start()
                child.close()
                running[parent] = (task, process)
            if not running:
                raise ValueError("tasks: a cycle in 'after'")
            for conn in wait(list(running)):
                task, process = running.pop(conn)
                try:
                    status, payload, extra = pickle.loads(conn.recv_bytes())
                except EOFError:
                    raise RuntimeError(f"task {task.name}: its process ended without a result (exit code {process.exitcode})") from None
                finally:
                    conn.close()
                    process.join()
                if status == "error":
                    if isinstance(extra, str) and extra:
                        payload.add_note(f"in the process of task {task.name!r}:\n{extra}")
                    raise payload
                done[task.name] = payload
                _MEMO.update(extra)
                progress(len(done), len(tasks), task.name)
    finally:
        for conn, (_, process) in running.items():
            process.kill()
            process.join()
            conn.close()
    return done
