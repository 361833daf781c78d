"""Runs of the notebook API: :func:`impact` from objects, :func:`load` and :func:`run` of any case
file or built-in name (through :data:`softimpact.cases.KINDS`)."""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from pathlib import Path

from ..errors import InputError
from ._edge import _Heard, _naming, _point, _si, keywords
from ._options import python_terms
from .results import BarResult, BeamResult, ImpactResult, PlateResult, StaticPlateResult
from .structures import Bar, Beam, Plate, Sphere

__all__ = ["Case", "impact", "load", "press", "run"]


# --- runs ---------------------------------------------------------------------------------------------


def _beam_gauges(gauges: dict | None):
    from ..workflows.beam_impact import BeamGauge

    out = []
    for name, g in (gauges or {}).items():
        g = g if isinstance(g, dict) else {"position": g}
        extra = set(g) - {"position", "surface", "length"}
        if extra:
            raise InputError(f"gauges[{name!r}]: unknown key {sorted(extra)[0]!r} (position, surface, length)")
        length = _si(g["length"], "length", f"gauges[{name!r}].length") if "length" in g else BeamGauge.length
        out.append(BeamGauge(str(name), _si(g["position"], "length", f"gauges[{name!r}].position", positive=False), g.get("surface", "bottom"), length))
    return tuple(out)


def _plate_gauges(gauges: dict | None):
    from ..workflows.plate import PlateGauge

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
    a law object, or a law.json path read by the one reader (:func:`softimpact.formats.law_json.read_law`,
    its errors naming ``law``) with the warnings a case file's ``law_file`` gets when the sphere lies outside
    what the law was identified on (:func:`softimpact.input.contact_law.warn_outside`)."""
    from ..models.contact_laws import MATERIAL_LAWS, law_name, resolve_law

    if _is_law_file(law):
        from ..formats.law_json import read_law
        from ..input.contact_law import check_family, warn_outside

        path = Path(law)
        identified = read_law(path, "law")
        check_family(identified, sphere.material, sphere.mass, sphere.diameter, f"law ({path.name})", "the Sphere's material")
        warn_outside(identified.identified_on, sphere.velocity, sphere.diameter, path, sphere.mass)
        return "identified", identified.law(sphere.mass, sphere.diameter, sphere.velocity), path
    if isinstance(law, str) and law in MATERIAL_LAWS:  # ice's crushing, gelatin's flow: the sphere's own law (a bird's its cylinder's)
        return law, sphere.law(law), None
    resolved = resolve_law(law, hertz)
    return law_name(law), resolved, None  # a law object by its CONTACT_LAWS name, as a case file names it


@keywords("si.impact")
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
        E3 on a laminate), ``"crushing"`` (an ice sphere) or ``"hydrodynamic"`` (a gelatin sphere),
        built from the sphere's material, any contact law object (:mod:`softimpact.models.contact_laws`), or
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
    with _Heard() as heard, python_terms():
        res = _impact(structure, at, impactor, law, time_step, duration, gauges, target_modulus, contact_radius, beta, gamma, units, title)
    return replace(res, warnings=tuple(heard.texts))


def _impact(structure, at, impactor, law, time_step, duration, gauges, target_modulus, contact_radius, beta, gamma, units, title):
    """:func:`impact`, its warnings left to the caller."""
    from ..fem.newmark import NewmarkParameters, SolverSpec
    from ..models.contact_laws import HertzLaw

    if not isinstance(impactor, Sphere):
        raise InputError(f"impactor: expected a si.Sphere, got {type(impactor).__name__}")
    _check_units(units)  # before anything is built: an unknown display system is refused now, not at .write()
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
        from ..workflows.beam_impact import BeamLoad, BeamProblem

        with _naming():
            target = BeamProblem(spec, BeamLoad(_si(at, "length", "at", positive=False), radius, None), solver, _beam_gauges(gauges), title)
    else:
        from ..workflows.plate import PlateLoad, PlateProblem

        with _naming():
            load = PlateLoad(_point(at, "at"), radius, None, grow=True)
            target = PlateProblem(
                spec,
                load,
                solver,
                _plate_gauges(gauges),
                title=title,
                kinematics=structure.kinematics,
                in_plane=structure.in_plane,
                plasticity=structure.plasticity,
            )
    from ..cases import KINDS
    from ..workflows.coupled import ImpactProblem

    problem = ImpactProblem(target, "(Python API)", impactor.impactor, impactor.material, name, resolved, title, impactor.threat)
    KINDS["impact"].check(problem)  # the resource guards of the command, before anything is built
    return _run(Case("impact", problem, () if law_file is None else (law_file,), units=units))


@keywords("si.press")
def press(plate: Plate, *, pressure, load_steps: int = 10, units: str = "in-lbf-s", title: str = "") -> StaticPlateResult:
    """A uniform pressure on the plate's top face, solved statically in ``load_steps`` equal increments
    (full Newton on the von Kármán plate; one linear solve with ``kinematics="linear"``): the case file's
    ``[load] pressure`` with ``[solver] analysis = "static"``.

    Parameters
    ----------
    plate : Plate
        The plate, with its ``kinematics`` and ``in_plane`` restraint.
    pressure : str or pint.Quantity
        The uniform pressure [stress], pushing down, e.g. ``"2 psi"``.
    load_steps : int
        Equal load increments (Newton from the previous step's solution); default 10.
    units : str
        Display units of the written summary, ``"in-lbf-s"`` (default) or ``"SI"``; numbers stay SI.
    title : str
        A title for the outputs.

    Returns
    -------
    StaticPlateResult
        Frozen; ``max_deflection`` [m], ``converged``, ``summary()`` (``max_deflection_m``,
        ``max_deflection_over_thickness``, Newton's iterations per step), ``.plot()``, ``.write(dir)``.

    Raises
    ------
    softimpact.errors.InputError
        A missing unit, a non-positive pressure or load step count, a problem too large for the machine.

    Examples
    --------
    >>> import softimpact as si
    >>> lam = si.Laminate("T300/934", "[90/0]5s")
    >>> plate = si.Plate(length="8 in", width="8 in", laminate=lam, elements=(4, 4), kinematics="von-karman")
    >>> res = si.press(plate, pressure="20 psi", load_steps=4)
    >>> res.converged and res.summary()["kinematics"]
    'von-karman'
    """
    from ..workflows.plate import PlateProblem

    if not isinstance(plate, Plate):
        raise InputError(f"plate: expected a si.Plate, got {type(plate).__name__}")
    _check_units(units)
    q = _si(pressure, "stress", "pressure")
    if not q > 0:
        raise InputError(f"pressure: must be positive (pushing on the top face), got {pressure!r} ({q:.6g} Pa)")
    with _Heard() as heard, python_terms():
        with _naming():
            problem = PlateProblem(
                plate.spec,
                None,
                None,
                title=title,
                kinematics=plate.kinematics,
                in_plane=plate.in_plane,
                analysis="static",
                pressure=q,
                load_steps=load_steps,
                plasticity=plate.plasticity,
            )
        from ..cases import KINDS

        KINDS["plate"].check(problem)
        res = _run(Case("plate", problem, units=units))
    return replace(res, warnings=tuple(heard.texts))


def _bar_impact(bar: Bar, at, sphere: Sphere, law, solver, gauges, units: str, title: str) -> BarResult:
    from ..models.specimens import Gauge, Impactor
    from ..workflows.bar_impact import BarImpactProblem

    if at is not None:
        raise InputError("at: a bar is struck on its end (leave at out)")
    from ..models.contact_laws import MATERIAL_LAWS

    law_file = None
    if _is_law_file(law) or (isinstance(law, str) and law in MATERIAL_LAWS):
        _, law, law_file = _law(law, None, sphere)
    gs = tuple(Gauge(str(n), _si(p, "length", f"gauges[{n!r}]", positive=False)) for n, p in (gauges or {}).items())
    projectile = Impactor(sphere.mass, sphere.diameter, sphere.velocity, sphere.material)
    return _run(Case("bar", BarImpactProblem(bar.spec, projectile, solver, gs, law, title), () if law_file is None else (law_file,), units=units))


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
    units : str
        The display system of its figures and tables (the case file's ``units``: ``"in-lbf-s"`` or ``"SI"``);
        the problem holds SI numbers only.
    """

    kind: str
    problem: object
    files: tuple = ()
    warnings: tuple = field(default=(), compare=False)
    units: str = "in-lbf-s"


@keywords("si.load")
def load(case, *, history: int | None = None, units: str | None = None) -> Case:
    """Read a case file or a built-in case by name, of any kind, and check it.

    Parameters
    ----------
    case : str or Path
        A case file (TOML, quantities with their units) or a built-in name (``softimpact cases``).
    history : int, optional
        Beam and plate cases: row N (1-based) of the case's ``[[load.table]]``.
    units : {'in-lbf-s', 'SI'}, optional
        Display units of the result's figures and tables (default: the case's own ``units`` key, else in-lbf-s;
        the command line's ``--units``); the numbers stay SI.

    Returns
    -------
    Case
        The kind, the problem in SI, the files read and the display system.

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
    from ..app.options import display_system
    from ..cases import case_kind
    from ..input.toml import case_units

    _check_units(units)
    with _Heard() as heard, python_terms():
        kind, _ = case_kind(str(case))
        problem, files = kind.load(str(case), history)
        kind.check(problem)
        system = display_system(units, case_units(str(case)))
    return Case(kind.name, problem, tuple(Path(f) for f in (files if isinstance(files, tuple) else (files,))), tuple(heard.texts), system)


def _check_units(units) -> None:
    """``units`` None or a display system; else an InputError naming it, before anything is read."""
    from ..app.options import DISPLAY_SYSTEMS

    if units is not None and units not in DISPLAY_SYSTEMS:
        raise InputError(f"units: {units!r} is not one of {', '.join(DISPLAY_SYSTEMS)}")


@keywords("si.run")
def run(problem, *, figures: bool = True, units: str | None = None):
    """Run a case (from :func:`load`) or a problem object as its command would.

    Parameters
    ----------
    problem : Case or problem
        A :class:`Case`, or an ImpactProblem, BeamProblem, PlateProblem or BarImpactProblem (SI).
    figures : bool
        Beam and plate: keep the displacement history the deformed-shape figures and
        :meth:`write_fields` draw on (memory n_dofs × n_steps on a beam).
    units : {'in-lbf-s', 'SI'}, optional
        Display units of the result's figures and tables (default: the Case's, else in-lbf-s); the numbers stay SI.

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
    _check_units(units)
    case = problem if isinstance(problem, Case) else Case(_kind_of(problem), problem)
    if units is not None:
        case = replace(case, units=units)
    with _Heard() as heard, python_terms():
        res = _run(case, figures)
    return replace(res, warnings=(*case.warnings, *heard.texts))


def _run(case: Case, figures: bool = True):
    """:func:`run`, its warnings left to the caller (each as the command warns it: the one run path,
    :func:`softimpact.cases.run.execute`)."""
    from ..cases import kind_for
    from ..cases.run import execute
    from ..models.validity import warn

    run = execute(case.problem, figures=figures)
    if case.kind == "impact":  # an identified law's envelope, from the law.json read (the command line's check)
        from ..cases.impact import with_identified_envelope

        run = with_identified_envelope(run, next((f for f in case.files if Path(f).suffix == ".json"), None))
    warn(run.warnings)
    kind = kind_for(run.problem).name  # an impact case on a bar target reads as a bar problem, and runs as one
    if kind == "bar":
        return BarResult(run.problem, run.result, run.plain, run.inferred, case.files, units=case.units)
    if kind == "plate" and run.problem.analysis == "static":
        return StaticPlateResult(run.problem, run.result, run.model, case.files, run_summary=run.summary, units=case.units)
    result_type = {"impact": ImpactResult, "beam": BeamResult, "plate": PlateResult}[kind]
    return result_type(run.problem, run.result, run.model, case.files, run_summary=run.summary, units=case.units)


def _kind_of(problem) -> str:
    names = {"ImpactProblem": "impact", "BeamProblem": "beam", "PlateProblem": "plate", "BarImpactProblem": "bar"}
    name = names.get(type(problem).__name__)
    if name is None:
        raise InputError(f"problem: expected a si.Case or a problem object, got {type(problem).__name__}")
    return name
