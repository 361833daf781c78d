"""The report tells the truth about its references: what the paper's Tables II and III can decide, from their rows."""

import re

import numpy as np
import pytest

from softimpact.app.paper.question import _table_consistency

from _support.problems import TABLE_II, TABLE_III


def _numbers(text: str, before: str) -> float:
    """The number right after ``before`` in ``text``."""
    return float(re.search(re.escape(before) + r"\s*([-+]?\d+(?:\.\d+)?)", text).group(1))


@pytest.fixture(scope="module")
def consistency() -> str:
    """The report's paragraph on Tables II and III."""
    return " ".join(_table_consistency())


@pytest.mark.parametrize("table, beam", [(TABLE_II, "long"), (TABLE_III, "short")])
def test_power_of_V_in_the_tables(consistency, table, beam):
    """F0 ∝ V^b from the paper's rows as printed (log-log least squares here): 1.64 (long), 1.45 (short), as the V&V review found."""
    V, F0 = np.array([r[0] for r in table]), np.array([r[1] for r in table])
    b = np.polyfit(np.log(V), np.log(F0), 1)[0]
    assert _numbers(consistency, "V^" if beam == "long" else "and V^") == pytest.approx(b, abs=0.005)
    assert b == pytest.approx({"long": 1.64, "short": 1.45}[beam], abs=0.01)


def test_floors_of_a_common_law(consistency):
    """The least mean |error| of any F0 = cV² (and T = c/V) common to both tables, by a scan over c here: 18.2 % and 10.3 %."""
    rows = np.array(TABLE_II + TABLE_III, float)
    V, F0, T = rows[:, 0], rows[:, 1], rows[:, 3]
    cs = np.linspace(0.5, 2.0, 30001)
    floor_F = min(np.mean(np.abs(c * np.median(F0 / V**2) * V**2 / F0 - 1)) for c in cs)
    floor_T = min(np.mean(np.abs(c * np.median(T * V) / V / T - 1)) for c in cs)
    assert _numbers(consistency, "common to both beams is at least") == pytest.approx(100 * floor_F, abs=0.06)
    assert _numbers(consistency, "any T = c/V at least") == pytest.approx(100 * floor_T, abs=0.06)
    assert (round(100 * floor_F, 1), round(100 * floor_T, 1)) == (18.2, 10.3)


def test_tables_skew_is_stated(consistency):
    """The tables' t_F0/T range (from the rows here) is in the text beside Table I's 0.25."""
    rows = np.array(TABLE_II + TABLE_III, float)
    skew = rows[:, 2] / rows[:, 3]
    assert f"{skew.min():.3f}–{skew.max():.3f}" in consistency and "0.25" in consistency
