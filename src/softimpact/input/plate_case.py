"""Plate case files (``softimpact plate``): TOML → :class:`PlateProblem`.

``[plate]`` (length, width, elements, element ``mitc9`` or ``mitc4`` (default: see
``DEFAULT_ELEMENT``), support per edge, model, ``kinematics`` (``"linear"``, the default, or
``"von-karman"``), ``in_plane`` (``"immovable"``, the default, or ``"movable"``: see
``DEFAULT_IN_PLANE``), ``[plate.laminate]`` — or for a metal skin ``material`` (a catalogue metal by name, e.g.
``"Al 2024-T3"``, or an inline table of its constants: :func:`read_metal`), ``thickness`` and ``plasticity``
(true, the default for a metal: elastic–plastic; false: elastic, checked against yield)),
``[load]`` (position, contact_radius, history and ``[[load.table]]`` rows, read as in
beam cases; or, with ``[solver] analysis = "static"``, a uniform ``pressure`` alone),
``[solver]`` (time step and duration; or ``analysis = "static"`` and ``load_steps``) and
``[[gauges]]``; see README.md, ``data/cases/plate-ss-8in.toml`` and
``data/cases/plate-ss-pressure-vk.toml``.
"""

from __future__ import annotations

import math
from pathlib import Path

from .. import units
from ..errors import InputError
from ..fem.plate import EDGES, ELEMENTS
from ..fem.plate_vk import IN_PLANE, KINEMATICS
from ..models.laminate import Stack, parse_layup
from ..models.metals import METALS, Metal, bilinear_hardening, metal
from ..models.plasticity import LinearHardening
from ..models.specimens import GAUGE_LENGTH
from ..workflows.plate import ANALYSES, PlateGauge, PlateLoad, PlateProblem, PlateSpec, check_problem
from .beam_case import read_load_history, read_ply
from .toml import Table, load_case_toml, locate, naming, read_solver, read_units

__all__ = ["PLATE_SUPPORTS", "PLATE_MODELS", "check_supports", "plate_problem", "read_plate_gauges", "load_plate_case", "read_metal"]

PLATE_SUPPORTS = ("clamped", "simply-supported", "free", "symmetry")  # symmetry: a mirror plane (quarter models)
PLATE_MODELS = ("fsdt",)  # the layered solid model is not implemented: not a choice (a case naming it is told so)
MIN_ELEMENTS = 2  # per direction: one element cannot place a load or gauge inside the plate
# The element when a case names none, in every command that reads a plate case (plate,
# converge, impact, sweep): MITC9, whose flexural dispersion error is O(h⁴) (1.8 % on the
# issue's plate at 48², where MITC4 needs ~360²). ``element = "mitc4"`` asks for MITC4.
DEFAULT_ELEMENT = "mitc9"
# The in-plane restraint of supported edges under von Kármán kinematics when a case names none: immovable,
# a panel fastened to a stiff frame (the classical large-deflection benchmarks' edges, Levy's and the Ritz
# oracle's of tests/test_plate_vk.py); "movable" lets the edges draw in. Linear kinematics ignores it.
DEFAULT_IN_PLANE = "immovable"
DEFAULT_LOAD_STEPS = 10  # equal pressure increments of a static run: 3-6 Newton iterations each to w/h ~ 3


def _point(tbl: Table, name: str) -> tuple[float, float]:
    value = tbl.raw(name)
    if not (isinstance(value, list) and len(value) == 2):
        raise InputError(f"{tbl.key(name)}: expected [x, y] (two lengths), got {value!r}")
    return tuple(units.parse(v, "length", tbl.key(name)) for v in value)


def _supports(tbl: Table) -> tuple[str, str, str, str]:
    """``support``: one kind for all four edges (``support = "simply-supported"``, as ``si.Plate`` takes it) or a table
    of the four edges."""
    value = tbl.raw("support")
    if isinstance(value, str):
        if value not in PLATE_SUPPORTS:
            raise InputError(f"{tbl.key('support')}: {value!r} is not one of {', '.join(PLATE_SUPPORTS)}")
        out = (value,) * 4
    elif isinstance(value, dict):
        s = Table(value, tbl.key("support"))
        out = tuple(s.string(e, choices=PLATE_SUPPORTS) for e in EDGES)
        s.done()
    else:
        raise InputError(f"{tbl.key('support')}: expected one support for all edges or a table {{ x0 = ..., x1 = ..., y0 = ..., y1 = ... }}, got {value!r}")
    check_supports(out, tbl.key("support"))
    return out


# What each support stops of the plate's rigid motions w = c0 + c1·x + c2·y (unit square, edges x0: x = 0, x1: x = 1,
# y0: y = 0, y1: y = 1): rows of the linear conditions on (c0, c1, c2). A simply supported edge holds w = 0 along it
# (two conditions), a clamped one its slope across too, a symmetry edge only that slope (w free along it), a free
# edge nothing.
_HELD = {
    "x0": {"simply-supported": [[1, 0, 0], [0, 0, 1]], "clamped": [[1, 0, 0], [0, 0, 1], [0, 1, 0]], "symmetry": [[0, 1, 0]]},
    "x1": {"simply-supported": [[1, 1, 0], [0, 0, 1]], "clamped": [[1, 1, 0], [0, 0, 1], [0, 1, 0]], "symmetry": [[0, 1, 0]]},
    "y0": {"simply-supported": [[1, 0, 0], [0, 1, 0]], "clamped": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "symmetry": [[0, 0, 1]]},
    "y1": {"simply-supported": [[1, 0, 1], [0, 1, 0]], "clamped": [[1, 0, 1], [0, 1, 0], [0, 0, 1]], "symmetry": [[0, 0, 1]]},
}


def check_supports(supports, key: str = "support") -> None:
    """Refuse edges (x0, x1, y0, y1) that leave the plate a mechanism: a rigid motion w = c0 + c1·x + c2·y that no
    edge stops (:data:`_HELD`: the conditions have rank 3 exactly when none is left). A clamped edge, two simply
    supported ones, or one with a symmetry edge across it hold the plate; a half or quarter model's symmetry edges
    count for the slope they hold (the rule of case files and of ``si.Plate``)."""
    import numpy as np

    rows = [r for edge, kind in zip(EDGES, supports) for r in _HELD[edge].get(kind, [])]
    if not rows or np.linalg.matrix_rank(np.array(rows, float)) < 3:
        raise InputError(
            f"{key}: {dict(zip(EDGES, supports))} leaves the plate a mechanism: a rigid motion no edge stops (it needs a clamped edge, "
            "two simply supported edges, or a simply supported edge and a symmetry edge across it)"
        )


def read_metal(tbl: Table, name: str = "material") -> Metal:
    """A metal: a catalogue name (:data:`softimpact.models.metals.METALS`) or an inline table of its constants,
    ``youngs_modulus``, ``poisson_ratio``, ``density``, ``yield_stress`` and either ``hardening_modulus`` (linear
    hardening, default 0: perfectly plastic) or ``ultimate_strength`` with ``elongation`` (the catalogue's bilinear
    estimate through them)."""
    value = tbl.raw(name)
    if isinstance(value, str):
        return metal(value, tbl.key(name))
    if not isinstance(value, dict):
        raise InputError(f"{tbl.key(name)}: expected a metal's name ({', '.join(METALS)}) or a table of its constants, got {value!r}")
    m = Table(value, tbl.key(name))
    E = m.quantity("youngs_modulus", "stress")
    nu = m.number("poisson_ratio")
    rho = m.quantity("density", "density")
    sy = m.quantity("yield_stress", "stress")
    with naming({None: m.path}):
        if "ultimate_strength" in m or "elongation" in m:
            if "hardening_modulus" in m:
                raise InputError(f"{m.key('hardening_modulus')}: give the hardening modulus or the ultimate strength and elongation, not both")
            su, ef = m.quantity("ultimate_strength", "stress"), m.number("elongation")
            hardening = bilinear_hardening(E, sy, su, ef)
        else:
            su = ef = None
            hardening = LinearHardening(sy, m.quantity("hardening_modulus", "stress", default=0.0, positive=False))
        out = Metal("user metal", E, nu, rho, f"inline in {tbl.key(name)}", hardening=hardening, ultimate=su, elongation=ef)
    m.done()
    return out


def read_plate_gauges(top: Table) -> tuple[PlateGauge, ...]:
    """The ``[[gauges]]`` of a plate case (or of an impact case on a plate): name, position [x, y],
    surface, direction ("x", "y" or degrees from x) and length."""
    gauges = []
    for g in top.tables("gauges", optional=True):
        direction = g.raw("direction", "x")
        if isinstance(direction, bool) or not isinstance(direction, (str, int, float)):
            raise InputError(f"{g.key('direction')}: expected 'x', 'y' or an angle in degrees from x, got {direction!r}")
        if isinstance(direction, str) and direction not in ("x", "y"):
            raise InputError(f"{g.key('direction')}: {direction!r} is not 'x', 'y' or an angle in degrees from x")
        if not isinstance(direction, str) and not math.isfinite(direction):
            raise InputError(f"{g.key('direction')}: {direction!r} is not a finite angle (expected 'x', 'y' or degrees from x)")
        with naming({None: g.path}):
            gauges.append(
                PlateGauge(
                    g.string("name"),
                    _point(g, "position"),
                    g.string("surface", "bottom", choices=("top", "bottom")),
                    direction if isinstance(direction, str) else float(direction),
                    g.quantity("length", "length", default=GAUGE_LENGTH),
                )
            )
        g.done()
    if len({g.name for g in gauges}) != len(gauges):
        raise InputError("gauges: names must be unique")
    return tuple(gauges)


def plate_problem(data: dict, base: Path = Path("."), history: int | None = None) -> PlateProblem:
    """A plate case (parsed TOML) as a PlateProblem; ``history`` picks a row of [[load.table]] (1-based)."""
    top = Table(data)
    title = top.string("title", "")
    read_units(top)  # checked here; the display system is the edge's (input.toml.case_units), not the problem's
    p = top.table("plate")
    if p.raw("model", PLATE_MODELS[0]) == "solid":
        raise InputError(f"{p.key('model')}: the layered solid model is not implemented yet (use 'fsdt')")
    p.string("model", PLATE_MODELS[0], choices=PLATE_MODELS)
    element = p.string("element", DEFAULT_ELEMENT, choices=ELEMENTS)
    elements = p.raw("elements", [48, 48])
    if not (isinstance(elements, list) and len(elements) == 2 and all(isinstance(e, int) and not isinstance(e, bool) for e in elements)):
        raise InputError(f"{p.key('elements')}: expected [along x, along y] (two integers), got {elements!r}")
    if min(elements) < MIN_ELEMENTS:
        raise InputError(f"{p.key('elements')}: the FSDT plate needs at least {MIN_ELEMENTS} elements each way, got {elements!r}")
    supports = _supports(p)
    kinematics = p.string("kinematics", KINEMATICS[0], choices=KINEMATICS)
    in_plane = p.string("in_plane", DEFAULT_IN_PLANE, choices=IN_PLANE)
    plasticity = p.raw("plasticity", None)
    if plasticity is not None and not isinstance(plasticity, bool):
        raise InputError(f"{p.key('plasticity')}: expected true or false, got {plasticity!r}")
    if "material" in p:  # a metal skin: its material and thickness instead of a laminate
        if "laminate" in p:
            raise InputError(f"{p.key('material')}: a plate is a laminate ([plate.laminate]) or a metal (material and thickness), not both")
        material, stack = read_metal(p), None
        thickness = p.quantity("thickness", "length")
    else:
        if "thickness" in p or plasticity is not None:
            key = p.key("thickness" if "thickness" in p else "plasticity")
            raise InputError(f"{key}: goes with a metal plate's material; a laminate's thickness is its plies' and it is elastic")
        lam = p.table("laminate")
        ply = read_ply(lam)
        layup = lam.string("layup")  # (read outside the naming: its own errors name the key already)
        with naming({None: lam.key("layup")}):
            stack = Stack(ply, parse_layup(layup))
        lam.done()
        material = thickness = None
    with naming({"thickness": p.key("thickness"), "material": p.key("material")}):
        spec = PlateSpec(
            p.quantity("length", "length"),
            p.quantity("width", "length"),
            tuple(elements),
            stack,
            supports,
            element=element,
            material=material,
            thickness=thickness,
        )
    p.done()

    sv = top.table("solver")
    analysis = sv.string("analysis", ANALYSES[0], choices=ANALYSES)
    ld = top.table("load")
    if analysis == "static":
        if history is not None:
            raise InputError(f"--history: a static plate case has no [[load.table]] rows to pick (its load is {ld.key('pressure')})", "history")
        if "pressure" not in ld:
            raise InputError(f"{ld.key('pressure')}: missing (a static plate run, {sv.key('analysis')} = 'static', takes a uniform pressure)")
        pressure = ld.quantity("pressure", "stress")
        ld.done()
        load_steps = sv.integer("load_steps", DEFAULT_LOAD_STEPS)
        sv.done()
        load = solver = None
    else:
        if "pressure" in ld:
            raise InputError(
                f"{ld.key('pressure')}: a uniform pressure is a static load: set {sv.key('analysis')} = 'static' (dynamic runs take a force history)"
            )
        if "load_steps" in sv:
            raise InputError(f"{sv.key('load_steps')}: load steps belong to a static run ({sv.key('analysis')} = 'static')")
        position = _point(ld, "position")
        radius = ld.quantity("contact_radius", "length")
        grow = ld.raw("grow", True)
        if not isinstance(grow, bool):
            raise InputError(f"{ld.key('grow')}: expected true or false, got {grow!r}")
        pulse, radius = read_load_history(ld, base, history, radius)
        ld.done()
        load = PlateLoad(position, radius, pulse, grow)
        solver = read_solver(sv)
        pressure, load_steps = None, DEFAULT_LOAD_STEPS
    gauges = read_plate_gauges(top)
    top.done()
    if analysis == "static" and gauges:
        raise InputError("gauges: a static plate run records the largest deflection only (gauges are for dynamic runs)")
    names = {
        None: "case",
        "kinematics": p.key("kinematics"),
        "in_plane": p.key("in_plane"),
        "pressure": "load.pressure",
        "load_steps": sv.key("load_steps"),
        "plasticity": p.key("plasticity"),
    }
    with naming(names):
        problem = PlateProblem(
            spec,
            load,
            solver,
            gauges,
            title=title,
            kinematics=kinematics,
            in_plane=in_plane,
            analysis=analysis,
            pressure=pressure,
            load_steps=load_steps,
            plasticity=plasticity,
        )
    check_problem(problem)
    return problem


def load_plate_case(case: str, history: int | None = None) -> tuple[PlateProblem, Path]:
    path = locate(case)
    return plate_problem(load_case_toml(path, "plate"), path.parent, history), path
