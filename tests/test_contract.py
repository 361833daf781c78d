"""The output contract: every command's files, columns and numbers as before the edges were restructured.

``tests/data/contract.json`` was written by ``tools/make_contract.py`` from the
code before the restructuring (commit 93e128b). This is a regression check of
that restructuring — same files, same CSV columns and JSON keys, numbers equal
to round-off — not a physics test; the physics is tested beside each solver.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))

from make_contract import COMMANDS, fingerprint, run  # noqa: E402

RECORDED = json.loads((ROOT / "tests" / "data" / "contract.json").read_text(encoding="utf-8"))
RTOL = 1e-6  # round-off, and the MAD scale 1.4826 replaced by its exact value 1/Φ⁻¹(3/4) in the noise estimate
ATOL = 1e-9  # values at round-off level (an energy balance of 2e-10) differ by round-off


def _close(a, b) -> bool:
    if isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
        return math.isclose(a, b, rel_tol=RTOL, abs_tol=ATOL)
    return True  # text (paths, messages, versions) may change wording; numbers may not


def _compare(old, new, where: str) -> list[str]:
    problems = []
    if isinstance(old, dict):
        if not isinstance(new, dict):
            return [f"{where}: expected a table"]
        for k, v in old.items():
            if k not in new:
                problems.append(f"{where}.{k}: missing")
            else:
                problems += _compare(v, new[k], f"{where}.{k}")
    elif isinstance(old, list):
        if not isinstance(new, list) or len(old) != len(new):
            return [f"{where}: {old!r} became {new!r}"]
        for i, (a, b) in enumerate(zip(old, new)):
            problems += _compare(a, b, f"{where}[{i}]")
    elif old is None:
        if new is not None:
            problems.append(f"{where}: None became {new!r}")
    elif not _close(old, new):
        problems.append(f"{where}: {old!r} became {new!r}")
    return problems


@pytest.mark.parametrize("name, args", COMMANDS, ids=[c[0] for c in COMMANDS])
def test_outputs_as_before(tmp_path, name, args):
    """The command writes the same files, columns, keys and numbers as before the restructuring."""
    run(args, tmp_path / name)
    now = fingerprint(tmp_path / name)
    before = RECORDED[name]
    # manifest.json (issue 14) is new in every output folder, on purpose: the run's record, not a result.
    assert [f for f in now["files"] if f != "manifest.json"] == before["files"]
    problems = _compare({k: v for k, v in before.items() if k != "files"}, now, name)
    assert not problems, "\n".join(problems[:20])
