"""Units at the edge: strings with units in, SI floats out."""

import math

import pytest
from conftest import INCH, LB_PER_IN3, PSI

from softimpact.errors import InputError
from softimpact.units import display, parse


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
