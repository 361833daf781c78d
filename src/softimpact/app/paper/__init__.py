"""``softimpact paper``: the whole paper on the built-in cases, into one report.

One module per section of the report, each a function ``(figures, files) →
sections`` that adds its files to ``files``; :func:`paper` runs them in the
order of :data:`STEPS` and renders report.html. Only this package may import
other app modules (it reuses the commands' own steps).
"""

from __future__ import annotations

import time

from ...errors import HeldWarnings
from ...output.report import render_report
from .. import Outcome, Progress, no_progress
from .bar_calibration import bar_calibration_sections
from .beam_as_plate import beam_as_plate_section
from .beams import beam_sections
from .calibrations import calibration_sections
from .discretisation import discretisation_sections
from .hail import hail_section
from .notes import NOTES, SYSTEM
from .question import question_section
from .rubber_series import rubber_series_sections
from .thresholds import threshold_section

__all__ = ["paper", "NOTES", "SYSTEM", "STEPS"]

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


def paper(*, figures: bool = True, progress: Progress = no_progress) -> Outcome:
    """Run every section of the paper on the built-in cases; the outcome holds report.html and its files."""
    t0 = time.perf_counter()
    files: dict[str, bytes | str] = {}
    sections, warned = [], []
    for k, (label, step) in enumerate(STEPS):
        progress(k, len(STEPS), label)
        with HeldWarnings() as held:  # the run's warnings, listed in the report and (as the outcome's) shown and in the manifest
            sections.extend(step(figures, files))
        warned += [" ".join(str(w.message).split()) for w in held.held]
    progress(len(STEPS), len(STEPS), "report")
    if not figures:
        for s in sections:
            s.figures = []
    files["report.html"] = render_report("softimpact: the paper, end to end", sections, NOTES, files, warnings=warned)
    return Outcome(files, f"report.html ({len(files)} files, {time.perf_counter() - t0:.1f} s)", warnings=tuple(warned))
