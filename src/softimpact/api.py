"""The notebook edge of softimpact: objects in, frozen results out (``import softimpact as si``).

Quantities are given as unit strings (``"6 in"``, ``"0.5 us"``, ``"100 in/s"``) or
pint quantities, and converted to SI floats ONCE, here, by :func:`softimpact.units.parse`
(the same conversion a case file's keys go through, so a run from objects and the
same run from a case file agree to the last bit). Everything below this module is SI.
A plain number is refused where a unit is needed: ``6`` could be inches or metres.

Structures: :class:`Beam`, :class:`Plate`, :class:`Bar`, made of a :class:`Laminate`
or a catalogue material; the impactor: :class:`Sphere`. Runs: :func:`impact` (the one
coupled stepper, :func:`softimpact.workflows.coupled.run_impact`), :func:`load` and
:func:`run` for any case file or built-in name (through :data:`softimpact.cases.KINDS`).
The rest of the chain wraps the commands' own functions (:mod:`softimpact.app`):
:func:`reduce`, :func:`fit`, :func:`predict`, :func:`identify`, :func:`calibrate`,
:func:`converge`, :func:`sweep`; and :func:`read_record` reads one channel of a lab record.

Warnings: what the command line shows as ``softimpact: warning:`` lines (a model past its validity
envelope, a law used outside what it was identified on) the API warns as
:class:`~softimpact.errors.SoftimpactWarning` s pointing at the user's call, raised by the same
functions; the result keeps them (``res.warnings``) and ``write`` lists them in manifest.json,
with the files read (a law.json with its SHA-256), as the command line does.

Results are frozen; they carry their inputs in SI (``res.problem``) and offer
``.plot(ax=None)``, ``.write(dir)`` (the command's files and manifest.json, written
atomically as the command line writes them), ``.summary()`` (summary.json's numbers)
and ``.to_frame()`` (a pandas DataFrame; the ``table`` extra).

Why pandas and not xarray for the tabular view: every history here has one dimension,
time, so a DataFrame indexed by time holds it exactly; pandas is what users of lab
data already know, and the CSV files of the contract read back into the same frame.
"""

from __future__ import annotations

import json
import math
import os
import sys
import warnings
from dataclasses import dataclass, field, replace
from pathlib import Path

from .errors import HeldWarnings, InputError, SoftimpactWarning

__all__ = [
    "Laminate",
    "Beam",
    "Plate",
    "Bar",
    "Sphere",
    "impact",
    "load",
    "run",
    "Case",
    "ImpactResult",
    "BeamResult",
    "PlateResult",
    "BarResult",
    "CommandResult",
    "Record",
    "reduce",
    "fit",
    "predict",
    "identify",
    "calibrate",
    "converge",
    "sweep",
    "read_record",
]


# --- quantities at the edge ---------------------------------------------------------------------


def _si(value, kind: str, name: str) -> float:
    """``value`` (a unit string or a pint quantity) as an SI float of ``kind``; InputError naming ``name``."""
    from . import units

    if hasattr(value, "magnitude") and hasattr(value, "to"):  # a pint quantity, of any registry
        try:
            si = float(value.to(units.SI_UNITS[kind]).magnitude)
        except Exception:  # pint's DimensionalityError and friends
            raise InputError(f"{name}: {value!r} is not {units.a_or_an(kind)}") from None
        if not math.isfinite(si):
            raise InputError(f"{name}: {value!r} is not a finite {kind}")
        return si
    return units.parse(value, kind, name)


def _text(value, kind: str, name: str) -> str | None:
    """A quantity as the text an app function parses; None stays None. Checked here (an error names
    ``name``); a unit string passes as given (the app parses it with the same :func:`softimpact.units.parse`,
    to the same float, and its lines and warnings then quote the user's units as the command line's do),
    a pint quantity as its SI value (``"0.0127 m"``)."""
    if value is None:
        return None
    from .units import SI_UNITS

    si = _si(value, kind, name)
    return value if isinstance(value, str) else f"{si!r} {SI_UNITS[kind]}"


def _material(value, name: str):
    from .models.materials import Material, lookup

    if isinstance(value, Material):
        return value
    if not isinstance(value, str):
        raise InputError(f"{name}: expected a catalogue material name or a Material, got {type(value).__name__}")
    return lookup(value, name)


def _point(value, name: str) -> tuple[float, float]:
    if isinstance(value, str) or not hasattr(value, "__len__") or len(value) != 2:
        raise InputError(f"{name}: expected a point (x, y) of two lengths, got {value!r}")
    return (_si(value[0], "length", f"{name}[0]"), _si(value[1], "length", f"{name}[1]"))


def _elements(value, count: int, name: str) -> tuple[int, ...]:
    values = (value,) if isinstance(value, int) and count == 1 else tuple(value) if hasattr(value, "__len__") else ()
    if len(values) != count or not all(isinstance(n, int) and not isinstance(n, bool) and n >= 1 for n in values):
        raise InputError(f"{name}: expected {count} positive integer(s), got {value!r}")
    return values


# --- warnings at the edge --------------------------------------------------------------------------

_PACKAGE = tuple({os.path.dirname(__file__) + os.sep, str(Path(__file__).resolve().parent) + os.sep})  # as imported, and resolved


def _one_line(text) -> str:
    """A warning's text on one line, as the command line shows it and keeps it for manifest.json."""
    return " ".join(str(text).split())


class _Heard(HeldWarnings):
    """Collects the warnings raised below one API call and, on leaving, warns them again at the user's line.

    The command line shows each :class:`~softimpact.errors.SoftimpactWarning` raised below a command
    (:func:`softimpact.models.validity.warn` and friends) as a ``softimpact: warning:`` line and keeps
    it for manifest.json; here each is warned again, a SoftimpactWarning pointing at the first frame
    outside softimpact (the user's call), and its one-line text kept in :attr:`texts` for the result's
    manifest.json. Any other warning passes on unchanged (:class:`~softimpact.errors.HeldWarnings`).
    Used as ``with _Heard() as heard: ...``.
    """

    def __enter__(self):
        self.texts: list[str] = []
        return super().__enter__()

    def __exit__(self, *exc):
        super().__exit__(*exc)
        level, frame = 1, sys._getframe(0)
        while frame is not None and frame.f_code.co_filename.startswith(_PACKAGE):
            level, frame = level + 1, frame.f_back
        for w in self.held:
            self.texts.append(_one_line(w.message))
            warnings.warn(w.message, stacklevel=level)
        return False


def _write(out, files: dict, inputs, manifest: dict, force: bool) -> list[Path]:
    """:func:`softimpact.output.files.write_outputs`, its errors naming ``write`` and ``force=True``
    (the API's terms) where the command line's name ``--out`` and ``--force``."""
    from .output.files import write_outputs

    try:
        return write_outputs(out, files, inputs=inputs, manifest=manifest, force=force)
    except InputError as exc:
        text = str(exc)
        if not text.startswith("--out: "):
            raise
        text = "write: " + text.removeprefix("--out: ")
        raise InputError(text.replace("`softimpact --force ...`", "write(..., force=True)"), exc.argument) from None


# --- inputs ---------------------------------------------------------------------------------------


@dataclass(frozen=True, init=False)
class Laminate:
    """A laminate: a ply of the catalogue and a stacking sequence.

    Parameters
    ----------
    ply : str or softimpact.models.laminate.Ply
        A catalogue ply (``"T300/934"``, :data:`softimpact.models.laminate.PLIES`) or a Ply
        (moduli [Pa], density [kg/m³], ply thickness [m]).
    layup : str
        Stacking sequence in degrees from the x axis, ``"[90/0]5s"``, ``"[0/±45/90]s"``.

    Attributes
    ----------
    stack : softimpact.models.laminate.Stack
        The ply and its angles [°]; ``stack.thickness`` [m].

    Raises
    ------
    softimpact.errors.InputError
        An unknown ply or a layup that cannot be read.

    Examples
    --------
    >>> import softimpact as si
    >>> lam = si.Laminate("T300/934", "[90/0]5s")
    >>> len(lam.stack.angles)
    20
    """

    ply: str
    layup: str
    stack: object = field(repr=False, compare=False)

    def __init__(self, ply, layup: str):
        from .models.laminate import PLIES, Ply, Stack, parse_layup

        if isinstance(ply, str):
            if ply not in PLIES:
                raise InputError(f"ply: unknown ply {ply!r} (catalogue: {', '.join(PLIES)})")
            resolved = PLIES[ply]
        elif isinstance(ply, Ply):
            resolved = ply
        else:
            raise InputError(f"ply: expected a catalogue name or a Ply, got {type(ply).__name__}")
        if not isinstance(layup, str):
            raise InputError(f"layup: expected a text such as '[90/0]5s', got {layup!r}")
        object.__setattr__(self, "ply", resolved.name)
        object.__setattr__(self, "layup", layup)
        object.__setattr__(self, "stack", Stack(resolved, parse_layup(layup)))


@dataclass(frozen=True, init=False)
class Beam:
    """A laminated (or isotropic) beam in plane strain, clamped at x = 0 (paper Figs 16–22).

    Parameters
    ----------
    length : str or pint.Quantity
        Free length [length], e.g. ``"6 in"``; x runs from the support (x = 0).
    width : str or pint.Quantity
        Width [length], e.g. ``"1 in"``.
    laminate : Laminate, optional
        The laminate (give this or ``material`` and ``thickness``).
    material : str or Material, optional
        An isotropic catalogue material (``"Al 6061-T6"``) instead of a laminate.
    thickness : str or pint.Quantity, optional
        Thickness [length] of an isotropic beam (a laminate's is its plies').
    elements : (int, int)
        Q4 elements along the length and through the thickness; default (200, 6).
    support : str
        ``"clamped-free"`` (default) or another of :data:`softimpact.fem.plane.SUPPORTS`.
    model : str
        ``"smeared"`` (homogenised laminate, default) or ``"layered"`` (ply group by ply group).
    plane : str
        ``"strain"`` (default) or ``"stress"`` across the width.
    lumped : bool
        Lumped instead of consistent mass matrix.

    Attributes
    ----------
    spec : softimpact.workflows.beam_impact.BeamSpec
        The beam in SI.

    Raises
    ------
    softimpact.errors.InputError
        A missing unit, a non-positive size, both or neither of laminate and material.

    Examples
    --------
    >>> import softimpact as si
    >>> beam = si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(200, 6))
    >>> round(beam.spec.length / 0.0254, 12)
    6.0
    """

    spec: object

    def __init__(
        self,
        *,
        length,
        width,
        laminate: Laminate | None = None,
        material=None,
        thickness=None,
        elements=(200, 6),
        support: str = "clamped-free",
        model: str = "smeared",
        plane: str = "strain",
        lumped: bool = False,
    ):
        from .fem.plane import SUPPORTS
        from .workflows.beam_impact import BeamSpec

        if (laminate is None) == (material is None):
            raise InputError("Beam: give exactly one of laminate and material")
        if support not in SUPPORTS:
            raise InputError(f"support: {support!r} is not one of {', '.join(SUPPORTS)}")
        nx, nz = _elements(elements, 2, "elements")
        mat = _material(material, "material") if material is not None else None
        if mat is not None and thickness is None:
            raise InputError("thickness: an isotropic beam needs its thickness")
        h = _si(thickness, "length", "thickness") if mat is not None else 0.0
        spec = BeamSpec(
            _si(length, "length", "length"),
            _si(width, "length", "width"),
            nx,
            nz,
            support,
            laminate.stack if laminate is not None else None,
            model,
            mat,
            h,
            plane,
            bool(lumped),
        )
        spec.plane_beam()  # checks sizes now, naming the argument
        object.__setattr__(self, "spec", spec)


@dataclass(frozen=True, init=False)
class Plate:
    """A rectangular laminated plate, first-order shear deformation theory (MITC9 or MITC4 elements).

    Parameters
    ----------
    length : str or pint.Quantity
        Length along x, the 0° fibres [length], e.g. ``"8 in"``.
    width : str or pint.Quantity
        Length along y [length].
    laminate : Laminate
        The laminate.
    elements : (int, int)
        Elements along x and y; default (48, 48).
    support : str or dict
        One support for all four edges, or ``{"x0": ..., "x1": ..., "y0": ..., "y1": ...}``;
        each ``"clamped"``, ``"simply-supported"`` (default), ``"free"`` or ``"symmetry"``.
    element : str
        ``"mitc9"`` (default) or ``"mitc4"``.

    Attributes
    ----------
    spec : softimpact.workflows.plate_impact.PlateSpec
        The plate in SI.

    Raises
    ------
    softimpact.errors.InputError
        A missing unit, an unknown support, a plate left a mechanism.

    Examples
    --------
    >>> import softimpact as si
    >>> plate = si.Plate(length="8 in", width="8 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(8, 8))
    >>> plate.spec.supports
    ('simply-supported', 'simply-supported', 'simply-supported', 'simply-supported')
    """

    spec: object

    def __init__(self, *, length, width, laminate: Laminate, elements=(48, 48), support="simply-supported", element: str = "mitc9"):
        from .input.plate_case import PLATE_SUPPORTS
        from .workflows.plate_impact import PlateSpec

        edges = ("x0", "x1", "y0", "y1")
        if isinstance(support, str):
            supports = (support,) * 4
        elif isinstance(support, dict) and set(support) == set(edges):
            supports = tuple(support[e] for e in edges)
        else:
            raise InputError(f"support: expected one support or a dict of the edges {edges}, got {support!r}")
        for s in supports:
            if s not in PLATE_SUPPORTS:
                raise InputError(f"support: {s!r} is not one of {', '.join(PLATE_SUPPORTS)}")
        if not isinstance(laminate, Laminate):
            raise InputError(f"laminate: expected a si.Laminate, got {type(laminate).__name__}")
        spec = PlateSpec(
            _si(length, "length", "length"), _si(width, "length", "width"), _elements(elements, 2, "elements"), laminate.stack, supports, element=element
        )
        object.__setattr__(self, "spec", spec)


@dataclass(frozen=True, init=False)
class Bar:
    """A uniform circular bar struck on its end (the paper's instrumented bar, Figs 4–6).

    Parameters
    ----------
    material : str or Material
        A catalogue material, e.g. ``"Al 6061-T6"``.
    length : str or pint.Quantity
        Length [length], e.g. ``"36 in"``.
    diameter : str or pint.Quantity
        Diameter [length], e.g. ``"0.5 in"``.
    elements : int
        Hermite rod elements; default 39.
    end_cap : dict, optional
        A cap on the struck end, ``{"material": ..., "diameter": ..., "length": ...}`` [length].

    Attributes
    ----------
    spec : softimpact.models.specimens.BarSpec
        The bar in SI; gauge positions are measured from the struck end.

    Raises
    ------
    softimpact.errors.InputError
        A missing unit or an unknown material.

    Examples
    --------
    >>> import softimpact as si
    >>> bar = si.Bar("Al 6061-T6", length="36 in", diameter="0.5 in")
    >>> bar.spec.elements
    39
    """

    spec: object

    def __init__(self, material, *, length, diameter, elements: int = 39, end_cap: dict | None = None):
        from .models.specimens import BarSpec, EndCap

        cap = None
        if end_cap is not None:
            if not isinstance(end_cap, dict) or set(end_cap) != {"material", "diameter", "length"}:
                raise InputError(f"end_cap: expected {{'material', 'diameter', 'length'}}, got {end_cap!r}")
            cap = EndCap(
                _material(end_cap["material"], "end_cap.material"),
                _si(end_cap["diameter"], "length", "end_cap.diameter"),
                _si(end_cap["length"], "length", "end_cap.length"),
            )
        (n,) = _elements(elements, 1, "elements")
        spec = BarSpec(_material(material, "material"), _si(length, "length", "length"), _si(diameter, "length", "diameter"), n, cap)
        object.__setattr__(self, "spec", spec)


@dataclass(frozen=True, init=False)
class Sphere:
    """A rigid sphere striking the structure.

    Parameters
    ----------
    material : str or Material
        A catalogue material (``"steel"``); its elastic constants enter Hertz's law (eqs 1–3).
    diameter : str or pint.Quantity
        Diameter [length], e.g. ``"0.5 in"``.
    velocity : str or pint.Quantity
        Impact velocity toward the target [velocity], e.g. ``"100 in/s"``.
    mass : str or pint.Quantity, optional
        Mass [mass]; default that of a solid sphere of the material.

    Attributes
    ----------
    material : Material
    diameter : float
        [m]
    velocity : float
        [m/s]
    mass : float
        [kg]

    Raises
    ------
    softimpact.errors.InputError
        A missing unit, a non-positive size, an unknown material.

    Examples
    --------
    >>> import softimpact as si
    >>> ball = si.Sphere("steel", "0.5 in", velocity="100 in/s")
    >>> round(ball.velocity, 12)
    2.54
    """

    material: object
    diameter: float
    velocity: float
    mass: float

    def __init__(self, material, diameter, *, velocity, mass=None):
        from .models.materials import sphere_mass
        from .models.specimens import Impactor

        mat = _material(material, "material")
        d = _si(diameter, "length", "diameter")
        if not d > 0:  # before the mass it gives (the case file's check, naming the argument)
            raise InputError(f"diameter: must be positive, got {diameter!r}")
        v = _si(velocity, "velocity", "velocity")
        m = sphere_mass(mat, d) if mass is None else _si(mass, "mass", "mass")
        Impactor(m, d, v)  # the same checks as every other path
        for k, value in (("material", mat), ("diameter", d), ("velocity", v), ("mass", m)):
            object.__setattr__(self, k, value)

    @property
    def impactor(self):
        """The rigid impactor of the coupled stepper (:class:`softimpact.models.specimens.Impactor`)."""
        from .models.specimens import Impactor

        return Impactor(self.mass, self.diameter, self.velocity)


# --- results ----------------------------------------------------------------------------------------


class _Written:
    """What every result offers on top of its numbers: the command's files, written or parsed."""

    command = "softimpact"
    warnings: tuple[str, ...] = ()  # the SoftimpactWarnings of the run, one line each (as manifest.json lists them)

    def files(self, figures: bool = True) -> dict[str, bytes | str]:  # pragma: no cover - each result has its own
        raise NotImplementedError

    def inputs(self) -> tuple[Path, ...]:
        return ()

    def summary(self) -> dict:
        """The numbers of the command's summary.json (SI, unit-suffixed keys), as the command line writes them."""
        return json.loads(self.files(figures=False)["summary.json"])

    def write(self, out, *, figures: bool = True, force: bool = False) -> list[Path]:
        """Write the command's files into ``out`` with their manifest.json (the command line's contract).

        Parameters
        ----------
        out : str or Path
            Folder (created if needed); files of an earlier softimpact run there that this run
            does not rewrite are removed, anything else is left alone.
        figures : bool
            Draw the PNG figures too.
        force : bool
            Replace files in ``out`` that no softimpact run wrote.

        Returns
        -------
        list of Path
            The files written (manifest.json not included).
        """
        from .gates import status

        manifest = {
            "status": status((), False),
            "accept_poor": False,
            "command": f"{self.command} (Python API)",
            "arguments": {},
            "warnings": list(self.warnings),
            "gates": [],
        }
        return _write(out, self.files(figures), self.inputs(), manifest, force)


def _frame(columns: dict, units_of: dict):
    """A DataFrame of ``columns`` (``time_s`` first) indexed by time, with ``df.attrs["units"]``.

    pandas, not xarray: every history has one dimension (time), which a DataFrame index holds
    exactly, and pandas is what users of lab data know (the ``table`` extra)."""
    try:
        import pandas as pd
    except ImportError:  # pragma: no cover - depends on the environment
        raise ImportError("to_frame needs pandas: pip install 'softimpact[table]'") from None
    cols = dict(columns)
    time = cols.pop("time_s")
    df = pd.DataFrame(cols, index=pd.Index(time, name="time_s"))
    df.attrs["units"] = {"time_s": "s", **{k: units_of.get(k, "") for k in cols}}
    return df


def _unit_of(column: str) -> str:
    """The SI unit a contract column name ends in (``contact_force_N`` → ``N``)."""
    for suffix, unit in (("_m_s", "m/s"), ("_N_s", "N*s"), ("_N", "N"), ("_J", "J"), ("_m", "m"), ("_s", "s")):
        if column.endswith(suffix):
            return unit
    return "1"  # strains and other ratios


def _axes(ax):
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots()
    return ax


@dataclass(frozen=True)
class ImpactResult(_Written):
    """A coupled impact on a beam or plate (:func:`impact`, or :func:`run` of an impact case).

    Parameters
    ----------
    problem : softimpact.workflows.coupled.ImpactProblem
        Every input in SI (target, impactor, law, solver, gauges).
    result : softimpact.fem.impact.CoupledResult
        The histories and first-contact scalars (SI, compression +).
    model : StructureModel, optional
        The assembled model that ran (reused by ``write_fields``).
    case_files : tuple of Path
        The case files read (never overwritten by ``write``).
    warnings : tuple of str
        The run's :class:`~softimpact.errors.SoftimpactWarning` s, one line each (already warned at
        the call; listed in manifest.json by ``write``, as the command line lists them).

    Attributes
    ----------
    peak_force : float
        [N] of the first contact; ``time_of_peak`` [s], ``contact_duration`` [s] (nan when
        not separated), ``impulse`` [N·s].
    time, force : numpy.ndarray
        (n_steps + 1,) [s], [N].
    strain : dict of str to numpy.ndarray
        Gauge strain histories (n_steps + 1,), tension +.
    """

    problem: object
    result: object
    model: object = field(repr=False, compare=False, default=None)
    case_files: tuple = field(repr=False, default=())
    warnings: tuple = field(repr=False, compare=False, default=())
    command = "softimpact impact"

    peak_force = property(lambda self: self.result.peak_force, doc="Peak force of the first contact [N].")
    time_of_peak = property(lambda self: self.result.time_of_peak, doc="Time of the peak force [s] from first contact.")
    contact_duration = property(lambda self: self.result.contact_duration, doc="Duration of the first contact [s] (nan: not separated).")
    impulse = property(lambda self: self.result.impulse, doc="Impulse of the first contact [N·s].")
    time = property(lambda self: self.result.time, doc="Time [s], (n_steps + 1,).")
    force = property(lambda self: self.result.force, doc="Contact force [N], compression +, (n_steps + 1,).")

    @property
    def strain(self) -> dict:
        """Gauge strain histories by gauge name, each (n_steps + 1,), tension +."""
        from .studies.damage import split_damage

        _, result, _ = split_damage(self.problem, self.result)  # the damage indices' pseudo-gauges are not gauges
        return dict(zip(result.strain_names, result.strain))

    def inputs(self):
        return tuple(self.case_files)

    def files(self, figures: bool = True):
        """The files of ``softimpact impact`` (history.csv, summary.json, figures), by name."""
        from .output.impact import impact_files

        return impact_files(self.problem, self.result, figures, model=self.model)

    def to_frame(self):
        """The histories of history.csv as a pandas DataFrame indexed by time [s]; units in ``df.attrs["units"]``.

        pandas rather than xarray: one dimension (time), and users know it (the ``table`` extra)."""
        from .output.impact import impact_columns
        from .studies.damage import split_damage

        cols = impact_columns(split_damage(self.problem, self.result)[1])
        return _frame(cols, {k: _unit_of(k) for k in cols})

    def plot(self, ax=None):
        """The contact force against time, in the problem's display units; returns the matplotlib Axes."""
        from .units import display

        ax = _axes(ax)
        fu, tu = display(self.problem.units, "force"), display(self.problem.units, "time")
        ax.plot(self.time * tu.factor, self.force * fu.factor)
        ax.set_xlabel(f"time [{tu.label}]")
        ax.set_ylabel(f"contact force [{fu.label}]")
        return ax

    def write_fields(self, path, *, frames: int = 200):
        """Displacement fields of the target over time as XDMF for ParaView (:func:`softimpact.output.fields.write_fields`).

        Parameters
        ----------
        path : str or Path
            The .xdmf file; its heavy data go beside it with the suffix .h5.
        frames : int
            At most this many time steps, evenly sampled (every k-th step).

        Returns
        -------
        numpy.ndarray
            The step indices written.
        """
        from .output.fields import write_fields

        return write_fields(path, self.model, self._snapshots(frames))

    def _snapshots(self, frames: int):
        from .output.fields import keeps, kept_frames, sampled_steps
        from .workflows.coupled import run_impact

        steps = sampled_steps(self.problem.solver.steps, frames)
        r = self.result
        if not keeps(r, steps):
            _, r = run_impact(self.problem, self.model, energy=False, snapshots=steps)
        return kept_frames(r, steps)


@dataclass(frozen=True)
class _Prescribed(_Written):
    """What a beam and a plate result share: a structure under a prescribed force history."""

    problem: object
    result: object
    model: object = field(repr=False, compare=False, default=None)
    case_files: tuple = field(repr=False, default=())
    warnings: tuple = field(repr=False, compare=False, default=())

    time = property(lambda self: self.result.time, doc="Time [s], (n_steps + 1,).")
    force = property(lambda self: self.result.force, doc="Applied force [N], (n_steps + 1,).")

    @property
    def strain(self) -> dict:
        """Gauge strain histories by gauge name, each (n_steps + 1,), tension +."""
        return {g.name: eps for g, eps in zip(self.problem.gauges, self.result.strain)}

    def inputs(self):
        return tuple(self.case_files)


@dataclass(frozen=True)
class BeamResult(_Prescribed):
    """A beam under a prescribed force history (:func:`run` of a beam case; ``softimpact beam``).

    Parameters
    ----------
    problem : softimpact.workflows.beam_impact.BeamProblem
        Every input in SI.
    result : softimpact.workflows.beam_impact.BeamResult
        time [s], force [N], strain (n_gauges, n_steps + 1), deflection [m], displacement.
    model : StructureModel, optional
        The assembled model that ran (reused by ``write_fields``).
    case_files : tuple of Path
        The case files read (never overwritten by ``write``).
    warnings : tuple of str
        The run's :class:`~softimpact.errors.SoftimpactWarning` s, one line each (already warned at
        the call; listed in manifest.json by ``write``, as the command line lists them).
    """

    command = "softimpact beam"

    def files(self, figures: bool = True):
        """The files of ``softimpact beam``, by name."""
        from .output.beam import beam_files

        return beam_files(self.model, self.result, figures)

    def to_frame(self):
        """Force and gauge strains as a pandas DataFrame indexed by time [s]; units in ``df.attrs["units"]``."""
        cols = {"time_s": self.time, "force_N": self.force, **{f"strain_{k}": v for k, v in self.strain.items()}}
        return _frame(cols, {k: _unit_of(k) for k in cols})

    def plot(self, ax=None):
        """The gauge strains against time [µs, µε]; returns the matplotlib Axes."""
        ax = _axes(ax)
        for name, eps in self.strain.items():
            ax.plot(self.time * 1e6, eps * 1e6, label=name)
        ax.set_xlabel("time [µs]")
        ax.set_ylabel("strain [µε]")
        ax.legend()
        return ax

    def write_fields(self, path, *, frames: int = 200):
        """Displacement fields over time as XDMF for ParaView; see :meth:`ImpactResult.write_fields`."""
        from .output.fields import sampled_steps, write_fields

        steps = sampled_steps(self.problem.solver.steps, frames)
        u = self.result.displacement
        if u is None:
            raise InputError("write_fields: this beam run kept no displacement (run it with displacement=True)")
        return write_fields(path, self.model, (steps, self.result.time[steps], u[:, steps]))


@dataclass(frozen=True)
class PlateResult(_Prescribed):
    """A plate under a prescribed force history (:func:`run` of a plate case; ``softimpact plate``).

    Parameters
    ----------
    problem : softimpact.workflows.plate_impact.PlateProblem
        Every input in SI.
    result : softimpact.workflows.plate_impact.PlateResult
        time [s], force [N], strain (n_gauges, n_steps + 1), deflection [m] (impact point first).
    model : StructureModel, optional
        The assembled model that ran (reused by ``write_fields``).
    case_files : tuple of Path
        The case files read (never overwritten by ``write``).
    warnings : tuple of str
        The run's :class:`~softimpact.errors.SoftimpactWarning` s, one line each (already warned at
        the call; listed in manifest.json by ``write``, as the command line lists them).
    """

    command = "softimpact plate"

    def files(self, figures: bool = True):
        """The files of ``softimpact plate``, by name."""
        from .output.plate import plate_files

        return plate_files(self.model, self.result, figures)

    def to_frame(self):
        """Force, deflection under the load and gauge strains, indexed by time [s]; units in ``df.attrs["units"]``."""
        cols = {"time_s": self.time, "force_N": self.force, "deflection_m": self.result.deflection[0], **{f"strain_{k}": v for k, v in self.strain.items()}}
        return _frame(cols, {k: _unit_of(k) for k in cols})

    def plot(self, ax=None):
        """The deflection under the load against time [µs, mm]; returns the matplotlib Axes."""
        ax = _axes(ax)
        ax.plot(self.time * 1e6, self.result.deflection[0] * 1e3)
        ax.set_xlabel("time [µs]")
        ax.set_ylabel("deflection under the load [mm]")
        return ax

    def write_fields(self, path, *, frames: int = 200):
        """Displacement fields over time as XDMF for ParaView; see :meth:`ImpactResult.write_fields`."""
        from .output.fields import keeps, kept_frames, sampled_steps, write_fields

        steps = sampled_steps(self.problem.solver.steps, frames)
        r = self.result if keeps(self.result, steps) else self.model.direct(energy=False, snapshots=steps)
        return write_fields(path, self.model, kept_frames(r, steps))


@dataclass(frozen=True)
class BarResult(_Written):
    """A sphere on the instrumented bar (:func:`impact` on a :class:`Bar`, :func:`run` of a bar case).

    Parameters
    ----------
    problem : softimpact.workflows.bar_impact.BarImpactProblem
        Every input in SI.
    result : softimpact.workflows.bar_impact.BarImpactResult
        The coupled run (contact force [N], gauge strains, …).
    plain : BarImpactResult, optional
        The same run without the end cap.
    inferred : (numpy.ndarray, numpy.ndarray, str), optional
        Time [s], force [N] read from the first gauge, and its name.
    case_files : tuple of Path
        The case files read.
    warnings : tuple of str
        The run's :class:`~softimpact.errors.SoftimpactWarning` s, one line each (already warned at
        the call; listed in manifest.json by ``write``, as the command line lists them).
    """

    problem: object
    result: object
    plain: object = field(repr=False, default=None)
    inferred: object = field(repr=False, default=None)
    case_files: tuple = field(repr=False, default=())
    warnings: tuple = field(repr=False, compare=False, default=())
    command = "softimpact bar"

    peak_force = property(lambda self: self.result.peak_force, doc="Peak contact force [N].")
    time_of_peak = property(lambda self: self.result.time_of_peak, doc="Time of the peak force [s].")
    contact_duration = property(lambda self: self.result.contact_duration, doc="Contact duration [s].")
    time = property(lambda self: self.result.time, doc="Time [s], (n_steps + 1,).")
    force = property(lambda self: self.result.force, doc="Contact force [N], (n_steps + 1,).")

    @property
    def strain(self) -> dict:
        """Gauge strain histories by gauge name, each (n_steps + 1,)."""
        return dict(zip(self.result.strain_names, self.result.strain))

    def inputs(self):
        return tuple(self.case_files)

    def files(self, figures: bool = True):
        """The files of ``softimpact bar``, by name."""
        from .output.bar import bar_files

        return bar_files(self.result, self.plain, self.inferred, figures)

    def to_frame(self):
        """Contact force and gauge strains indexed by time [s]; units in ``df.attrs["units"]``."""
        cols = {"time_s": self.time, "contact_force_N": self.force, **{f"strain_{k}": v for k, v in self.strain.items()}}
        return _frame(cols, {k: _unit_of(k) for k in cols})

    def plot(self, ax=None):
        """The contact force against time [µs, N]; returns the matplotlib Axes."""
        ax = _axes(ax)
        ax.plot(self.time * 1e6, self.force)
        ax.set_xlabel("time [µs]")
        ax.set_ylabel("contact force [N]")
        return ax


# --- runs ---------------------------------------------------------------------------------------------


def _beam_gauges(gauges: dict | None):
    from .workflows.beam_impact import BeamGauge

    out = []
    for name, g in (gauges or {}).items():
        g = g if isinstance(g, dict) else {"position": g}
        extra = set(g) - {"position", "surface", "length"}
        if extra:
            raise InputError(f"gauges[{name!r}]: unknown key {sorted(extra)[0]!r} (position, surface, length)")
        length = _si(g["length"], "length", f"gauges[{name!r}].length") if "length" in g else BeamGauge.length
        out.append(BeamGauge(str(name), _si(g["position"], "length", f"gauges[{name!r}].position"), g.get("surface", "bottom"), length))
    return tuple(out)


def _plate_gauges(gauges: dict | None):
    from .workflows.plate_impact import PlateGauge

    out = []
    for name, g in (gauges or {}).items():
        g = g if isinstance(g, dict) else {"position": g}
        extra = set(g) - {"position", "surface", "direction", "length"}
        if extra:
            raise InputError(f"gauges[{name!r}]: unknown key {sorted(extra)[0]!r} (position, surface, direction, length)")
        length = _si(g["length"], "length", f"gauges[{name!r}].length") if "length" in g else PlateGauge.length
        out.append(PlateGauge(str(name), _point(g["position"], f"gauges[{name!r}].position"), g.get("surface", "bottom"), g.get("direction", "x"), length))
    return tuple(out)


def _is_law_file(law) -> bool:
    return isinstance(law, Path) or (isinstance(law, str) and law.endswith(".json"))


def _law(law, hertz, sphere: Sphere):
    """(name, law, the law file read or None): a name of :data:`CONTACT_LAWS` resolved by :func:`resolve_law`,
    a law object, or a law.json path read as a case file's ``law_file`` is
    (:func:`softimpact.input.contact_law.read_contact_law`: the same warnings when the sphere lies outside
    what the law was identified on)."""
    from .models.contact_laws import resolve_law

    if _is_law_file(law):
        from .input.contact_law import read_contact_law
        from .input.toml import Table

        class _Argument(Table):  # the API's argument is ``law``, not the case file's ``contact.law_file``
            def key(self, name: str) -> str:
                return "law"

        resolved, path = read_contact_law(_Argument({"law_file": str(law)}), "identified", hertz, sphere.mass, sphere.diameter, sphere.velocity, Path())
        return "identified", resolved, path
    resolved = resolve_law(law, hertz)
    return (law if isinstance(law, str) else getattr(law, "name", type(law).__name__)), resolved, None


def impact(
    structure,
    *,
    at=None,
    impactor: Sphere,
    law="hertz",
    time_step,
    duration,
    gauges: dict | None = None,
    target_modulus=None,
    contact_radius=None,
    beta: float = 0.25,
    gamma: float = 0.5,
    units: str = "in-lbf-s",
    title: str = "",
):
    """Coupled impact of a sphere on a beam, plate or bar: Newmark on the structure, Newton on the
    scalar contact equation each step (:mod:`softimpact.fem.impact`, the one coupled stepper).

    Parameters
    ----------
    structure : Beam, Plate or Bar
        The target.
    at : str, pint.Quantity or (x, y), optional
        Impact point [length]: from the support along a beam, (x, y) on a plate; a bar is
        struck on its end (leave ``at`` out).
    impactor : Sphere
        The sphere, its diameter [length] and velocity [velocity].
    law : str, ContactLaw, HistoryLaw or path
        ``"hertz"`` (eqs 1–3; Sun's laminate form with the ply's through-thickness modulus
        E3 on a laminate), any contact law object (:mod:`softimpact.models.contact_laws`), or
        the path of a law.json written by ``softimpact identify``.
    time_step : str or pint.Quantity
        Newmark time step [time], e.g. ``"0.5 us"``.
    duration : str or pint.Quantity
        Length of the run [time], e.g. ``"400 us"``; time zero is first contact.
    gauges : dict, optional
        ``{name: position}`` [length] (a beam: from the support, bottom face; a plate: (x, y),
        strain along x; a bar: from the struck end), or ``{name: {"position": ...,
        "surface": "top"|"bottom", "direction": "x"|"y"|degrees, "length": ...}}``.
    target_modulus : str or pint.Quantity, optional
        Hertz: the target's transverse modulus [stress] (default the ply's E3).
    contact_radius : str or pint.Quantity, optional
        Widest contact radius the beam or plate model must load [length] (default the
        sphere's radius).
    beta, gamma : float
        Newmark parameters (default average acceleration, 1/4 and 1/2).
    units : str
        Display units of figures and tables, ``"in-lbf-s"`` (default) or ``"SI"``; numbers stay SI.
    title : str
        A title for the outputs.

    Returns
    -------
    ImpactResult or BarResult
        Frozen; ``peak_force`` [N], ``force`` [N], ``strain[name]``, ``.plot()``, ``.write(dir)``,
        ``.to_frame()``, ``.write_fields(path)``; inputs in SI in ``.problem``.

    Raises
    ------
    softimpact.errors.InputError
        A missing unit, an impact point off the structure, gauges off it, an unknown law,
        a problem too large for the machine.
    softimpact.errors.SolverFailed
        The contact iteration did not converge.

    Examples
    --------
    >>> import softimpact as si
    >>> beam = si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(100, 4))
    >>> res = si.impact(beam, at="3 in", impactor=si.Sphere("steel", "0.5 in", velocity="100 in/s"),
    ...                 time_step="1 us", duration="200 us", gauges={"g1": "2 in"})
    >>> 100 < res.peak_force < 1000  # N: a Hertz impact of a few hundred newtons
    True
    """
    with _Heard() as heard:
        res = _impact(structure, at, impactor, law, time_step, duration, gauges, target_modulus, contact_radius, beta, gamma, units, title)
    return replace(res, warnings=tuple(heard.texts))


def _impact(structure, at, impactor, law, time_step, duration, gauges, target_modulus, contact_radius, beta, gamma, units, title):
    """:func:`impact`, its warnings left to the caller."""
    from .fem.newmark import NewmarkParameters, SolverSpec
    from .models.contact_laws import HertzLaw

    if not isinstance(impactor, Sphere):
        raise InputError(f"impactor: expected a si.Sphere, got {type(impactor).__name__}")
    with _naming():
        solver = SolverSpec(_si(time_step, "time", "time_step"), _si(duration, "time", "duration"), NewmarkParameters(beta, gamma))
    modulus = _si(target_modulus, "stress", "target_modulus") if target_modulus is not None else None

    if isinstance(structure, Bar):
        return _bar_impact(structure, at, impactor, law, solver, gauges, units, title)
    if not isinstance(structure, (Beam, Plate)):
        raise InputError(f"structure: expected a si.Beam, si.Plate or si.Bar, got {type(structure).__name__}")
    spec = structure.spec
    radius = _si(contact_radius, "length", "contact_radius") if contact_radius is not None else impactor.diameter / 2

    def hertz():  # the reader's rule (softimpact.input.impact_case): Sun's form on a laminate
        if modulus is not None or spec.stack is not None:
            return HertzLaw.sphere_on_laminate(impactor.diameter / 2, impactor.material, modulus if modulus is not None else spec.stack.ply.E3)
        return HertzLaw.sphere_on_flat(impactor.diameter / 2, impactor.material, spec.material)

    name, resolved, law_file = _law(law, hertz, impactor)
    if at is None:
        raise InputError("at: give the impact point (a length along a beam, (x, y) on a plate)")
    if isinstance(structure, Beam):
        from .workflows.beam_impact import BeamLoad, BeamProblem

        with _naming():
            target = BeamProblem(spec, BeamLoad(_si(at, "length", "at"), radius, None), solver, _beam_gauges(gauges), title, units)
    else:
        from .workflows.plate_impact import PlateLoad, PlateProblem

        with _naming():
            target = PlateProblem(spec, PlateLoad(_point(at, "at"), radius, None, grow=True), solver, _plate_gauges(gauges), title=title, units=units)
    from .cases import KINDS
    from .workflows.coupled import ImpactProblem

    problem = ImpactProblem(target, "(Python API)", impactor.impactor, impactor.material, name, resolved, title, units)
    KINDS["impact"].check(problem)  # the resource guards of the command, before anything is built
    return _run(Case("impact", problem, () if law_file is None else (law_file,)))


def _naming():
    """Errors of the problem classes name the API's arguments (time_step, at, gauges)."""
    from .input.toml import naming

    return naming({"position": "at", "gauges": "gauges", "time_step": "time_step", "duration": "duration"})


def _bar_impact(bar: Bar, at, sphere: Sphere, law, solver, gauges, units: str, title: str) -> BarResult:
    from .models.specimens import Gauge, Projectile
    from .workflows.bar_impact import BarImpactProblem

    if at is not None:
        raise InputError("at: a bar is struck on its end (leave at out)")
    law_file = None
    if _is_law_file(law):
        _, law, law_file = _law(law, None, sphere)
    gs = tuple(Gauge(str(n), _si(p, "length", f"gauges[{n!r}]")) for n, p in (gauges or {}).items())
    projectile = Projectile(sphere.material, sphere.diameter, sphere.velocity, sphere.mass)
    return _run(Case("bar", BarImpactProblem(bar.spec, projectile, solver, gs, law, title, units), () if law_file is None else (law_file,)))


@dataclass(frozen=True)
class Case:
    """A case read and checked (:func:`load`), ready for :func:`run`.

    Parameters
    ----------
    kind : str
        ``"bar"``, ``"beam"``, ``"plate"`` or ``"impact"`` (:data:`softimpact.cases.KINDS`).
    problem : object
        The resolved problem, SI.
    files : tuple of Path
        The files read (case first).
    warnings : tuple of str
        The warnings reading it raised (already shown; :func:`run` keeps them for manifest.json).
    """

    kind: str
    problem: object
    files: tuple = ()
    warnings: tuple = field(default=(), compare=False)


def load(case, *, history: int | None = None) -> Case:
    """Read a case file or a built-in case by name, of any kind, and check it.

    Parameters
    ----------
    case : str or Path
        A case file (TOML, quantities with their units) or a built-in name (``softimpact cases``).
    history : int, optional
        Beam and plate cases: row N (1-based) of the case's ``[[load.table]]``.

    Returns
    -------
    Case
        The kind, the problem in SI and the files read.

    Raises
    ------
    softimpact.errors.InputError
        A missing file, a key without its unit, a problem too large for the machine.

    Examples
    --------
    >>> import softimpact as si
    >>> case = si.load("paper-long-beam-impact")
    >>> case.kind, round(case.problem.impactor.velocity, 9)
    ('impact', 2.54)
    """
    from .cases import case_kind

    with _Heard() as heard:
        kind, _ = case_kind(str(case))
        problem, files = kind.load(str(case), history)
        kind.check(problem)
    return Case(kind.name, problem, tuple(Path(f) for f in (files if isinstance(files, tuple) else (files,))), tuple(heard.texts))


def run(problem, *, figures: bool = True):
    """Run a case (from :func:`load`) or a problem object as its command would.

    Parameters
    ----------
    problem : Case or problem
        A :class:`Case`, or an ImpactProblem, BeamProblem, PlateProblem or BarImpactProblem (SI).
    figures : bool
        Beam and plate: keep the displacement history the deformed-shape figures and
        :meth:`write_fields` draw on (memory n_dofs × n_steps on a beam).

    Returns
    -------
    ImpactResult, BeamResult, PlateResult or BarResult
        The frozen result; its ``summary()`` holds the numbers of the command's summary.json.

    Raises
    ------
    softimpact.errors.InputError
        A problem too large for the machine, a contact that outgrows its room.
    softimpact.errors.SolverFailed
        A coupled run whose contact iteration did not converge.

    Examples
    --------
    >>> import softimpact as si
    >>> res = si.run(si.load("paper-calibration"))
    >>> 900 < res.peak_force < 1300  # N: paper Fig 5, about 250 lbf (1100 N)
    True
    """
    case = problem if isinstance(problem, Case) else Case(_kind_of(problem), problem)
    with _Heard() as heard:
        res = _run(case, figures)
    return replace(res, warnings=(*case.warnings, *heard.texts))


def _run(case: Case, figures: bool = True):
    """:func:`run`, its warnings left to the caller (each as the command warns it: the same functions)."""
    from .models.validity import Validity, warn

    p, files = case.problem, case.files
    if case.kind == "impact" and hasattr(p, "projectile"):  # an impact case on a bar target runs as the bar
        case = Case("bar", p, files)
    if case.kind == "impact":
        from .output.impact import snapshot_steps
        from .studies.damage import damage_problem
        from .workflows.coupled import impact_model, run_impact

        p = damage_problem(p)  # as the command: + the pseudo-gauges of the damage indices (a layup with strengths)
        model = impact_model(p)
        snaps = snapshot_steps(p.solver.steps) if figures and p.on_plate else ()
        model, result = run_impact(p, model, snapshots=snaps)
        from .app.impact import warn_validity
        from .output.impact import impact_summary

        warn_validity(impact_summary(p, result, model))
        return ImpactResult(p, result, model, files)
    if case.kind == "beam":
        from .output.beam import beam_validity
        from .workflows.beam_impact import BeamModel

        model = BeamModel(p)
        result = model.direct(displacement=figures)
        warn(beam_validity(result))
        return BeamResult(p, result, model, files)
    if case.kind == "plate":
        from .app.plate import _mirrored_loads
        from .output.plate import plate_validity, snapshot_steps
        from .workflows.plate_impact import PlateModel

        model = PlateModel(p)
        result = model.direct(snapshots=snapshot_steps(p.solver.steps) if figures else ())
        warn(Validity({}, _mirrored_loads(p)) + plate_validity(result))  # the command's order
        return PlateResult(p, result, model, files)
    from .app.bar import run_bar
    from .output.bar import bar_validity

    result, plain, inferred = run_bar(p)
    warn(bar_validity(result))
    return BarResult(p, result, plain, inferred, files)


def _kind_of(problem) -> str:
    names = {"ImpactProblem": "impact", "BeamProblem": "beam", "PlateProblem": "plate", "BarImpactProblem": "bar"}
    name = names.get(type(problem).__name__)
    if name is None:
        raise InputError(f"problem: expected a si.Case or a problem object, got {type(problem).__name__}")
    return name


# --- the chain of the paper: the commands' own functions ---------------------------------------------


@dataclass(frozen=True)
class CommandResult(_Written):
    """What a command made (:class:`softimpact.app.Outcome`): its files by name and its one line.

    Parameters
    ----------
    command : str
        The equivalent command line.
    outcome : softimpact.app.Outcome
        ``files`` (name → text or bytes; numbers in SI with unit-suffixed names), ``line``,
        ``inputs``, ``warnings``, ``gates``. A failed quality gate does not raise here (the
        command line exits 3); :meth:`write` marks it ``"status": "failed"`` in manifest.json.
    warnings : tuple of str
        The :class:`~softimpact.errors.SoftimpactWarning` s raised while the command ran, one line each
        (already warned at the call, as the outcome's own ``warnings`` were); manifest.json lists the
        outcome's, then these, as the command line does.
    """

    command: str
    outcome: object = field(repr=False, default=None)
    warnings: tuple = field(repr=False, compare=False, default=())

    @property
    def line(self) -> str:
        """The line the command prints."""
        return self.outcome.line

    def files(self, figures: bool = True):
        return {k: v for k, v in self.outcome.files.items() if figures or not k.endswith((".png", ".svg", ".pdf"))}

    def inputs(self):
        return tuple(self.outcome.inputs)

    def json(self, name: str) -> dict:
        """A JSON file of the outcome (``"scaling.json"``, ``"law.json"``, …), parsed."""
        return json.loads(self.outcome.files[name])

    def table(self, name: str):
        """A CSV file of the outcome (``"tests.csv"``, ``"history.csv"``, …) as a pandas DataFrame."""
        import io

        import pandas as pd

        return pd.read_csv(io.StringIO(self.outcome.files[name]))

    def summary(self) -> dict:
        return self.json("summary.json")

    def plot(self, ax=None):
        """The first figure of the outcome shown on ``ax`` (an image); returns the Axes."""
        import io

        import matplotlib.image as mpimg

        pngs = [k for k in self.outcome.files if k.endswith(".png")]
        if not pngs:
            raise InputError(f"{self.command}: made no figure (figures=False?)")
        ax = _axes(ax)
        ax.imshow(mpimg.imread(io.BytesIO(self.outcome.files[pngs[0]])))
        ax.set_axis_off()
        ax.set_title(pngs[0])
        return ax

    def write(self, out, *, figures: bool = True, force: bool = False) -> list[Path]:
        """Write the command's files and manifest.json into ``out`` (see :meth:`ImpactResult.write`)."""
        from .gates import status

        gates = tuple(self.outcome.gates)
        manifest = {
            "status": status(gates, False),
            "accept_poor": False,
            "command": f"{self.command} (Python API)",
            "arguments": {},
            "warnings": [*map(_one_line, self.outcome.warnings), *self.warnings],  # the command line's order
            "gates": [g.as_dict() for g in gates],
        }
        return _write(out, self.files(figures), self.inputs(), manifest, force)


def _command(command: str, call) -> CommandResult:
    """``call()``, an app command's :class:`~softimpact.app.Outcome`, as a CommandResult: the warnings raised
    while it ran kept and warned again at the user's line, then the outcome's own warnings warned (the
    command line shows both, in this order)."""
    with _Heard() as heard:
        outcome = call()
    with _Heard():
        for text in outcome.warnings:
            warnings.warn(_one_line(text), SoftimpactWarning, stacklevel=1)
    return CommandResult(command, outcome, tuple(heard.texts))


def reduce(series, *, figures: bool = True) -> CommandResult:
    """Reduce the bar strain records of a series to force histories and eq-15 pulse parameters (Fig 7).

    Parameters
    ----------
    series : str or Path
        A series file or a built-in series name (quantities with their units inside).
    figures : bool
        Draw the figures.

    Returns
    -------
    CommandResult
        ``table("tests.csv")``: per test peak force [N], times [s], impulse [N·s]; the files of
        ``softimpact reduce``.

    Raises
    ------
    softimpact.errors.InputError
        A missing or unreadable record.

    Examples
    --------
    >>> import softimpact as si
    >>> res = si.reduce("paper-silicone", figures=False)  # doctest: +SKIP
    """
    from .app.series import reduce as command

    return _command("softimpact reduce", lambda: command(series_name=str(series), figures=figures))


def fit(series, *, figures: bool = True) -> CommandResult:
    """Reduce a series, then fit the scaling constants α1–α4 of eqs (4)–(7) (Table I).

    Parameters
    ----------
    series : str or Path
        A series file or a built-in series name.
    figures : bool
        Draw the figures (Figs 8–11).

    Returns
    -------
    CommandResult
        ``json("scaling.json")``: the constants (dimensionless exponents, SI prefactors).

    Raises
    ------
    softimpact.errors.InputError
        A missing or unreadable record.

    Examples
    --------
    >>> import softimpact as si
    >>> si.fit("paper-silicone").json("scaling.json")  # doctest: +SKIP
    """
    from .app.series import fit as command

    return _command("softimpact fit", lambda: command(series_name=str(series), figures=figures))


def predict(
    *,
    velocity,
    projectile: str | None = None,
    mass=None,
    diameter=None,
    model: str = "empirical",
    constants: str | None = None,
    group: str = "pooled",
    tail: bool = False,
    material: str = "silicone rubber",
    target: str = "Al 6061-T6",
    bar: str | None = None,
    beam: str | None = None,
    units: str = "in-lbf-s",
    figures: bool = True,
) -> CommandResult:
    """Force history of a projectile at a velocity: the empirical model (eqs 4–7, 15), Hertz or Wilbeck.

    Parameters
    ----------
    velocity : str or pint.Quantity
        Impact velocity [velocity], e.g. ``"1166 in/s"``.
    projectile : str, optional
        A named projectile (``"rubber-1/2in"``), or give ``mass`` and ``diameter``.
    mass : str or pint.Quantity, optional
        Projectile mass [mass].
    diameter : str or pint.Quantity, optional
        Projectile diameter [length].
    model : str
        ``"empirical"``, ``"hertz"`` or ``"wilbeck"``.
    constants : str, optional
        Scaling constants: a preset or a scaling.json path.
    group : str
        Group of a scaling.json.
    tail : bool
        Empirical model: add the tail carrying the rest of eq (7)'s impulse.
    material, target : str
        Projectile and target materials (hertz, wilbeck).
    bar, beam : str, optional
        A bar or beam case driven by the predicted force.
    units : str
        Display units of the line and figure.
    figures : bool
        Draw the figure.

    Returns
    -------
    CommandResult
        ``table("history.csv")``: time_s and force_N (and strains); ``summary()``: peak force [N], …

    Raises
    ------
    softimpact.errors.InputError
        A missing unit, an unknown projectile or preset.

    Examples
    --------
    >>> import softimpact as si
    >>> res = si.predict(projectile="rubber-1/2in", velocity="1166 in/s", figures=False)
    >>> 100 < res.summary()["peak_force_N"] < 400  # N: Table II gives 44 lbf = 196 N
    True
    """
    from .app.predict import predict as command

    outcome = lambda: command(  # noqa: E731
        projectile=projectile,
        mass=_text(mass, "mass", "mass"),
        diameter=_text(diameter, "length", "diameter"),
        velocity=_text(velocity, "velocity", "velocity"),
        model=model,
        constants=constants,
        group=group,
        tail=tail,
        material=material,
        target=target,
        bar_case=bar,
        beam_case=beam,
        system=units,
        figures=figures,
    )
    return _command("softimpact predict", outcome)


def identify(series, *, figures: bool = True) -> CommandResult:
    """Identify a soft projectile's contact law from a series of bar tests (law.json).

    Parameters
    ----------
    series : str or Path
        A series file or a built-in series name.
    figures : bool
        Draw the figures.

    Returns
    -------
    CommandResult
        ``json("law.json")``: the law's parameters (SI) and the range identified on; pass
        the written law.json as ``law=`` to :func:`impact`.

    Raises
    ------
    softimpact.errors.InputError
        A missing or unreadable record.

    Examples
    --------
    >>> import softimpact as si
    >>> si.identify("paper-silicone").json("law.json")  # doctest: +SKIP
    """
    from .app.identify import identify as command

    return _command("softimpact identify", lambda: command(series_name=str(series), figures=figures))


def calibrate(
    case,
    *,
    measured=None,
    velocity=None,
    method: str = "least-squares",
    contact_radius=None,
    contact_time=None,
    fit_radius: bool = False,
    projectile: str = "rubber-1/2in",
    constants: str | None = None,
    budget: float = 20.0,
    figures: bool = True,
) -> CommandResult:
    """Force history that makes a beam's computed gauge strains match measured ones.

    Parameters
    ----------
    case : str or Path
        A beam case (with ``measured`` and ``velocity``) or a calibration series.
    measured : str or Path, optional
        CSV of measured strains: ``time_s`` and ``strain_<gauge>`` columns.
    velocity : str or pint.Quantity, optional
        Impact velocity [velocity].
    method : str
        ``"least-squares"`` (eq 15), ``"paper"`` or ``"deconvolve"``.
    contact_radius : str or pint.Quantity, optional
        r0 [length] (default the case's).
    contact_time : str or pint.Quantity, optional
        First contact on the record's clock [time].
    fit_radius : bool
        Least squares: fit r0 too.
    projectile, constants : str
        The bar-model start.
    budget : float
        Seconds that refining the model may cost.
    figures : bool
        Draw the figures.

    Returns
    -------
    CommandResult
        ``json("calibration.json")``: the fitted pulse (N, s) and its standard errors.

    Raises
    ------
    softimpact.errors.InputError
        A missing file or unit.

    Examples
    --------
    >>> import softimpact as si
    >>> si.calibrate("paper-calibration-series")  # doctest: +SKIP
    """
    from .app.calibrate import calibrate_command

    outcome = lambda: calibrate_command(  # noqa: E731
        case=str(case),
        measured=None if measured is None else str(measured),
        velocity=_text(velocity, "velocity", "velocity"),
        method=method,
        contact_radius=_text(contact_radius, "length", "contact_radius"),
        contact_time=_text(contact_time, "time", "contact_time"),
        fit_radius=fit_radius,
        projectile=projectile,
        constants=constants,
        figures=figures,
        budget=budget,
    )
    return _command("softimpact calibrate", outcome)


def converge(case, *, levels: int = 3, ratio: int = 2, history: int | None = None, figures: bool = True) -> CommandResult:
    """Discretisation error of a bar, beam, plate or impact case by systematic refinement (Richardson).

    Parameters
    ----------
    case : str or Path
        A case file or built-in name.
    levels : int
        Number of discretisations (2 to 5): the case's own, then refined by ``ratio`` each.
    ratio : int
        Refinement ratio between levels (elements × ratio, time step / ratio).
    history : int, optional
        Beam cases: row N of the case's ``[[load.table]]``.
    figures : bool
        Draw the figures.

    Returns
    -------
    CommandResult
        ``table("convergence.csv")``: per output the observed order, values (SI, unit-suffixed
        names), extrapolation, GCI.

    Raises
    ------
    softimpact.errors.InputError
        A bad case or a refinement too large for the machine.

    Examples
    --------
    >>> import softimpact as si
    >>> si.converge("paper-calibration", levels=2)  # doctest: +SKIP
    """
    from .app.converge import converge as command

    return _command("softimpact converge", lambda: command(case=str(case), levels=levels, ratio=ratio, history=history, figures=figures))


def sweep(spec, *, out, workers: int | None = 0, scheduler: str | None = None, figures: bool = True) -> CommandResult:
    """Grids and Monte Carlo runs of a case as a sweep spec says, locally or on Dask.

    Parameters
    ----------
    spec : str or Path
        A sweep spec file (TOML).
    out : str or Path
        Folder of the checkpoints (``out/checkpoints``): the same call resumes where it stopped.
        The spec's quantities carry their units; the results are SI.
    workers : int, optional
        Local Dask worker processes; 0 (default here): a plain loop, no Dask; None: the machine's cores.
    scheduler : str, optional
        Address of a running Dask scheduler.
    figures : bool
        Draw the figures.

    Returns
    -------
    CommandResult
        ``outcome.files["runs.parquet"]`` (a row per run) and ``summary()`` (statistics).

    Raises
    ------
    softimpact.errors.InputError
        A bad spec.

    Examples
    --------
    >>> import softimpact as si
    >>> si.sweep("my-sweep.toml", out="sweep-out")  # doctest: +SKIP
    """
    from .app.sweep import sweep as command

    return _command("softimpact sweep", lambda: command(spec=str(spec), out_dir=str(out), workers=workers, scheduler=scheduler, figures=figures))


@dataclass(frozen=True)
class Record:
    """One channel of a lab record (:func:`read_record`).

    Parameters
    ----------
    time : numpy.ndarray
        [s], 1-D, increasing (negative before the trigger).
    signal : numpy.ndarray
        Same shape, in ``unit``.
    unit : str
        ``"V"``, ``"strain"``, ``"microstrain"`` or the file's own unit text.
    metadata : dict
        File, format, channel, sample rate [Hz], trigger, the header's items.
    """

    time: object
    signal: object
    unit: str
    metadata: dict = field(default_factory=dict, compare=False)

    def to_frame(self):
        """The channel as a pandas DataFrame indexed by time [s]; its unit in ``df.attrs["units"]``."""
        return _frame({"time_s": self.time, "signal": self.signal}, {"signal": self.unit})

    def plot(self, ax=None):
        """The signal against time [µs]; returns the matplotlib Axes."""
        ax = _axes(ax)
        ax.plot(self.time * 1e6, self.signal)
        ax.set_xlabel("time [µs]")
        ax.set_ylabel(f"signal [{self.unit}]")
        return ax


def read_record(path, *, channel: str | int | None = None) -> Record:
    """Read one channel of a lab record file (TDMS, MAT, HDF5, CSV, Tektronix, …).

    Parameters
    ----------
    path : str or Path
        The record file; its format is detected from extension and first bytes.
    channel : str or int, optional
        A channel name (``"group/channel"`` or ``"channel"``), an index, or None for a file of one channel.

    Returns
    -------
    Record
        ``time`` [s], ``signal`` in ``unit`` (V, strain, microstrain, …), ``metadata``.

    Raises
    ------
    softimpact.errors.InputError
        An unreadable file, an unknown channel, no time base.

    Examples
    --------
    >>> import softimpact as si
    >>> rec = si.read_record("scope.csv", channel="CH1")  # doctest: +SKIP
    """
    from .input.records import read_lab_record

    r = read_lab_record(Path(path), channel)
    return Record(r.time, r.signal, r.unit, dict(r.metadata))
