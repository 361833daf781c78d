"""Bar case files (``softimpact bar``): TOML → :class:`BarImpactProblem`.

``[bar]`` (with ``[bar.end_cap]``), ``[projectile]`` (a sphere, or a hail ``threat``:
:mod:`softimpact.input.projectile`), ``[contact]`` (``law`` and
its keys, :mod:`softimpact.input.contact_law`; the Hertz laws use the sphere on
the bar's end, or on its end cap; ``crushing`` and ``hydrodynamic`` the projectile's
material, ice or gelatin),
``[solver]``, ``[[gauges]]`` and ``[output]``; see README.md for the format.
"""

from __future__ import annotations

from pathlib import Path

from .. import units
from ..errors import InputError
from ..fem.bar import Rod
from ..models.contact_laws import HertzLaw
from ..models.specimens import BarSpec, EndCap, Gauge, Impactor
from ..workflows.bar_impact import BarImpactProblem, check_problem
from .bar_file import bar_tables
from .contact_law import CONTACT_LAWS, note_law_keys, read_contact_law
from .projectile import read_sphere
from .toml import Table, load_case_toml, locate, naming, read_material, read_solver, read_units

__all__ = ["read_bar", "read_gauges", "bar_problem", "load_bar_case"]


def read_bar(tbl: Table, default_elements: int = 39) -> BarSpec:
    """The ``[bar]`` table (with its optional ``[bar.end_cap]``)."""
    cap_tbl = tbl.table("end_cap", optional=True)
    cap = None
    if cap_tbl is not None:
        cap = EndCap(read_material(cap_tbl), cap_tbl.quantity("diameter", "length"), cap_tbl.quantity("length", "length"))
        cap_tbl.done()
    bar = BarSpec(
        read_material(tbl),
        tbl.quantity("length", "length"),
        tbl.quantity("diameter", "length"),
        tbl.integer("elements", default_elements),
        cap,
    )
    with naming({"elements": tbl.key("elements"), "end_mass": tbl.key("end_cap")}):
        Rod.of(bar)
    tbl.done()
    return bar


def read_gauges(top: Table, length: float) -> tuple[Gauge, ...]:
    """The ``[[gauges]]`` of a bar: name and position from the struck end, on the bar."""
    gauges = []
    for g in top.tables("gauges", optional=True):
        gauge = Gauge(g.string("name"), g.quantity("position", "length", positive=False))
        if not 0.0 <= gauge.position <= length:
            raise InputError(f"{g.key('position')}: {g.raw('position')!r} is outside the bar (0 to {length:.6g} m)")
        g.done()
        gauges.append(gauge)
    names = [g.name for g in gauges]
    if len(set(names)) != len(names):
        raise InputError(f"gauges: names must be unique, got {names}")
    return tuple(gauges)


def bar_problem(data: dict, base: Path = Path(".")) -> BarImpactProblem:
    """A bar case (already parsed TOML) as a :class:`BarImpactProblem`."""
    top = Table(data)
    title = top.string("title", "")
    read_units(top)  # checked here; the display system is the edge's (input.toml.case_units), not the problem's
    bar = read_bar(bar_tables(top, base, gauge_key=None)[0])  # the bar's own table, or a bar file's (input/bar_file.py)
    p = top.table("projectile")
    sphere = read_sphere(p)
    material, diameter = sphere.material, sphere.diameter
    projectile = Impactor(sphere.mass, diameter, sphere.velocity, material)
    p.done()
    contact_tbl = top.table("contact", optional=True)
    law = "hertz"
    if contact_tbl is not None:
        name = contact_tbl.string("law", law, choices=CONTACT_LAWS)
        note_law_keys(contact_tbl)
        if name != "hertz":
            flat = bar.material if bar.end_cap is None else bar.end_cap.material

            def hertz():
                return HertzLaw.sphere_on_flat(diameter / 2, material, flat)

            law, _ = read_contact_law(
                contact_tbl, name, hertz, projectile.mass, diameter, projectile.velocity, base, material, p.key("material"), sphere.length
            )
        contact_tbl.done()
    solver = read_solver(top.table("solver"))
    gauges = read_gauges(top, bar.length)
    snapshots = ()
    output = top.table("output", optional=True)
    if output is not None:
        raw = output.raw("snapshots", [])
        if not isinstance(raw, list):
            raise InputError(f"output.snapshots: expected a list of times, got {raw!r}")
        snapshots = tuple(units.parse(v, "time", f"output.snapshots[{i}]") for i, v in enumerate(raw))
        for i, t in enumerate(snapshots):
            if not 0 <= t <= solver.duration:
                raise InputError(f"output.snapshots[{i}]: {raw[i]!r} is outside the run (0 to {top.raw('solver')['duration']})")
        output.done()
    top.done()
    with naming({"gauges": "gauges", "law": "contact.law"}):
        return BarImpactProblem(bar, projectile, solver, gauges, law, title, snapshots)


def load_bar_case(case: str) -> tuple[BarImpactProblem, Path]:
    """Read a bar case by path or built-in name; returns the problem and its file."""
    path = locate(case)
    problem = bar_problem(load_case_toml(path, "bar"), path.parent)
    with naming({"elements": "bar.elements", "time_step": "solver.time_step"}):
        check_problem(problem)
    return problem, path
