"""Impact case files (``softimpact impact``): TOML → :class:`ImpactProblem`.

``[target]`` (``case``: a beam or plate case, file or built-in name; its ``[load]``
position is the impact point, its force history is ignored), ``[impactor]``
(``material``, ``diameter``, ``velocity`` toward the target, optional ``mass``; or a ``threat``,
``{ hail = "38.1 mm" }``: :mod:`softimpact.input.projectile`),
``[contact]`` (``law`` = hertz | hertz-unloading | hunt-crossley | identified |
crushing (an ice impactor) | hydrodynamic (a gelatin impactor), with the law's own keys),
``[solver]`` and optional ``[[gauges]]`` (default: the target case's, beam or plate gauges
as the target); an optional ``[damage]`` with ``cohesive = [{ between = [k, k + 1] }, ...]`` splits a
plate target's laminate into sublaminates tied by cohesive interfaces (:func:`read_cohesive`). See README.md,
``data/cases/paper-long-beam-impact.toml`` and ``data/cases/plate-ss-8in-impact.toml``.

Contact keys: those of :mod:`softimpact.input.contact_law`, and for the Hertz
laws ``target_modulus`` (default: a laminate's through-thickness modulus E3 of
its ply, Sun's form, for a beam or a plate; an isotropic beam: Hertz with its material).
"""

from __future__ import annotations

from pathlib import Path

from ..errors import InputError
from ..models.cohesive import BilinearCohesive
from ..models.contact_laws import HertzLaw
from ..models.materials import Material
from ..workflows.beam_impact import BeamProblem
from ..workflows.coupled import Impactor, ImpactProblem
from ..workflows.plate import PlateProblem
from .beam_case import beam_problem, read_beam_gauges
from .contact_law import CONTACT_LAWS, read_contact_law
from .plate_case import plate_problem, read_plate_gauges
from .projectile import read_sphere
from .toml import Table, load_case_toml, load_toml, locate, naming, read_solver, read_units

__all__ = ["CONTACT_LAWS", "ImpactProblem", "impact_problem", "load_impact_case"]


def _mirrors_through_impact(target: PlateProblem, where: str) -> None:
    """A plate struck by an impactor: a dynamic plate with an impact point (a static plate under a uniform pressure has
    neither steps nor a load point: refused naming it); its symmetry edges mirror the impactor too, so each must pass
    through the impact point (a half or quarter model of one impact), else the model would be struck twice."""
    if target.analysis == "static":
        raise InputError(
            f"{where}: a static plate case (solver.analysis = 'static', a uniform pressure): an impact strikes a dynamic plate "
            "at its load.position; give a plate case with a [load] position and a [solver] time step"
        )
    mirrored = target.mirrored_edges()
    if mirrored:
        raise InputError(
            f"{where}: plate.support.{mirrored[0]} is a symmetry edge that does not pass through the impact point "
            f"(load.position): it would mirror the impactor; put the impact point on it or model the whole plate"
        )


# The target cases an impact strikes, by the table only that kind of case has: its reader, the reader of an
# impact case's own [[gauges]] for it, and a check of the target as struck (None: nothing more to check).
TARGETS = (("plate", plate_problem, read_plate_gauges, _mirrors_through_impact), ("beam", beam_problem, read_beam_gauges, None))


def _target(tbl: Table, base: Path):
    """The target case (a plate or beam case, by its table: :data:`TARGETS`) as a problem, its path and its row of :data:`TARGETS`."""
    case = tbl.string("case")
    path = base / case if (base / case).is_file() else locate(case)
    try:
        data = load_toml(path)
        if "projectile" in data:  # a bar case: cases.impact.bar_target runs it for sweep and converge
            raise InputError(
                "a bar case: `softimpact impact` strikes beams and plates (run a bar with `softimpact bar`; sweep and converge take this impact case)"
            )
        row = next((r for r in TARGETS if r[0] in data), TARGETS[-1])  # no [plate]: a beam case (its reader names what is missing)
        problem = row[1](data, path.parent)
    except InputError as exc:
        raise InputError(f"{tbl.key('case')} ({path}): {exc}") from None
    return problem, path, row


def _hertz(c: Table, target: BeamProblem | PlateProblem, radius: float, sphere: Material) -> HertzLaw:
    if "target_modulus" in c or target.stack is not None:
        default = target.stack.ply.E3 if target.stack is not None else None
        with naming({"transverse modulus E2": c.key("target_modulus")}):
            return HertzLaw.sphere_on_laminate(radius, sphere, c.quantity("target_modulus", "stress", default=default))
    return HertzLaw.sphere_on_flat(radius, sphere, target.material)


def impact_problem(data: dict, base: Path = Path(".")) -> tuple[ImpactProblem, tuple[Path, ...]]:
    """An impact case (parsed TOML) as an ImpactProblem, and the files it read (target case, law file)."""
    top = Table(data)
    title = top.string("title", "")
    read_units(top)  # checked here; the display system is the edge's (input.toml.case_units), not the problem's
    t = top.table("target")
    target, target_path, (_, _, read_gauges, check) = _target(t, base)
    if check is not None:
        check(target, f"{t.key('case')} ({target_path})")
    t.done()
    i = top.table("impactor")
    sphere = read_sphere(i)
    material, diameter, velocity = sphere.material, sphere.diameter, sphere.velocity
    impactor = Impactor(sphere.mass, diameter, velocity)
    i.done()
    c = top.table("contact")
    name = c.string("law", choices=CONTACT_LAWS)
    law, law_path = read_contact_law(
        c, name, lambda: _hertz(c, target, diameter / 2, material), impactor.mass, diameter, velocity, base, material, i.key("material"), sphere.length
    )
    c.done()
    solver = read_solver(top.table("solver"))
    gauges = read_gauges(top) if "gauges" in top else target.gauges
    cohesive = read_cohesive(top.table("damage", optional=True), target, diameter)
    top.done()
    with naming({"gauges": "gauges", "time_step": "solver.time_step", "position": f"target.case ({target_path}): load.position"}):
        resolved = target.for_impact(solver, gauges)  # the force comes from the contact
    if cohesive is not None:
        from ..workflows.plate.cohesive import CohesivePlateProblem

        splits, interface_law, zone = cohesive
        names = {"cohesive": "damage.cohesive", "kinematics": f"target.case ({target_path}): plate.kinematics"}
        names.update({k: f"damage.{k}" for k in ("near_field", "element_size", "turon")})
        with naming(names):
            resolved = CohesivePlateProblem.of(resolved, splits, interface_law, **zone)
    files = (target_path,) if law_path is None else (target_path, law_path)
    return ImpactProblem(resolved, str(target_path), impactor, material, name, law, title, sphere.threat), files


NEAR_FIELD_DIAMETERS = 1.5  # the stacked near field's default half-width, in impactor diameters (a drop weight's delaminations reach ~1-2 d)


def read_cohesive(d: Table | None, target, diameter: float | None = None) -> tuple[tuple[int, ...], BilinearCohesive, dict] | None:
    """``[damage]``: ``cohesive``, the interfaces ``[{ between = [k, k + 1] }, ...]`` (plies counted from the top,
    1 = the top ply) or ``"dissimilar"`` (every interface between plies of different angles) tying a plate's
    sublaminates, and their bilinear law (:class:`~softimpact.models.cohesive.BilinearCohesive`):
    ``penalty`` [N/m³] (required: the interface stiffness is a modelling choice), ``G_Ic`` (required: the
    catalogue's plies have no mode-I toughness), ``bk_exponent`` (Benzeggagh–Kenane's η, required), and by default
    the ply's ``G_IIc``, its transverse tensile strength Y_t as ``normal_strength`` and its in-plane shear strength
    S12 as ``shear_strength``; the stacked near field's half-width ``near_field`` (default
    :data:`NEAR_FIELD_DIAMETERS` impactor diameters; ``"whole"``: the whole plate on its own mesh), its
    ``element_size`` (default: the process zone's, :meth:`~softimpact.workflows.plate.cohesive.CohesivePlateProblem.resolution`)
    and ``turon`` (Turon et al.'s strengths for that size; default false). None without a ``[damage]`` table."""
    if d is None:
        return None
    if not isinstance(target, PlateProblem):
        raise InputError(f"{d.key('cohesive')}: cohesive interfaces split a plate's laminate: the target is not a plate")
    angles = getattr(target.plate.stack, "angles", None) or ()
    n = len(angles)
    if d.raw("cohesive", None) == "dissimilar":
        splits = [k for k in range(1, n) if angles[k - 1] != angles[k]]
        if not splits:
            raise InputError(f"{d.key('cohesive')}: 'dissimilar': the laminate has no two adjacent plies of different angles")
    else:
        rows = d.tables("cohesive")
        if not rows:
            raise InputError(f"{d.key('cohesive')}: name at least one interface ({{ between = [k, k + 1] }}) or 'dissimilar'")
        splits = []
        for row in rows:
            pair = row.raw("between")
            if not (isinstance(pair, list) and len(pair) == 2 and all(isinstance(k, int) and not isinstance(k, bool) for k in pair) and pair[1] == pair[0] + 1):
                raise InputError(f"{row.key('between')}: expected two consecutive ply numbers [k, k + 1] (1 = the top ply), got {pair!r}")
            if not 1 <= pair[0] < n:
                raise InputError(f"{row.key('between')}: plies {pair!r} are not both in the laminate's {n} plies (a layup is needed)")
            if pair[0] in splits:
                raise InputError(f"{row.key('between')}: the interface {pair!r} is named twice")
            splits.append(pair[0])
            row.done()
    strength = target.plate.stack.ply.strength
    ply = "the ply's" if strength is not None else None

    def from_ply(key, kind, value):
        got = d.quantity(key, kind, default=None)
        if got is None and value is None:
            raise InputError(f"{d.key(key)}: missing (required: the ply {target.plate.stack.ply.name} has no strengths to default to)")
        return value if got is None else got

    with naming(
        {
            k: d.key(v)
            for k, v in (("K", "penalty"), ("N", "normal_strength"), ("S", "shear_strength"), ("GIc", "G_Ic"), ("GIIc", "G_IIc"), ("eta", "bk_exponent"))
        }
    ):
        law = BilinearCohesive(
            K=d.quantity("penalty", "interface_stiffness"),
            N=from_ply("normal_strength", "stress", ply and strength.Yt),
            S=from_ply("shear_strength", "stress", ply and strength.S12),
            GIc=d.quantity("G_Ic", "toughness"),
            GIIc=from_ply("G_IIc", "toughness", ply and strength.GIIc),
            eta=d.number("bk_exponent"),
        )
    if d.raw("near_field", None) == "whole":
        near = None
        if "element_size" in d:
            raise InputError(f"{d.key('element_size')}: the whole plate stacked keeps its own mesh; an element size goes with a near field")
    else:
        default = None if diameter is None else NEAR_FIELD_DIAMETERS * diameter
        near = d.quantity("near_field", "length", default=default)
        if diameter is not None and near is not None and near <= diameter:
            raise InputError(
                f"{d.key('near_field')}: a near field of half-width {near * 1e3:.4g} mm does not hold the contact, which may reach the "
                f"impactor's diameter ({diameter * 1e3:.4g} mm) from the impact point: give more than that (the default, "
                f"{NEAR_FIELD_DIAMETERS:g} diameters, {NEAR_FIELD_DIAMETERS * diameter * 1e3:.4g} mm)"
            )
    zone = {"near_field": near, "element_size": d.quantity("element_size", "length", default=None), "turon": d.raw("turon", False)}
    if not isinstance(zone["turon"], bool):
        raise InputError(f"{d.key('turon')}: expected true or false, got {zone['turon']!r}")
    d.done()
    return tuple(splits), law, zone


def load_impact_case(case: str) -> tuple[ImpactProblem, tuple[Path, ...]]:
    """Read an impact case by path or built-in name; returns the problem and every file it read (case first)."""
    path = locate(case)
    problem, files = impact_problem(load_case_toml(path, "impact"), path.parent)
    return problem, (path, *files)
