"""Units at the edge: strings with units in, SI floats out."""

import math

import pytest

from softimpact.errors import InputError
from softimpact.units import display, parse

from _support.constants import INCH, LB_PER_IN3, PSI


@pytest.mark.parametrize(
    "text, kind, si",
    [
        ("0.5 in", "length", 0.5 * INCH),
        ("1.1 g", "mass", 1.1e-3),
        ("62.1 in/s", "velocity", 62.1 * INCH),
        ("0.5 us", "time", 0.5e-6),
        ("10.0e6 psi", "stress", 10.0e6 * PSI),
        ("0.0975 lb/in^3", "density", 0.0975 * LB_PER_IN3),
        ("44 lbf", "force", 44 * 4.4482216152605),
    ],
)
def test_parse_gives_si(text, kind, si):
    """Each case-file quantity converts to SI by the exact definitions of the inch, pound and pound-force."""
    assert math.isclose(parse(text, kind, "k"), si, rel_tol=1e-12)


@pytest.mark.parametrize("value", ["0.5", 0.5, "0.5 furlongs_per_fortnight_xyz"])
def test_missing_or_unknown_unit_is_refused(value):
    """A bare number or an unknown unit for a dimensional quantity is an error naming the key."""
    with pytest.raises(InputError, match="bar.length"):
        parse(value, "length", "bar.length")


def test_wrong_dimension_is_refused():
    """A velocity given where a length is expected is an error naming the key and value."""
    with pytest.raises(InputError, match=r"bar.length: '3 m/s' is not a length"):
        parse("3 m/s", "length", "bar.length")


def test_display_factors():
    """Display units: SI newtons shown as lbf, seconds as microseconds."""
    assert math.isclose(display("in-lbf-s", "force").factor, 1 / 4.4482216152605, rel_tol=1e-12)
    assert math.isclose(display("SI", "time").factor, 1e6)


def _fresh_cache(monkeypatch, folder):
    """A new, empty in-memory unit-factor cache backed by ``folder``."""
    from softimpact import units

    monkeypatch.setenv("SOFTIMPACT_CACHE_DIR", str(folder))
    cache = units._FactorCache()
    monkeypatch.setattr(units, "_FACTORS", cache)
    return cache


def test_cached_factors_are_pints_and_survive_a_restart(tmp_path, monkeypatch):
    """A unit seen once is remembered in the cache file; a new process (a new cache
    object) reading it gives the same SI values, equal to the exact definitions."""
    _fresh_cache(monkeypatch, tmp_path)
    first = [parse("0.5 in", "length", "k"), parse("44 lbf", "force", "k"), parse("10.0e6 psi", "stress", "k")]
    assert len(list(tmp_path.glob("units-*.json"))) == 1
    _fresh_cache(monkeypatch, tmp_path)
    again = [parse("0.5 in", "length", "k"), parse("44 lbf", "force", "k"), parse("10.0e6 psi", "stress", "k")]
    assert again == first
    assert math.isclose(again[0], 0.5 * INCH, rel_tol=1e-15) and math.isclose(again[2], 10.0e6 * PSI, rel_tol=1e-12)


def test_a_damaged_cache_is_ignored_and_errors_still_come_from_pint(tmp_path, monkeypatch):
    """A cache file that is not JSON, or holds a non-positive factor, is not used; a wrong
    unit is refused whatever the cache holds, and nothing is cached for it."""
    cache = _fresh_cache(monkeypatch, tmp_path)
    tmp_path.mkdir(exist_ok=True)
    cache.path.write_text('{"length|in": -1.0}')
    assert math.isclose(parse("2 in", "length", "k"), 2 * INCH, rel_tol=1e-15)
    cache = _fresh_cache(monkeypatch, tmp_path)
    cache.path.write_text("not json")
    assert math.isclose(parse("2 in", "length", "k"), 2 * INCH, rel_tol=1e-15)
    with pytest.raises(InputError, match="is not a length"):
        parse("3 m/s", "length", "k")
    assert "length|m/s" not in cache.path.read_text()


def test_a_warm_cache_spares_the_pint_import(tmp_path):
    """The point of the cache: a process whose units are all cached never imports pint."""
    import os
    import subprocess
    import sys

    code = "import sys; from softimpact.units import parse, display; parse('0.5 in', 'length', 'k'); display('SI', 'force'); print('pint' in sys.modules)"
    env = os.environ | {"SOFTIMPACT_CACHE_DIR": str(tmp_path)}
    runs = [subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True).stdout.strip() for _ in range(2)]
    assert runs == ["True", "False"]
