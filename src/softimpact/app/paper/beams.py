"""The report's section on the laminated beams under the paper's history 1 (paper Figs 16-22)."""

from __future__ import annotations

from ...input.beam_case import load_beam_case
from ...output.beam import beam_files, beam_section
from ...output.report import Section
from ...workflows.beam_impact import BeamModel

__all__ = ["beam_sections"]


def beam_sections(figures: bool, files: dict) -> list[Section]:
    """The long and the short beam, each under row 1 of its [[load.table]] (Tables II and III)."""
    sections = []
    for name in ("paper-long-beam", "paper-short-beam"):
        problem, _ = load_beam_case(name, 1)
        model = BeamModel(problem)
        result = model.direct()
        prefix = name.removeprefix("paper-") + "/"
        files.update(beam_files(model, result, figures, prefix=prefix))
        sections.append(beam_section(model, result, prefix))
    return sections
