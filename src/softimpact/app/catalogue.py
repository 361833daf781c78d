"""The catalogue: every named material, ply, projectile, scaling-constant set, contact law and built-in case.

One function, :func:`catalogue`, reads the tables of the models (:data:`softimpact.models.materials.CATALOGUE`,
:data:`softimpact.models.metals.METALS`, :data:`softimpact.models.laminate.PLIES`, :data:`softimpact.models.empirical.PROJECTILES` and ``PRESETS``,
:data:`softimpact.models.projectiles.PROJECTILES`, :data:`softimpact.models.contact_laws.CONTACT_LAWS`) and
the built-in cases (:func:`softimpact.cases.builtin_listing`) into frozen :class:`Table` s: the same rows
feed ``softimpact catalogue``, ``si.catalogue()`` and the docs page (docs/_ext/catalogue_page.py). Values are
SI, each column with its unit; every row ends with its source.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Table", "Catalogue", "catalogue", "markdown", "text"]


@dataclass(frozen=True)
class Table:
    """One catalogue table: its ``name`` (``materials``…), ``title``, ``columns`` and their ``units`` ("" for a
    text column; values SI), and ``rows`` (one tuple per entry, its name first and its source last)."""

    name: str
    title: str
    columns: tuple[str, ...]
    units: tuple[str, ...]
    rows: tuple[tuple, ...]

    @property
    def names(self) -> tuple[str, ...]:
        """The entries' names (the first column)."""
        return tuple(r[0] for r in self.rows)

    def to_frame(self):
        """A pandas DataFrame, one row per entry, columns headed "name [unit]" (needs pandas: the ``table`` extra)."""
        import pandas as pd

        return pd.DataFrame(list(self.rows), columns=[_head(c, u) for c, u in zip(self.columns, self.units, strict=True)])


@dataclass(frozen=True)
class Catalogue:
    """Every catalogue table (:class:`Table`), one attribute each."""

    materials: Table
    metals: Table
    plies: Table
    projectiles: Table
    projectile_materials: Table
    scaling_constants: Table
    contact_laws: Table
    cases: Table

    @property
    def tables(self) -> tuple[Table, ...]:
        """The tables in the order they are shown."""
        return (self.materials, self.metals, self.plies, self.projectiles, self.projectile_materials, self.scaling_constants, self.contact_laws, self.cases)

    def to_frame(self, table: str):
        """The DataFrame of the table named ``table`` (``"materials"``, ``"plies"``…; needs pandas); an InputError naming
        a name that is not a table's, with the nearest one."""
        import difflib

        names = [t.name for t in self.tables]
        if table not in names:
            from ..errors import InputError

            near = difflib.get_close_matches(str(table), names, n=1, cutoff=0.6)
            raise InputError(f"table: {table!r} is not a table of the catalogue ({f'did you mean {near[0]!r}? ' if near else ''}known: {', '.join(names)})")
        return getattr(self, table).to_frame()


def _head(column: str, unit: str) -> str:
    return f"{column} [{unit}]" if unit else column


_LAW_UNITS = "F [N], alpha [m], rate [m/s]"  # every contact law maps the approach and its rate to a force


def _first_line(doc: str | None) -> str:
    lines = (doc or "").strip().splitlines()
    return lines[0].strip() if lines else ""


def _metals() -> Table:
    """The metals' table (:data:`softimpact.models.metals.METALS`)."""
    from ..models.metals import METALS

    return Table(
        "metals",
        "Metals (elastic-plastic skins: plate.material; J2 plasticity with the hardening named)",
        ("name", "E", "nu", "density", "yield stress", "ultimate strength", "elongation", "hardening", "strain rate", "source"),
        ("", "Pa", "-", "kg/m^3", "Pa", "Pa", "-", "", "", ""),
        tuple(
            (m.name, m.youngs_modulus, m.poisson_ratio, m.density, m.yield_stress, m.ultimate, m.elongation, m.hardening_source, m.rate_source, m.source)
            for m in METALS.values()
        ),
    )


def catalogue() -> Catalogue:
    """The catalogue read from the models' own tables (nothing copied: a new entry there shows here)."""
    from ..cases import builtin_listing
    from ..input.toml import builtin_cases
    from ..models.contact_laws import CONTACT_LAWS
    from ..models.empirical import PRESETS, PROJECTILES
    from ..models.laminate import PLIES
    from ..models.materials import CATALOGUE
    from ..models.projectiles import PROJECTILES as PROJECTILE_MATERIALS

    materials = Table(
        "materials",
        "Materials (isotropic, linear elastic)",
        ("name", "E", "nu", "density", "bar wave speed", "source"),
        ("", "Pa", "-", "kg/m^3", "m/s", ""),
        tuple((m.name, m.youngs_modulus, m.poisson_ratio, m.density, m.wave_speed, m.source) for m in CATALOGUE.values()),
    )
    metals = _metals()
    plies = Table(
        "plies",
        "Plies (laminate materials, in their material axes)",
        ("name", "E1", "E2", "G12", "nu12", "nu23", "density", "thickness", "strengths", "source"),
        ("", "Pa", "Pa", "Pa", "-", "-", "kg/m^3", "m", "", ""),
        tuple((p.name, p.E1, p.E2, p.G12, p.nu12, p.nu23, p.density, p.thickness, "yes" if p.strength is not None else "no", p.source) for p in PLIES.values()),
    )
    projectiles = Table(
        "projectiles",
        "Projectiles (the paper's named balls, --projectile)",
        ("name", "diameter", "mass", "material", "scaling constants", "source"),
        ("", "m", "kg", "", "", ""),
        tuple((p.name, p.diameter, p.mass, p.material, p.law, p.source) for p in PROJECTILES.values()),
    )
    projectile_materials = Table(
        "projectile_materials",
        "Projectile materials (hail, bird substitute: crushing strength or Hugoniot)",
        ("name", "density", "strength A", "strength exponent m", "reference rate", "Hugoniot c0", "Hugoniot k", "source"),
        ("", "kg/m^3", "Pa", "-", "1/s", "m/s", "-", ""),
        tuple(
            (
                key,
                p.density,
                *((p.strength.coefficient, p.strength.exponent, p.strength.reference_rate) if p.strength is not None else (None, None, None)),
                p.hugoniot.c0 if p.hugoniot is not None else None,
                p.hugoniot.k if p.hugoniot is not None else None,
                p.source,
            )
            for key, p in PROJECTILE_MATERIALS.items()
        ),
    )
    scaling_constants = Table(
        "scaling_constants",
        "Scaling constants (eqs 4-7, --constants)",
        ("name", "alpha1", "alpha2", "alpha3", "alpha4", "velocity from", "velocity to", "source"),
        ("", "-", "-", "-", "-", "m/s", "m/s", ""),
        tuple((key, s.alpha1, s.alpha2, s.alpha3, s.alpha4, *s.velocity_range, s.source) for key, s in PRESETS.items()),
    )
    contact_laws = Table(
        "contact_laws",
        "Contact laws (force F [N] of the approach alpha [m] and its rate [m/s])",
        ("name", "description", "units", "source"),
        ("", "", "", ""),
        tuple((key, _first_line(law.__doc__), _LAW_UNITS, law.source) for key, law in CONTACT_LAWS.items()),
    )
    paths = builtin_cases()
    cases = Table(
        "cases",
        "Built-in cases and series (a unit string beside every quantity of the file)",
        ("name", "kind", "title", "source"),
        ("", "", "", ""),
        tuple((name, kind, title, f"softimpact/data/{paths[name].parent.name}/{paths[name].name}") for name, kind, title in builtin_listing()),
    )
    return Catalogue(materials, metals, plies, projectiles, projectile_materials, scaling_constants, contact_laws, cases)


def _cell(value) -> str:
    if value is None:
        return "-"
    if isinstance(value, float):
        return f"{value:.4g}"
    return str(value)


def text(cat: Catalogue | None = None) -> str:
    """The catalogue as plain text (``softimpact catalogue``): a block per table, one line per entry, each
    value with its unit, the source on the entry's last line."""
    cat = cat or catalogue()
    out = []
    for t in cat.tables:
        out.append(f"{t.title}:")
        for row in t.rows:
            cells = [f"{c} {_cell(v)}{(' ' + u) if u and v is not None else ''}" for c, u, v in zip(t.columns[1:-1], t.units[1:-1], row[1:-1], strict=True)]
            out.append(f"  {row[0]}: " + ", ".join(cells))
            out.append(f"      source: {row[-1]}")
        out.append("")
    return "\n".join(out)


def _md(cell: str) -> str:
    """A table cell's text with the characters Markdown would read as markup escaped."""
    for ch in ("\\", "|", "*", "_", "`", "<", "[", "]"):
        cell = cell.replace(ch, "\\" + ch)
    return cell


def markdown(cat: Catalogue | None = None) -> str:
    """The catalogue as a MyST page (the docs page): a section and a table per catalogue table."""
    cat = cat or catalogue()
    out = [
        "# Catalogue",
        "",
        "Every named material, ply, projectile, set of scaling constants, contact law and built-in case, with its",
        "values in SI and its source. The same tables: `softimpact catalogue` on the command line,",
        "`si.catalogue()` in Python. Written from the code's own tables at each docs build.",
        "",
    ]
    for t in cat.tables:
        out += [f"## {t.title}", ""]
        out.append("| " + " | ".join(_head(c, u) for c, u in zip(t.columns, t.units, strict=True)) + " |")
        out.append("|" + "---|" * len(t.columns))
        for row in t.rows:
            out.append("| " + " | ".join(_md(_cell(v)) if i else f"`{v}`" for i, v in enumerate(row)) + " |")
        out.append("")
    return "\n".join(out)
