"""Record files: one reader per format and a registry (:mod:`.registry`) that detects the format.

softimpact's own CSV (:mod:`.softimpact_csv`: ``time_s``/``strain`` columns, measured ``strain_<gauge>``)
is read by :func:`read_record`, :func:`read_strains` and :func:`read_columns`. Laboratory gauge records
from data-acquisition and oscilloscope files: :func:`read_lab_record` returns one channel as a :class:`LabRecord` (time [s],
signal, unit, metadata); :func:`list_channels` names what a file holds. The
format is chosen by extension and confirmed by the file's first bytes:

========================  ====================  =========================================
format                    read with             time base
========================  ====================  =========================================
.tdms (NI LabVIEW)        npTDMS                wf_increment, wf_start_offset (waveform
                                                properties), else a time channel in the group
.mat v4–v7 (MATLAB)       scipy.io.loadmat      a time vector (t, time, …), else dt/fs and t0
.mat v7.3, .h5, .hdf5     h5py                  a time dataset beside the signal, else dt/fs
                                                and t0 attributes (or scalar datasets)
.csv .txt .tsv .dat       csv (stdlib)          a time column, else a sample interval among
                                                the metadata lines
.csv Tektronix TDS1000/   csv (stdlib)          the first time stamp + k·Sample Interval (header),
TDS2000 (18 header items                        checked against the time column; Trigger
in columns 1-3 beside                           Point and Vertical Units from the header
the data in columns 4-5)
.isf .wfm (Tektronix),    RigolWFM (optional:   the scope's own header (XINCR, XZERO, …)
.trc (LeCroy)             pip install RigolWFM)
========================  ====================  =========================================

Delimited text may carry vendor metadata lines (Tektronix, LeCroy, PicoScope,
Excel exports): ``key<delimiter>value`` lines, then a header row (names, with
units as "Time (s)", "CH1 [mV]" or on a PicoScope units row "(us),(mV)"), then
numbers. Delimiters ``,`` ``;`` and tab are sniffed; a UTF-8 byte-order mark is
accepted; a semicolon file with decimal commas (European Excel) is read too.

Units: time is converted to seconds; mV/µV to V; "strain", "m/m" → ``strain``;
"µε", "microstrain", "um/m" → ``microstrain``; other units are kept as written;
none stated → ``V``, and ``metadata["unit_stated"]`` is False.

Every problem (unreadable or truncated file, unknown channel, no time base,
text among the numbers, unequal lengths, NaN) raises
:class:`softimpact.errors.InputError` with one line naming the file.
"""

from __future__ import annotations

from pathlib import Path

from ._common import LabRecord
from .registry import FORMATS, READERS, detect
from .softimpact_csv import SIGNAL_COLUMNS, TIME_COLUMNS, read_columns, read_record, read_strains

__all__ = [
    "LabRecord",
    "read_lab_record",
    "list_channels",
    "FORMATS",
    "READERS",
    "TIME_COLUMNS",
    "SIGNAL_COLUMNS",
    "read_columns",
    "read_record",
    "read_strains",
]


def list_channels(path) -> list[str]:
    """Names of the signal channels in a record file (time columns excluded), in file order."""
    path = Path(path)
    return READERS[detect(path)].channels(path)


def read_lab_record(path, channel: str | int | None = None) -> LabRecord:
    """One channel of a record file as a :class:`LabRecord` (module docstring for formats).

    ``channel``: a name (``"group/channel"`` or just ``"channel"`` when unique,
    any case), an index into :func:`list_channels`, or None when the file holds
    one channel.
    """
    path = Path(path)
    return READERS[detect(path)].read(path, channel)
