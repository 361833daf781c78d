"""law.json and scaling.json: read and written in formats/ only, and the files main wrote still load."""

import ast
import json
from pathlib import Path

import numpy as np
import pytest

from softimpact.errors import InputError
from softimpact.formats.law_json import law_json, read_law
from softimpact.formats.scaling_json import read_scaling_law

DATA = Path(__file__).parent / "data"
SRC = Path(__file__).parents[1] / "src" / "softimpact"
LAW = DATA / "law-v-main.json"  # written by `softimpact identify paper-rubber-series` on main e41e951
SCALING = DATA / "scaling-v-main.json"  # written by `softimpact fit paper-rubber-series` on main e41e951


def test_law_json_written_by_main_still_loads():
    """Every parameter, half-width, d_ref and identified range of main's law.json comes back as written (plain json as the reference)."""
    raw = json.loads(LAW.read_text())
    law = read_law(LAW)
    for name, value, half in zip(law.names, law.values, law.half_widths):
        assert value == raw["parameters"][name]["value"]
        assert half == raw["parameters"][name]["ci95_half_width"]
    assert law.d_ref == raw["d_ref_m"]
    assert law.identified_on == raw["identified_on"]
    assert list(law.rms_per_test) == list(raw["fit"]["rms_over_F0"].values())


def test_law_json_round_trip(tmp_path):
    """A law read from main's file, written by formats and read again, is the same law (equal parameters, equal law object for one impactor)."""
    law = read_law(LAW)
    names = list(json.loads(LAW.read_text())["fit"]["rms_over_F0"])
    path = tmp_path / "law.json"
    path.write_text(law_json(law, names))
    again = read_law(path)
    assert np.array_equal(again.values, law.values) and np.array_equal(again.half_widths, law.half_widths) and again.d_ref == law.d_ref
    m, d, v = 1.1e-3, 0.0127, 50.0
    assert again.law(m, d, v) == law.law(m, d, v)


@pytest.mark.parametrize("group", ["pooled", "0.375 in", "0.5 in"])
def test_scaling_json_written_by_main_still_loads(group):
    """The α's of each group of main's scaling.json come back as written (plain json as the reference)."""
    raw = json.loads(SCALING.read_text())
    g = raw["pooled"] if group == "pooled" else raw["groups"][group]
    law = read_scaling_law(SCALING, group)
    assert (law.alpha1, law.alpha2, law.alpha3, law.alpha4) == tuple(g[f"alpha{i}"]["value"] for i in range(1, 5))


def _imports(path: Path) -> set[str]:
    """Relative modules a source file imports, resolved against the softimpact package."""
    tree = ast.parse(path.read_text())
    pkg = path.parent.relative_to(SRC.parent).parts
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.level:
            base = pkg[: len(pkg) - node.level + 1]
            out.add(".".join((*base, node.module or "")))
    return out


def test_formats_is_neutral_and_input_reads_through_it():
    """formats/ imports neither input/ nor output/, and input/contact_law reads law.json from formats/ (no back arrow into output/)."""
    for f in (SRC / "formats").glob("*.py"):
        assert not any(m.startswith(("softimpact.input", "softimpact.output")) for m in _imports(f)), f
    used = _imports(SRC / "input" / "contact_law.py")
    assert "softimpact.formats.law_json" in used and not any(m.startswith("softimpact.output") for m in used)


@pytest.mark.parametrize("units", ["in-lbf-s", "imperial", 3])
def test_law_json_in_other_units_is_refused(tmp_path, units):
    """A law.json that says its numbers are not SI is refused naming the field (its d_ref read as metres would scale the law)."""
    raw = json.loads(LAW.read_text())
    raw["units"] = units
    path = tmp_path / "law.json"
    path.write_text(json.dumps(raw))
    with pytest.raises(InputError, match="units"):
        read_law(path)


def test_scaling_json_in_other_units_is_refused(tmp_path):
    """A scaling.json that says "units": "in-lbf-s" is refused; main's file (no units field) reads as SI."""
    raw = json.loads(SCALING.read_text())
    assert "units" not in raw
    raw["units"] = "in-lbf-s"
    path = tmp_path / "scaling.json"
    path.write_text(json.dumps(raw))
    with pytest.raises(InputError, match="only SI"):
        read_scaling_law(path)
