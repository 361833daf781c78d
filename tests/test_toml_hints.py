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


@pytest.mark.parametrize(
    "law, key, value, reader",
    [
        ("crushing", "law_file", "law.json", "identified"),
        ("hertz", "restitution", 0.5, "hunt-crossley"),
        ("hertz", "law_file", "law.json", "identified"),
        ("crushing", "sound_speed", "1500 m/s", "hydrodynamic"),
    ],
)
def test_a_contact_key_of_another_law_names_the_law_that_reads_it(tmp_path, law, key, value, reader):
    """A bar case's ``[contact]`` key that only another law reads (``law_file`` beside ``law = "crushing"``) names that law."""
    from softimpact.input.bar_case import load_bar_case

    path = tmp_path / "case.toml"
    path.write_text(
        'units = "SI"\n[bar]\nmaterial = "Al 6061-T6"\nlength = "36 in"\ndiameter = "2 in"\nelements = 39\n'
        '[projectile]\nmaterial = "ice"\ndiameter = "50.8 mm"\nvelocity = "61 m/s"\n'
        f'[contact]\nlaw = "{law}"\n{key} = {value!r}\n'.replace("'", '"')
        + '[solver]\ntime_step = "0.5 us"\nduration = "100 us"\n'
    )
    with pytest.raises(InputError, match=rf'contact.{key}: not read here .*read only with contact.law = "{reader}"'):
        load_bar_case(str(path))
