"""A case file's unknown key that looks like an optional key the reader asked for (and took the default of) is named as a
likely misspelling: the run would otherwise have silently used the default."""

import pytest

from softimpact.errors import InputError
from softimpact.input.toml import Table


def test_a_misspelt_optional_key_is_named():
    """``inplane`` beside the optional ``in_plane``: the error names both."""
    t = Table({"inplane": "movable"}, "plate")
    assert t.string("in_plane", "immovable") == "immovable"
    with pytest.raises(InputError, match=r"plate.inplane: unknown key .*misspelling of 'in_plane'"):
        t.done()


def test_an_unrelated_unknown_key_gets_no_hint():
    """A key like nothing the reader asked for is just unknown."""
    t = Table({"colour": "red"}, "plate")
    t.string("in_plane", "immovable")
    with pytest.raises(InputError) as err:
        t.done()
    assert "misspelling" not in str(err.value)
