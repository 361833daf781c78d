"""The documentation cannot rot: the case-file reference lists every key the readers accept, and the site builds with no warning."""

import ast
import importlib.util
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


@pytest.mark.slow
@pytest.mark.skipif(importlib.util.find_spec("sphinx") is None, reason="the docs extra is not installed")
def test_docs_build_with_no_warning(tmp_path):
    """sphinx-build -W (warnings are errors) builds the site: a broken reference, a bad docstring or a missing page fails."""
    src = tmp_path / "docs"
    shutil.copytree(ROOT / "docs", src, ignore=shutil.ignore_patterns("_build", "_generated", "gallery", "sg_execution_times.rst"))
    (src / "conf.py").write_text((ROOT / "docs" / "conf.py").read_text().replace('HERE.parent / "examples"', f"Path({str(ROOT / 'examples')!r})"))
    run = subprocess.run(
        [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html", str(src), str(tmp_path / "html")], capture_output=True, text=True
    )
    assert run.returncode == 0, run.stderr[-4000:]
    assert (tmp_path / "html" / "index.html").is_file()


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
