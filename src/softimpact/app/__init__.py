"""One function per command: arguments in, an :class:`Outcome` out (files, inputs, one line).

The app layer reads the inputs (:mod:`softimpact.input`), runs the workflows,
and turns results into the file contract (:mod:`softimpact.output`); the
command line (:mod:`softimpact.cli`) only parses arguments, writes the
outcome's files and prints its line. Long runs report progress through a
callback ``progress(done, total, label)``; nothing here prints or writes.

Each command is a function of keyword-only options (``predict(*, projectile=...,
velocity=..., ...)``) that parses, calls a workflow (or a study of several,
:mod:`softimpact.studies`), hands the result to output and returns an
:class:`Outcome`. No app module imports another, except the report's package
:mod:`softimpact.app.paper` (one module per section), which reuses them.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["Outcome", "Progress", "no_progress"]

Progress = Callable[[int, int, str], None]


def no_progress(done: int, total: int, label: str) -> None:
    """The default progress callback: silent."""


@dataclass(frozen=True)
class Outcome:
    """What a command made: ``files`` (relative name → content) to write into the
    output folder, the ``inputs`` they must never overwrite, the one ``line`` to
    print, ``warnings`` to show before it, and the quality ``gates`` of a fit
    (:mod:`softimpact.gates`): if one failed, the command line still writes the
    files, then exits 3 (or 0 under ``--accept-poor``)."""

    files: dict[str, bytes | str]
    line: str
    inputs: tuple[Path, ...] = ()
    warnings: tuple[str, ...] = field(default_factory=tuple)
    gates: tuple = ()  # of softimpact.gates.Gate
