"""si.read_record reads softimpact's own record CSVs (``time_us``, ``microstrain`` columns) in SI."""

from pathlib import Path

import numpy as np

import softimpact
import softimpact as si
from softimpact.input.records import read_record


def test_own_series_record_reads_in_seconds_and_microstrain():
    """A built-in series record through the generic lab reader: the same time [s] and signal as the series' own reader."""
    path = Path(softimpact.__file__).parent / "data" / "series" / "paper-rubber-series" / "1_2in-1000.csv"
    rec = si.read_record(path)
    time, signal, kind = read_record(path)
    assert np.allclose(rec.time, time, rtol=1e-12, atol=0)
    assert rec.time[-1] < 1.0  # seconds, not microseconds
    assert rec.unit == "microstrain"
    assert kind == "strain"
    assert np.allclose(rec.signal * 1e-6, signal, rtol=1e-12, atol=0)
