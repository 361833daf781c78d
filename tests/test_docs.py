"""The documentation cannot rot: the case-file reference lists every key the readers accept, and the site builds with no warning."""

import ast
import importlib.util
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[1]
READERS = ROOT / "src" / "softimpact" / "input"
# Table methods a reader asks a key with (their first argument is the key) ...
TABLE_METHODS = {"quantity", "number", "integer", "string", "table", "tables", "raw"}
# ... and the readers' helpers that take a key name as a literal argument.
KEY_HELPERS = {"read_material", "read_ply", "read_history", "_point", "_read_record_key"}


def _casekeys():
    spec = importlib.util.spec_from_file_location("casekeys", ROOT / "docs" / "_ext" / "casekeys.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules["casekeys"] = module  # dataclasses look their module up
    spec.loader.exec_module(module)
    return module


def _keys_in_source() -> dict[str, str]:
    """Every key name written as a literal in a reader's call, by a static scan of input/ (key → file:line)."""
    found = {}
    for path in sorted(READERS.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if not isinstance(node, ast.Call):
                continue
            func = node.func
            if isinstance(func, ast.Attribute) and func.attr in TABLE_METHODS and node.args:
                args = node.args[:1]
            elif isinstance(func, ast.Name) and func.id in KEY_HELPERS:
                args = node.args[1:]
            else:
                continue
            for a in args:
                if isinstance(a, ast.Constant) and isinstance(a.value, str):
                    found.setdefault(a.value, f"{path.relative_to(ROOT)}:{node.lineno}")
    return found


@pytest.fixture(scope="module")
def recorded():
    return _casekeys().record()


def test_reference_lists_every_key_the_readers_name(recorded):
    """Every key a reader asks for by name (static scan of src/softimpact/input) is in the generated reference."""
    names = {path.rsplit(".", 1)[-1].removesuffix("[]") for keys in recorded.values() for path in keys}
    missing = {k: where for k, where in _keys_in_source().items() if k not in names}
    assert not missing, f"keys the readers accept but the reference does not list (add a variant in docs/_ext/casekeys.py): {missing}"


def test_reference_gives_units_and_defaults(recorded):
    """Every quantity in the reference has its SI unit, and the known keys their defaults and choices (README's bar case)."""
    text = _casekeys().markdown(recorded)
    assert "| `bar.elements` | integer | `39` | ≥ 1 |" in text
    assert "| `solver.time_step` | time [s] | required | > 0 |" in text
    assert "`hertz`, `hertz-unloading`, `hunt-crossley`, `identified`" in text
    for fmt, keys in recorded.items():
        assert keys, f"no key recorded for {fmt}"


DOCS_EXTRA = ["sphinx", "numpydoc", "sphinx_gallery", "sphinx_click", "myst_parser", "pydata_sphinx_theme", "sphinx_copybutton", "sphinx-mathjax-offline"]
MISSING_EXTRA = [m for m in DOCS_EXTRA if importlib.util.find_spec(m) is None]
needs_docs = pytest.mark.skipif(bool(MISSING_EXTRA), reason=f"the docs extra is not installed ({', '.join(MISSING_EXTRA)})")


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """The site built once for this file's checks, as ``make docs`` builds it (quick examples executed); (the run, the HTML folder)."""
    tmp = tmp_path_factory.mktemp("site")
    src = tmp / "docs"
    shutil.copytree(ROOT / "docs", src, ignore=shutil.ignore_patterns("_build", "_generated", "gallery", "sg_execution_times.rst"))
    (src / "conf.py").write_text((ROOT / "docs" / "conf.py").read_text().replace('HERE.parent / "examples"', f"Path({str(ROOT / 'examples')!r})"))
    env = {**os.environ, "MPLBACKEND": "Agg", "OMP_NUM_THREADS": "1", "SOFTIMPACT_DOCS_RUN_EXAMPLES": "quick"}
    run = subprocess.run(
        [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html", str(src), str(tmp / "html")], capture_output=True, text=True, env=env
    )
    return run, tmp / "html"


def _pages(html: Path) -> dict[str, str]:
    return {str(p.relative_to(html)): p.read_text(encoding="utf-8") for p in html.rglob("*.html")}


@pytest.mark.slow
@needs_docs
def test_docs_build_with_no_warning(site):
    """sphinx-build -W (warnings are errors) builds the site: a broken reference, a bad docstring or a missing page fails."""
    run, html = site
    assert run.returncode == 0, run.stderr[-4000:]
    assert (html / "index.html").is_file()


@pytest.mark.slow
@needs_docs
def test_site_loads_nothing_from_another_host(site):
    """The equations are typeset by a MathJax the site carries (fonts included), and no page loads a script, style or font from a network."""
    run, html = site
    assert run.returncode == 0, run.stderr[-4000:]
    theory = (html / "theory.html").read_text(encoding="utf-8")
    scripts = re.findall(r"<script[^>]*\bsrc=\"([^\"]+)\"", theory)
    mathjax = [s for s in scripts if "mathjax" in s.lower()]
    assert mathjax == ["_static/mathjax/tex-chtml.js"], scripts
    assert (html / "_static" / "mathjax" / "tex-chtml.js").stat().st_size > 100_000
    assert list((html / "_static" / "mathjax" / "output" / "chtml" / "fonts" / "woff-v2").glob("MathJax_Main-Regular.woff"))
    assert "\\[F = K\\alpha^{n}" in theory  # eq (1) left as TeX for MathJax, in a math block
    remote = []
    for name, text in _pages(html).items():
        for tag, attr in (("script", "src"), ("link", "href"), ("img", "src"), ("iframe", "src")):
            remote += [f"{name}: {u}" for u in re.findall(rf"<{tag}\b[^>]*\b{attr}=\"((?:https?:)?//[^\"]+)\"", text)]
    for css in (html / "_static").rglob("*.css"):
        remote += [
            f"{css.name}: {u}"
            for u in re.findall(r"(?:@import\s+|url\()\s*[\"']?((?:https?:)?//[^\"')\s]+)", css.read_text(encoding="utf-8", errors="replace"))
        ]
    assert not remote, remote


@pytest.mark.slow
@needs_docs
def test_gallery_shows_figures(site):
    """Every gallery thumbnail is a figure, not sphinx-gallery's placeholder, and the quick examples' pages show the figures they drew."""
    from sphinx_gallery.gen_rst import scale_image  # the placeholder as sphinx-gallery makes it

    run, html = site
    assert run.returncode == 0, run.stderr[-4000:]
    gallery = (html / "gallery" / "index.html").read_text(encoding="utf-8")
    thumbs = re.findall(r"<img[^>]*src=\"([^\"]*_thumb\.png)\"", gallery)
    assert len(thumbs) == len(list((ROOT / "examples").glob("[0-9][0-9]_*.py")))
    placeholder = html.parent / "placeholder.png"
    scale_image(str(Path(importlib.util.find_spec("sphinx_gallery").origin).parent / "_static" / "no_image.png"), str(placeholder), 400, 280)
    for thumb in thumbs:
        data = (html / "gallery" / thumb).read_bytes()
        assert data != placeholder.read_bytes(), f"{thumb} is the placeholder"
        assert len(data) > 5_000, f"{thumb} is nearly blank"
    for stem in _conf_quick_examples():
        page = (html / "gallery" / f"{stem}.html").read_text(encoding="utf-8")
        figures = re.findall(rf"<img[^>]*src=\"\.\./(_images/sphx_glr_{stem}_\d+\.png)\"", page)
        assert figures and all((html / f).stat().st_size > 5_000 for f in figures), f"{stem}: no figure on its page"


def _conf_quick_examples() -> tuple[str, ...]:
    """QUICK_EXAMPLES of docs/conf.py (the examples the docs build executes), each an example of examples/."""
    tree = ast.parse((ROOT / "docs" / "conf.py").read_text())
    (value,) = [n.value for n in tree.body if isinstance(n, ast.Assign) and any(getattr(t, "id", None) == "QUICK_EXAMPLES" for t in n.targets)]
    quick = tuple(ast.literal_eval(value))
    assert quick and all((ROOT / "examples" / f"{s}.py").is_file() for s in quick)
    return quick


@pytest.mark.slow
@needs_docs
def test_cli_reference_keeps_double_dashes(site):
    """Smart quotes are off: the command-line reference writes options as typed (--out), never with an en dash (–out)."""
    run, html = site
    assert run.returncode == 0, run.stderr[-4000:]
    text = re.sub(r"<[^>]+>", "", (html / "reference" / "cli.html").read_text(encoding="utf-8"))
    assert "--out" in text
    assert not re.findall(r"(?<![\w–-])[–—][a-z]", text)
    assert "copybutton.js" in (html / "reference" / "cli.html").read_text(encoding="utf-8")


@pytest.mark.slow
@needs_docs
def test_built_pages_cite_no_work_item(site):
    """No built page, docstrings of the API reference included, cites a work-item number ("issue 21", "#21", "stage 3")."""
    from test_citations import WORK_ITEM

    run, html = site
    assert run.returncode == 0, run.stderr[-4000:]
    hits = []
    for name, page in _pages(html).items():
        text = re.sub(r"<(script|style)\b.*?</\1>|<[^>]+>", " ", page, flags=re.DOTALL)
        hits += [f"{name}: {m.group(0)}" for m in WORK_ITEM.finditer(text)]
    assert not hits, hits


def _recorded_columns(command: str) -> list[str]:
    """The history.csv columns of a command in the recorded output contract, gauge names as ``<gauge>``."""
    import json
    import re

    recorded = json.loads((ROOT / "tests" / "data" / "contract.json").read_text(encoding="utf-8"))[command]["history.csv"]
    return list(dict.fromkeys(re.sub(r"^(strain|bending_strain)_.+$", r"\1_<gauge>", c) for c in recorded))


@pytest.mark.parametrize("command", ["bar", "beam"])
def test_output_contract_page_lists_the_recorded_columns(command):
    """The history.csv columns docs/reference/outputs.md gives for a command are those of the recorded output contract, in order."""
    import re

    page = (ROOT / "docs" / "reference" / "outputs.md").read_text(encoding="utf-8")
    row = next(line for line in page.splitlines() if line.startswith(f"| `{command}` |") and "time_s" in line)
    assert re.findall(r"`([^`]+)`", row.split("|")[2]) == _recorded_columns(command)


@pytest.mark.parametrize("command", ["bar", "beam"])
def test_naming_table_names_every_recorded_column(command):
    """Every history.csv column of the recorded output contract has its line in the naming table (docs/naming.md)."""
    table = (ROOT / "docs" / "naming.md").read_text(encoding="utf-8")
    assert [c for c in _recorded_columns(command) if f"`{c}`" not in table] == []


def test_every_key_read_whole_says_what_it_holds(recorded):
    """A key a reader takes whole (Table.raw: lists, inline tables, names or tables) has its value described in casekeys.RAW_VALUES."""
    casekeys = _casekeys()
    bare = [f"{fmt}: {path}" for fmt, keys in recorded.items() for path, k in keys.items() if k.method == "raw" and casekeys.raw_value(path) is None]
    assert not bare, f"describe these in docs/_ext/casekeys.py RAW_VALUES: {bare}"


@pytest.mark.slow
@needs_docs
def test_catalogue_page_lists_every_entry(site):
    """The built catalogue page (docs/_ext/catalogue_page.py) names every material, ply, projectile, scaling-constant set, contact law and built-in case."""
    from softimpact.input.toml import builtin_cases
    from softimpact.models.contact_laws import CONTACT_LAWS
    from softimpact.models.empirical import PRESETS, PROJECTILES
    from softimpact.models.laminate import PLIES
    from softimpact.models.materials import CATALOGUE

    run, html = site
    assert run.returncode == 0, run.stderr[-4000:]
    page = re.sub(r"<[^>]+>", "", (html / "_generated" / "catalogue.html").read_text(encoding="utf-8")).replace("&#160;", " ")
    names = [*CATALOGUE, *PLIES, *PROJECTILES, *PRESETS, *CONTACT_LAWS, *builtin_cases()]
    missing = [n for n in names if n not in page]
    assert not missing, f"not on the catalogue page: {missing}"
