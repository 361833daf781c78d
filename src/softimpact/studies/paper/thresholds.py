"""The paper report's threshold computations (:mod:`softimpact.app.paper.thresholds` shows them): the contact law
identified from the rubber series, the threshold and onset maps of the paper's beams and the 8-in plate from coupled
impact (:mod:`softimpact.studies.thresholds`), the plate's maps on both kinematics, the beams' large-deflection check,
and the carried-over thresholds of prescribed force histories (:mod:`softimpact.cases.sweep` in a plain loop). Each is
computed once per run (:func:`softimpact.studies.tasks.once`), structure by structure or mesh by mesh, so that the report's
tasks share them and run them on both cores.
"""

from __future__ import annotations

import math

import numpy as np

from ... import units
from ...units import INCH
from ..tasks import once

__all__ = [
    "PAPER_BEAMS",
    "PAPER_PLATE",
    "paper_plate_case",
    "paper_identification",
    "structure_maps",
    "paper_threshold_maps",
    "paper_onset_map",
    "paper_kinematics_maps",
    "beam_kinematics_check",
]


PAPER_BEAMS = ("paper-long-beam", "paper-short-beam")


PAPER_PLATE = "plate-ss-8in"
PAPER_PLATE_ELEMENTS = 32  # per side of the quarter: 1/8-in elements (discretisation error in paper_plate_case)
PAPER_PLATE_MESHES = (16, 32, 64)  # the report's plate thresholds: on the finest, with the error over the three
PAPER_PLATE_DURATION = "400 us"  # the index peaks under the load by 250 us at 1000 in/s, by 80 us at 3000 in/s

# The threshold maps (coupled impact, identified law): rubber balls of the paper's family (mass ∝ d³,
# the paper's 1.1 g at 1/2 in), the layered laminate on the beams, both meshes' steps and the draws
# chosen so the maps cost about 30 s (paper_threshold_maps).
MAP_DIAMETERS_IN = (0.375, 0.5, 0.625, 0.75)  # the law was identified on 3/8 and 1/2 in: 5/8 and 3/4 in extrapolate it
MAP_DRAWS = 8  # law-parameter draws (Latin hypercube) per diameter and index
MAP_STRENGTH_COV = 0.10  # 1σ of a common factor on every ply strength and on √G_IIc (stated material scatter)
MAP_DURATION = 400e-6  # s: the pulses at the thresholds last under 250 µs
MAP_BEAM_MESHES = (((100, 3), 2e-6), ((200, 6), 1e-6))  # (nx, nz), step: coarse, fine (the paper's mesh: the map's)
MAP_PLATE_MESHES = ((32, 2e-6), (64, 1e-6))  # quarter elements a side, step: coarse, fine (the map's)
MAP_RANGE_IN_S = (200.0, 20000.0)  # in/s: the velocities searched
# The plate's map inside validity: von Kármán kinematics (immovable edges; every run stepped directly, no kernels)
# beside the linear map on the SAME meshes and steps (kernel runs), both coarser than the linear map's above (a
# nonlinear run costs several linear ones): quarter elements a side, step: coarse, fine. The beams join when the beam
# case takes kinematics = "von-karman" (:data:`VK_STRUCTURES`).
VK_PLATE_MESHES = ((8, 4e-6), (16, 2e-6))
VK_STRUCTURES = (PAPER_PLATE,)


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


@once
def paper_identification():
    """The contact law identified from the built-in rubber series by ``softimpact identify``'s function
    (:func:`~softimpact.workflows.identification.identify_series`), once per process (about 20 s; the
    question section and the threshold maps share it): (rod, bar tests, law, approaches, closure)."""
    from ...fem.bar import Rod
    from ...workflows.identification import identify_series
    from .series import rubber_series

    series, reduced = rubber_series()
    rod = Rod.of(series.bar)
    return (rod, *identify_series(rod, reduced))


def _map_structures(name: str, law, kinematics: str = "linear"):
    """(map mesh, coarse mesh) :class:`~softimpact.studies.thresholds.ThresholdStructure` of a paper beam
    (layered laminate) or of the plate's quarter (:func:`paper_plate_case`, MITC4); with ``kinematics`` other than
    "linear" the plate on :data:`VK_PLATE_MESHES` with that kinematics (and the linear plate there with "linear-vk-meshes"),
    a beam on the linear map's meshes with ``[beam] kinematics`` set (for a build whose beam case takes the key)."""
    from ...input.beam_case import beam_problem
    from ...input.plate_case import plate_problem
    from ...input.toml import load_toml, locate
    from ...models.materials import lookup
    from ..thresholds import structure

    rho = lookup("silicone rubber").density
    widest = max(MAP_DIAMETERS_IN) * INCH
    out = []
    if name == PAPER_PLATE:
        meshes = MAP_PLATE_MESHES if kinematics == "linear" else VK_PLATE_MESHES
        for n, dt in meshes:
            data = paper_plate_case(n, f"{MAP_DURATION / 1e-6:g} us")
            data["plate"]["kinematics"] = kinematics.removesuffix("-vk-meshes")
            target = plate_problem(data, locate(PAPER_PLATE).parent)
            out.append(structure("8-in plate", target, widest, rho, dt, MAP_DURATION, law))
    else:
        for (nx, nz), dt in MAP_BEAM_MESHES:
            data = load_toml(locate(name))
            data["beam"]["elements"] = [nx, nz]
            data["beam"]["laminate"]["model"] = "layered"
            if kinematics.removesuffix("-vk-meshes") != "linear":  # a beam case that takes kinematics (the maps' meshes)
                data["beam"]["kinematics"] = kinematics
            label = f"{name.removeprefix('paper-').removesuffix('-beam')} beam"
            out.append(structure(label, beam_problem(data, locate(name).parent), widest, rho, dt, MAP_DURATION, law))
    return out[1], out[0]


@once
def structure_maps(name: str, draws: int = MAP_DRAWS) -> tuple[tuple[dict, ...], tuple[dict, ...]]:
    """(threshold map, onset map) rows of one structure (of :data:`PAPER_BEAMS` and :data:`PAPER_PLATE`) on one build of
    its kernels, once per run: both maps from ONE :func:`~softimpact.studies.thresholds.threshold_map` (their indices'
    scans share their coupled runs)."""
    from ..thresholds import INDICES, ONSET, threshold_map

    law = paper_identification()[2]
    lo, hi = (v * INCH for v in MAP_RANGE_IN_S)
    diameters = [d * INCH for d in MAP_DIAMETERS_IN]
    fine, coarse = _map_structures(name, law)
    rows = [r.as_dict() for r in threshold_map(fine, law, diameters, lo, hi, draws, MAP_STRENGTH_COV, coarse=coarse, indices=(*INDICES, ONSET))]
    return tuple(r for r in rows if r["index"] != ONSET), tuple(r for r in rows if r["index"] == ONSET)


def _paper_maps(draws: int = MAP_DRAWS) -> tuple[tuple[dict, ...], tuple[dict, ...]]:
    """(threshold maps, onset map) rows of the three structures (:func:`structure_maps`, structure by structure)."""
    per = [structure_maps(name, draws) for name in (*PAPER_BEAMS, PAPER_PLATE)]
    return tuple(r for m, _ in per for r in m), tuple(r for _, o in per for r in o)


def paper_threshold_maps(draws: int = MAP_DRAWS) -> list[dict]:
    """Threshold maps of the long beam, the short beam and the 8-in plate from coupled impact with the
    identified law (:func:`softimpact.studies.thresholds.threshold_map`): rows as dicts (SI)."""
    return [dict(r) for r in _paper_maps(draws)[0]]


def paper_onset_map(draws: int = MAP_DRAWS) -> list[dict]:
    """The onset map of the same structures and balls: the velocity at which the coupled peak force reaches Olsson's
    quasi-static threshold F_d (:data:`softimpact.studies.thresholds.ONSET`), each row with its regime: rows as dicts (SI)."""
    return [dict(r) for r in _paper_maps(draws)[1]]


@once
def _kinematics_maps(draws: int) -> tuple[tuple[dict, ...], tuple[dict, ...]]:
    """(linear, von Kármán) threshold-map rows of the plate's quarter on :data:`VK_PLATE_MESHES`: the linear map with its
    own draws (kernel runs), the von Kármán map stepped directly from the linear thresholds, its band carried over."""
    from ..thresholds import INDICES, threshold_map

    law = paper_identification()[2]
    lo, hi = (v * INCH for v in MAP_RANGE_IN_S)
    diameters = [d * INCH for d in MAP_DIAMETERS_IN]
    linear, nonlinear = [], []
    for name in VK_STRUCTURES:
        fine, coarse = _map_structures(name, law, "linear-vk-meshes")
        rows = threshold_map(fine, law, diameters, lo, hi, draws, MAP_STRENGTH_COV, coarse=coarse, indices=INDICES)
        fine, coarse = _map_structures(name, law, "von-karman")
        vk = threshold_map(fine, law, diameters, lo, hi, draws, MAP_STRENGTH_COV, coarse=coarse, indices=INDICES, band_from=rows)
        linear += [r.as_dict() for r in rows]
        nonlinear += [r.as_dict() for r in vk]
    return tuple(linear), tuple(nonlinear)


BEAM_CHECK_DIAMETER_IN = 0.5  # the ball of the beams' kinematics check (the law's own diameter)


@once
def beam_kinematics_check() -> tuple[tuple, ...]:
    """The beams' large-deflection check at one threshold each: the 1/2-in ball at the linear map's delamination threshold
    on the map's mesh, run once linear (direct stepping) and once with the beam's total Lagrangian form
    (``[beam] kinematics = "von-karman"``, :mod:`softimpact.fem.plane_tl`): (structure, V* [m/s], linear peak force [N],
    nonlinear peak force [N], linear w/h, nonlinear w/h) per beam."""
    import dataclasses

    from ..thresholds import stepped_run

    law = paper_identification()[2]
    d = BEAM_CHECK_DIAMETER_IN * INCH
    out = []
    for name in PAPER_BEAMS:
        vk, _ = _map_structures(name, law, "von-karman")
        row = next(
            r for r in structure_maps(name, MAP_DRAWS)[0] if r["structure"] == vk.name and r["index"] == "delamination" and math.isclose(r["diameter_m"], d)
        )
        v = row["threshold_velocity_nominal_m_s"]
        if not math.isfinite(v):
            continue
        problem = vk.problem_at(law, d, v)
        target = problem.target
        linear = dataclasses.replace(problem, target=dataclasses.replace(target, beam=dataclasses.replace(target.beam, kinematics="linear")))
        h = target.thickness
        runs = [stepped_run(p) for p in (linear, problem)]
        f = [float(np.max(r.force)) for r in runs]
        wh = [float(np.max(np.abs(r.target_displacement))) / h for r in runs]
        out.append((vk.name, v, f[0], f[1], wh[0], wh[1]))
    return tuple(out)


def paper_kinematics_maps(draws: int = MAP_DRAWS) -> tuple[list[dict], list[dict]]:
    """The 8-in plate's threshold maps on the quarter of :data:`VK_PLATE_MESHES`, linear and von Kármán (immovable edges),
    same law, balls and indices (:func:`softimpact.studies.thresholds.threshold_map`; the von Kármán band carried over from
    the linear map's relative band, ``band_from``): (linear rows, von Kármán rows) as dicts (SI)."""
    linear, nonlinear = _kinematics_maps(draws)
    return [dict(r) for r in linear], [dict(r) for r in nonlinear]
