"""The catalogue page, written from the code's own tables so it cannot drift.

The Sphinx hook :func:`setup` writes ``docs/_generated/catalogue.md`` before each build from
:func:`softimpact.app.catalogue.markdown` (the same tables as ``softimpact catalogue`` and
``si.catalogue()``); ``tests/test_docs.py`` checks the built page lists every entry.
"""

from __future__ import annotations

from pathlib import Path


def _write(app) -> None:
    from softimpact.app.catalogue import markdown

    out = Path(app.srcdir) / "_generated"
    out.mkdir(exist_ok=True)
    text = markdown()
    target = out / "catalogue.md"
    if not target.exists() or target.read_text() != text:
        target.write_text(text)


def setup(app):
    app.connect("builder-inited", _write)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
