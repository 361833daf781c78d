"""The paper report's damage thresholds: threshold maps from COUPLED impact with the law identified
from the rubber series (:mod:`softimpact.studies.thresholds`: damage-onset velocity against the
ball's diameter, per structure, with bands from the law's draws, the strengths' scatter and the
mesh), beside the carried-over thresholds of PRESCRIBED force histories (the paper's beams and the
quarter of the 8-in plate swept over velocity with the α's of the built-in rubber series drawn
from their covariance, :mod:`softimpact.cases.sweep` in a plain loop), as a report section with
CSVs and figures.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ... import units
from ...cases.sweep import plan_sweep, plan_thresholds, prepare_group, run_chunk, run_table
from ...studies.paper.thresholds import (
    MAP_BEAM_MESHES,
    MAP_DRAWS,
    MAP_DURATION,
    MAP_PLATE_MESHES,
    MAP_RANGE_IN_S,
    MAP_STRENGTH_COV,
    PAPER_BEAMS,
    PAPER_PLATE,
    PAPER_PLATE_MESHES,
    paper_identification,
    paper_kinematics_maps,
    paper_onset_map,
    paper_plate_case,
    paper_threshold_maps,
)
from ...studies.tasks import once
from ...units import INCH

__all__ = [
    "threshold_section",
    "paper_thresholds",
    "paper_plate_thresholds",
    "plate_mesh_thresholds",
    "paper_plate_case",
    "paper_identification",
    "paper_threshold_maps",
    "paper_onset_map",
    "PAPER_PLATE",
    "MAP_RANGE_IN_S",
]

PAPER_PROJECTILES = {"rubber-3/8in": "0.375 in", "rubber-1/2in": "0.5 in"}  # projectile → its group in the fit
PAPER_DRAWS = 16  # α draws (Latin hypercube) per ball for the report's thresholds
PAPER_DAMAGE = ["damage.max_strain", "damage.tsai_wu", "damage.hashin", "damage.delamination"]


def paper_plate_thresholds(draws: int = PAPER_DRAWS, levels: int = 10, meshes: tuple[int, ...] = PAPER_PLATE_MESHES) -> list[dict]:
    """Threshold velocities of :func:`paper_plate_case` for both balls, as :func:`paper_thresholds`
    does for the beams (one plate model and one set of impulse responses for both), with
    their discretisation error.

    The thresholds are computed on each of ``meshes`` (elements a side of the quarter,
    coarse → fine, ratio 2) and reported on the finest, with Richardson's observed order
    and GCI over the last three (:func:`softimpact.workflows.convergence.richardson`,
    safety factor 1.25 when the observed order is near the formal 2, else 3; an oscillating sequence gets half its range, a diverging one the
    whole of its last change): ``discretisation_error_m_s`` is that GCI in m/s, and the
    5–95 % band of the α draws is widened by it on both sides, so the band covers the
    mesh's error too.
    """
    from ...workflows.convergence import richardson

    per_mesh = [plate_mesh_thresholds(elements, draws, levels) for elements in meshes]
    out = []
    for i, row in enumerate(per_mesh[-1]):
        values = np.array([rows[i]["threshold_velocity_median_m_s"] for rows in per_mesh], dtype=float)
        error, order = math.nan, math.nan
        if len(values) >= 3 and np.all(np.isfinite(values[-3:])):
            conv = richardson(values[-3:], 2.0, formal_order=2.0, name=f"{row['levels']} {row['index']}")
            order = conv.order
            gci = conv.gci_fine if math.isfinite(conv.gci_fine) else abs(values[-1] - values[-2]) / abs(values[-1])
            error = gci * abs(values[-1])
        widen = error if math.isfinite(error) else 0.0
        out.append(
            row
            | {
                "threshold_velocity_p05_m_s": row["threshold_velocity_p05_m_s"] - widen,
                "threshold_velocity_p95_m_s": row["threshold_velocity_p95_m_s"] + widen,
                "discretisation_error_m_s": error,
                "observed_order": order,
                "elements": meshes[-1],
            }
        )
    return out


@once
def plate_mesh_thresholds(elements: int, draws: int = PAPER_DRAWS, levels: int = 10) -> tuple[dict, ...]:
    """The prescribed-force thresholds of :func:`paper_plate_case` on ``elements`` a side of the quarter, both balls
    (:func:`paper_plate_thresholds`' rows of one mesh), once per run."""
    return tuple(_ball_thresholds(PAPER_PLATE, "8-in plate", draws, levels, paper_plate_case(elements)))


@once
def _paper_fit() -> dict:
    """The scaling.json contents of the built-in rubber series' fit (computed once per process; not to be changed)."""
    from ...formats.scaling_json import scaling_summary
    from ...studies.paper.series import rubber_series_fits

    return scaling_summary(rubber_series_fits())


def _paper_spec(case: str, projectile: str, draws: int, levels: int) -> dict:
    return {
        "sweep": {
            "case": case,
            "method": "latin-hypercube",
            "runs": draws,
            "seed": 1,
            "outputs": list(PAPER_DAMAGE),
            "parameter": [
                {"key": "load.history", "value": {"shape": "empirical", "projectile": projectile, "velocity": "1000 in/s"}},
                {"key": "load.history.velocity", "range": ["1000 in/s", "8000 in/s", levels]},
            ],
        }
    }


@once
def paper_thresholds(draws: int = PAPER_DRAWS, levels: int = 10) -> list[dict]:
    """Threshold velocities of the paper's beams for both balls: the α's drawn from the
    covariance of the built-in rubber series' fit, velocity 1000–8000 in/s (a plain loop)."""
    return [row for beam in PAPER_BEAMS for row in _ball_thresholds(beam, f"{beam.removeprefix('paper-').removesuffix('-beam')} beam", draws, levels)]


def _ball_thresholds(case: str, label: str, draws: int, levels: int, case_data: dict | None = None) -> list[dict]:
    """Threshold velocities of one structure (built-in ``case``, or ``case_data`` in its place) for
    each of the paper's balls, the α's drawn from the covariance of the built-in rubber series'
    fit; one model and one set of impulse responses serve both balls. Rows labelled "label, ball"."""
    import dataclasses

    from ...input.sweep_spec import Scaling, read_sweep_spec, scaling_covariance

    fit = _paper_fit()
    rows, prepared = [], None
    for proj, group in PAPER_PROJECTILES.items():
        spec = read_sweep_spec(_paper_spec(case, proj, draws, levels), Path("."))
        mean, cov = scaling_covariance(fit, group)
        parameters = spec.parameters + (Scaling("load.history", mean, cov, f"paper-rubber-series:{group}"),)
        spec = dataclasses.replace(spec, parameters=parameters, case_data=spec.case_data if case_data is None else case_data)
        plan = plan_sweep(spec)
        base = str(spec.case_path.parent)
        if prepared is None:
            prepared = prepare_group(plan.kind, [plan.chunks[0].items[0][1]], base, len(PAPER_PROJECTILES) * len(plan.runs), spec.outputs)
        done = {r["run"]: r for c in plan.chunks for r in run_chunk(plan.kind, prepared, c.items, base, spec.outputs)}
        rows += [{**t, "levels": f"{label}, {proj}"} for t in plan_thresholds(plan, run_table(plan, done))]
    return rows


def _threshold_files(beams, plate, maps, figures: bool, files: dict, prefix: str, system: str) -> list[tuple[str, str]]:
    """The threshold maps and curves written into ``files`` (CSV, and PNG with ``figures``); returns the figures' (path, caption)."""
    from ...output.files import figure_bytes
    from ...output.sweep import threshold_csv, threshold_figure, threshold_map_figure

    figs = []
    files[f"{prefix}threshold-maps.csv"] = threshold_csv(maps)
    if figures:
        files[f"{prefix}threshold-maps.png"] = figure_bytes(
            threshold_map_figure(
                maps,
                _prescribed_points(beams + plate),
                system,
                "Damage-onset velocity against the rubber ball's diameter: coupled impact, identified law (lines, bands) and prescribed force (squares)",
            )
        )
        figs.append(
            (
                f"{prefix}threshold-maps.png",
                "Threshold maps: velocity at which Tsai-Wu under the load or the Davies-Zhang index reaches 1, per structure, against the ball's "
                "diameter (mass ∝ d³): median over the identified law's draws and 5-95 % band (law draws × strength scatter, widened by the "
                "two-mesh GCI); squares: the prescribed-force thresholds of the Table I law below (beams: Tsai-Wu at the gauge sections)",
            )
        )
    for name, th, title, caption in (
        (
            "thresholds",
            beams,
            "Paper's beams: velocity at which a damage index first reaches 1",
            "Threshold velocity by criterion: median and 5-95 % band over the α draws",
        ),
        (
            "plate-thresholds",
            plate,
            "8 x 8 in simply supported [90/0]5s plate, struck at the centre: velocity at which a damage index first reaches 1",
            "The plate's threshold velocity by criterion and ball: median and 5-95 % band over the α draws, widened by the mesh's discretisation error",
        ),
    ):
        files[f"{prefix}{name}.csv"] = threshold_csv(th)
        if figures:
            files[f"{prefix}{name}.png"] = figure_bytes(threshold_figure(th, system, title))
            figs.append((f"{prefix}{name}.png", caption))
    return figs


def _threshold_cell(t: dict, vu) -> str:
    """One threshold row as a table cell: median [5-95 %] in display units, and the draws reaching 1 when not all did."""
    if not t["draws_reaching_1"]:
        return "above 8000"
    m, lo, hi = (t[f"threshold_velocity_{q}_m_s"] * vu.factor for q in ("median", "p05", "p95"))
    part = "" if t["draws_reaching_1"] == t["draws"] else f" ({t['draws_reaching_1']}/{t['draws']} draws)"
    return f"{m:.0f} [{lo:.0f}-{hi:.0f}]{part}"


def _plate_error_text(plate) -> str:
    """The plate's first-ply thresholds' discretisation errors and observed orders, as a phrase."""
    first_ply = [t for t in plate if t["index"] != "delamination" and math.isfinite(t["discretisation_error_m_s"])]
    if not first_ply:
        return "not estimable (a threshold above the range on a mesh)"
    return (
        "first-ply thresholds ± "
        + ", ".join(f"{t['discretisation_error_m_s'] / t['threshold_velocity_median_m_s']:.1%} ({t['index']}, {t['levels'].split(', ')[1]})" for t in first_ply)
        + f", observed orders {min(t['observed_order'] for t in first_ply):.2g}-{max(t['observed_order'] for t in first_ply):.2g}"
    )


def threshold_section(figures: bool, files: dict, prefix: str = "thresholds/"):
    """The report section: threshold velocity curves of the paper's beams and of a plate
    (first-ply failure, delamination), each as a CSV and a figure."""
    from ...output.report import Section
    from ...units import display
    from .kinematics import kinematics_parts

    system = "in-lbf-s"
    vu = display(system, "velocity")
    beams, plate = paper_thresholds(), paper_plate_thresholds()
    maps, onset = paper_threshold_maps(), paper_onset_map()
    figs = _threshold_files(beams, plate, maps, figures, files, prefix, system)
    figs += _onset_files(onset, figures, files, prefix, system)
    kin_figs, kin_table, kin_text, kin_headline = kinematics_parts(maps, figures, files, prefix, system, vu)
    figs += kin_figs
    plate_h = f"{PAPER_PLATE_MESHES[-1]} × {PAPER_PLATE_MESHES[-1]}"
    plate_err = _plate_error_text(plate)
    th = beams + plate
    labels = list(dict.fromkeys(t["levels"] for t in th))
    indices = list(dict.fromkeys(t["index"] for t in th))
    rows = [[lab] + [_threshold_cell(next(t for t in th if t["levels"] == lab and t["index"] == i), vu) for i in indices] for lab in labels]
    map_table, map_text = _map_table(maps, vu)
    validity_table, validity_text = _validity_table(maps)
    onset_table, onset_text = _onset_table(onset, vu)
    section = Section(
        "Damage thresholds of the paper's beams and of a plate",
        map_text
        + validity_text
        + kin_text
        + onset_text
        + [
            "Velocity at which each damage index first reaches 1 (first-ply failure by maximum strain, Tsai-Wu and Hashin; "
            "Davies-Zhang delamination force against the peak force), for the two rubber balls under the empirical "
            f"law, with α1-α4 drawn (Latin hypercube, {PAPER_DRAWS} draws) from the covariance of the built-in rubber series' fit; velocity "
            "levels 1000-8000 in/s (the law is fitted on 1000-5000 in/s: above, an extrapolation). Strengths: T300/5208 values "
            "of Tsai & Hahn standing in for T300/934 (docs/modelling-notes.md). Beams: first-ply failure at the gauge sections.",
            "Plate: the built-in 8 × 8 in simply supported [90/0]5s T300/934 plate (plate-ss-8in) struck at its centre, the "
            "ball's contact disc (0.25 in, growing with the force by eq 10) as on the beams; FSDT on the quarter with symmetry "
            f"edges, 1 µs, through the response engine, on {', '.join(f'{n} × {n}' for n in PAPER_PLATE_MESHES)} elements; "
            f"the thresholds are those of the finest ({plate_h}), and their band is widened on both sides by the "
            "discretisation error estimated from the three meshes (Richardson's observed order, GCI with safety factor 1.25 "
            "when that order is within 25 % of 2, else 3; one factor, the mesh, is refined): "
            f"{plate_err}.",
            "First-ply failure under the impact point, where it peaks: ply stresses at both faces of every ply "
            "from the top- and bottom-face strains in x, y and 45°. Halving the step changes no threshold by 1 in/s; the "
            "delamination threshold depends on the force alone and has no mesh error.",
            "The beams' rows are on the paper's "
            "meshes, whose gauge-strain error grows as the pulse shortens (history by history in the section 'Discretisation "
            "error of the paper's meshes, history by history'; the threshold pulses are shorter still and not studied "
            "there); their bands are the α draws' only.",
        ],
        [
            map_table,
            validity_table,
            kin_table,
            onset_table,
            (f"Prescribed force (carried-over Table I law): threshold velocity [{vu.label}], median [5-95 %]", ["structure, ball"] + indices, rows),
        ],
        figs,
    )
    section.summary = [_map_headline(maps, vu), kin_headline]
    linear, nonlinear = paper_kinematics_maps()
    section.flagged = (
        map_flags("Threshold maps (coupled impact, identified law)", maps)
        + map_flags("Onset map (Olsson's F_d)", onset)
        + map_flags("The 8-in plate's map, linear kinematics", linear)
        + map_flags("The 8-in plate's map, von Karman kinematics", nonlinear)
    )
    return section


def map_flags(name: str, rows: list[dict]) -> list[tuple[str, str, str]]:
    """(map, row, flag) of every row of map ``name`` (threshold-map rows, :meth:`MapRow.as_dict`) whose run at its
    threshold raised a validity flag, once per flag (:data:`softimpact.models.validity.FLAG_LABELS`' words)."""
    from ...models.validity import FLAG_LABELS

    return [
        (name, f"{r['structure']}, {r['index']}, d = {r['diameter_m'] / INCH:.3g} in", FLAG_LABELS.get(f, f)) for r in rows for f in r.get("validity_flags", [])
    ]


def _map_headline(maps: list[dict], vu) -> str:
    """The threshold maps' headline for the report's summary: for the 1/2-in ball (the paper's), each structure's
    lowest median threshold velocity and the index that reaches 1 there (the maps' own rows)."""
    d_half = min({r["diameter_m"] for r in maps}, key=lambda d: abs(d - 0.5 * INCH))
    parts = []
    for name in dict.fromkeys(r["structure"] for r in maps):
        rows = [r for r in maps if r["structure"] == name and r["diameter_m"] == d_half and r["draws_reaching_1"]]
        if not rows:
            parts.append(f"{name} above {MAP_RANGE_IN_S[1]:.0f}")
            continue
        low = min(rows, key=lambda r: r["threshold_velocity_median_m_s"])
        parts.append(f"{name} {low['threshold_velocity_median_m_s'] * vu.factor:.0f} ({low['index']})")
    return f"Threshold maps, {d_half / INCH:.3g}-in ball (coupled impact, identified law): lowest median threshold velocity [{vu.label}]: " + ", ".join(parts)


def _onset_files(onset: list[dict], figures: bool, files: dict, prefix: str, system: str) -> list[tuple[str, str]]:
    """The onset map written into ``files`` (onset-map.csv, and onset-map.png with ``figures``); returns the figure's (path, caption)."""
    from ...output.files import figure_bytes
    from ...output.sweep import threshold_csv, threshold_map_figure

    files[f"{prefix}onset-map.csv"] = threshold_csv(onset)
    if not figures:
        return []
    title = "Delamination-onset velocity (peak force = Olsson's F_d) against the rubber ball's diameter: coupled impact, identified law"
    files[f"{prefix}onset-map.png"] = figure_bytes(threshold_map_figure(onset, [], system, title))
    return [
        (
            f"{prefix}onset-map.png",
            "Onset map: velocity at which the coupled peak force reaches Olsson's quasi-static threshold F_d, per structure, against the "
            "ball's diameter: median over the identified law's draws and 5-95 % band (as the threshold maps); each row's regime in onset-map.csv",
        )
    ]


def _onset_table(onset: list[dict], vu) -> tuple[tuple, list[str]]:
    """The onset map as a table (structure × diameter, each cell with its regime) and its paragraph."""
    from ...models.delamination import REGIME_BOUNDS_NOTE

    diameters = sorted({r["diameter_m"] for r in onset})
    names = list(dict.fromkeys(r["structure"] for r in onset))

    def cell(r):
        ratio = f"{r['regime']}, M_i/M_p {r['impactor_over_target_mass']:.2g}"
        if r.get("inside_validity") is not None:  # the validity at the threshold (threshold-maps' table has its flags)
            ratio += f", w/h {r['deflection_over_thickness']:.2f}" + ("" if r["inside_validity"] else ", outside validity")
        if not r["draws_reaching_1"]:
            return f"above {MAP_RANGE_IN_S[1]:.0f} ({ratio})"
        m, lo, hi = (r[f"threshold_velocity_{q}_m_s"] * vu.factor for q in ("median", "p05", "p95"))
        return f"{m:.0f} [{lo:.0f}-{hi:.0f}] ({ratio})"

    rows = [[n] + [cell(next(r for r in onset if (r["structure"], r["diameter_m"]) == (n, d))) for d in diameters] for n in names]
    table = (
        f"Onset map (coupled impact, identified law): velocity [{vu.label}] at which the peak force reaches Olsson's F_d, median [5-95 %], "
        "with the row's response regime, w/h at the threshold and whether it lies outside validity (onset-map.csv: its flags)",
        ["structure"] + [f"d = {d / INCH:.3g} in" for d in diameters],
        rows,
    )
    quasi = sum(r["regime"] == "quasi-static" for r in onset)
    text = [
        "Onset map: the same structures, balls, law draws, strength scatter and meshes, with the index the coupled peak force "
        "over Olsson's quasi-static delamination threshold F_d = π·sqrt(32·D*·G_IIc/9), D* from the laminate's bending stiffnesses "
        "(docs/delamination.md; the formula as given to the project, its source not retrieved). Each row states its validity: the ball's mass "
        f"over the structure's (the whole plate's) and the response regime it falls in. {REGIME_BOUNDS_NOTE}.",
        f"F_d is a quasi-static threshold: {quasi} of the {len(onset)} rows are in the quasi-static regime; elsewhere the map gives the velocity at which the "
        "peak force reaches F_d, not a validated onset (Olsson's dynamic threshold for small-mass impact was not retrieved).",
    ]
    return table, text


def _prescribed_points(th: list[dict]) -> list[dict]:
    """The prescribed-force threshold rows ("structure, ball" levels) as points of a map figure: structure, index, diameter [m]."""
    out = []
    for t in th:
        name, _, ball = t["levels"].rpartition(", ")
        if ball in PAPER_PROJECTILES:
            out.append(t | {"structure": name, "diameter_m": units.parse(PAPER_PROJECTILES[ball], "length", ball)})
    return out


def _map_table(maps: list[dict], vu) -> tuple[tuple, list[str]]:
    """The threshold maps as a table (structure, index × diameter) and the section's paragraphs on them."""
    diameters = sorted({r["diameter_m"] for r in maps})
    keys = list(dict.fromkeys((r["structure"], r["index"]) for r in maps))

    def cell(r):
        if not r["draws_reaching_1"]:
            return f"above {MAP_RANGE_IN_S[1]:.0f}"
        m, lo, hi = (r[f"threshold_velocity_{q}_m_s"] * vu.factor for q in ("median", "p05", "p95"))
        return f"{m:.0f} [{lo:.0f}-{hi:.0f}]"

    rows = [[f"{s}, {i}"] + [cell(next(r for r in maps if (r["structure"], r["index"], r["diameter_m"]) == (s, i, d))) for d in diameters] for s, i in keys]
    table = (
        f"Threshold maps (coupled impact, identified law): threshold velocity [{vu.label}], median [5-95 %], by ball diameter",
        ["structure, index"] + [f"d = {d / INCH:.3g} in" for d in diameters],
        rows,
    )

    def spread(what):
        rel = [r[what] / r["threshold_velocity_median_m_s"] for r in maps if r["draws_reaching_1"]]
        return f"{min(rel):.1%}-{max(rel):.1%}"

    for r in maps:
        r["law_half_range_m_s"] = 0.5 * (r["law_p95_m_s"] - r["law_p05_m_s"])
    tw = {(r["structure"], r["diameter_m"]): r["threshold_velocity_median_m_s"] * vu.factor for r in maps if r["index"] == "tsai_wu"}
    de = {(r["structure"], r["diameter_m"]): r["threshold_velocity_median_m_s"] * vu.factor for r in maps if r["index"] == "delamination"}
    d_half = min(diameters, key=lambda d: abs(d - 0.5 * INCH))
    names = list(dict.fromkeys(r["structure"] for r in maps))
    delam_spread = max((max(v) - min(v)) / min(v) for d in diameters for v in [[de[(n, d)] for n in names]])
    text = [
        "Threshold maps from coupled impact: the velocity at which a damage index first reaches 1 for rubber balls of the paper's "
        f"family ({', '.join(f'{d / INCH:.3g}' for d in diameters)} in; mass ∝ d³, the paper's 1.1 g at 1/2 in), struck normally at the case's "
        "impact point, with the contact law identified from the rubber-ball bar series (the section on the paper's question; its Maxwell arm "
        "included), on the beams' layered laminate (beam.laminate.model = layered) and the plate's quarter (MITC4, symmetry edges). The law "
        "was identified on 3/8 and 1/2 in balls at 1000-5000 in/s: larger balls and faster impacts extrapolate it.",
        "Indices: Tsai-Wu (1/R) "
        "at the load point, over both faces of every ply; Davies-Zhang delamination, the coupled peak force over P_c. Each threshold is "
        "the root of ln I(V) = 0 over contact-kernel runs (one kernel build per structure and mesh, milliseconds a run; the root gives I "
        "within 0.5 % of 1 on direct stepping, tests/test_threshold_maps.py).",
        f"Bands (5-95 %): (a) the law's uncertainty, {MAP_DRAWS} Latin-hypercube draws of its parameters from the identification's "
        f"covariance (threshold half-range {spread('law_half_range_m_s')} of the median); (b) material scatter, stated: every ply strength "
        f"and √G_IIc (hence P_c) scaled by one factor s ~ N(1, {MAP_STRENGTH_COV:.0%}); both indices are homogeneous of degree -1 in s, so "
        "the threshold moves as s^(1/β), β the local power of the index in V at the threshold (from two runs at ±2 %), each law draw "
        "paired with 9 quantiles of s.",
        "(c) The discretisation error: the two-mesh GCI (safety factor 3, formal order 2, ratio 2) from the "
        f"map's mesh and one coarser by 2 in elements and step: beams {MAP_BEAM_MESHES[1][0][0]} × {MAP_BEAM_MESHES[1][0][1]} at "
        f"{MAP_BEAM_MESHES[1][1] * 1e6:g} µs against {MAP_BEAM_MESHES[0][0][0]} × {MAP_BEAM_MESHES[0][0][1]} at {MAP_BEAM_MESHES[0][1] * 1e6:g} µs, "
        f"the plate's quarter {MAP_PLATE_MESHES[1][0]}² at {MAP_PLATE_MESHES[1][1] * 1e6:g} µs against {MAP_PLATE_MESHES[0][0]}² at "
        f"{MAP_PLATE_MESHES[0][1] * 1e6:g} µs (GCI {spread('discretisation_error_m_s')} of the median), which widens the band on both "
        "sides.",
        f"Runs last {MAP_DURATION * 1e6:.0f} µs. Few draws and two meshes keep the maps to about 20 s of the report; the material "
        "scatter dominates the bands, the law's draws add little.",
        "The maps differ between the structures in first-ply failure: at "
        + ", ".join(f"{n} {tw[(n, d_half)]:.0f}" for n in names)
        + f" {vu.label} for the 1/2-in ball (Tsai-Wu): the strain under the load follows each structure's own bending (the clamped "
        "cantilevers' span and the plate's two-way bending), and so does the threshold's fall with the diameter. They hardly differ in "
        "delamination ("
        + ", ".join(f"{n} {de[(n, d_half)]:.0f}" for n in names)
        + f" {vu.label}): that index is the peak force over P_c, and the soft ball's contact is far more compliant than any of the three "
        "targets, so its peak force is set by the ball and the velocity almost alone (the structures' delamination thresholds differ "
        f"by at most {delam_spread:.1%}).",
        "Every threshold falls with the diameter: the ball's mass, momentum and peak force grow as d³ at a given velocity. Beside them, "
        "the carried-over thresholds of prescribed force histories (below): the Table I law is the same on every structure, so its "
        "delamination threshold is the same on all three by construction.",
    ]
    return table, text


def _validity_cell(r: dict) -> str:
    """A map row's validity at its threshold as a table cell: w/h, contact radius over the ball's, the maximum-strain index
    and, when outside, the flags raised (:data:`softimpact.models.validity.FLAG_LABELS`)."""
    from ...models.validity import FLAG_LABELS

    if r.get("inside_validity") is None:
        return "no threshold"
    text = f"w/h {r['deflection_over_thickness']:.2f}, a/R {r['contact_radius_over_projectile_radius']:.2f}, ε/ε_a {r['max_strain_index']:.2f}"
    if r["inside_validity"]:
        return text + ": inside"
    return text + ": outside (" + "; ".join(FLAG_LABELS.get(f, f) for f in r["validity_flags"]) + ")"


def _validity_table(maps: list[dict]) -> tuple[tuple, list[str]]:
    """The threshold maps' validity at each threshold (structure, index × diameter) and its paragraph."""
    from ...models.validity import DEFLECTION_OVER_THICKNESS

    diameters = sorted({r["diameter_m"] for r in maps})
    keys = list(dict.fromkeys((r["structure"], r["index"]) for r in maps))
    rows = [
        [f"{s}, {i}"] + [_validity_cell(next(r for r in maps if (r["structure"], r["index"], r["diameter_m"]) == (s, i, d))) for d in diameters]
        for s, i in keys
    ]
    table = (
        "Threshold maps: validity of the law's mean run at each threshold (the impact command's checks; w/h under the impact point, "
        "contact radius over the ball's radius, maximum-strain index against the ply allowables)",
        ["structure, index"] + [f"d = {d / INCH:.3g} in" for d in diameters],
        rows,
    )
    checked = [r for r in maps if r.get("inside_validity") is not None]
    past = [r for r in checked if "deflection_past_linear" in r["validity_flags"]]
    per = {n: [r["deflection_over_thickness"] for r in checked if r["structure"] == n] for n in dict.fromkeys(r["structure"] for r in checked)}
    text = [
        "Each threshold states its validity: the coupled run of the law's mean at the row's V*, checked as `softimpact impact` checks a "
        "single run (columns deflection_over_thickness, contact_radius_over_projectile_radius, approach_over_diameter, max_strain_index, "
        "validity_flags and inside_validity of threshold-maps.csv). "
        f"{sum(1 for r in checked if r['inside_validity'])} of the {len(checked)} thresholds lie inside every envelope; "
        f"{len(past)} deflect the structure past w/h = {DEFLECTION_OVER_THICKNESS:g}, the limit of linear theory ("
        + ", ".join(f"{n} w/h {min(v):.2f}-{max(v):.2f}" for n, v in per.items())
        + "). "
        + f"{sum('contact_past_projectile_radius' in r['validity_flags'] for r in checked)} of them flatten the ball past its radius: "
        "the identified law's contact radius sqrt(d·α) passes the ball's radius once the approach passes d/4; the law is fitted to the "
        "rubber's flattening, and a/R > 1 says the ball is flattened past a hemisphere, where the law's form is extrapolated. "
        f"{sum(any(f.startswith('extrapolated_') for f in r['validity_flags']) for r in checked)} lie outside the diameters or "
        "velocities the law was identified on (the flags the command warns of when it reads the law). In the figure, open circles "
        "mark the thresholds outside validity.",
    ]
    return table, text
