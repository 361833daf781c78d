"""Refresh the stored figures of the gallery's slow examples: ``python docs/_ext/gallery_figures.py``.

``make docs`` executes only the quick examples (``QUICK_EXAMPLES`` in docs/conf.py); a slow one is
shown as code, its thumbnail taken from ``docs/_static/thumbnails/<example>.png`` (the script's
``# sphinx_gallery_thumbnail_path`` comment). This script runs each slow example as
``tests/test_examples.py`` does (matplotlib's Agg backend, in a temporary folder) and stores the
figure sphinx-gallery would take as its thumbnail (``# sphinx_gallery_thumbnail_number``, else the
first). Run it after changing a slow example or what it computes. Names given on the command line
(``02_reduce_and_fit``) restrict it to those examples.
"""

from __future__ import annotations

import ast
import os
import re
import runpy
import sys
import tempfile
import time
from pathlib import Path

DOCS = Path(__file__).resolve().parents[1]
EXAMPLES = DOCS.parent / "examples"
STORE = DOCS / "_static" / "thumbnails"


def quick_examples() -> tuple[str, ...]:
    """QUICK_EXAMPLES of docs/conf.py, read without running the configuration."""
    for node in ast.parse((DOCS / "conf.py").read_text(encoding="utf-8")).body:
        if isinstance(node, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "QUICK_EXAMPLES" for t in node.targets):
            return tuple(ast.literal_eval(node.value))
    raise LookupError("docs/conf.py defines no QUICK_EXAMPLES")


def thumbnail_number(source: str) -> int:
    """The figure sphinx-gallery takes as the thumbnail: the script's config comment, else the first."""
    found = re.search(r"^# sphinx_gallery_thumbnail_number\s*=\s*(-?\d+)", source, flags=re.MULTILINE)
    return int(found.group(1)) if found else 1


def store_figure(path: Path) -> Path:
    """Run one example and save its thumbnail figure into docs/_static/thumbnails; returns the PNG's path."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    plt.close("all")
    here = Path.cwd()
    with tempfile.TemporaryDirectory() as work:
        os.chdir(work)
        saved, tempfile.tempdir = tempfile.tempdir, work  # the examples write into tempfile.mkdtemp()
        try:
            runpy.run_path(str(path), run_name="__main__")
            numbers = plt.get_fignums()
            if not numbers:
                raise RuntimeError(f"{path.name} draws no figure")
            n = thumbnail_number(path.read_text(encoding="utf-8"))
            figure = plt.figure(numbers[n - 1 if n > 0 else n])
            STORE.mkdir(parents=True, exist_ok=True)
            out = STORE / f"{path.stem}.png"
            figure.savefig(out, dpi=100)
        finally:
            tempfile.tempdir = saved
            os.chdir(here)
            plt.close("all")
    return out


def main(names: list[str]) -> None:
    quick = quick_examples()
    slow = [p for p in sorted(EXAMPLES.glob("[0-9][0-9]_*.py")) if p.stem not in quick and (not names or p.stem in names)]
    for path in slow:
        start = time.perf_counter()
        out = store_figure(path)
        print(f"{path.stem}: {time.perf_counter() - start:.1f} s -> {out.relative_to(DOCS.parent)}")


if __name__ == "__main__":
    main(sys.argv[1:])
