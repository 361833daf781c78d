"""The report's section on the discretisation error of the paper's meshes (bar, long and short beams)."""

from __future__ import annotations

from ...cases import KINDS
from ...input.bar_case import load_bar_case
from ...input.beam_case import load_beam_case
from ...output.converge import converge_files, converge_section
from ...output.report import Section
from ...workflows.convergence import study_case
from ...workflows.refinement import coarsen_beam

__all__ = ["discretisation_sections"]


def discretisation_sections(figures: bool, files: dict) -> list[Section]:
    """Richardson studies of the bar case and of both beams, the paper's mesh in the middle of three levels."""
    sections = []
    problem, _ = load_bar_case("paper-calibration")
    result, sizes = study_case(KINDS["bar"], problem, 3, 2)
    files.update(converge_files(result, sizes, problem, "bar", figures, prefix="convergence/bar/"))
    sections.append(converge_section(result, sizes, "Discretisation error: the bar (paper-calibration)", "convergence/bar/", figures))
    for name in ("paper-long-beam", "paper-short-beam"):
        problem, _ = load_beam_case(name, 1)
        base = coarsen_beam(problem, 2)  # levels ½, 1, 2: the paper's mesh in the middle
        result, sizes = study_case(KINDS["beam"], base, 3, 2, case_level=1)
        prefix = f"convergence/{name.removeprefix('paper-')}/"
        files.update(converge_files(result, sizes, base, "beam", figures, prefix=prefix, case_level=1))
        title = f"Discretisation error: the {name.removeprefix('paper-').replace('-', ' ')} (history 1)"
        sections.append(converge_section(result, sizes, title, prefix, figures, case_level=1))
    return sections
