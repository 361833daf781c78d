"""Beam case files (``softimpact beam``, ``calibrate``): TOML → :class:`BeamProblem`.

``[beam]`` (``[beam.laminate]`` or ``[beam.material]``, ``[beam.damping]``, ``kinematics``:
``"linear"``, the default, or ``"von-karman"``, large deflection: the plane model's total Lagrangian
form, :mod:`softimpact.fem.plane_tl`),
``[load]`` (with its ``history`` and ``[[load.table]]`` rows), ``[solver]`` and
``[[gauges]]``; see README.md and ``data/cases/paper-long-beam.toml``.
"""

from __future__ import annotations

import math
from pathlib import Path

from .. import units
from ..errors import InputError
from ..fem.plane import SUPPORTS
from ..fem.plate_vk import KINEMATICS
from ..models.empirical import PRESETS, PROJECTILES, ScalingLaw
from ..models.laminate import PLANES, PLIES, STRENGTH_KEYS, Blend, Ply, PlyStrength, Stack, parse_layup
from ..models.materials import Material
from ..models.pulses import SkewedPulse, TabulatedPulse
from ..workflows.beam_impact import LAMINATE_MODELS, BeamGauge, BeamLoad, BeamProblem, BeamSpec, check_problem
from .records import read_columns
from .toml import Table, load_case_toml, load_toml, locate, naming, read_material, read_solver, read_units

__all__ = [
    "HISTORY_SHAPES",
    "MASS_MATRICES",
    "read_ply",
    "read_strength",
    "read_history",
    "read_load_history",
    "read_beam_gauges",
    "beam_problem",
    "load_beam_case",
    "table_rows",
]

HISTORY_SHAPES = ("skewed", "table", "empirical")  # eq (15), a CSV table, the empirical model of eqs (4)-(7)
MASS_MATRICES = ("consistent", "lumped")


def read_ply(tbl: Table, name: str = "ply"):
    value = tbl.raw(name)
    if isinstance(value, str):
        if value not in PLIES:
            raise InputError(f"{tbl.key(name)}: unknown ply {value!r} (catalogue: {', '.join(PLIES)})")
        return PLIES[value]
    p = Table(value, tbl.key(name))
    mods = {k: p.quantity(k, "stress") for k in ("E1", "E2", "E3", "G12", "G13", "G23")}
    ply = Ply(
        p.string("name", "inline ply"),
        mods["E1"],
        mods["E2"],
        mods["E3"],
        mods["G12"],
        mods["G13"],
        mods["G23"],
        p.number("nu12"),
        p.number("nu13"),
        p.number("nu23"),
        p.quantity("density", "density"),
        p.quantity("thickness", "length"),
        p.string("source", "user input"),
        read_strength(p),
    )
    p.done()
    return ply


def read_strength(p: Table) -> PlyStrength | None:
    """An inline ply's strengths: Xt, Xc, Yt, Yc, S (stresses), G_IIc (energy per area), optional S23
    (Hashin's transverse shear strength, default S). None when the table gives none of them; some
    but not all is an error naming the missing keys. A catalogue ply's name in ``name`` gives no
    strengths: they belong to the catalogue ply's moduli, not to this table's."""
    given = [k for k in STRENGTH_KEYS if k in p]
    if not given:
        if "S23" in p:
            raise InputError(f"{p.key('S23')}: given without the other strengths {', '.join(STRENGTH_KEYS)}")
        return None
    missing = [k for k in STRENGTH_KEYS if k not in p]
    if missing:
        raise InputError(
            f"{p.path}: strengths {', '.join(given)} given without {', '.join(missing)} (the damage outputs need all of {', '.join(STRENGTH_KEYS)})"
        )
    s = {k: p.quantity(k, "stress") for k in ("Xt", "Xc", "Yt", "Yc", "S")}
    return PlyStrength(s["Xt"], s["Xc"], s["Yt"], s["Yc"], s["S"], p.quantity("S23", "stress", default=s["S"]), p.quantity("G_IIc", "toughness"), "user input")


def read_history(tbl: Table, name: str, base: Path):
    """A force history: eq (15) ('skewed'), a CSV table ('table'), or the empirical model ('empirical')."""
    h = tbl.table(name)
    shape = h.string("shape", HISTORY_SHAPES[0], choices=HISTORY_SHAPES)
    if shape == "skewed":
        pulse = SkewedPulse(h.quantity("peak_force", "force"), h.quantity("time_of_peak", "time"), h.quantity("duration", "time"))
    elif shape == "table":
        path = base / h.string("file")
        names, data = read_columns(path)
        if "time_s" not in names or "force_N" not in names:
            raise InputError(f"{h.key('file')}: {path} needs columns time_s and force_N")
        pulse = TabulatedPulse(data[:, names.index("time_s")], data[:, names.index("force_N")])
    else:
        proj = h.string("projectile", choices=tuple(PROJECTILES))
        P = PROJECTILES[proj]
        law = PRESETS[h.string("constants", P.law, choices=tuple(PRESETS))]
        alphas = [f"alpha{i}" for i in range(1, 5)]
        if any(a in h for a in alphas):  # the preset's α's, some replaced (sweeps draw them)
            with naming({a: h.key(a) for a in alphas}):
                law = ScalingLaw(*(h.number(a, getattr(law, a)) for a in alphas), name=f"{law.name} (alphas replaced)", source=h.path)
        velocity = h.quantity("velocity", "velocity")
        from ..models.validity import warn

        warn(law.envelope(P.diameter, velocity, f"{h.key('velocity')}: the empirical history of {law.name}"))
        pulse = law.pulse(P.mass, P.diameter, velocity)
    h.done()
    return pulse


def read_beam_gauges(top: Table) -> tuple[BeamGauge, ...]:
    """The ``[[gauges]]`` of a beam: name, position from the support, face, length."""
    gauges = []
    for g in top.tables("gauges", optional=True):
        gauges.append(
            BeamGauge(
                g.string("name"),
                g.quantity("position", "length", positive=False),
                g.string("surface", "bottom", choices=("top", "bottom")),
                g.quantity("length", "length", default=BeamGauge.length),
            )
        )
        g.done()
    if len({g.name for g in gauges}) != len(gauges):
        raise InputError("gauges: names must be unique")
    return tuple(gauges)


def read_load_history(ld: Table, base: Path, history: int | None, radius: float):
    """The ``[load]`` table's force history and contact radius: its ``history``, or with
    ``history`` = N the N-th row (1-based) of its ``[[load.table]]`` (eq-15 parameters,
    optionally its own contact radius). Shared by the beam and plate cases."""
    pulse = read_history(ld, "history", base)
    rows = ld.tables("table", optional=True)
    if history is not None:
        if not 1 <= history <= len(rows):
            raise InputError(f"load.table: history {history} is not a row of [[load.table]] (1 to {len(rows)})")
        row = rows[history - 1]
        pulse = SkewedPulse(row.quantity("peak_force", "force"), row.quantity("time_of_peak", "time"), row.quantity("duration", "time"))
        radius = row.quantity("contact_radius", "length", default=radius)
        row.quantity("velocity", "velocity", default=None)
        row.done()
    else:
        for row in rows:
            row._used.update(row.data)
    return pulse, radius


def _read_section(b: Table):
    """The beam's cross-section: ``[beam.laminate]`` (a layup, or a blend of angle fractions) or
    ``[beam.material]`` (isotropic, with its thickness), exactly one. Returns (stack, model, material, thickness)."""
    lam = b.table("laminate", optional=True)
    mat = b.table("material", optional=True)
    if (lam is None) == (mat is None):
        raise InputError("beam: give exactly one of [beam.laminate] and [beam.material]")
    stack = material = None
    thickness = 0.0
    model = "smeared"
    if lam is not None:
        ply = read_ply(lam)
        model = lam.string("model", LAMINATE_MODELS[0], choices=LAMINATE_MODELS)
        if "fractions" in lam:
            fr = lam.raw("fractions")
            if not isinstance(fr, dict) or not fr:
                raise InputError(f"beam.laminate.fractions: expected a table of angle = fraction, got {fr!r}")
            try:
                pairs = tuple((float(k), float(v)) for k, v in fr.items())
            except ValueError:
                raise InputError(f"beam.laminate.fractions: angles and fractions must be numbers, got {fr!r}") from None
            with naming({"fractions": lam.key("fractions"), "thickness": lam.key("thickness")}):
                stack = Blend(ply, pairs, lam.quantity("thickness", "length"))
        else:
            layup = lam.string("layup")  # (read outside the naming: its own errors name the key already)
            with naming({None: lam.key("layup")}):
                stack = Stack(ply, parse_layup(layup))
        lam.done()
    else:
        if "material" in mat:
            material = read_material(mat)
        else:
            material = Material(
                mat.string("name", "inline material"), mat.quantity("youngs_modulus", "stress"), mat.number("poisson_ratio"), mat.quantity("density", "density")
            )
        thickness = mat.quantity("thickness", "length")
        mat.done()
    return stack, model, material, thickness


def _read_damping(b: Table) -> tuple[float, float]:
    """Rayleigh damping (α, β) of ``[beam.damping]``: ζ(ω) = α/(2ω) + βω/2 equal to ``ratio`` at its two ``frequencies``; (0, 0) without one."""
    damping = (0.0, 0.0)
    d = b.table("damping", optional=True)
    if d is not None:
        ratio = d.number("ratio")
        freqs = d.raw("frequencies")
        if not (isinstance(freqs, list) and len(freqs) == 2):
            raise InputError(f"beam.damping.frequencies: expected two frequencies, got {freqs!r}")
        w1, w2 = (2 * math.pi * units.parse(f, "frequency", "beam.damping.frequencies") for f in freqs)
        # ζ(ω) = α/(2ω) + βω/2 equal to the ratio at both frequencies.
        damping = (2 * ratio * w1 * w2 / (w1 + w2), 2 * ratio / (w1 + w2))
        d.done()
    return damping


def beam_problem(data: dict, base: Path = Path("."), history: int | None = None):
    """A beam case (parsed TOML) as a BeamProblem; ``history`` picks a row of [[load.table]] (1-based)."""
    top = Table(data)
    title = top.string("title", "")
    read_units(top)  # checked here; the display system is the edge's (input.toml.case_units), not the problem's
    b = top.table("beam")
    elements = b.raw("elements", [200, 6])
    if not (isinstance(elements, list) and len(elements) == 2 and all(isinstance(e, int) and not isinstance(e, bool) and e >= 1 for e in elements)):
        raise InputError(f"beam.elements: expected [along the length, through the thickness], got {elements!r}")
    stack, model, material, thickness = _read_section(b)
    damping = _read_damping(b)
    with naming({"stack": "beam", "model": "beam.laminate.model"}):
        spec = BeamSpec(
            b.quantity("length", "length"),
            b.quantity("width", "length"),
            elements[0],
            elements[1],
            b.string("support", SUPPORTS[0], choices=SUPPORTS),
            stack,
            model,
            material,
            thickness,
            b.string("plane", PLANES[0], choices=PLANES),
            b.string("mass", MASS_MATRICES[0], choices=MASS_MATRICES) == "lumped",
            damping,
            kinematics=b.string("kinematics", KINEMATICS[0], choices=KINEMATICS),
        )
        with naming({k: f"beam.{k}" for k in ("length", "thickness", "width", "density", "elements")} | {"model": "beam.laminate.model"}):
            spec.plane_beam()
    b.done()
    ld = top.table("load")
    position = ld.quantity("position", "length")
    radius = ld.quantity("contact_radius", "length")
    pulse, radius = read_load_history(ld, base, history, radius)
    ld.done()
    solver = read_solver(top.table("solver"))
    gauges = read_beam_gauges(top)
    top.done()
    keys = {"position": "load.position", "gauges": "gauges", "time_step": "solver.time_step", "history": "load.history"}
    with naming(keys):
        return BeamProblem(spec, BeamLoad(position, radius, pulse), solver, tuple(gauges), title)


def load_beam_case(case: str, history: int | None = None):
    path = locate(case)
    problem = beam_problem(load_case_toml(path, "beam"), path.parent, history)
    with naming({"elements": "beam.elements"}):
        check_problem(problem)
    return problem, path


def table_rows(case: str) -> list[dict]:
    """The [[load.table]] rows of a beam case, in SI: velocity, F0, tF0, T, r0."""
    path = locate(case)
    out = []
    for row in Table(load_toml(path)).table("load").tables("table", optional=True):
        out.append(
            {
                "velocity": row.quantity("velocity", "velocity"),
                "peak_force": row.quantity("peak_force", "force"),
                "time_of_peak": row.quantity("time_of_peak", "time"),
                "duration": row.quantity("duration", "time"),
                "contact_radius": row.quantity("contact_radius", "length"),
            }
        )
    return out
