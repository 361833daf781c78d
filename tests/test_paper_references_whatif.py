"""The report's what-if with the tables' α3: bar records made like the built-in series with another α3, and the α3 the
tables imply, checked against the stored records, the reduction and the paper's rows."""

from dataclasses import replace

import numpy as np
import pytest

from softimpact.app.paper.question import tables_alpha3
from softimpact.input.series import load_series
from softimpact.input.series_records import read_series_records
from softimpact.models.empirical import PRESETS, PROJECTILES
from softimpact.studies.references import synthetic_series_records
from softimpact.studies.series import fit_series, reduce_series

from _support.problems import TABLE_II, TABLE_III

HALF_INCH = PROJECTILES["rubber-1/2in"].diameter


@pytest.fixture(scope="module")
def half_inch_series():
    """The 1/2-in tests of the built-in synthetic bar series."""
    s = load_series("paper-rubber-series")
    return replace(s, tests=tuple(t for t in s.tests if abs(t.diameter - HALF_INCH) < 1e-9))


def test_tables_alpha3_from_the_rows():
    """The tables' α3 is t_F0·V/(α2·d) averaged over the 8 rows of Tables II and III (α2 = 0.93, d = 0.5 in, Table I): 0.085."""
    rows = np.array(TABLE_II + TABLE_III, float)  # V [in/s], F0 [lbf], t_F0 [µs], T [µs], r0 [in]
    expected = np.mean(rows[:, 2] * 1e-6 * rows[:, 0] / (0.93 * 0.5))
    assert tables_alpha3() == pytest.approx(expected, rel=1e-9)
    assert round(expected, 3) == 0.085


def test_generator_remakes_the_builtin_records(half_inch_series):
    """With Table I's constants the generator gives the stored records of tools/make_rubber_series.py (to their printed digits)."""
    made = synthetic_series_records(half_inch_series, [PRESETS["silicone-1/2in"]] * len(half_inch_series.tests))
    stored, _ = read_series_records(half_inch_series)
    for m, s in zip(made, stored):
        assert m.time.shape == s.time.shape
        assert np.max(np.abs(m.time - s.time)) < 1e-9
        assert np.max(np.abs(m.signal - s.signal)) < 1e-5 * np.max(np.abs(s.signal))


def test_made_series_reduces_to_its_alpha3(half_inch_series):
    """Records made with α3 = 0.085 reduce (conditioning, reduction and the eq 4-7 fit, blind to the generator) to that α3
    within 3 % and Table I's α2 within 1 % (1 % noise, the eq-15 fit of a sampled pulse)."""
    law = replace(PRESETS["silicone-1/2in"], alpha3=0.085)
    made = synthetic_series_records(half_inch_series, [law] * len(half_inch_series.tests))
    (fit,) = fit_series(reduce_series(half_inch_series, made)).values()  # one diameter: one group
    assert fit.law().alpha3 == pytest.approx(0.085, rel=0.03)
    assert fit.law().alpha2 == pytest.approx(0.93, rel=0.01)
