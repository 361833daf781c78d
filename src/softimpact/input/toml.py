"""Case files in TOML: the reader shared by every file format.

:class:`Table` reads a TOML table key by key, parsing quantities with units
once (:mod:`softimpact.units`), and rejects keys nobody asked for. Errors name
the file key and the value the user wrote. :func:`naming` turns the core's
errors, which name a Python argument (``InputError.argument``), into errors
that name the key of the file. Built-in cases (``softimpact cases``) are
addressed by name as well as by path.
"""

from __future__ import annotations

import difflib
import math
import tomllib
from collections.abc import Iterator
from contextlib import contextmanager
from importlib import resources
from pathlib import Path

from .. import units
from ..errors import InputError
from ..fem.newmark import NewmarkParameters, SolverSpec
from ..models.materials import Material, lookup

__all__ = [
    "Table",
    "naming",
    "PHYSICAL_RANGES",
    "check_physical",
    "builtin_cases",
    "locate",
    "load_toml",
    "read_material",
    "read_solver",
    "read_units",
    "case_units",
]

_MISSING = object()

# The physical range of a quantity of each kind in a case or an API call, SI: (least positive value, largest magnitude,
# why). Past it no structure, projectile or material of this toolkit's problems exists, and the answer's arithmetic
# means nothing (a strength of 1e300 Pa gives forces of 1e300 N; a sphere of 1e300 m overflows its volume): such a
# value is a slip (a unit, an exponent), refused naming the key. The least value binds only where a key must be
# positive (a size, a step), never a position or an offset.
PHYSICAL_RANGES = {
    "length": (1e-9, 1e4, "a nanometre (below it no continuum) to 10 km"),
    "mass": (1e-12, 1e7, "a nanogram to 10 000 t"),
    "time": (1e-12, 1e5, "a picosecond to a day"),
    "velocity": (0.0, 1e4, "10 km/s, past any bird, hail or debris impact (hypervelocity impact is other physics)"),
    "stress": (0.0, 1e13, "ten times diamond's modulus"),
    "density": (1.0, 1e5, "from below any foam to four times osmium's"),
    "force": (0.0, 1e10, "10 GN"),
    "impulse": (0.0, 1e8, "1e8 N s"),
    "energy": (0.0, 1e10, "10 GJ"),
    "moment": (0.0, 1e10, "10 GN m"),
    "toughness": (0.0, 1e7, "a hundred times a tough metal's fracture energy"),
    "interface_stiffness": (0.0, 1e21, "1e21 N/m^3, a million times a stiff adhesive layer's E/t"),
    "frequency": (0.0, 1e12, "a terahertz"),
    "voltage": (0.0, 1e6, "a megavolt"),
}


def check_physical(si: float, kind: str, key: str, given, positive: bool = True) -> float:
    """``si`` (the SI value of ``given``, a quantity of ``kind``) within :data:`PHYSICAL_RANGES`: its magnitude at most
    the kind's largest and, when ``positive``, at least its least positive value; else an InputError naming ``key``
    and echoing ``given`` as written (its unit with it). Returns ``si``."""
    lo, hi, why = PHYSICAL_RANGES.get(kind, (0.0, float("inf"), ""))
    if abs(si) > hi or (positive and 0.0 < si < lo):
        bound = f"at most {hi:g} {units.SI_UNITS[kind]}" if abs(si) > hi else f"at least {lo:g} {units.SI_UNITS[kind]}"
        raise InputError(f"{key}: {given!r} is outside the physical range of {units.a_or_an(kind)} ({bound}: {why})")
    return si


@contextmanager
def naming(keys: dict[str, str]) -> Iterator[None]:
    """Re-raise a core :class:`InputError` whose ``argument`` is in ``keys`` as one naming the file key."""
    try:
        yield
    except InputError as exc:
        key = keys.get(exc.argument)
        if key is None:
            raise
        raise InputError(f"{key}: {exc}") from None


class Table:
    """A TOML table read key by key; :meth:`done` rejects keys nobody asked for."""

    def __init__(self, data: dict, path: str = ""):
        if not isinstance(data, dict):
            raise InputError(f"{path or 'case'}: expected a table, got {data!r}")
        self.data, self.path, self._used, self._read_with = data, path, set(), {}

    def key(self, name: str) -> str:
        return f"{self.path}.{name}" if self.path else name

    def read_with(self, keys: dict[str, str]) -> None:
        """Keys this table reads only with another choice (key → that choice, e.g. ``law = "identified"``): given
        beside a choice that does not read them, :meth:`done` names the choice that does."""
        self._read_with.update(keys)

    def __contains__(self, name: str) -> bool:
        return name in self.data

    def raw(self, name: str, default=_MISSING):
        self._used.add(name)
        if name not in self.data:
            if default is _MISSING:
                raise InputError(f"{self.key(name)}: missing (required){self._misspelt(name)}")
            return default
        return self.data[name]

    def _misspelt(self, name: str) -> str:
        """A hint naming a key of the table nobody has asked for that looks like ``name`` (a misspelling: the
        error would otherwise be "missing" for the key and, later, "unknown" for the other)."""
        near = difflib.get_close_matches(name, [k for k in self.data if k not in self._used], n=1, cutoff=0.75)
        return f"; the table has {near[0]!r}: is it a misspelling of {name!r}?" if near else ""

    def quantity(self, name: str, kind: str, default=_MISSING, positive: bool = True) -> float:
        value = self.raw(name, default)
        if value is default and default is not _MISSING:
            return value
        q = units.parse(value, kind, self.key(name))
        if positive and not q > 0:
            raise InputError(f"{self.key(name)}: must be positive, got {value!r}")
        return check_physical(q, kind, self.key(name), value, positive)

    def number(self, name: str, default=_MISSING, lo: float = -math.inf, hi: float = math.inf, why: str = "") -> float:
        """A plain number, finite and within [``lo``, ``hi``] (``why``: the reason for the bounds, in the error)."""
        value = self.raw(name, default)
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise InputError(f"{self.key(name)}: expected a number, got {value!r}")
        if not math.isfinite(value):
            raise InputError(f"{self.key(name)}: expected a finite number, got {value!r}")
        if not lo <= value <= hi:
            raise InputError(f"{self.key(name)}: {value!r} is outside {lo:g} to {hi:g}{f' ({why})' if why else ''}")
        return float(value)

    def integer(self, name: str, default=_MISSING, minimum: int = 1) -> int:
        value = self.raw(name, default)
        if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
            raise InputError(f"{self.key(name)}: expected an integer >= {minimum}, got {value!r}")
        return value

    def string(self, name: str, default=_MISSING, choices=None) -> str:
        value = self.raw(name, default)
        if not isinstance(value, str):
            raise InputError(f"{self.key(name)}: expected text, got {value!r}")
        if choices is not None and value not in choices:
            raise InputError(f"{self.key(name)}: {value!r} is not one of {', '.join(map(str, choices))}")
        return value

    def table(self, name: str, optional: bool = False) -> Table | None:
        value = self.raw(name, None if optional else _MISSING)
        return None if value is None else Table(value, self.key(name))

    def tables(self, name: str, optional: bool = False) -> list[Table]:
        value = self.raw(name, [] if optional else _MISSING)
        if not isinstance(value, list):
            raise InputError(f"{self.key(name)}: expected an array of tables ([[{name}]]), got {value!r}")
        return [Table(v, f"{self.key(name)}[{i}]") for i, v in enumerate(value)]

    def done(self) -> None:
        unknown = sorted(set(self.data) - self._used)
        if unknown:
            name = unknown[0]
            if name in self._read_with:
                raise InputError(f"{self.key(name)}: not read here (value {self.data[name]!r}); it is read only with {self._read_with[name]}")
            # an optional key asked for and not given that looks like it (its default was taken: a misspelling)
            near = difflib.get_close_matches(name, [k for k in self._used if k not in self.data], n=1, cutoff=0.75)
            # or a key the table read that is also given (a sweep's misspelt key set beside the case's own)
            near = near or difflib.get_close_matches(name, sorted(self._used - {name}), n=1, cutoff=0.75)
            hint = f"; is it a misspelling of {near[0]!r}?" if near else ""
            raise InputError(f"{self.key(name)}: unknown key (value {self.data[name]!r}){hint}")


def builtin_cases() -> dict[str, Path]:
    """Built-in case and series files by name (file stem)."""
    found = {}
    root = resources.files("softimpact") / "data"
    for folder in ("cases", "series"):
        d = root / folder
        if d.is_dir():
            for entry in d.iterdir():
                if entry.name.endswith(".toml"):
                    found[entry.name[: -len(".toml")]] = Path(str(entry))
    return dict(sorted(found.items()))


def locate(case: str) -> Path:
    """A case argument as a path: an existing file, or a built-in name."""
    path = Path(case)
    if path.is_file():
        return path
    known = builtin_cases()
    if case in known:
        return known[case]
    raise InputError(f"CASE: {case!r} is neither a file nor a built-in case (built-ins: {', '.join(known)})")


# The top table that marks each kind of case file (a bar case may also be known by its [projectile]).
_CASE_TABLES = {"bar": ("bar", "projectile"), "beam": ("beam",), "plate": ("plate",), "impact": ("target",)}


def load_case_toml(path: Path, kind: str) -> dict:
    """:func:`load_toml` of a case expected to be of ``kind`` (bar, beam, plate, impact); a case of
    another kind is refused naming both ("x.toml is a bar case: a beam case is expected here")."""
    data = load_toml(path)
    if not any(t in data for t in _CASE_TABLES[kind]):
        other = next((k for k, tables in _CASE_TABLES.items() if k != kind and any(t in data for t in tables)), None)
        if other is not None:
            art = "an" if other == "impact" else "a"
            raise InputError(
                f"{path.name} is {art} {other} case: {'an' if kind == 'impact' else 'a'} {kind} case (one with a [{_CASE_TABLES[kind][0]}] table) is expected here"
            )
    return data


def load_toml(path: Path) -> dict:
    try:
        with open(path, "rb") as fh:
            return tomllib.load(fh)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{path}: not valid TOML ({exc})") from None
    except UnicodeDecodeError as exc:  # TOML is UTF-8: a binary or Latin-1 file
        raise InputError(f"{path}: not valid TOML (not UTF-8 text: byte {exc.object[exc.start]:#04x} at offset {exc.start})") from None
    except OSError as exc:
        raise InputError(f"{path}: cannot read ({exc.strerror})") from None


def read_material(tbl: Table, name: str = "material") -> Material:
    """A catalogue name, or an inline table of E, ν, ρ."""
    value = tbl.raw(name)
    if isinstance(value, str):
        return lookup(value, tbl.key(name))
    inline = Table(value, tbl.key(name))
    mat = Material(
        inline.string("name", "inline material"),
        inline.quantity("youngs_modulus", "stress"),
        inline.number("poisson_ratio"),
        inline.quantity("density", "density"),
        inline.string("source", "user input"),
    )
    inline.done()
    return mat


def read_solver(tbl: Table) -> SolverSpec:
    """The ``[solver]`` table: time step, duration, Newmark β and γ."""
    keys = {"time_step": tbl.key("time_step"), "duration": tbl.key("duration"), None: tbl.path}
    with naming(keys):
        spec = SolverSpec(
            tbl.quantity("time_step", "time"),
            tbl.quantity("duration", "time"),
            NewmarkParameters(tbl.number("beta", 0.25), tbl.number("gamma", 0.5)),
        )
    tbl.done()
    return spec


def read_units(top: Table) -> str:
    """The display system of a case (``units = "in-lbf-s" | "SI"``)."""
    return top.string("units", "in-lbf-s", choices=tuple(units.DISPLAY_SYSTEMS))


def case_units(case) -> str:
    """The display system of a case file or built-in name (its ``units``, :func:`read_units`): a choice of the
    edges (app, api) for tables and figures; the problem read from the case holds SI numbers only."""
    return read_units(Table(load_toml(locate(str(case)))))
