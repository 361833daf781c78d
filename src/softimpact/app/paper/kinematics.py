"""The paper report's threshold maps on two kinematics: the 8-in plate's map with von Kármán kinematics beside the
linear one (every nonlinear run stepped directly, :mod:`softimpact.studies.thresholds`), and the beams' large-deflection
check at one threshold (their total Lagrangian form, ``[beam] kinematics = "von-karman"``), as the tables, figures and
paragraphs of the thresholds section (:mod:`softimpact.app.paper.thresholds`).
"""

from __future__ import annotations

import math

from ...studies.paper.thresholds import MAP_RANGE_IN_S, VK_PLATE_MESHES, beam_kinematics_check, paper_kinematics_maps
from ...units import INCH

__all__ = ["paper_kinematics_maps", "kinematics_parts"]


def kinematics_parts(maps: list[dict], figures: bool, files: dict, prefix: str, system: str, vu):
    """What the thresholds section shows of the two kinematics: (figures, table, paragraphs, summary line), from
    the plate's maps on both kinematics and the linear ``maps`` of every structure (the beams' rows)."""
    linear, nonlinear = paper_kinematics_maps()
    figs = _kinematics_files(linear, nonlinear, figures, files, prefix, system)
    table, pairs = _kinematics_table(linear, nonlinear, vu)
    text = _kinematics_text(pairs, linear, nonlinear) + [_beams_text(maps, vu)]
    return figs, table, text, _kinematics_headline(linear, nonlinear, maps)


def _kinematics_headline(linear: list[dict], nonlinear: list[dict], maps: list[dict]) -> str:
    """The validity of the maps and the von Kármán plate's change, as one summary line (the same rows as the tables)."""
    from ...models.validity import DEFLECTION_OVER_THICKNESS

    checked = [r for r in maps if r.get("inside_validity") is not None]
    past = sum("deflection_past_linear" in r["validity_flags"] for r in checked)
    parts = []
    for i in dict.fromkeys(r["index"] for r in linear):
        v = [
            b["threshold_velocity_nominal_m_s"] / a["threshold_velocity_nominal_m_s"]
            for a, b in zip(linear, nonlinear)
            if a["index"] == i and math.isfinite(a["threshold_velocity_nominal_m_s"]) and math.isfinite(b["threshold_velocity_nominal_m_s"])
        ]
        if v:
            parts.append(f"{i} × {min(v):.3f}-{max(v):.3f}")
    return (
        f"Threshold maps' validity: {past} of {len(checked)} thresholds deflect the structure past w/h = {DEFLECTION_OVER_THICKNESS:g} "
        f"(linear theory); the plate's von Kármán map against its linear one on the same mesh: " + ", ".join(parts)
    )


def _kinematics_files(linear: list[dict], nonlinear: list[dict], figures: bool, files: dict, prefix: str, system: str) -> list[tuple[str, str]]:
    """The plate's linear and von Kármán maps written into ``files`` (plate-kinematics-map.csv, and the figure with
    ``figures``); returns the figure's (path, caption)."""
    from ...output.files import figure_bytes
    from ...output.sweep import kinematics_map_figure, threshold_csv

    files[f"{prefix}plate-kinematics-map.csv"] = threshold_csv(linear + nonlinear)
    if not figures:
        return []
    title = "8-in plate (quarter, 16 elements a side): threshold maps with linear and von Kármán kinematics, same law and balls"
    files[f"{prefix}plate-kinematics-map.png"] = figure_bytes(kinematics_map_figure(linear + nonlinear, system, title))
    return [
        (
            f"{prefix}plate-kinematics-map.png",
            "The plate's threshold maps with linear (solid, shaded band) and von Kármán kinematics (dashed, hatched band: the linear "
            "map's relative band carried over, widened by the nonlinear map's own GCI), per index, against the ball's diameter; "
            "open markers: outside validity at the threshold; below, the ratio of the von Kármán threshold to the linear one on the map's "
            "mesh and on the coarser mesh",
        )
    ]


def _kinematics_table(linear: list[dict], nonlinear: list[dict], vu) -> tuple[tuple, list]:
    """The plate's linear and von Kármán thresholds side by side with their validity: (table, the (linear, von Kármán)
    row pairs)."""

    def cell(r):
        if not r["draws_reaching_1"] or not math.isfinite(r["threshold_velocity_nominal_m_s"]):
            return f"above {MAP_RANGE_IN_S[1]:.0f}"
        return f"{r['threshold_velocity_nominal_m_s'] * vu.factor:.0f} ± {r['discretisation_error_m_s'] * vu.factor:.0f}"

    pairs = [(a, next(b for b in nonlinear if (b["index"], b["diameter_m"]) == (a["index"], a["diameter_m"]))) for a in linear]
    rows = []
    for a, b in pairs:
        ratio = b["threshold_velocity_nominal_m_s"] / a["threshold_velocity_nominal_m_s"]
        rows.append(
            [
                f"{a['index']}, d = {a['diameter_m'] / INCH:.3g} in",
                cell(a),
                cell(b),
                f"{ratio:.4f}",
                f"{a['deflection_over_thickness']:.2f} / {b['deflection_over_thickness']:.2f}",
                f"{a['max_strain_index']:.3f} / {b['max_strain_index']:.3f}",
                "inside" if a["inside_validity"] else ", ".join(a["validity_flags"]),
                "inside" if b["inside_validity"] else ", ".join(b["validity_flags"]),
            ]
        )
    table = (
        f"8-in plate, quarter on {VK_PLATE_MESHES[1][0]} MITC4 elements a side: threshold velocity [{vu.label}] of the law's mean ± the "
        "two-mesh GCI, linear and von Kármán kinematics, with w/h and the maximum-strain index at each threshold (linear / von Kármán) "
        "and the flags raised",
        ["index, ball", "linear", "von Kármán", "ratio", "w/h", "ε/ε_a", "linear: validity", "von Kármán: validity"],
        rows,
    )
    return table, pairs


def _kinematics_text(pairs: list, linear: list[dict], nonlinear: list[dict]) -> list[str]:
    """The paragraphs on the plate's two maps: how the von Kármán one is computed, and what changes and why
    (``pairs``: (linear row, von Kármán row) of one index and ball, :func:`_kinematics_table`'s)."""
    from ...models.validity import DEFLECTION_OVER_THICKNESS

    indices = list(dict.fromkeys(r["index"] for r in linear))
    past = [(a, b) for a, b in pairs if a["deflection_over_thickness"] > DEFLECTION_OVER_THICKNESS]
    gci = [r["discretisation_error_m_s"] / r["threshold_velocity_nominal_m_s"] for r in nonlinear if math.isfinite(r["discretisation_error_m_s"])]
    wh_lin = [a["deflection_over_thickness"] for a, _ in pairs]
    wh_vk = [b["deflection_over_thickness"] for _, b in pairs]

    def ratio(a, b, key):
        return b[key] / a[key] if math.isfinite(a[key]) and math.isfinite(b[key]) else math.nan

    def moved(i):
        mine = [(a, b) for a, b in pairs if a["index"] == i]
        fine = [ratio(a, b, "threshold_velocity_nominal_m_s") for a, b in mine]
        coarse = [ratio(a, b, "threshold_velocity_coarse_mesh_m_s") for a, b in mine]
        if not all(math.isfinite(x) for x in fine + coarse):
            return f"{i}: not every threshold reached"
        text = f"{i} × {min(fine):.4f}-{max(fine):.4f} [{min(coarse):.4f}-{max(coarse):.4f}]"
        if max(fine + coarse) < 1.0:
            return text + ", lower on both meshes for every ball"
        if min(fine + coarse) > 1.0:
            return text + ", higher on both meshes for every ball"
        unsure = [f"{a['diameter_m'] / INCH:.3g}" for (a, _), f, c in zip(mine, fine, coarse) if (f - 1.0) * (c - 1.0) <= 0.0]
        return text + (f", its sense changing with the mesh for the {', '.join(unsure)}-in balls (not resolved by these meshes)" if unsure else "")

    return [
        "The plate's map inside validity: the same quarter plate with von Kármán kinematics (in-plane displacements and membrane forces "
        'coupled to bending, the edges immovable in their plane; plate.kinematics = "von-karman"), every run stepped directly by '
        "the nonlinear plate's Newmark–Newton with the contact inside its Newton (no kernels: they hold a linear structure's impulse "
        "responses), the same identified law with its Maxwell arm, balls and indices, each threshold found by the same root-finding "
        "starting from the linear one ("
        + f"{min(r['nominal_threshold_runs'] for r in nonlinear)}-{max(r['nominal_threshold_runs'] for r in nonlinear)} runs a threshold, "
        "then one at V* for its validity and the coarse mesh's root-finding). A nonlinear run costs about a dozen linear direct ones on "
        "this mesh, so both maps of this comparison are on quarters of "
        f"{VK_PLATE_MESHES[1][0]} elements a side at {VK_PLATE_MESHES[1][1] * 1e6:g} µs, with the discretisation error from "
        f"{VK_PLATE_MESHES[0][0]} at {VK_PLATE_MESHES[0][1] * 1e6:g} µs (two-mesh GCI as above: "
        f"{min(gci):.1%}-{max(gci):.1%} of the von Kármán thresholds; the Tsai-Wu point strain under the load converges slowly, as the "
        "linear map's 32 and 64 elements show, the force-based delamination index fast). The von Kármán bands carry the linear map's "
        "relative law-and-strength band over (band_from = linear map in plate-kinematics-map.csv) rather than drawing the law again. "
        "The comparison reads the ratio of the two thresholds on one mesh; how much that ratio changes between the two meshes says how "
        "far it is resolved.",
        "What changes (the von Kármán threshold over the linear one on the map's mesh, on the coarser mesh in brackets): "
        + "; ".join(moved(i) for i in indices)
        + f". At the thresholds the linear plate deflects to w/h {min(wh_lin):.2f}-{max(wh_lin):.2f} ({len(past)} of the {len(pairs)} "
        f"past the linear limit {DEFLECTION_OVER_THICKNESS:g}), the von Kármán plate to {min(wh_vk):.2f}-{max(wh_vk):.2f}: the membrane "
        "stretching of the mid-surface stiffens the plate as (w/h)², so the same impact deflects it less and the contact, pressing a "
        "stiffer plate, carries a higher peak force: the delamination index, the peak force over P_c, reaches 1 at a lower velocity. "
        "Under the load the bending strain follows the smaller curvature down while the membrane strain, a stretching of the mid-surface, "
        "adds tension on both faces; Tsai-Wu reads their sum, and which wins depends on w/h and on how finely the mesh resolves the "
        "strain under the load (the ratios above). The force moves least: the soft ball's contact is far more compliant than the plate "
        "(the three structures' delamination thresholds differ by little, above), so a stiffer plate changes the peak force little. "
        "The stiffening grows as (w/h)², so a thinner skin or a heavier ball moves both further. The von Kármán rows carry no deflection flag (the model holds past "
        "w/h = 0.5); the flags they keep are the law's (its contact radius past the ball's, its fitted range) and the strains'.",
    ]


def _beams_text(maps: list[dict], vu) -> str:
    """The paragraph on the beams' maps: linear and flagged, and the large-deflection check at one threshold
    (:func:`beam_kinematics_check`) that bounds what crossing the linear limit moves."""
    checked = [r for r in maps if r.get("inside_validity") is not None and "beam" in r["structure"]]
    beams = {n: [r["deflection_over_thickness"] for r in checked if r["structure"] == n] for n in dict.fromkeys(r["structure"] for r in checked)}
    return (
        "The beams' maps above are linear and flagged: their thresholds deflect them to w/h "
        + ", ".join(f"{min(v):.1f}-{max(v):.1f} ({n})" for n, v in beams.items())
        + ". Both beams are cantilevers (clamped-free): the free end carries no membrane tension, so large deflection changes "
        "them little. Checked at the 1/2-in ball's delamination threshold on the map's mesh, the beam's total Lagrangian form "
        '([beam] kinematics = "von-karman") against the linear run at the same velocity: '
        + "; ".join(
            f"{n}, {v * vu.factor:.0f} {vu.label}: peak force {100 * (fn / fl - 1):+.4f} %, w/h {wl:.2f} linear, {wn:.2f} nonlinear"
            for n, v, fl, fn, wl, wn in beam_kinematics_check()
        )
        + ". The beams' maps are therefore not recomputed nonlinear (a total Lagrangian run costs several linear ones and the "
        "maps run on contact kernels): their deflection flag marks the linear theory's limit, and the check above bounds what "
        "crossing it moves. The flags the beams' rows keep are the law's (contact radius past the ball's, fitted range)."
    )
