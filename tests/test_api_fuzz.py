"""A fuzz target over the Python API's edge: its constructors, ``si.load`` and ``result.write``.

Random and nasty inputs (texts, numbers without units or with wrong ones, NaN, infinities, negative and
zero sizes, wrong types, files of random bytes, folders holding another tool's manifest.json, user files
of the outputs' names, a companion .h5) must each end either in a valid object or in softimpact's
InputError: never another exception type (a traceback), and never a changed or deleted file of the user's.
"""

import contextlib
import hashlib
import json
import math
import os
import tempfile
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import softimpact as si
from softimpact.errors import InputError

# Derandomised (the same examples on every run: a merge is never failed by luck); SOFTIMPACT_FUZZ=N explores N random examples a test.
_EXPLORE = int(os.environ.get("SOFTIMPACT_FUZZ", "0"))
FUZZ = settings(max_examples=_EXPLORE or 40, deadline=None, suppress_health_check=[HealthCheck.too_slow], database=None, derandomize=not _EXPLORE)

UNITS = ["in", "m", "mm", "kg", "us", "s", "m/s", "in/s", "lbf", "", "furlong", "degC", "1/s", "in**2", "%"]
NUMBERS = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(min_value=-(10**12), max_value=10**12),
    st.sampled_from([0, -1, 1e-300, 1e300, "nan", "inf", "-0", "1e999", "0x10", "1_000", "½"]),
)
QUANTITY = st.one_of(
    st.builds(lambda x, u: f"{x} {u}".strip(), NUMBERS, st.sampled_from(UNITS)),
    st.text(max_size=12),
    NUMBERS,
    st.none(),
    st.booleans(),
    st.lists(st.integers(), max_size=3),
    st.just(b"6 in"),
    st.sampled_from(["6 in", "0.5 in", "100 in/s", "1 in", "0.1 in", "1.1 g", "38.1 mm", "27.3 m/s"]),
)
ELEMENTS = st.one_of(
    st.tuples(st.integers(-2, 60), st.integers(-2, 12)),
    st.tuples(st.integers(1, 8)),
    st.integers(-2, 10),
    st.text(max_size=5),
    st.none(),
    st.tuples(st.floats(), st.floats()),
    st.tuples(st.booleans(), st.booleans()),
)
ANGLE = st.sampled_from(["0", "90", "45", "-45", "±45", "30.5", "x", "", "1e9", "nan"])
LAYUP = st.one_of(
    st.builds(
        lambda a, n, s: "[" + "/".join(a) + "]" + n + s, st.lists(ANGLE, max_size=4), st.sampled_from(["", "2", "5", "0", "-1"]), st.sampled_from(["", "s"])
    ),
    st.text(max_size=10),
    st.none(),
    st.integers(),
)
PLY = st.one_of(st.just("T300/934"), st.text(max_size=8), st.none(), st.integers())
MATERIAL = st.one_of(st.sampled_from(["steel", "ice", "rubber", "Al 6061-T6", "gelatin"]), st.text(max_size=8), st.none(), st.floats())
NAME = st.one_of(
    st.sampled_from(["clamped-free", "clamped-clamped", "simply-supported", "free", "clamped", "mitc4", "mitc9", "smeared", "layered", "strain", "stress"]),
    st.text(max_size=8),
    st.none(),
    st.integers(),
)


def _outcome(make):
    """The object ``make()`` builds, or None when it refused with InputError (any other exception fails the test)."""
    try:
        return make()
    except InputError as exc:
        assert str(exc).strip(), "an InputError without a message"
        return None


@FUZZ
@given(material=MATERIAL, diameter=QUANTITY, velocity=QUANTITY, mass=st.one_of(st.none(), QUANTITY))
def test_sphere_takes_any_input_or_refuses_it(material, diameter, velocity, mass):
    """si.Sphere on random arguments builds a ball of positive finite diameter, mass and velocity, or raises InputError."""
    ball = _outcome(lambda: si.Sphere(material, diameter, velocity=velocity, mass=mass))
    if ball is not None:
        assert all(math.isfinite(v) and v > 0 for v in (ball.diameter, ball.mass)), ball
        assert math.isfinite(ball.velocity), ball


@settings(FUZZ, max_examples=_EXPLORE or 60)
@given(ply=PLY, layup=LAYUP, length=QUANTITY, width=QUANTITY, material=st.one_of(st.none(), MATERIAL), thickness=QUANTITY, elements=ELEMENTS)
def test_beam_takes_any_input_or_refuses_it(ply, layup, length, width, material, thickness, elements):
    """si.Laminate and si.Beam on random arguments build a beam of positive finite size, or raise InputError."""
    laminate = _outcome(lambda: si.Laminate(ply, layup)) if material is None else None
    if material is None and laminate is None:
        return
    kwargs = {"laminate": laminate} if material is None else {"material": material, "thickness": thickness}
    beam = _outcome(lambda: si.Beam(length=length, width=width, elements=elements, **kwargs))
    if beam is not None:
        spec = beam.spec
        assert math.isfinite(spec.length) and spec.length > 0 and math.isfinite(spec.width) and spec.width > 0, spec


@FUZZ
@given(length=QUANTITY, width=QUANTITY, elements=ELEMENTS, support=st.one_of(NAME, st.tuples(NAME, NAME, NAME, NAME)), element=NAME)
def test_plate_takes_any_input_or_refuses_it(length, width, elements, support, element):
    """si.Plate on random arguments builds a plate of positive finite size, or raises InputError."""
    laminate = si.Laminate("T300/934", "[90/0]5s")
    plate = _outcome(lambda: si.Plate(length=length, width=width, laminate=laminate, elements=elements, support=support, element=element))
    if plate is not None:
        assert all(math.isfinite(v) and v > 0 for v in (plate.spec.length, plate.spec.width)), plate.spec


@FUZZ
@given(material=MATERIAL, length=QUANTITY, diameter=QUANTITY, elements=st.one_of(st.integers(-2, 50), ELEMENTS))
def test_bar_takes_any_input_or_refuses_it(material, length, diameter, elements):
    """si.Bar on random arguments builds a bar of positive finite size, or raises InputError."""
    bar = _outcome(lambda: si.Bar(material, length=length, diameter=diameter, elements=elements))
    if bar is not None:
        assert all(math.isfinite(v) and v > 0 for v in (bar.spec.length, bar.spec.diameter)), bar.spec


TOML_LINES = st.sampled_from(
    [
        'title = "x"',
        'units = "in-lbf-s"',
        'units = "parsecs"',
        "[beam]",
        "[bar]",
        "[target]",
        'case = "paper-long-beam"',
        'case = "../../etc/passwd"',
        'length = "6 in"',
        "length = 6",
        'length = "-6 in"',
        'length = "nan in"',
        "elements = [200, 6]",
        "elements = [0, -1]",
        "[load]",
        'position = "3 in"',
        "[solver]",
        'time_step = "1 us"',
        'duration = "0 us"',
        "[[gauges]]",
        'name = "g1"',
        "= = =",
        "[beam.laminate]",
        'layup = "[90/0]5s"',
    ]
)


@FUZZ
@given(
    content=st.one_of(st.binary(max_size=200), st.lists(TOML_LINES, max_size=12).map("\n".join), st.text(max_size=200)),
    suffix=st.sampled_from([".toml", ".json", ".csv", "", ".TOML"]),
    history=st.one_of(st.none(), st.integers(-3, 30), st.text(max_size=3), st.floats()),
)
def test_load_takes_any_file_or_refuses_it(content, suffix, history):
    """si.load of a file of random bytes, text or TOML lines returns a Case or raises InputError."""
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / f"case{suffix}"
        path.write_bytes(content if isinstance(content, bytes) else content.encode("utf-8", "surrogatepass"))
        case = _outcome(lambda: si.load(path, history=history))
    if case is not None:
        assert case.kind and case.problem is not None


@FUZZ
@given(
    name=st.one_of(st.text(max_size=30), st.sampled_from(["paper-long-beam", "paper-long-beam-impact", "plate-ss-8in", "", ".", "/", "\x00", "~", "-"])),
    history=st.one_of(st.none(), st.integers(-3, 30)),
)
def test_load_takes_any_name_or_refuses_it(name, history):
    """si.load of a random name (built-in or not, empty, a folder, a NUL) returns a Case or raises InputError."""
    with tempfile.TemporaryDirectory() as folder, contextlib.chdir(folder):
        case = _outcome(lambda: si.load(name, history=history))
    if case is not None:
        assert case.kind and case.problem is not None


class _Once:
    """The result, behind a short repr (hypothesis prints its test's arguments on a failure)."""

    def __init__(self, result):
        self.result = result

    def __repr__(self):
        return "small_result"


@pytest.fixture(scope="module")
def small_result():
    """One small coupled impact (a coarse long beam, 100 µs), computed once for every write below."""
    return _Once(_small_impact())


def _small_impact():
    beam = si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(40, 4))
    return si.impact(beam, at="3 in", impactor=si.Sphere("steel", "0.5 in", velocity="100 in/s"), law="hertz", time_step="1 us", duration="100 us")


def _foreign_manifest(kind: str, listed: dict[str, bytes]) -> bytes:
    """A manifest.json softimpact did not write: another tool's, one claiming softimpact's name with a wrong signature, or junk."""
    hashes = {n: hashlib.sha256(b).hexdigest() for n, b in listed.items()}
    if kind == "other-tool":
        return json.dumps({"tool": "labview-export", "files": [{"name": n, "sha256": h} for n, h in hashes.items()]}).encode()
    if kind == "forged":
        return json.dumps({"generator": "softimpact", "files": hashes, "signature": "0" * 64}).encode()
    if kind == "list":
        return json.dumps(list(hashes)).encode()
    return b"\xff\xfe not json {"


USER_NAMES = st.sampled_from(["history.csv", "summary.json", "notes.txt", "history.h5", "fields.h5", "fields.xdmf", "figure.png", "sub/summary.json"])


def _hashes(folder: Path) -> dict[str, str]:
    return {p.relative_to(folder).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest() for p in folder.rglob("*") if p.is_file()}


@FUZZ
@given(
    user=st.dictionaries(USER_NAMES, st.binary(max_size=40), max_size=4),
    manifest=st.sampled_from(["none", "other-tool", "forged", "list", "junk"]),
    directory_named=st.one_of(st.none(), st.sampled_from(["history.csv", "summary.json", "manifest.json"])),
    force_fields=st.booleans(),
)
def test_write_keeps_every_user_file(small_result, user, manifest, directory_named, force_fields):
    """result.write (and write_fields) into a folder of the user's files, with another tool's or a forged manifest.json, a
    companion .h5 or a folder of an output's name, either writes or raises InputError, and leaves every user file unchanged."""
    with tempfile.TemporaryDirectory() as folder:
        out = Path(folder) / "out"
        out.mkdir()
        for name, data in user.items():
            (out / name).parent.mkdir(parents=True, exist_ok=True)
            (out / name).write_bytes(data)
        if manifest != "none":
            (out / "manifest.json").write_bytes(_foreign_manifest(manifest, user))
        if directory_named is not None and not (out / directory_named).exists():
            (out / directory_named).mkdir()
        before = _hashes(out)
        written = _outcome(lambda: small_result.result.write(out, figures=False))
        if force_fields:
            _outcome(lambda: small_result.result.write_fields(out / "fields.xdmf", frames=3))
        after = _hashes(out)
        assert {n: after.get(n) for n in before} == before, "a user's file changed or went"
        if written is not None:
            assert all(p.is_file() for p in written)


@FUZZ
@given(out=st.one_of(st.sampled_from(["", ".", "\x00", "a\x00b", "file.txt", "file.txt/sub"]), st.text(max_size=12)))
def test_write_to_a_nasty_path_writes_or_refuses(small_result, out):
    """result.write to an empty, NUL-bearing, file-named or random path writes there or raises InputError, leaving a user file alone."""
    with tempfile.TemporaryDirectory() as folder, contextlib.chdir(folder):
        Path("file.txt").write_bytes(b"the user's")
        written = _outcome(lambda: small_result.result.write(out, figures=False))
        assert Path("file.txt").read_bytes() == b"the user's"
        if written is not None:
            assert all(p.is_file() for p in written)
