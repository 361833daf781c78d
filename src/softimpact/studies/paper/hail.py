"""The paper report's hail computations: Rhymer's three panels as plate cases of the stand-in ply, and the hail map
(:func:`softimpact.studies.hail.hail_map`, delamination onset of ice spheres from coupled impact with the crushing law)
on the linear and the von Kármán panels, one panel at a time (each a task of the report, :mod:`softimpact.studies.tasks`).
"""

from __future__ import annotations

from ...models.laminate import PLIES
from ..hail import RHYMER_LAYUPS, RHYMER_THICKNESSES, STAND_IN_PLY, CatalogueIce, hail_map
from ..tasks import once
from ..thresholds import ONSET

__all__ = [
    "BASE_CASE",
    "HAIL_MESHES",
    "VK_MESHES",
    "HAIL_DURATION",
    "HAIL_RANGE",
    "hail_plate_case",
    "panel_target",
    "panel_rows",
    "panel_vk_rows",
    "hail_rows",
    "hail_vk_rows",
    "paper_hail_map",
]

BASE_CASE = "hail-plate-qi"  # the panel's size, supports and load point

HAIL_MESHES = ((4, 4e-6), (8, 2e-6))  # (elements a side, step): coarse, map's — the section costs about 40 s of CPU
# the von Kármán panels' meshes (coarse, map's): each run steps the whole nonlinear plate, so coarser than the linear
# map's (6 × 6 at 3 µs is within 2 % of 8 × 8 at 2 µs on the peak force: the 1.59-mm panel, 61-mm ice at 8 m/s)
VK_MESHES = ((3, 6e-6), (6, 3e-6))
HAIL_DURATION = 1.5e-3  # s: the peaks come by 1.21 ms (measured: the 1.59-mm panel, 61-mm sphere; a 4-ms run has the same peak)
HAIL_RANGE = (5.0, 300.0)  # m/s: the velocities searched (the lowest onset is 11.7 m/s)


def _ply_table(thickness: float) -> dict:
    """The stand-in ply as a case file's inline ply: the catalogue's IM7/8552, its thickness ``thickness`` [m]."""
    p = PLIES[STAND_IN_PLY]
    s = p.strength
    pa = {k: f"{getattr(p, k)!r} Pa" for k in ("E1", "E2", "E3", "G12", "G13", "G23")}
    strengths = {"Xt": s.Xt, "Xc": s.Xc, "Yt": s.Yt, "Yc": s.Yc, "S": s.S12, "S23": s.S23}
    return {
        "name": f"{p.name} (stand-in for T800/3900-2)",
        **pa,
        "nu12": p.nu12,
        "nu13": p.nu13,
        "nu23": p.nu23,
        "density": f"{p.density!r} kg/m^3",
        "thickness": f"{thickness!r} m",
        **{k: f"{v!r} Pa" for k, v in strengths.items()},
        "G_IIc": f"{s.GIIc!r} J/m^2",
        "source": f"{p.source}; thickness set to the panel's over its plies",
    }


def hail_plate_case(
    thickness: float, layup: str, elements: int, duration: float, kinematics: str = "linear", side: float | None = None, support: str | None = None
) -> dict:
    """The panel as a plate case (parsed TOML): :data:`BASE_CASE` with the stand-in ply of ``thickness``/plies,
    ``layup``, ``elements`` a side, ``duration`` [s], ``kinematics`` ("linear" or "von-karman"); no gauges. ``side`` [m]
    and ``support`` (of all four edges) replace the base case's square and supports, struck at the centre (None: the
    base case's; benchmarks/hail_panel_sensitivity.py varies them)."""
    from ...input.toml import load_toml, locate
    from ...models.laminate import parse_layup

    data = load_toml(locate(BASE_CASE))
    plies = len(parse_layup(layup))
    data["title"] = f"Rhymer's {thickness * 1e3:.2f}-mm panel, {layup} of the {STAND_IN_PLY} stand-in"
    data["plate"]["laminate"] = {"ply": _ply_table(thickness / plies), "layup": layup}
    data["plate"]["elements"] = [elements, elements]
    data["solver"]["duration"] = f"{duration / 1e-6!r} us"
    if kinematics != "linear":
        data["plate"]["kinematics"] = kinematics
    if side is not None:
        data["plate"]["length"] = data["plate"]["width"] = f"{side!r} m"
        data["load"]["position"] = [f"{side / 2!r} m"] * 2
    if support is not None:
        data["plate"]["support"] = dict.fromkeys(("x0", "x1", "y0", "y1"), support)
    data.pop("gauges", None)
    return data


def panel_target(
    thickness: float, layup: str, elements: int, duration: float, kinematics: str = "linear", side: float | None = None, support: str | None = None
):
    """The resolved plate target of :func:`hail_plate_case` (what :func:`softimpact.studies.hail.hail_map` builds its
    threshold structures on)."""
    from ...input.plate_case import plate_problem
    from ...input.toml import locate

    return plate_problem(hail_plate_case(thickness, layup, elements, duration, kinematics, side, support), locate(BASE_CASE).parent)


@once
def panel_rows(k: int) -> tuple:
    """The linear hail map's rows of panel ``k`` (of :data:`~softimpact.studies.hail.RHYMER_THICKNESSES`), once per run."""
    h, layup = RHYMER_THICKNESSES[k], RHYMER_LAYUPS[k]
    return tuple(hail_map(CatalogueIce(), panel_target, (h,), layups=(layup,), meshes=HAIL_MESHES, duration=HAIL_DURATION, lo=HAIL_RANGE[0], hi=HAIL_RANGE[1]))


@once
def panel_vk_rows(k: int) -> tuple:
    """Olsson's onset on von Kármán panel ``k`` (:data:`VK_MESHES`), each root's secant steps from the linear map's V*."""
    h, layup = RHYMER_THICKNESSES[k], RHYMER_LAYUPS[k]
    return tuple(
        hail_map(
            CatalogueIce(),
            panel_target,
            (h,),
            layups=(layup,),
            meshes=VK_MESHES,
            duration=HAIL_DURATION,
            lo=HAIL_RANGE[0],
            hi=HAIL_RANGE[1],
            indices=(ONSET,),
            kinematics="von-karman",
            guesses=panel_rows(k),
        )
    )


def hail_rows() -> tuple:
    """The linear hail map's rows, panel by panel (:func:`panel_rows`)."""
    return tuple(r for k in range(len(RHYMER_THICKNESSES)) for r in panel_rows(k))


def hail_vk_rows() -> tuple:
    """The von Kármán panels' onset rows, panel by panel (:func:`panel_vk_rows`)."""
    return tuple(r for k in range(len(RHYMER_THICKNESSES)) for r in panel_vk_rows(k))


def paper_hail_map() -> list[dict]:
    """The hail map's rows (:meth:`~softimpact.studies.hail.HailRow.as_dict`, SI), computed once per process."""
    return [r.as_dict() for r in hail_rows()]
