"""The options of the commands, written once: each one's name, type or unit kind, default and help.

Two edges read these tables: the command line (:mod:`softimpact.cli` builds its click options from
them: ``--name``, ``--name/--no-name`` for a bool, a choice list, the default shown) and the Python API
(:mod:`softimpact.api.chain` builds its keyword arguments, their checks and the Parameters section of
its docstrings from them). An option's ``name`` is the keyword everywhere: of the app function, of
the API function and of click's parameter (``--units`` → ``units``). The app functions that take a
table's options take them keyword-only and all required (:func:`softimpact.app.predict.predict`):
the defaults live here alone. No click here (only cli.py imports click).
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = [
    "Option",
    "FIGURES",
    "UNITS",
    "CASE",
    "SERIES",
    "IDENTIFY",
    "PREDICT",
    "CALIBRATE",
    "CONVERGE",
    "SWEEP",
    "DISPLAY_SYSTEMS",
    "defaults",
    "display_system",
    "HELP_TABLES",
    "filled",
]


@dataclass(frozen=True)
class Option:
    """One option of a command.

    Parameters
    ----------
    name : str
        The keyword (Python identifier); the command line's flag is ``--name`` with ``_`` as ``-``.
    help : str
        One or two sentences, in words both edges can show (no flag names); units as examples.
    default : object
        The default (None: not given).
    kind : str, optional
        A unit kind of :data:`softimpact.units.SI_UNITS` (``"velocity"``): a quantity given with its
        unit, ``"1166 in/s"``; the API also takes a pint quantity.
    type : type
        ``str`` (default), ``bool``, ``int`` or ``float``.
    choices : tuple of str
        The allowed values (empty: any).
    required : bool
        No default: the option must be given.
    file : bool
        A path to an existing file.
    """

    name: str
    help: str
    default: object = None
    kind: str | None = None
    type: type = str
    choices: tuple[str, ...] = ()
    required: bool = False
    file: bool = False

    @property
    def flag(self) -> str:
        """The command line's flag, ``--contact-radius``."""
        return "--" + self.name.replace("_", "-")


def _names(module: str, table: str) -> str:
    """The names of the table ``table`` of ``softimpact.<module>``, comma-separated (imported when asked)."""
    import importlib

    return ", ".join(getattr(importlib.import_module(f"softimpact.{module}"), table))


# The tables a help text lists the choices of, by the placeholder it writes (``{contact_laws}``): filled from the table
# itself when the help is shown (:func:`filled`), so a new row (a contact law, a projectile) appears in --help with it.
HELP_TABLES = {
    "contact_laws": lambda: _names("models.contact_laws", "CONTACT_LAWS"),
    "projectiles": lambda: _names("models.empirical", "PROJECTILES"),
    "scaling_presets": lambda: _names("models.empirical", "PRESETS"),
    "materials": lambda: _names("models.materials", "CATALOGUE"),
}


def filled(text: str | None) -> str | None:
    """``text`` with each placeholder of :data:`HELP_TABLES` (``{contact_laws}``) replaced by its table's names; any
    other brace (a TOML inline table of an example) left as written."""
    import re

    if not text or "{" not in text:
        return text
    return re.sub(r"\{(\w+)\}", lambda m: HELP_TABLES[m.group(1)]() if m.group(1) in HELP_TABLES else m.group(0), text)


def defaults(table: tuple[Option, ...]) -> dict:
    """The default of every option of ``table`` that has one, by name."""
    return {o.name: o.default for o in table if not o.required}


DISPLAY_SYSTEMS = ("in-lbf-s", "SI")  # the display systems of :func:`softimpact.units.display`

FIGURES = Option("figures", "Draw the figures (the numbers are written either way).", True, type=bool)

# None: the case's (or series') own ``units`` key, else in-lbf-s (the paper's system); the files stay SI either way
UNITS = Option(
    "units",
    f"Display units of the printed lines, tables and figures: {' or '.join(DISPLAY_SYSTEMS)} (default: the case's or series' own units key, "
    "else in-lbf-s). The files (summary.json, CSV) stay SI.",
    choices=DISPLAY_SYSTEMS,
)


def display_system(units: str | None, own: str | None = None) -> str:
    """The display system a command shows: ``units`` when given (the :data:`UNITS` option), else the case's or
    series' own ``own``, else in-lbf-s (the paper's system)."""
    return units or own or DISPLAY_SYSTEMS[0]


CASE = (UNITS, FIGURES)  # bar, beam, plate and impact: a case (file or built-in name), its display units and the figures

SERIES = (UNITS, FIGURES)  # reduce and fit: a series (file or built-in name), its display units and the figures

IDENTIFY = (
    Option(
        "law",
        "The law family to identify: the visco-elastic soft law (rubber, gel) or the crushing law of ice spheres "
        "(its strength at a reference rate and the rate exponent).",
        "soft",
        choices=("soft", "crushing"),
    ),
    UNITS,
    FIGURES,
)

PREDICT = (
    Option("projectile", "A named projectile ({projectiles}), or give the mass and the diameter."),
    Option("mass", 'Projectile mass, e.g. "1.1 g".', kind="mass"),
    Option("diameter", 'Projectile diameter, e.g. "0.5 in".', kind="length"),
    Option("velocity", 'Impact velocity, e.g. "1166 in/s".', kind="velocity", required=True),
    Option(
        "model",
        "Empirical (eqs 4-7, 15), elastic Hertz (eqs 1-3), steady-flow Wilbeck, or the crushing (ice) or hydrodynamic (gelatin) "
        "law of the projectile's material on a rigid target.",
        "empirical",
        choices=("empirical", "hertz", "wilbeck", "crushing", "hydrodynamic"),
    ),
    Option(
        "constants",
        "Scaling constants: a projectile's ({projectiles}: Table I) or a scaling.json from `softimpact fit` "
        "(the old names {scaling_presets} are deprecated aliases, still accepted).",
    ),
    Option("group", "Group of a scaling.json to use (a diameter such as '0.5 in', or pooled).", "pooled"),
    Option("tail", "Empirical model: add the tail that carries the rest of eq (7)'s impulse.", False, type=bool),
    Option("material", "Projectile material, one of {materials} (hertz and wilbeck models; ice for crushing, gelatin for hydrodynamic).", "silicone rubber"),
    Option("target", "Target material (hertz model), one of {materials}.", "Al 6061-T6"),
    Option("bar", "Drive the bar of this bar case (file or built-in name) with the predicted force."),
    Option("beam", "Drive this beam case (file or built-in name) with the predicted force."),
    UNITS,
    FIGURES,
)

CALIBRATE = (
    Option("measured", "CSV of measured strains: time_s and strain_<gauge> columns.", file=True),
    Option("velocity", 'Impact velocity, e.g. "1166 in/s" (sets the bar-model start).', kind="velocity"),
    Option(
        "method",
        "Least squares on eq (15), the paper's iteration, or non-negative deconvolution.",
        "least-squares",
        choices=("least-squares", "paper", "deconvolve"),
    ),
    Option("contact_radius", 'r0 from the imprint, e.g. "0.25 in" (default: the case\'s).', kind="length"),
    Option("contact_time", 'First contact on the record\'s clock, e.g. "100 us" (default: estimated).', kind="time"),
    Option("fit_radius", "Least squares: fit r0 too.", False, type=bool),
    Option("projectile", "Projectile of the bar-model start, one of {projectiles}.", "rubber-1/2in"),
    Option(
        "constants",
        "Scaling constants of the start: a projectile's ({projectiles}) or a scaling.json (default: the projectile's; "
        "the old names {scaling_presets} are deprecated aliases, still accepted).",
    ),
    Option(
        "budget",
        "Seconds that refining the model may cost: the mesh is refined until its discretisation error moves no "
        "parameter by more than half a noise standard error, or this budget is spent.",
        20.0,
        type=float,
    ),
    UNITS,
    FIGURES,
)

CONVERGE = (
    Option("levels", "Number of discretisations: the case's own, then refined by the ratio each (2 to 5).", 3, type=int),
    Option("ratio", "Refinement ratio between levels (elements × ratio, time step / ratio).", 2, type=int),
    Option("history", "Beam cases: row N of the case's [[load.table]].", type=int),
    UNITS,
    FIGURES,
)

SWEEP = (
    Option(
        "workers",
        "Local Dask worker processes (default: the machine's cores, since a sweep is many independent runs and "
        "running them side by side is what it is for; 0: a plain loop in this process, no Dask).",
        type=int,
    ),
    Option("scheduler", "Address of a running Dask scheduler (tcp://host:8786) to run on instead."),
    UNITS,
    FIGURES,
)

CALIBRATE_BAR = (UNITS, FIGURES)  # calibrate-bar: a calibration file (file or built-in name), its display units and the figures

SHPB = (UNITS, FIGURES)  # shpb: a two-bar series (file or built-in name), its display units and the figures

__all__ += ["CALIBRATE_BAR", "SHPB"]
