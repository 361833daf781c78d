"""The catalogue (``softimpact catalogue``, ``si.catalogue()``, the docs page) lists every named entry of the models' tables, each with its units and its source."""

import math

import pytest
from click.testing import CliRunner

import softimpact as si
from softimpact.cli import main
from softimpact.models.contact_laws import CONTACT_LAWS
from softimpact.models.empirical import PRESETS, PROJECTILES
from softimpact.models.laminate import PLIES
from softimpact.models.materials import CATALOGUE
from softimpact.models.metals import METALS
from softimpact.models.projectiles import PROJECTILES as PROJECTILE_MATERIALS

# The models' own tables, read here independently of softimpact.app.catalogue: (catalogue table, names).
SOURCES = {
    "materials": tuple(CATALOGUE),
    "metals": tuple(METALS),
    "plies": tuple(PLIES),
    "projectiles": tuple(PROJECTILES),
    "projectile_materials": tuple(PROJECTILE_MATERIALS),
    "scaling_constants": tuple(PRESETS),
    "contact_laws": tuple(CONTACT_LAWS),
}


@pytest.fixture(scope="module")
def cat():
    return si.catalogue()


@pytest.fixture(scope="module")
def listing():
    run = CliRunner().invoke(main, ["catalogue"])
    assert run.exit_code == 0, run.output
    return run.output


def _builtin_names():
    from softimpact.input.toml import builtin_cases

    return tuple(builtin_cases())


@pytest.mark.parametrize("table", [*SOURCES, "cases"])
def test_every_entry_is_in_the_python_catalogue(cat, table):
    """Every name of the models' table (and every built-in case file) is a row of ``si.catalogue()``'s table, once."""
    names = SOURCES[table] if table != "cases" else _builtin_names()
    got = getattr(cat, table).names
    assert sorted(got) == sorted(names)


@pytest.mark.parametrize("table", [*SOURCES, "cases"])
def test_every_entry_has_units_and_a_source(cat, table):
    """Every numeric column of a table has a unit, and every entry a non-empty source (its last column)."""
    t = getattr(cat, table)
    assert t.columns[-1] == "source" and len(t.units) == len(t.columns)
    for row in t.rows:
        assert len(row) == len(t.columns)
        assert isinstance(row[-1], str) and row[-1].strip() and row[-1] != "user input", f"{table}: {row[0]} has no source"
        for column, unit, value in zip(t.columns, t.units, row, strict=True):
            if isinstance(value, float):
                assert unit, f"{table}: column {column} is numeric and has no unit"


@pytest.mark.parametrize("table", [*SOURCES, "cases"])
def test_command_lists_every_entry_with_its_source(cat, listing, table):
    """``softimpact catalogue`` prints every entry's name and its source line."""
    t = getattr(cat, table)
    for row in t.rows:
        assert f"  {row[0]}: " in listing
        assert f"source: {row[-1]}" in listing


def test_command_shows_units(listing):
    """The listing gives values with their SI units (steel's E in Pa, a ply thickness in m, a ball's mass in kg)."""
    steel = next(line for line in listing.splitlines() if line.startswith("  steel: "))
    assert " Pa" in steel and " kg/m^3" in steel
    assert "thickness " in listing and " m," in listing and " kg," in listing


def test_contact_law_description_is_its_docstring_first_line(cat):
    """A contact law's description is the first line of its class's docstring."""
    for name, description, *_ in cat.contact_laws.rows:
        assert description == CONTACT_LAWS[name].__doc__.strip().splitlines()[0]


def test_material_wave_speed_is_bar_speed(cat):
    """The listed bar wave speed is c = sqrt(E/rho) of the listed E and density (computed here)."""
    for _name, E, _nu, rho, c, _source in cat.materials.rows:
        assert c == pytest.approx(math.sqrt(E / rho), rel=1e-12)


def test_half_inch_ball_as_in_the_paper(cat):
    """The 1/2-in ball: diameter 0.5 in = 12.7 mm and mass 1.1 g (the paper's text); its scaling constants a listed set."""
    row = dict(zip(cat.projectiles.columns, next(r for r in cat.projectiles.rows if r[0] == "rubber-1/2in"), strict=True))
    assert row["diameter"] == pytest.approx(0.0127, rel=1e-12)
    assert row["mass"] == pytest.approx(1.1e-3, rel=1e-12)
    assert row["scaling constants"] in cat.scaling_constants.names


def test_catalogue_is_frozen(cat):
    """The catalogue and its tables are frozen: an entry cannot be changed by a user's script."""
    import dataclasses

    with pytest.raises(dataclasses.FrozenInstanceError):
        cat.materials = cat.plies
    with pytest.raises(dataclasses.FrozenInstanceError):
        cat.materials.rows = ()


def test_to_frame_heads_columns_with_units(cat):
    """``to_frame`` gives one DataFrame row per entry, columns headed with their units."""
    pytest.importorskip("pandas")
    frame = cat.to_frame("materials")
    assert len(frame) == len(CATALOGUE)
    assert "E [Pa]" in frame.columns and "density [kg/m^3]" in frame.columns


def test_docs_page_lists_every_entry(cat):
    """The docs page (markdown written at each docs build) has a table row for every entry of every table."""
    from softimpact.app.catalogue import markdown

    page = markdown(cat)
    for t in cat.tables:
        for row in t.rows:
            assert f"| `{row[0]}` |" in page
