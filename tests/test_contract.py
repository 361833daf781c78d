"""The output contract (golden master): every command's files, columns, text and numbers as recorded.

``tests/data/contract.json`` was recorded by ``tools/make_contract.py`` (``_support.contract``) on the
code before the edges were restructured (commit 93e128b). This is a regression check — same files, same
CSV columns and JSON keys, the same text word for word, numbers within the tolerances stated in
``_support.contract`` — not a physics test; the physics is tested beside each solver.
"""

from __future__ import annotations

import copy
import json
from pathlib import Path

import pytest

from _support.contract import COMMANDS, compare, fingerprint, run

RECORDED = json.loads((Path(__file__).parent / "data" / "contract.json").read_text(encoding="utf-8"))


SLOW_COMMANDS = {"fit", "reduce"}  # the built-in series reduced and fitted (seconds): the slow tier


@pytest.mark.parametrize("name, args", [pytest.param(n, a, id=n, marks=[pytest.mark.slow] if n in SLOW_COMMANDS else []) for n, a in COMMANDS])
def test_outputs_as_before(tmp_path, name, args):
    """The command writes the same files, columns, keys, text and numbers (within tolerance) as recorded."""
    run(args, tmp_path / name)
    now = fingerprint(tmp_path / name)
    before = RECORDED[name]
    assert now["files"] == before["files"]
    problems = compare({k: v for k, v in before.items() if k != "files"}, now, name)
    assert not problems, "\n".join(problems[:20])


def test_comparison_reports_a_changed_number_and_a_changed_word():
    """The comparison fails on a number moved beyond its tolerance (1e-5 relative) and on one word changed,
    reports each by its path, and passes the record unchanged and a number moved within tolerance (1e-8)."""
    before = RECORDED["bar"]
    assert compare(before, before, "bar") == []
    near = copy.deepcopy(before)
    near["summary.json"]["peak_force_N"] *= 1 + 1e-8
    assert compare(before, near, "bar") == []
    after = copy.deepcopy(before)
    after["summary.json"]["peak_force_N"] *= 1 + 1e-5
    after["summary.json"]["rebound_velocity_note"] = after["summary.json"]["rebound_velocity_note"].replace("positive", "negative", 1)
    problems = compare(before, after, "bar")
    assert len(problems) == 2
    assert any(p.startswith("bar.summary.json.peak_force_N: number") for p in problems)
    assert any(p.startswith("bar.summary.json.rebound_velocity_note: text") for p in problems)


@pytest.mark.parametrize(
    "old, new, differs",
    [
        ("lag m/ρcA = 5.0 µs", "lag m/ρcA = 5.1 µs", False),  # a displayed number moved by one unit of its last digit: rounding
        ("lag m/ρcA = 5.0 µs", "lag m/ρcA = 5.2 µs", True),
        ("residual 55 ≤ 55.3", "residual 55 < 55.3", True),
        ("alpha1 = 4.020356573799584", "alpha1 = 4.020356573799585", False),
        ("alpha1 = 4.020356573799584", "alpha1 = 4.0204", True),
        ("{data}/series/a.toml", "{data}/series/b.toml", True),
    ],
)
def test_numbers_inside_text(old, new, differs):
    """Text compares word for word; a number printed in it within round-off or one unit of its last printed digit."""
    assert bool(compare(old, new)) is differs
