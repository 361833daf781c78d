"""The case registry: one :class:`CaseKind` per kind of case (bar, beam, plate, impact).

Every command that takes a case, ``sweep`` and ``converge`` read a case through its
kind (:data:`KINDS`, :func:`kind_of`). A kind provides

- ``table``: the TOML table only that kind of case has (``detect(data)`` looks for it);
- ``load(case, history=None) -> (problem, inputs)``: a case file or built-in name read and checked;
- ``problem(data, base)``: a parsed case (a dict) as a problem (raises InputError);
- ``check(problem)``: resolution and resource guards, before anything is built;
- ``refine(problem, factor)``: mesh and time step refined together (``converge``);
- ``study(problem, stride, progress) -> (outputs, size)``: one level of a convergence
  study: the kind's :meth:`summary` scalars, the histories every ``stride``-th sample,
  and the size of the model that ran (its true DOF count);
- ``structure_key(data)``: a text equal for two cases exactly when they share the
  expensive part (mesh, factorisation, impulse responses): sweep runs are grouped by it;
- ``prepare(data, base, runs, outputs, cases)`` / ``run(prepared, data, base, outputs)``: that
  expensive part built once per group, covering every run of the group (``cases``: their case
  dicts; it must pickle: it travels to Dask workers), and one run → the kind's :meth:`summary`;
- ``summary(problem, result, model)``: the ONE set of scalar outputs of the kind, as the
  command's summary.json names them (sweep outputs and converge read the same keys);
- ``output_keys(problem)``: the dotted outputs a sweep may ask for;
- ``expand(data, key)``: make ``key`` settable (a catalogue ply turned into its inline table);
- ``problem_class()``: the type of its problems (:func:`kind_for` finds a problem's kind by it);
- ``execute(problem, *, figures, fields, damage, method, kernels, model, energy, stop_after, progress) -> Run``:
  the one run of a problem (:func:`softimpact.cases.run.execute`, which dispatches here);
- ``damage_refusal(problem)``: why the problem has no damage outputs (None when it has them, or has none to give);
- ``refusal(problem, study)``: why ``study`` ("a sweep", "converge") cannot run the problem (None when it can):
  both ask before any run, so a kind of run a study does not take is refused at once, never run by run.

This package sits below app: it imports input, output, workflows, fem and models.
"""

from __future__ import annotations

from pathlib import Path

from ..errors import InputError
from ._common import CaseKind, flatten
from .bar import BarKind
from .beam import BeamKind
from .impact import ImpactKind
from .plate import PlateKind

__all__ = ["CaseKind", "KINDS", "kind_of", "kind_for", "case_kind", "builtin_listing", "flatten", "BarKind", "BeamKind", "PlateKind", "ImpactKind"]

# Order matters only for files holding several tables: an impact case names its target in [target].
KINDS: dict[str, CaseKind] = {"impact": ImpactKind(), "beam": BeamKind(), "plate": PlateKind(), "bar": BarKind()}


def kind_of(data: dict, where: str = "case") -> CaseKind:
    """The kind of a parsed case (the table only that kind has); InputError naming ``where`` otherwise."""
    if "test" in data or "tests" in data:
        raise InputError(f"{where}: a series (its [[test]] tables are reduced by `softimpact reduce`/`fit`), not a case")
    if "sweep" in data:
        raise InputError(f"{where}: a sweep spec (run it with `softimpact sweep`), not a case")
    for kind in KINDS.values():
        if kind.detect(data):
            return kind
    tables = ", ".join(f"[{k.table}]" for k in KINDS.values())
    raise InputError(f"{where}: not a case: none of the tables {tables} is present")


def kind_for(problem) -> CaseKind:
    """The kind whose problems ``problem`` is (by its type, :meth:`CaseKind.problem_class`): an impact case
    on a bar target reads as a bar problem, and runs as one."""
    for kind in KINDS.values():
        if isinstance(problem, kind.problem_class()):
            return kind
    raise InputError(f"problem: expected a bar, beam, plate or impact problem, got {type(problem).__name__}")


def case_kind(case: str) -> tuple[CaseKind, Path]:
    """The kind of a case file or built-in name, and its path."""
    from ..input.toml import load_toml, locate

    path = locate(case)
    return kind_of(load_toml(path), str(path)), path


def builtin_listing() -> list[tuple[str, str, str]]:
    """The built-in cases and series (``softimpact cases``): (name, kind, title); the kind of a
    series is "series", of a file no kind detects "?"."""
    from ..input.toml import builtin_cases, load_toml

    rows = []
    for name, path in builtin_cases().items():
        data = load_toml(path)
        try:
            kind = kind_of(data).name
        except InputError:
            kind = "two-bar" if "incident_bar" in data else "bar-cal" if "shot" in data else "series" if ("test" in data or "tests" in data) else "?"
        rows.append((name, kind, str(data.get("title", ""))))
    return rows
