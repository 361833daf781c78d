"""The records of a bar test series, read and turned into strain: what ``reduce``, ``fit`` and
``identify`` read before :mod:`softimpact.studies.series` reduces them.

A file that cannot be read (missing, truncated, no such channel, no time base, text among
the numbers, a unit other than volts or strain) is bad input: InputError naming it.
Records in volts go through the series' bridge (``[gauge]``).
"""

from __future__ import annotations

from ..errors import InputError
from .series import Series, TestRecord, read_test_record

__all__ = ["read_records", "read_series_records"]


def read_records(series: Series, second: bool = False) -> list[TestRecord]:
    """Every record of the series (or of its second gauge), as strain where the bridge turns volts into strain (InputError on a bad file)."""
    out = []
    for test in series.tests:
        rec = read_test_record(test, second)
        if rec.kind == "voltage":
            if series.bridge is None:
                if rec.metadata.get("unit_stated", True):
                    raise InputError(f"{test.record}: a record in volts needs the bridge in [gauge] (gauge_factor, bridge, excitation)")
                raise InputError(
                    f"{test.record}: channel {rec.metadata.get('channel')!r} states no unit (read as volts) and [gauge] has no bridge: "
                    "name the unit in the file (time_s, microstrain, ... or 'CH1 (mV)') or give record = { file = ..., unit = ... }"
                )
            rec = TestRecord(rec.time, series.bridge.strain(rec.signal), "strain", {**rec.metadata, "bridge": series.bridge.configuration})
        out.append(rec)
    return out


def read_series_records(series: Series) -> tuple[list[TestRecord], list[TestRecord] | None]:
    """(the first gauge's records, the second gauge's or None): the arguments of
    :func:`softimpact.studies.series.reduce_series` after the series."""
    return read_records(series), (read_records(series, second=True) if series.second_position is not None else None)
