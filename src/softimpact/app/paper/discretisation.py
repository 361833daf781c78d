"""The report's section on the discretisation error of the paper's meshes (bar, long and short beams)."""

from __future__ import annotations

import numpy as np

from ...cases import KINDS
from ...errors import InputError
from ...input.bar_case import load_bar_case
from ...input.beam_case import load_beam_case
from ...models.pulses import SkewedPulse
from ...output.converge import converge_files, converge_section
from ...output.report import Section
from ...studies.tasks import once
from ...workflows.convergence import study_case
from ...workflows.refinement import coarsen_beam

__all__ = ["discretisation_sections"]

MAX_HISTORIES = 8  # rows of a beam case's [[load.table]] studied (Tables II and III have 4)


def discretisation_sections(figures: bool, files: dict) -> list[Section]:
    """Richardson studies of the bar case and of both beams, the paper's mesh in the middle of three levels."""
    sections, first = [], {}
    result, sizes, problem = bar_study()
    files.update(converge_files(result, sizes, problem, "bar", figures, prefix="convergence/bar/"))
    sections.append(converge_section(result, sizes, "Discretisation error: the bar (paper-calibration)", "convergence/bar/", figures))
    for name in ("paper-long-beam", "paper-short-beam"):
        result, sizes, base, _ = history_study(name, 1)
        first[name] = result  # history 1: also the first row of the per-history section
        prefix = f"convergence/{name.removeprefix('paper-')}/"
        files.update(converge_files(result, sizes, base, "beam", figures, prefix=prefix, case_level=1))
        title = f"Discretisation error: the {name.removeprefix('paper-').replace('-', ' ')} (history 1)"
        sections.append(converge_section(result, sizes, title, prefix, figures, case_level=1))
    sections.append(_per_history_section(first))
    return sections


@once
def bar_study() -> tuple:
    """The bar case's Richardson study on three levels (result, sizes, problem), once per run (a task of the report)."""
    problem, _ = load_bar_case("paper-calibration")
    return (*study_case(KINDS["bar"], problem, 3, 2), problem)


@once
def history_study(name: str, history: int):
    """The Richardson study of beam ``name`` under row ``history`` of its table on levels ½, 1, 2 of its mesh (the paper's
    mesh in the middle): (result, sizes, base problem, problem), or None when the table has no such row; once per run."""
    try:
        problem, _ = load_beam_case(name, history)
    except InputError:
        return None
    base = coarsen_beam(problem, 2)  # levels ½, 1, 2: the paper's mesh in the middle
    return (*study_case(KINDS["beam"], base, 3, 2, case_level=1), base, problem)


def beam_studies(name: str) -> int:
    """Every history's study of beam ``name`` (:func:`history_study`, up to MAX_HISTORIES): how many there are."""
    history = 1
    while history <= MAX_HISTORIES and history_study(name, history) is not None:
        history += 1
    return history - 1


def _per_history_section(first: dict | None = None) -> Section:
    """The discretisation error of the paper's beam meshes history by history (each row of Tables II and
    III on levels ½, 1, 2 of the paper's mesh): one range for all would hide the short pulses' larger error.
    ``first``: beam case name → its study of history 1 when already made (the same study, not run again)."""
    first = first or {}
    rows, raw = [], []
    for name in ("paper-long-beam", "paper-short-beam"):
        history = 1
        while True:
            study = history_study(name, history)
            if study is None:
                break
            result, _, _, problem = study
            result = first.get(name, result) if history == 1 else result
            gauges = [o for o in result.outputs if o.kind == "history"]
            pulse = problem.load.history  # a Pulse; Tables II and III give eq-15 pulses (t_F0 and T)
            shape = f"{pulse.time_of_peak * 1e6:.0f} / {pulse.duration * 1e6:.0f}" if isinstance(pulse, SkewedPulse) else f"– / {pulse.duration * 1e6:.0f}"
            for o in gauges:
                if np.isfinite(o.errors[1]):
                    raw.append((float(o.errors[1]), name.removeprefix("paper-").replace("-", " "), history))
                rows.append(
                    [
                        name.removeprefix("paper-"),
                        str(history),
                        shape,
                        o.name,
                        o.status,
                        f"{100 * o.errors[1]:.2g} %",
                        f"{100 * o.gci_fine:.2g} % ({o.safety_factor:g})" if np.isfinite(o.gci_fine) else "",
                    ]
                )
            history += 1
            if history > MAX_HISTORIES:
                break
    worst = max(raw) if raw else None
    summary = (
        [f"Discretisation error of the paper's beam meshes (gauge strain histories, RMS): at most {100 * worst[0]:.2g} % ({worst[1]}, history {worst[2]})"]
        if worst
        else []
    )
    header = ["beam", "history", "tF0 / T [µs]", "gauge history", "status", "error of the paper's mesh (RMS)", "GCI of the finest (Fs)"]
    return Section(
        "Discretisation error of the paper's meshes, history by history",
        [
            "Each history of Tables II and III on the paper's mesh and step (level 2 of ½, 1, 2): the normalised RMS error "
            "of each gauge's strain history against the Richardson extrapolation. The error grows as the pulse shortens; "
            "a statement about history 1 does not carry over to the others."
        ],
        [("Gauge-history error of the paper's mesh, per history", header, rows)],
        [],
        summary,
    )
