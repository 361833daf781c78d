"""The output contract (golden master): every command's files, columns, text and numbers as recorded.

``tests/data/contract.json`` was recorded by ``tools/make_contract.py`` (``_support.contract``) on the
code before the edges were restructured (commit 93e128b). This is a regression check — same files, same
CSV columns and JSON keys, the same text word for word, numbers within the tolerances stated in
``_support.contract`` — not a physics test; the physics is tested beside each solver. What depends on
the floating-point path (a solver's iteration count, the time of a sampled maximum) is compared by what it
means, so that the record holds on any CPU and BLAS build (``test_outputs_on_other_blas_kernels``).

To regenerate the record after an intended change, re-record only the commands it changes and say
why in ``_support/contract.py``'s docstring:

    .venv/bin/python tools/make_contract.py tests/data/contract.json calibrate
"""

from __future__ import annotations

import copy
import json
import os
import subprocess
import sys
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


@pytest.mark.parametrize(
    "old, new, same",
    [
        (9, 8, True),  # seen: OpenBLAS's default kernels against its Haswell ones on one AMD EPYC
        (9, 12, True),  # seen: its Prescott kernels
        (9, 19, False),  # more than twice the work: not the same convergence
        (9, 4, False),
        (9, 0, False),  # no iteration at all is not a converged solve
    ],
)
def test_iteration_counts_compare_by_convergence(old, new, same):
    """An iteration count (a key or a count printed in a message) compares as the same convergence, within a
    factor 2, not digit for digit; every other integer stays exact."""
    assert (compare({"iterations": old}, {"iterations": new}) == []) is same
    assert (compare(f"converged after {old} model runs", f"converged after {new} model runs") == []) is same
    assert compare({"elements": old}, {"elements": new}) != []


@pytest.mark.parametrize("shift, same", [(0.0, True), (1e-6, True), (-1e-6, True), (2e-6, False)])
def test_time_of_sampled_peak_within_one_step(shift, same):
    """The time of a sampled maximum may move by one time step of its file (two samples tied to round-off),
    no further; without a recorded time step it compares within RTOL like any number."""
    old = {"case_SI.solver.time_step": 1e-6, "gauges.g1.time_of_peak_tensile_strain_s": 4.25e-4}
    new = dict(old, **{"gauges.g1.time_of_peak_tensile_strain_s": 4.25e-4 + shift})
    assert (compare(old, new) == []) is same
    no_step = {k: v for k, v in new.items() if "time_step" not in k}
    assert (compare({k: v for k, v in old.items() if "time_step" not in k}, no_step) == []) is (shift == 0.0)


CONTRACT_CHILD = """
import json, sys
from pathlib import Path
sys.path.insert(0, sys.argv[1])
from _support.contract import COMMANDS, fingerprint, run
args = dict(COMMANDS)[sys.argv[2]]
run(args, Path(sys.argv[3]))
print(json.dumps(fingerprint(Path(sys.argv[3]))))
"""


@pytest.mark.slow
@pytest.mark.parametrize("coretype", ["Prescott", "Haswell", "SkylakeX"])
def test_outputs_on_other_blas_kernels(tmp_path, coretype):
    """calibrate, the command whose fit is most sensitive to round-off (its iteration count moves with the
    kernels), matches the record on OpenBLAS's other kernels (OPENBLAS_CORETYPE), as on another CPU."""
    env = dict(os.environ, OPENBLAS_CORETYPE=coretype, OMP_NUM_THREADS="1", MPLBACKEND="Agg")
    done = subprocess.run(
        [sys.executable, "-c", CONTRACT_CHILD, str(Path(__file__).parent), "calibrate", str(tmp_path / "calibrate")],
        env=env,
        capture_output=True,
        text=True,
        check=True,
    )
    now = json.loads(done.stdout.strip().splitlines()[-1])
    problems = compare({k: v for k, v in RECORDED["calibrate"].items() if k != "files"}, now, "calibrate")
    assert not problems, "\n".join(problems[:20])
