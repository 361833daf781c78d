"""Laboratory record readers: one volts record written by each format's own writer reads back the same."""

import csv
import sys

import numpy as np
import pytest
import scipy.io

try:  # readers' optional back ends: their tests skip until pyproject installs them
    import h5py
except ImportError:
    h5py = None
try:
    from nptdms import ChannelObject, GroupObject, RootObject, TdmsWriter
except ImportError:
    TdmsWriter = None

from softimpact.errors import InputError
from softimpact.input.records import LabRecord, list_channels, read_lab_record

needs_h5py = pytest.mark.skipif(h5py is None, reason="h5py not installed")
needs_nptdms = pytest.mark.skipif(TdmsWriter is None, reason="npTDMS not installed")

DT = 1e-7  # s, 10 MS/s
T0 = -20e-6  # s: 200 samples of pre-trigger
N = 1000
TIME = T0 + DT * np.arange(N)
RNG = np.random.default_rng(7)
VOLTS = -0.8 * np.exp(-(((TIME - 30e-6) / 8e-6) ** 2)) + 1e-3 * RNG.standard_normal(N)
TRIGGER = np.where(TIME >= 0, 5.0, 0.0)


def check(rec: LabRecord, rtol=1e-12):
    """The record holds TIME and VOLTS (to rtol), in volts."""
    assert isinstance(rec, LabRecord)
    assert rec.unit == "V"
    np.testing.assert_allclose(rec.time, TIME, rtol=0, atol=rtol * abs(T0) + 1e-18)
    np.testing.assert_allclose(rec.signal, VOLTS, rtol=rtol, atol=rtol)
    assert rec.metadata["sample_rate"] == pytest.approx(1 / DT, rel=1e-6)
    assert rec.metadata["pretrigger_samples"] == 200


# ------------------------------------------------------------------ writers


def write_tdms(path, with_time_props=True):
    props = {"wf_increment": DT, "wf_start_offset": T0, "unit_string": "V", "wf_start_time": np.datetime64("2024-05-01T10:00:00")}
    with TdmsWriter(path) as w:
        w.write_segment(
            [
                RootObject({"author": "lab"}),
                GroupObject("Bar"),
                ChannelObject("Bar", "Gauge1", VOLTS, properties=props if with_time_props else {"unit_string": "V"}),
                ChannelObject("Bar", "Trigger", TRIGGER, properties=props if with_time_props else {}),
            ]
        )
    return path


def write_mat_v73(path, with_time=True):
    """A MATLAB v7.3 file as MATLAB writes it: HDF5 with a 512-byte userblock, MATLAB_class attributes, column vectors stored (1, n)."""
    with h5py.File(path, "w", userblock_size=512) as f:
        for name, data in (("time", TIME), ("gauge1", VOLTS), ("trigger", TRIGGER)):
            if name == "time" and not with_time:
                continue
            ds = f.create_dataset(name, data=data.reshape(1, -1))
            ds.attrs["MATLAB_class"] = np.bytes_("double")
        unit = f.create_dataset("gauge1_unit", data=np.array([[ord(c)] for c in "V"], dtype=np.uint16))
        unit.attrs["MATLAB_class"] = np.bytes_("char")
    header = b"MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Wed May  1 10:00:00 2024 HDF5 schema 1.00 ."
    with open(path, "r+b") as fh:
        fh.write(header.ljust(116, b" ") + b"\x00" * 8 + b"\x00\x02" + b"IM")
    return path


def write_csv(path, lines, encoding="utf-8"):
    with open(path, "w", newline="", encoding=encoding) as fh:
        fh.write(lines)
    return path


def csv_rows(rows, delimiter=","):
    import io

    buf = io.StringIO()
    w = csv.writer(buf, delimiter=delimiter, lineterminator="\r\n")
    for r in rows:
        w.writerow(r)
    return buf.getvalue()


def data_rows(tscale=1.0, yscale=1.0, fmt=repr):
    return [[fmt(float(t) / tscale), fmt(float(y) / yscale)] for t, y in zip(TIME, VOLTS)]


# ------------------------------------------------------------------ round trips


@needs_nptdms
def test_tdms_round_trip(tmp_path):
    """A TDMS file from npTDMS's TdmsWriter reads back with its waveform time base and date."""
    path = write_tdms(tmp_path / "shot.tdms")
    assert list_channels(path) == ["Bar/Gauge1", "Bar/Trigger"]
    rec = read_lab_record(path, "Gauge1")
    check(rec)
    assert rec.metadata["source_format"] == "tdms"
    assert rec.metadata["channel"] == "Bar/Gauge1"
    assert rec.metadata["date"].startswith("2024-05-01T10:00:00")


@needs_nptdms
def test_tdms_time_channel_instead_of_waveform_properties(tmp_path):
    """Without wf_increment, a 'Time' channel in the same group is the time base."""
    path = tmp_path / "timed.tdms"
    with TdmsWriter(path) as w:
        w.write_segment([ChannelObject("Bar", "Time", TIME), ChannelObject("Bar", "Gauge1", VOLTS, properties={"unit_string": "V"})])
    assert list_channels(path) == ["Bar/Gauge1"]
    check(read_lab_record(path))


def test_mat_v5_round_trip_with_time_vector(tmp_path):
    """A .mat written by scipy.io.savemat with a time vector reads back exactly."""
    path = tmp_path / "shot.mat"
    scipy.io.savemat(path, {"time": TIME.reshape(-1, 1), "gauge1": VOLTS.reshape(-1, 1), "trigger": TRIGGER, "gauge1_unit": "V"})
    assert sorted(list_channels(path)) == ["gauge1", "trigger"]
    rec = read_lab_record(path, "gauge1")
    check(rec)
    assert rec.metadata["unit_stated"]


def test_mat_v5_round_trip_with_sample_interval(tmp_path):
    """A .mat holding dt and t0 scalars instead of a time vector gets the same time base."""
    path = tmp_path / "shot_dt.mat"
    scipy.io.savemat(path, {"dt": DT, "t0": T0, "gauge1": VOLTS})
    check(read_lab_record(path))


def test_mat_v5_struct_fields(tmp_path):
    """A struct with time and signal fields is a group: its signal reads as 'shot/gauge1'."""
    path = tmp_path / "struct.mat"
    scipy.io.savemat(path, {"shot": {"time": TIME, "gauge1": VOLTS}})
    check(read_lab_record(path, "shot/gauge1"))


@needs_h5py
def test_mat_v73_round_trip(tmp_path):
    """A MATLAB v7.3 (HDF5 with userblock) file reads back, its char unit decoded, as 'mat-v7.3'."""
    path = write_mat_v73(tmp_path / "shot73.mat")
    assert h5py.is_hdf5(path)
    rec = read_lab_record(path, "gauge1")
    check(rec)
    assert rec.metadata["source_format"] == "mat-v7.3"
    assert rec.metadata["unit"] == "V"


@needs_h5py
def test_hdf5_round_trip_with_attributes(tmp_path):
    """An HDF5 dataset with dt, t0 and unit attributes reads back with that time base."""
    path = tmp_path / "shot.h5"
    with h5py.File(path, "w") as f:
        g = f.create_group("bar")
        ds = g.create_dataset("gauge1", data=VOLTS * 1e3)
        ds.attrs.update({"dt": DT, "t0": T0, "unit": "mV"})
        g.create_dataset("trigger", data=TRIGGER).attrs.update({"dt": DT, "t0": T0})
    assert list_channels(path) == ["bar/gauge1", "bar/trigger"]
    check(read_lab_record(path, "gauge1"), rtol=1e-12)


def test_tektronix_style_csv(tmp_path):
    """Tektronix MSO export: metadata lines, a 'TIME,CH1' header, then numbers."""
    meta = [
        ["Model", "MSO54"],
        ["Firmware Version", "1.30"],
        ["Record Length", str(N)],
        ["Sample Interval", repr(DT)],
        ["Trigger Point", "200"],
        ["Date", "2024-05-01"],
        [""],
        ["TIME", "CH1"],
    ]
    path = write_csv(tmp_path / "tek.csv", csv_rows(meta + data_rows()))
    rec = read_lab_record(path)
    check(rec)
    assert rec.metadata["header"]["Model"] == "MSO54"
    assert rec.metadata["date"] == "2024-05-01"


def tds_csv(header_items, times, values, time_fmt="{:.12f}", value_fmt="{:.5f}"):
    """Tektronix TDS1000/TDS2000 layout: 18 header items in columns 1-3 beside the samples in columns 4-5, a trailing comma."""
    lines = []
    for k, (t, v) in enumerate(zip(times, values)):
        name, value = header_items[k] if k < len(header_items) else ("", "")
        lines.append(f"{name},{value},,{time_fmt.format(t)},{value_fmt.format(v)},\r\n")
    return "".join(lines)


TDS_HEADER = [
    ("Record Length", f"{N:.6e}"),
    ("Sample Interval", f"{DT:.6e}"),
    ("Trigger Point", f"{200:.12e}"),
    ("", ""),
    ("", ""),
    ("", ""),
    ("Source", "CH1"),
    ("Vertical Units", "V"),
    ("Vertical Scale", "2.000000e-01"),
    ("Vertical Offset", "0.000000e+00"),
    ("Horizontal Units", "s"),
    ("Horizontal Scale", "5.000000e-06"),
    ("Pt Fmt", "Y"),
    ("Yzero", "0.000000e+00"),
    ("Probe Atten", "1.000000e+00"),
    ("Model Number", "TDS2024B"),
    ("Serial Number", "C012345"),
    ("Firmware Version", "FV:v22.11"),
]


def test_tektronix_tds_side_by_side_csv(tmp_path):
    """TDS1000/2000 CSV (header items beside the data): time from Sample Interval, volts as written, Trigger Point and units from the header."""
    written = np.round(VOLTS, 5)  # the 5 decimals the file holds
    path = write_csv(tmp_path / "F0001CH1.CSV", tds_csv(TDS_HEADER, TIME, written))
    assert list_channels(path) == ["CH1"]
    rec = read_lab_record(path)
    np.testing.assert_allclose(rec.time, TIME, rtol=0, atol=1e-15)
    np.testing.assert_allclose(rec.signal, written, rtol=0, atol=1e-12)
    assert rec.unit == "V" and rec.metadata["unit_stated"]
    assert rec.metadata["sample_rate"] == pytest.approx(1 / DT, rel=1e-9)
    assert rec.metadata["pretrigger_samples"] == 200 and rec.metadata["trigger"] == "200"
    assert rec.metadata["source_format"] == "tektronix-csv" and rec.metadata["channel"] == "CH1"
    assert rec.metadata["header"]["Model Number"] == "TDS2024B" and rec.metadata["header"]["Probe Atten"] == "1.000000e+00"


def test_tektronix_tds_csv_in_millivolts_and_microseconds(tmp_path):
    """Vertical Units mV and Horizontal Units us are converted: volts and seconds come out."""
    items = [(k, {"Vertical Units": "mV", "Horizontal Units": "us", "Sample Interval": f"{DT * 1e6:.6e}"}.get(k, v)) for k, v in TDS_HEADER]
    path = write_csv(tmp_path / "tds-mv.csv", tds_csv(items, TIME * 1e6, VOLTS * 1e3, time_fmt="{:.6f}", value_fmt="{:.4f}"))
    rec = read_lab_record(path)
    assert rec.unit == "V"
    np.testing.assert_allclose(rec.time, TIME, rtol=0, atol=1e-15)
    np.testing.assert_allclose(rec.signal, VOLTS, rtol=0, atol=0.51e-7)  # 4 decimals of mV


def test_tektronix_tds_csv_cut_short(tmp_path):
    """A TDS CSV with fewer samples than its Record Length says so (truncated file)."""
    path = write_csv(tmp_path / "cut.csv", tds_csv(TDS_HEADER, TIME[:600], VOLTS[:600]))
    one_line_error(path, match="Record Length")


def test_tektronix_tds_csv_time_column_against_sample_interval(tmp_path):
    """A time column that disagrees with the header's Sample Interval is refused, naming both in plain numbers."""
    path = write_csv(tmp_path / "bad-dt.csv", tds_csv(TDS_HEADER, T0 + 2 * DT * np.arange(N), VOLTS))
    message = one_line_error(path, match="Sample Interval")
    assert "np.float64" not in message


def test_repeated_time_stamps_are_named_in_plain_numbers(tmp_path):
    """Two equal time stamps: the message gives the sample and the times as plain numbers (no numpy repr)."""
    rows = [["Time (s)", "CH1 (V)"]] + data_rows()
    rows[301][0] = rows[300][0]
    message = one_line_error(write_csv(tmp_path / "dup.csv", csv_rows(rows)), match="repeated or unordered time stamps")
    assert "np.float64" not in message and f"{TIME[299]:.9g} s then {TIME[299]:.9g} s" in message


def test_registry_names_a_reader_for_every_format(tmp_path):
    """Each format of the registry has its reader (channels and read), and detection picks the TDS layout apart from other text."""
    from softimpact.input.records import FORMATS, READERS
    from softimpact.input.records.registry import detect

    assert set(FORMATS) == {"tdms", "mat", "hdf5", "tektronix-csv", "text", "scope"}
    assert all(callable(READERS[f].read) and callable(READERS[f].channels) for f in FORMATS)
    tds = write_csv(tmp_path / "tds.csv", tds_csv(TDS_HEADER, TIME, VOLTS))
    plain = write_csv(tmp_path / "plain.csv", csv_rows([["Time (s)", "CH1 (V)"]] + data_rows()))
    assert detect(tds) == "tektronix-csv" and detect(plain) == "text"


def test_lecroy_style_csv(tmp_path):
    """LeCroy export: instrument line, segment lines, a 'Time,Ampl' header."""
    meta = [
        ["LECROYWR64Xi", "51181", "Waveform"],
        ["Segments", "1", "SegmentSize", str(N)],
        ["Segment", "TrigTime", "TimeSinceSegment1"],
        ["#1", "01-May-2024 10:00:00", "0"],
        ["Time", "Ampl"],
    ]
    check(read_lab_record(write_csv(tmp_path / "lecroy.csv", csv_rows(meta + data_rows()))))


def test_picoscope_style_csv_with_units_row(tmp_path):
    """PicoScope export: 'Time,Channel A', a units row '(us),(mV)', a blank line, numbers in µs and mV."""
    rows = [["Time", "Channel A"], ["(us)", "(mV)"], []] + [[repr(float(t) * 1e6), repr(float(y) * 1e3)] for t, y in zip(TIME, VOLTS)]
    rec = read_lab_record(write_csv(tmp_path / "pico.csv", csv_rows(rows)), "Channel A")
    check(rec, rtol=1e-12)


def test_excel_semicolon_decimal_comma_with_bom(tmp_path):
    """European Excel: UTF-8 BOM, ';' delimiter, decimal commas, units in the header 'Zeit [ms]'."""
    rows = [["Versuch", "Schuss 12"], ["Zeit [ms]", "Dehnung [V]"]] + [
        [repr(float(t) * 1e3).replace(".", ","), repr(float(y)).replace(".", ",")] for t, y in zip(TIME, VOLTS)
    ]
    path = write_csv(tmp_path / "excel.csv", csv_rows(rows, ";"), encoding="utf-8-sig")
    assert open(path, "rb").read(3) == b"\xef\xbb\xbf"
    check(read_lab_record(path), rtol=1e-12)


def test_tab_delimited_text_with_sample_interval_only(tmp_path):
    """A tab-delimited file with two signal columns and 'Sample Interval' in the header: time from the header."""
    rows = [["Sample Interval", repr(DT)], ["Horizontal Offset", repr(T0)], ["CH1 (V)", "CH2 (V)"]] + [
        [repr(float(y)), repr(float(z))] for y, z in zip(VOLTS, TRIGGER)
    ]
    path = write_csv(tmp_path / "scope.txt", csv_rows(rows, "\t"))
    assert list_channels(path) == ["CH1", "CH2"]
    check(read_lab_record(path, 0))


@pytest.mark.parametrize("written", [f"{DT * 1e6!r} us", f"{DT * 1e9!r} ns", f"{DT * 1e6!r},us", f"{DT!r} s"])
def test_vendor_header_sample_interval_with_its_unit(tmp_path, written):
    """'Sample Interval,0.1 us' (unit in the cell or the next one) is 1e-7 s, not 0.1 s: the record's
    time step equals the one written, converted by hand in the test."""
    rows = [["Sample Interval", *written.split(",")], ["CH1 (V)"]] + [[repr(float(y))] for y in VOLTS]
    rec = read_lab_record(write_csv(tmp_path / "scope.csv", csv_rows(rows)))
    assert np.diff(rec.time) == pytest.approx(DT, rel=1e-9)


def test_vendor_header_sample_interval_in_an_unknown_unit_is_refused(tmp_path):
    """'Sample Interval,0.5 furlongs' names the unit it does not understand instead of reading seconds."""
    rows = [["Sample Interval", "0.5 furlongs"], ["CH1 (V)"]] + [[repr(float(y))] for y in VOLTS]
    one_line_error(write_csv(tmp_path / "scope.csv", csv_rows(rows)), match="furlongs")


def test_microstrain_unit_kept(tmp_path):
    """A column labelled 'strain (µε)' reads as unit 'microstrain', values unchanged."""
    rows = [["time_us", "strain (µε)"]] + [[repr(float(t) * 1e6), repr(float(y) * 100)] for t, y in zip(TIME, VOLTS)]
    rec = read_lab_record(write_csv(tmp_path / "ue.csv", csv_rows(rows)))
    assert rec.unit == "microstrain"
    np.testing.assert_allclose(rec.signal, VOLTS * 100, rtol=1e-12)


# ------------------------------------------------------------------ bad files


def one_line_error(path, channel=None, match=None):
    with pytest.raises(InputError) as info:
        read_lab_record(path, channel)
    msg = str(info.value)
    assert "\n" not in msg and str(path) in msg
    if match:
        assert match in msg, msg
    return msg


@needs_nptdms
def test_truncated_tdms(tmp_path):
    """A TDMS file cut in half gives a one-line InputError naming the file, not an npTDMS traceback."""
    good = write_tdms(tmp_path / "good.tdms").read_bytes()
    path = tmp_path / "cut.tdms"
    path.write_bytes(good[: len(good) // 2])
    one_line_error(path, "Gauge1")


@needs_h5py
def test_truncated_hdf5(tmp_path):
    """A v7.3 MAT file cut short is a one-line InputError."""
    good = write_mat_v73(tmp_path / "good.mat").read_bytes()
    path = tmp_path / "cut.mat"
    path.write_bytes(good[:1500])
    one_line_error(path, "gauge1")


@needs_nptdms
def test_unknown_channel_lists_the_available_ones(tmp_path):
    """Asking for a channel that is not there names the ones that are."""
    msg = one_line_error(write_tdms(tmp_path / "shot.tdms"), "Gauge7", match="'Bar/Gauge1', 'Bar/Trigger'")
    assert "Gauge7" in msg


@needs_nptdms
def test_several_channels_need_a_choice(tmp_path):
    """channel=None on a two-channel file is an InputError listing both."""
    one_line_error(write_tdms(tmp_path / "shot.tdms"), None, match="choose one")


@needs_nptdms
def test_channel_index_out_of_range(tmp_path):
    """An index past the last channel is an InputError listing the channels."""
    one_line_error(write_tdms(tmp_path / "shot.tdms"), 5, match="out of range")


@needs_nptdms
def test_tdms_without_time_base(tmp_path):
    """A TDMS channel with neither waveform properties nor a time channel says so."""
    one_line_error(write_tdms(tmp_path / "notime.tdms", with_time_props=False), "Gauge1", match="no time base")


def test_mat_without_time_base(tmp_path):
    """A .mat with a signal but no time vector and no dt says so."""
    path = tmp_path / "notime.mat"
    scipy.io.savemat(path, {"gauge1": VOLTS})
    one_line_error(path, match="no time base")


def test_mat_unequal_lengths(tmp_path):
    """A time vector shorter than the signal is an InputError giving both lengths."""
    path = tmp_path / "short.mat"
    scipy.io.savemat(path, {"time": TIME[:-3], "gauge1": VOLTS})
    one_line_error(path, match="997")


@needs_h5py
def test_nan_in_signal(tmp_path):
    """A NaN in the signal is an InputError naming the first bad sample."""
    y = VOLTS.copy()
    y[123] = np.nan
    path = tmp_path / "nan.h5"
    with h5py.File(path, "w") as f:
        f.create_dataset("time", data=TIME)
        f.create_dataset("gauge1", data=y)
    one_line_error(path, match="sample 123")


def test_text_in_numbers(tmp_path):
    """A word among the numbers is an InputError naming its line and column."""
    rows = [["Time (s)", "CH1 (V)"]] + data_rows()
    rows[50][1] = "overflow"
    one_line_error(write_csv(tmp_path / "bad.csv", csv_rows(rows)), match="line 51, column 'CH1': 'overflow' is not a number")


def test_text_short_row(tmp_path):
    """A data row with a missing cell is reported as columns of unequal length."""
    rows = [["Time (s)", "CH1 (V)"]] + data_rows()
    rows[40] = rows[40][:1]
    one_line_error(write_csv(tmp_path / "short.csv", csv_rows(rows)), match="unequal length")


def test_text_without_time_base(tmp_path):
    """A single unlabelled column with no sample interval in the header says there is no time base."""
    rows = [["CH1"]] + [[repr(float(y))] for y in VOLTS]
    one_line_error(write_csv(tmp_path / "col.csv", csv_rows(rows)), match="no time base")


def test_decreasing_time(tmp_path):
    """Time that goes backwards is an InputError naming the sample."""
    rows = [["Time (s)", "CH1 (V)"]] + data_rows()
    rows[300][0], rows[301][0] = rows[301][0], rows[300][0]
    one_line_error(write_csv(tmp_path / "back.csv", csv_rows(rows)), match="not strictly increasing")


@pytest.mark.parametrize(
    ("name", "content", "match"),
    [
        ("empty.csv", b"", "empty file"),
        ("noise.bin", b"\x00\x01\x02garbage\x00" * 10, "unknown binary format"),
        ("fake.tdms", b"hello world, not tdms", "not a TDMS file"),
        ("fake.h5", b"hello", "not an HDF5 file"),
        ("fake.mat", b"MATLAB 5.0 MAT-file, garbage" + b"\x00" * 20, "not a readable MAT file"),
    ],
)
def test_unreadable_files(tmp_path, name, content, match):
    """Empty, garbage and mislabelled files give one-line InputErrors saying what is wrong."""
    path = tmp_path / name
    path.write_bytes(content)
    one_line_error(path, match=match)


def test_missing_file(tmp_path):
    """A path that does not exist is an InputError, not FileNotFoundError."""
    one_line_error(tmp_path / "nope.csv", match="no such file")


# ------------------------------------------------------------------ oscilloscope binaries (optional RigolWFM)


def write_isf(path):
    """A Tektronix ISF file per the programmer manual: WFMPRE header, then '#<n><bytes>' and int16 big-endian curve."""
    ymult = 2.0 / 32768 / 2
    adc = np.round(VOLTS / ymult).astype(">i2")
    volts = adc.astype(float) * ymult
    payload = adc.tobytes()
    header = (
        f':WFMPRE:BYT_NR 2;BIT_NR 16;ENCDG BIN;BN_FMT RI;BYT_OR MSB;WFID "Ch1, DC coupling, 100.0mV/div, 2.000us/div, {N} points, Sample mode";'
        f'NR_PT {N};PT_FMT Y;XUNIT "s";XINCR {DT:.6E};XZERO {T0:.6E};PT_OFF 0;YUNIT "V";YMULT {ymult:.6E};YOFF 0.0E+0;YZERO 0.0E+0;'
        f":CURVE #{len(str(len(payload)))}{len(payload)}"
    )
    path.write_bytes(header.encode("ascii") + payload + b"\n")
    return path, volts


def test_isf_round_trip_with_rigolwfm(tmp_path):
    """A hand-written Tektronix .isf reads back through RigolWFM (a test extra): time base from XINCR/XZERO, volts from YMULT."""
    path, volts = write_isf(tmp_path / "tek0001.isf")
    names = list_channels(path)
    rec = read_lab_record(path, names[0])
    np.testing.assert_allclose(rec.signal, volts, atol=1e-6)
    np.testing.assert_allclose(rec.time, TIME, atol=1e-12)
    assert rec.metadata["source_format"] == "scope"


def write_trc(path):
    """A LeCroy .trc per the LECROY_2_3 template: a 346-byte WAVEDESC (little endian, 16-bit words), then the int16 samples."""
    import struct

    gain, offset = np.float32(2.0 / 32768), np.float32(0.0)  # volts = VERTICAL_GAIN·adc − VERTICAL_OFFSET
    adc = np.round(VOLTS / gain).astype("<i2")
    desc = bytearray(346)

    def put(at, fmt, value):
        struct.pack_into("<" + fmt, desc, at, value)

    desc[0:16], desc[16:32] = b"WAVEDESC".ljust(16, b"\0"), b"LECROY_2_3".ljust(16, b"\0")
    put(32, "h", 1)  # COMM_TYPE: word
    put(34, "h", 1)  # COMM_ORDER: LOFIRST
    put(36, "i", 346)  # WAVE_DESCRIPTOR length
    put(60, "i", adc.nbytes)  # WAVE_ARRAY_1 length
    desc[76:92] = b"LECROYWR64Xi".ljust(16, b"\0")  # INSTRUMENT_NAME
    for at, value in ((116, N), (120, N), (124, 0), (128, N - 1), (136, 1), (148, 1)):  # counts, first/last valid point, sparsing, sweeps
        put(at, "i", value)
    put(156, "f", gain)
    put(160, "f", offset)
    put(172, "h", 16)  # NOMINAL_BITS
    put(174, "h", 1)  # NOM_SUBARRAY_COUNT
    put(176, "f", DT)  # HORIZ_INTERVAL (float32)
    put(180, "d", T0)  # HORIZ_OFFSET
    desc[196:244], desc[244:292] = b"V".ljust(48, b"\0"), b"S".ljust(48, b"\0")  # VERTUNIT, HORUNIT
    put(328, "f", 1.0)  # PROBE_ATT
    path.write_bytes(bytes(desc) + adc.tobytes())
    return path, adc * gain - offset, T0 + float(np.float32(DT)) * np.arange(N)


def test_lecroy_trc_round_trip_with_rigolwfm(tmp_path):
    """A hand-written LeCroy .trc (LECROY_2_3) reads back through RigolWFM: t = HORIZ_OFFSET + i·HORIZ_INTERVAL, volts = gain·adc − offset."""
    path, volts, time = write_trc(tmp_path / "C1shot00001.trc")
    rec = read_lab_record(path)
    np.testing.assert_allclose(rec.signal, volts, rtol=0, atol=1e-9)
    np.testing.assert_allclose(rec.time, time, rtol=0, atol=1e-15)
    assert rec.unit == "V" and rec.metadata["source_format"] == "scope" and rec.metadata["pretrigger_samples"] == 200


def test_scope_format_without_rigolwfm_says_what_to_install(tmp_path, monkeypatch):
    """With RigolWFM not importable, a .trc file gives a one-line InputError naming the package."""
    monkeypatch.setitem(sys.modules, "RigolWFM", None)
    path = tmp_path / "C1.trc"
    path.write_bytes(b"\x00" * 400)
    one_line_error(path, match="pip install RigolWFM")
