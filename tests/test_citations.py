"""What the documentation and the paper report cite exists, and they speak to a reader, not to the project's tracker.

A reader of the site or of report.html has the repository, not the project's work items: a page that
says "issue 21", "#21" or "stage 3", or that points at a file the repository does not hold (a style
guide, a paper text kept elsewhere), sends them nowhere. The texts read: the Markdown and
reStructuredText pages of docs/, the gallery's scripts (examples/, pages of the site), the case-file
page docs/_ext/casekeys.py generates, and the string constants of the report's modules
(src/softimpact/app/paper/*.py, src/softimpact/output/report.py), docstrings of those modules excluded.
"""

import ast
import importlib.util
import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[1]
PACKAGE = ROOT / "src" / "softimpact"
DOCS = ROOT / "docs"
GENERATED = {"_build", "_generated", "gallery", "sg_execution_times.rst"}  # written by the docs build, not sources

# An internal work-item number: "issue 21", "issues 9–14", "issue #21", "#21", "stage 3", "work item".
WORK_ITEM = re.compile(
    r"\bissues?\s+#?\d+|(?<![\w&:#/.'\"-])#\d+\b|\bstages?\s+\d+\b|\bwork[- ]items?\b",
    flags=re.IGNORECASE,
)
# A path inside the repository: from a top-level folder (with or without a file at its end), or a
# source or text file with a folder before it ("models/failure.py", relative to the package or to
# docs/). A figure or data file with a folder before it ("models/force-models-1166.png") is one the
# report writes beside itself: not a citation.
TOP = r"(?:src|tests|docs|examples|benchmarks|tools|shared|paper)"
SUFFIX = r"\.(?:py|md|txt|rst|toml|cfg|ini|sh)"
REPO_PATH = re.compile(rf"(?<![\w./-])(?:{TOP}/[\w./-]*[\w/]|[\w.-]+(?:/[\w.-]+)*/[\w.-]+{SUFFIX})(?![\w/])")
# A source or text file named alone ("BENCHMARKS.md", "STYLE.md", "notes.txt"): it must be in the repository.
# Output files named alone (summary.json, history.csv, my-case.toml) are what the program writes or a user brings.
BARE_FILE = re.compile(r"(?<![\w./-])[\w-]+(?:\.[\w-]+)*\.(?:py|md|txt|rst)(?![\w/])")
# Folders whose files the program, the docs build or the user makes: paths in them are outputs, not citations.
OUTPUT_FOLDERS = {"out", "results", "work"} | GENERATED


def _repo_names() -> set[str]:
    """Names of the files in the repository (its tracked areas; the venv and build outputs excluded)."""
    names = {p.name for p in ROOT.iterdir() if p.is_file()}
    for top in ("src", "tests", "docs", "examples", "benchmarks", "tools"):
        names |= {p.name for p in (ROOT / top).rglob("*") if p.is_file() and not GENERATED & set(p.relative_to(ROOT).parts)}
    return names


def _exists(path: str) -> bool:
    """The path names a file or folder of the repository: from its root, the package, docs/ or examples/."""
    path = path.rstrip("/.")
    return any((base / path).exists() for base in (ROOT, PACKAGE, DOCS, ROOT / "examples"))


def _strings(path: Path) -> list[tuple[int, str]]:
    """The string constants of a module with their lines (f-strings' literal parts), docstrings excluded."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    docstrings = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)) and node.body:
            first = node.body[0]
            if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) and isinstance(first.value.value, str):
                docstrings.add(id(first.value))
    return [
        (node.lineno, node.value) for node in ast.walk(tree) if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docstrings
    ]


def _texts() -> list[tuple[str, str]]:
    """(where, text) of every page of the site's sources and every string of the report's modules."""
    texts = []
    for path in sorted([*DOCS.rglob("*.md"), *DOCS.rglob("*.rst"), ROOT / "examples" / "GALLERY_HEADER.rst", *(ROOT / "examples").glob("*.py")]):
        if GENERATED & set(path.relative_to(DOCS if path.is_relative_to(DOCS) else ROOT).parts):
            continue
        for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            texts.append((f"{path.relative_to(ROOT)}:{n}", line))
    for path in [*sorted((PACKAGE / "app" / "paper").glob("*.py")), PACKAGE / "output" / "report.py"]:
        texts += [(f"{path.relative_to(ROOT)}:{n}", s) for n, s in _strings(path)]
    spec = importlib.util.spec_from_file_location("casekeys", DOCS / "_ext" / "casekeys.py")
    casekeys = importlib.util.module_from_spec(spec)
    sys.modules["casekeys"] = casekeys  # dataclasses look their module up
    spec.loader.exec_module(casekeys)
    page = casekeys.markdown(casekeys.record())
    texts += [(f"docs/_generated/case-files.md:{n}", line) for n, line in enumerate(page.splitlines(), 1)]
    return texts


TEXTS = _texts()


def test_texts_are_found():
    """The scan reads the pages and the report's strings (a moved folder would make the checks below vacuous)."""
    where = {w.split(":")[0] for w, _ in TEXTS}
    assert {
        "docs/theory.md",
        "docs/verification.md",
        "docs/_generated/case-files.md",
        "examples/01_bar_test.py",
        "src/softimpact/app/paper/thresholds.py",
        "src/softimpact/output/report.py",
    } <= where


@pytest.mark.parametrize(
    "text, found",
    [
        ("as issue 30 gives it", True),
        ("(issues 9–14)", True),
        ("see #21", True),
        ("## Stage 3 — One engine", True),
        ("color:#444;background:#eee", False),
        ("&#8212; a dash", False),
        ("a two-stage fit; staged runs", False),
        ("Issue a warning per run", False),
    ],
)
def test_work_item_pattern(text, found):
    """The work-item pattern catches tracker references and passes CSS colours, HTML entities and ordinary words."""
    assert bool(WORK_ITEM.search(text)) is found


def test_no_internal_work_item_numbers():
    """No page of the site and no string of the report cites a work-item number ("issue 21", "#21", "stage 3")."""
    hits = [f"{where}: {m.group(0)!r}" for where, text in TEXTS for m in WORK_ITEM.finditer(text)]
    assert not hits, "cite the feature, the module or the changelog entry instead:\n" + "\n".join(hits)


@pytest.mark.parametrize(
    "text, paths",
    [
        ("the tests (`tests/test_plate.py`, `tests/test_beam.py`)", ["tests/test_plate.py", "tests/test_beam.py"]),
        ("`models/failure.py` `STRENGTHS`", ["models/failure.py"]),
        ("copied from `src/softimpact/data/cases/` as a start", ["src/softimpact/data/cases/"]),
        ("a velocity of 62.1 in/s, lbf·s²/in, out/bar/my-case.toml", ["out/bar/my-case.toml"]),
        ("the report's figure models/force-models-1166.png", []),
    ],
)
def test_path_pattern(text, paths):
    """The path pattern finds files and folders of the repository and leaves units such as in/s alone."""
    assert REPO_PATH.findall(text) == paths


def test_cited_files_exist():
    """Every file or folder a page or the report cites (a path, or a .py/.md/.txt/.rst file by name) is in the repository."""
    names = _repo_names()
    missing = []
    for where, text in TEXTS:
        for path in REPO_PATH.findall(text):
            if not OUTPUT_FOLDERS & set(path.split("/")) and not _exists(path):
                missing.append(f"{where}: {path}")
        for name in BARE_FILE.findall(text):
            if name not in names:
                missing.append(f"{where}: {name}")
    assert not missing, "cited but not in the repository:\n" + "\n".join(missing)
