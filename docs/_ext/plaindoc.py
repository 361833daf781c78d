"""Read the package's docstrings, written for ``help()`` as plain text, as reStructuredText.

The docstrings carry formulas with absolute values (``|f2 − f1|``), formulas indented under the
last line of a paragraph and lists that follow a paragraph line directly: readable in a terminal,
errors for docutils (a substitution, "unexpected indentation"). Before numpydoc reads a docstring
this hook escapes ``|`` (the docstrings use no substitutions and no tables) and opens a blank line
where plain text means a new block: before a line indented under a multi-line paragraph, and
before a list item that follows a paragraph line. Any other docutils error still fails ``-W``.
"""

from __future__ import annotations

import re

_ITEM = re.compile(r"^\s*(?:[-*•]|\d+[.)])\s")
_UNDERLINE = re.compile(r"^\s*([-=~^\"'`#*+])\1{2,}\s*$")  # a section title's underline


def _indent(line: str) -> int:
    return len(line) - len(line.lstrip())


def plain_to_rst(lines: list[str]) -> list[str]:
    """The docstring's lines with ``|`` escaped and the blank lines plain text implies (module docstring)."""
    out: list[str] = []
    for line in lines:
        line = line.replace("|", "\\|")
        if out and line.strip() and out[-1].strip() and not out[-1].rstrip().endswith("::"):
            prev = out[-1]
            before = out[-2] if len(out) > 1 else ""
            paragraph_goes_on = before.strip() and _indent(before) == _indent(prev) and not _ITEM.match(prev) and not _UNDERLINE.match(before)
            if _indent(line) > _indent(prev) and paragraph_goes_on and not _ITEM.match(prev):
                out.append("")
            elif _ITEM.match(line) and not _ITEM.match(prev) and _indent(line) == _indent(prev):
                out.append("")
        out.append(line)
    return out


def _process(app, what, name, obj, options, lines):
    lines[:] = plain_to_rst(lines)


def setup(app):
    app.connect("autodoc-process-docstring", _process, priority=100)  # before numpydoc (500)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
