"""The paper report's damage thresholds: the paper's beams and the quarter of the 8-in plate
swept over velocity with the α's of the built-in rubber series drawn from their covariance
(:mod:`softimpact.cases.sweep` in a plain loop), as a report section with CSVs and figures.
"""

from __future__ import annotations

import functools
import math
from pathlib import Path

import numpy as np

from ... import units
from ...cases.sweep import plan_sweep, plan_thresholds, prepare_group, run_chunk, run_table
from ...units import INCH

__all__ = ["threshold_section", "paper_thresholds", "paper_plate_thresholds", "paper_plate_case"]


PAPER_BEAMS = ("paper-long-beam", "paper-short-beam")
PAPER_PROJECTILES = {"rubber-3/8in": "0.375 in", "rubber-1/2in": "0.5 in"}  # projectile → its group in the fit


PAPER_PLATE = "plate-ss-8in"
PAPER_PLATE_ELEMENTS = 32  # per side of the quarter: 1/8-in elements (discretisation error in paper_plate_case)
PAPER_PLATE_MESHES = (16, 32, 64)  # the report's plate thresholds: on the finest, with the error over the three
PAPER_DRAWS = 16  # α draws (Latin hypercube) per ball for the report's thresholds
PAPER_PLATE_DURATION = "400 us"  # the index peaks under the load by 250 us at 1000 in/s, by 80 us at 3000 in/s
PAPER_DAMAGE = ["damage.max_strain", "damage.tsai_wu", "damage.hashin", "damage.delamination"]


def paper_plate_case(elements: int = PAPER_PLATE_ELEMENTS, duration: str = PAPER_PLATE_DURATION) -> dict:
    """The built-in 8 × 8 in simply supported [90/0]5s plate as the quarter x, y ≤ 4 in with
    symmetry edges on the centre lines, struck at the centre (the quarter's corner) by a ball
    whose contact disc (r0 0.25 in, as the beams') grows with the force by eq (10); no gauges
    (damage under the impact point only, where it peaks: the case's gauges 1 and 2 in away
    see under half of it).

    Discretisation error (measured on :func:`paper_plate_thresholds`, quarter meshes of 16,
    24, 32, 48 and 64 elements a side): the Tsai–Wu threshold of the 3/8-in ball is 6349,
    5801, 5570, 5396 and 5336 in/s, converging at order ≈ 2 in the element size from 32
    on toward ≈ 5260 in/s; the 32-element quarter's first-ply thresholds are 5–6 % high
    (its indices ≈ 9 % low: Tsai–Wu at 4000 in/s, 1/2-in ball, 1.097, 1.150 and 1.170 on
    32, 48 and 64 elements, extrapolating to ≈ 1.20; the index grows about like V^1.6). Halving the
    1 µs step moves no threshold by 1 in/s. The delamination threshold depends on the
    force alone: no mesh error.

    The element is MITC4, named in the case: its thresholds converge monotonically (the three
    meshes give a Richardson estimate). MITC9, the default element, converges faster in
    the gauge strains of the Navier check but not in the point strain at the corner node
    under the load that the damage indices use: its quarters of 8, 16 and 32 elements give
    5287, 5091 and 5169 in/s (oscillating, ≈ 2 % below MITC4's extrapolation).
    """
    from ...input.toml import load_toml, locate

    data = load_toml(locate(PAPER_PLATE))
    half_x, half_y = (f"{units.parse(data['plate'][k], 'length', k) / 2 / INCH!r} in" for k in ("length", "width"))
    data["title"] = "Quarter of " + data.get("title", PAPER_PLATE)
    data["plate"].update(length=half_x, width=half_y, elements=[elements, elements], element="mitc4")
    data["plate"]["support"] = dict(data["plate"]["support"], x1="symmetry", y1="symmetry")
    data["load"].update(position=[half_x, half_y], contact_radius="0.25 in", grow=True)
    data["solver"]["duration"] = duration
    data.pop("gauges", None)
    return data


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

    per_mesh = [_ball_thresholds(PAPER_PLATE, "8-in plate", draws, levels, paper_plate_case(elements)) for elements in meshes]
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


@functools.lru_cache(maxsize=1)
def _paper_fit() -> dict:
    """The scaling.json contents of the built-in rubber series' fit (computed once per process; not to be changed)."""
    from ...formats.scaling_json import scaling_summary
    from ...input.series import load_series
    from ...input.series_records import read_series_records
    from ...studies.series import fit_series, reduce_series

    series = load_series("paper-rubber-series")
    return scaling_summary(fit_series(reduce_series(series, *read_series_records(series))))


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


def threshold_section(figures: bool, files: dict, prefix: str = "thresholds/"):
    """The report section: threshold velocity curves of the paper's beams and of a plate
    (first-ply failure, delamination), each as a CSV and a figure."""
    from ...output.files import figure_bytes
    from ...output.report import Section
    from ...output.sweep import threshold_csv, threshold_figure
    from ...units import display

    system = "in-lbf-s"
    vu = display(system, "velocity")
    beams, plate = paper_thresholds(), paper_plate_thresholds()
    figs = []
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

    def cell(t):
        if not t["draws_reaching_1"]:
            return "above 8000"
        m, lo, hi = (t[f"threshold_velocity_{q}_m_s"] * vu.factor for q in ("median", "p05", "p95"))
        part = "" if t["draws_reaching_1"] == t["draws"] else f" ({t['draws_reaching_1']}/{t['draws']} draws)"
        return f"{m:.0f} [{lo:.0f}-{hi:.0f}]{part}"

    plate_h = f"{PAPER_PLATE_MESHES[-1]} × {PAPER_PLATE_MESHES[-1]}"
    first_ply = [t for t in plate if t["index"] != "delamination" and math.isfinite(t["discretisation_error_m_s"])]
    plate_err = (
        "first-ply thresholds ± "
        + ", ".join(f"{t['discretisation_error_m_s'] / t['threshold_velocity_median_m_s']:.1%} ({t['index']}, {t['levels'].split(', ')[1]})" for t in first_ply)
        + f", observed orders {min(t['observed_order'] for t in first_ply):.2g}-{max(t['observed_order'] for t in first_ply):.2g}"
        if first_ply
        else "not estimable (a threshold above the range on a mesh)"
    )
    th = beams + plate
    labels = list(dict.fromkeys(t["levels"] for t in th))
    indices = list(dict.fromkeys(t["index"] for t in th))
    rows = [[lab] + [cell(next(t for t in th if t["levels"] == lab and t["index"] == i)) for i in indices] for lab in labels]
    return Section(
        "Damage thresholds of the paper's beams and of a plate",
        [
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
            f"{plate_err}. First-ply failure under the impact point, where it peaks: ply stresses at both faces of every ply "
            "from the top- and bottom-face strains in x, y and 45°. Halving the step changes no threshold by 1 in/s; the "
            "delamination threshold depends on the force alone and has no mesh error. The beams' rows are on the paper's "
            "meshes, whose gauge-strain error grows as the pulse shortens (history by history in the section 'Discretisation "
            "error of the paper's meshes, history by history'; the threshold pulses are shorter still and not studied "
            "there); their bands are the α draws' only.",
        ],
        [(f"Threshold velocity [{vu.label}]: median [5-95 %]", ["structure, ball"] + indices, rows)],
        figs,
    )
