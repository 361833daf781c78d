"""``softimpact paper``: the whole paper on the built-in cases, into one report.

One module per section of the report, each a function ``(figures, files) → sections`` that adds its files to
``files``; :func:`paper` runs them, and the computations several of them share or that cost most
(:func:`computations`: the identified law, the threshold maps structure by structure, the hail map panel by panel,
:mod:`softimpact.studies.paper`), as tasks on the machine's cores (:func:`softimpact.studies.tasks.run_tasks`: each
when what it needs is done, the costliest first), then renders report.html from the sections in the order of
:data:`STEPS`. Only this package may import other app modules (it reuses the commands' own steps).
"""

from __future__ import annotations

import functools
import time

from ...output.report import render_report
from ...studies.paper import hail as hail_study
from ...studies.paper import question as question_study
from ...studies.paper import thresholds as threshold_study
from ...studies.paper.series import rubber_series_fits
from ...studies.tasks import Task, run_tasks, usable_workers
from .. import Outcome, Progress, no_progress
from .bar_calibration import bar_calibration_sections
from .beam_as_plate import beam_as_plate_section
from .beams import BEAMS, beam_run_section, beam_sections, crossing_section
from .calibrations import beam_calibration, calibration_sections
from .discretisation import bar_study, beam_studies, discretisation_sections
from .hail import hail_section
from .notes import NOTES, SYSTEM
from .question import question_section
from .rubber_series import rubber_series_sections
from .thresholds import PAPER_PLATE_MESHES, paper_thresholds, plate_mesh_thresholds, threshold_section

__all__ = ["paper", "NOTES", "SYSTEM", "STEPS", "UNITS", "SECTION_UNITS", "computations"]

# The report's sections in order: (progress label, function (figures, files) → list of sections).
STEPS = (
    ("bar calibration (Figs 4-6)", bar_calibration_sections),
    ("rubber-ball series, Table I (Figs 7-15)", rubber_series_sections),
    ("laminated beams (Figs 16-22)", beam_sections),
    ("calibration, Tables II and III (Figs 23-25)", calibration_sections),
    ("discretisation error of the paper's meshes", discretisation_sections),
    ("damage thresholds (sweep)", lambda figures, files: [threshold_section(figures, files)]),
    ("the paper's question: coupled impact from bar tests", lambda figures, files: [question_section(figures, files)]),
    ("beams as 1-inch-wide plates: the plane-strain assumption", lambda figures, files: [beam_as_plate_section(figures, files)]),
    ("hail on Rhymer's panels", lambda figures, files: [hail_section(figures, files)]),
)

_PANELS = range(len(hail_study.RHYMER_THICKNESSES))


def computations(figures: bool) -> tuple:
    """The computations the sections share or that cost most, each a task: (name, function, tasks it comes after, CPU
    [s] measured on the project's machine, so that the costliest ready task starts first; BENCHMARKS.md)."""
    return (
        ("rubber series", rubber_series_fits, (), 4.0),
        ("identified law", threshold_study.paper_identification, ("rubber series",), 17.0),
        ("predictive intervals", question_study.paper_predictions, ("identified law",), 4.0),
        *((f"what-if law, {w}", functools.partial(question_study.what_if_law, made), (), 8.0) for w, made in _WHAT_IF),
        *((f"maps: {n}", functools.partial(threshold_study.structure_maps, n), ("identified law",), c) for n, c in _MAPPED.items()),
        ("maps: both kinematics", threshold_study.paper_kinematics_maps, ("identified law",), 16.0),
        ("beams' kinematics check", threshold_study.beam_kinematics_check, tuple(f"maps: {n}" for n in threshold_study.PAPER_BEAMS), 3.0),
        ("prescribed: beams", paper_thresholds, ("rubber series",), 4.0),
        *((f"prescribed: plate {n}", functools.partial(plate_mesh_thresholds, n), ("rubber series",), n / 8) for n in PAPER_PLATE_MESHES),
        *((f"hail: panel {k}", functools.partial(hail_study.panel_rows, k), (), 2.5) for k in _PANELS),
        *((f"hail, von Karman: panel {k}", functools.partial(hail_study.panel_vk_rows, k), (f"hail: panel {k}",), 14.0) for k in _PANELS),
        *((f"calibration: {b} beam", functools.partial(beam_calibration, b, figures), (), 11.0) for b in ("long", "short")),
        *((f"beam: {n}", functools.partial(beam_run_section, n, figures), (), 2.0) for n in BEAMS),
        ("beams' first zero crossing", crossing_section, (), 10.0),
        ("convergence: bar", bar_study, (), 1.0),
        *((f"convergence: {n}", functools.partial(beam_studies, n), (), 6.0) for n in BEAMS),
    )


_WHAT_IF = (("built-in tests", False), ("tables' alpha3", True))
_MAPPED = {**dict.fromkeys(threshold_study.PAPER_BEAMS, 4.0), threshold_study.PAPER_PLATE: 14.0}

# each section's task (by its label in STEPS): the computations it comes after, and its own CPU [s] beyond them
_SECTION_NEEDS = {
    STEPS[1][0]: (("rubber series",), 4.0),
    STEPS[2][0]: ((*(f"beam: {n}" for n in BEAMS), "beams' first zero crossing"), 1.0),
    STEPS[3][0]: (("calibration: long beam", "calibration: short beam"), 1.0),
    STEPS[4][0]: (("convergence: bar", *(f"convergence: {n}" for n in BEAMS)), 1.0),
    STEPS[5][0]: (
        (*(f"maps: {n}" for n in _MAPPED), "maps: both kinematics", "beams' kinematics check", "prescribed: beams")
        + tuple(f"prescribed: plate {n}" for n in PAPER_PLATE_MESHES),
        3.0,
    ),
    STEPS[6][0]: (("identified law", "predictive intervals", *(f"what-if law, {w}" for w, _ in _WHAT_IF)), 6.0),
    STEPS[8][0]: (tuple(f"hail, von Karman: panel {k}" for k in _PANELS), 1.0),
}


# the unit system of each step's sections (said at their heads): the paper's, but where a section says otherwise
UNITS = {
    "in-lbf-s": "in, lbf, s (the paper's): lengths in in, forces in lbf, velocities in in/s, times in µs, strains in µε",
    "SI": "SI: lengths in m (panel thickness and ice diameter in mm), forces in N, velocities in m/s, energies in J",
}
SECTION_UNITS = {
    STEPS[4][0]: "none: errors relative to the Richardson extrapolation (%), time steps in µs",
    STEPS[8][0]: UNITS["SI"],
}


def _qualified(warnings: list[str], section) -> str:
    """Why a section's results hold only with a caveat, for the summary: its step's warnings and its map rows outside
    validity (both listed in the report's "Warnings of the run"); "" when it has neither."""
    parts = []
    if warnings:
        parts.append(f"{len(warnings)} warning{'' if len(warnings) == 1 else 's'} of its runs")
    rows = {(m, r) for m, r, _ in section.flagged}
    if rows:
        parts.append(f"{len(rows)} map rows outside the models' validity")
    return "; ".join(parts) + (", see Warnings of the run" if parts else "")


def _section(step, figures: bool) -> tuple[list, dict]:
    """One step of :data:`STEPS`: (its sections, the files it made)."""
    files: dict[str, bytes | str] = {}
    return step(figures, files), files


def _tasks(figures: bool) -> list[Task]:
    """The report's tasks: one per section of :data:`STEPS` (named by its label), and the :func:`computations` they
    need, directly or not."""
    sections = []
    for label, step in STEPS:
        after, cost = _SECTION_NEEDS.get(label, ((), 1.0))
        sections.append(Task(label, functools.partial(_section, step, figures), after, cost))
    computed = {name: Task(name, fn, after, cost) for name, fn, after, cost in computations(figures)}
    needed, todo = set(), [a for t in sections for a in t.after]
    while todo:
        name = todo.pop()
        if name not in needed:
            needed.add(name)
            todo += computed[name].after
    return [t for name, t in computed.items() if name in needed] + sections


def _needs(task: Task, by_name: dict) -> list[str]:
    """The tasks ``task`` comes after, directly or not, in the order of ``by_name``."""
    seen, todo = set(), list(task.after)
    while todo:
        name = todo.pop()
        if name not in seen:
            seen.add(name)
            todo += by_name[name].after
    return [name for name in by_name if name in seen]


def paper(*, figures: bool = True, progress: Progress = no_progress, workers: int | None = None, timings: list | None = None) -> Outcome:
    """Run every section of the paper on the built-in cases; the outcome holds report.html and its files.
    ``workers``: the processes the tasks run on (None: the cores this process may use; 1: one after the other, here);
    ``timings``: a list the tasks' (name, CPU [s], wall [s]) are appended to."""
    t0 = time.perf_counter()
    tasks = _tasks(figures)
    by_name = {t.name: t for t in tasks}
    done = run_tasks(tasks, usable_workers(workers), progress)
    if timings is not None:
        timings += [(t.name, done[t.name].cpu, done[t.name].wall) for t in tasks]
    progress(len(tasks), len(tasks), "report")
    files: dict[str, bytes | str] = {}
    sections, warned, told = [], [], set()
    for label, _ in STEPS:  # the run's warnings, listed in the report and (as the outcome's) shown and in the manifest
        mine = []
        for name in _needs(by_name[label], by_name):  # a shared computation's warnings once, with the first section using it
            if name not in told:
                told.add(name)
                mine += done[name].warnings
        these, made = done[label].value
        mine += done[label].warnings
        for section in these:
            section.units = section.units or SECTION_UNITS.get(label, UNITS[SYSTEM])
            section.qualified = section.qualified or _qualified(mine, section)
        sections += these
        files.update(made)
        warned += mine
    if not figures:
        for s in sections:
            s.figures = []
    files["report.html"] = render_report("softimpact: the paper, end to end", sections, NOTES, files, warnings=warned)
    return Outcome(files, f"report.html ({len(files)} files, {time.perf_counter() - t0:.1f} s)", warnings=tuple(warned))
