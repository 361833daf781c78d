"""What the paper report's references can tell: the beams' first zero crossing of gauge 1 (paper
Fig 21, ≈ 450 µs) and the free length or clamp compliance that would match it; and a bar series
made like the built-in synthetic one with another α3 (a what-if for the coupled predictions).

The paper calibrated the duration T of each transverse force history so that the computed
*bending* strain at gauge 1 crosses zero first where the measured one did, "approximately 450 µs
in fig. 21" (long beam, force history 1), and it warns that its fixture is no rigid clamp
(text after eq 15). Figure 16, with the specimens' dimensions and the gauge positions, did
not survive the text: the report's beams use assumed free lengths (6 in and 4 in). This module
measures that crossing on the report's beam model and searches, one parameter at a time, for
the free length (clamped span) and for the rotational compliance of the clamp that bring it
to a target.

- **Crossing** (:func:`first_zero_crossing`): the bending strain (ε_face − ε_opposite)/2 of
  the gauge starts with small lobes, the local flexural wave passing the gauge (15–20 % of the
  largest |strain| on the paper beams); the crossing the paper reads is the end of the first
  *main* lobe, the first lobe whose peak reaches :data:`MAIN_LOBE_FRACTION` of the largest
  |strain| in the window. Linear interpolation between the samples.
- **Free length** (:func:`at_free_length`): the span L from the clamp, the impact at the same
  fraction of L as in the case (mid-length in the paper cases), gauge 1 at the same distance
  from the impact toward the clamp, the same number of elements (so the crossing is continuous
  in L).
- **Clamp compliance** (:func:`beam_gauge_model`): the clamped face's axial DOFs held by springs
  instead of fixed (its transverse DOFs stay fixed), the springs proportional to each node's
  tributary height so that they act as one rotational spring of stiffness k_θ = 1/c [N·m/rad]
  on the section (for the whole width); c = 0 is the rigid clamp. Statically it adds the
  root rotation M·c, the rotation an extra length ΔL = c·EI of the beam under the same moment
  would add (:func:`equivalent_length`); unlike that length it adds no mass.
- **Synthetic bar series** (:func:`synthetic_series_records`): gauge records of a bar series made
  as the built-in ``paper-rubber-series`` was (tools/make_rubber_series.py): the Table I pulse of
  eqs (4)–(7) with eq (15) and its exponential tail, through the series' bar on 144 Hermite
  elements at 0.25 µs, 1 % noise, a baseline offset and an arbitrary clock from one seeded
  generator, but with each test's scaling constants given (e.g. α3 from Tables II/III).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..errors import InputError
from ..fem.linear import LinearModel
from ..fem.loads import PatchLoad
from ..fem.plane import PlaneModel
from ..workflows.synthetic import gauge_model, synthetic_record

__all__ = [
    "SyntheticRecord",
    "synthetic_series_records",
    "MAIN_LOBE_FRACTION",
    "first_zero_crossing",
    "lead_lobes",
    "at_free_length",
    "beam_gauge_model",
    "gauge_bending",
    "crossing_time",
    "equivalent_length",
    "CrossingMatch",
    "match_crossing",
]

MAIN_LOBE_FRACTION = 0.3  # a lobe is the main one when its peak reaches this share of the window's largest |strain|
# (the local-wave lobes before it are 15–20 % on the paper beams, the main lobe 35–70 %)


def first_zero_crossing(time: np.ndarray, strain: np.ndarray, fraction: float = MAIN_LOBE_FRACTION) -> float:
    """The end [s] of the first main lobe of ``strain`` (n,) sampled at ``time`` (n,) [s]: the first
    sign change after |strain| first reaches ``fraction`` of its largest value, linearly interpolated
    between the samples; NaN when the strain keeps its sign to the end of the window."""
    t, y = np.asarray(time, float), np.asarray(strain, float)
    a = np.abs(y)
    if not a.max() > 0:
        return math.nan
    k0 = int(np.flatnonzero(a >= fraction * a.max())[0])
    flips = np.flatnonzero(np.sign(y[k0:]) == -np.sign(y[k0]))
    if not flips.size:
        return math.nan
    k = k0 + int(flips[0])
    return float(t[k - 1] + (t[k] - t[k - 1]) * y[k - 1] / (y[k - 1] - y[k]))


def lead_lobes(time: np.ndarray, strain: np.ndarray, fraction: float = MAIN_LOBE_FRACTION) -> float:
    """The largest |strain| before the first main lobe (:func:`first_zero_crossing`) as a share of the
    largest |strain| in the window: how far below ``fraction`` the lobes the crossing skips stay."""
    y = np.asarray(strain, float)
    a = np.abs(y)
    k0 = int(np.flatnonzero(a >= fraction * a.max())[0])
    flips = np.flatnonzero(np.sign(y[:k0]) != np.sign(y[k0]))
    return float(a[: flips[-1] + 1].max() / a.max()) if flips.size else 0.0


def at_free_length(problem, length: float, gauge: int = 0):
    """The beam problem (:class:`~softimpact.workflows.beam_impact.BeamProblem`) with a free length
    ``length`` [m]: the impact at the same fraction of the span, only gauge ``gauge`` kept, at the
    same distance from the impact (toward the clamp), the same number of elements."""
    L0 = problem.beam.length
    g = problem.gauges[gauge]
    x_load = problem.load.position * length / L0
    x_gauge = x_load - (problem.load.position - g.position)
    if not 0 < x_gauge < x_load:
        raise InputError(f"free length {length!r} m: gauge {g.name!r} would leave the span (at {x_gauge!r} m)", "length")
    return replace(problem, beam=replace(problem.beam, length=length), load=replace(problem.load, position=x_load), gauges=(replace(g, position=x_gauge),))


def _face_weights(z: np.ndarray) -> np.ndarray:
    """Tributary heights [m] of the nodes at heights ``z`` (sorted) of a face."""
    mid = 0.5 * (z[1:] + z[:-1])
    return np.diff(np.r_[z[0], mid, z[-1]])


def beam_gauge_model(problem, compliance: float = 0.0, gauge: int = 0) -> LinearModel:
    """The beam of ``problem`` (clamped-free, plane model of the case's mesh and step) with a clamp of
    rotational compliance ``compliance`` [rad/(N·m)] (module docstring; 0: rigid), observing one output:
    the bending strain (ε_face − ε_opposite)/2 of gauge ``gauge``. Loaded by the case's patch (r0)."""
    if problem.beam.support != "clamped-free":
        raise InputError(f"clamp compliance: needs a clamped-free beam, got {problem.beam.support!r}", "support")
    if not compliance >= 0:
        raise InputError(f"clamp compliance must be ≥ 0, got {compliance!r}", "compliance")
    pm = PlaneModel(problem.beam.plane_beam())
    nd, p = pm.basis.nodal_dofs, pm.basis.mesh.p
    left = np.flatnonzero(np.isclose(p[0], 0.0))
    left = left[np.argsort(p[1, left])]
    K = pm.K_full.tolil()
    if compliance > 0:
        z = p[1, left]
        w = _face_weights(z)
        zc = z - 0.5 * problem.beam.thickness
        springs = w / (compliance * float(np.sum(w * zc**2)))  # Σ k_i·z_i² = k_θ = 1/c
        for dof, k in zip(nd[0, left], springs):
            K[dof, dof] += k
        fixed = nd[1, left]
    else:
        fixed = nd[:, left].ravel()
    free = np.setdiff1d(np.arange(pm.basis.N), fixed)
    index = np.full(pm.basis.N, -1)
    index[free] = np.arange(free.size)
    K = K.tocsr()[free][:, free].tocsr()
    M = pm.M_full[free][:, free].tocsr()

    def remap(row):  # a row over the rigid clamp's free DOFs → over this model's
        full = np.zeros(pm.basis.N)
        full[pm.free] = row
        return full[free]

    g = problem.gauges[gauge]
    other = "top" if g.surface == "bottom" else "bottom"
    O = 0.5 * (remap(pm.surface_strain(g.position, g.surface, g.length)) - remap(pm.surface_strain(g.position, other, g.length)))
    patch = PatchLoad(pm.node_x[pm.top_nodes], problem.load.position, problem.load.contact_radius)
    load_dofs = index[nd[1, pm.top_nodes[patch.nodes]]]
    return LinearModel(M, K, None, problem.solver, load_dofs, -1.0, O[None, :], patch, problem.load.contact_radius)


def gauge_bending(model: LinearModel, history) -> tuple[np.ndarray, np.ndarray]:
    """(time [s], bending strain of the model's gauge) under the force ``history`` (callable F(t) [N]),
    by direct Newmark stepping."""
    t = model.solver.times()
    y, _, _ = model.march(np.asarray(history(t), float), None, False)
    return t, y[0]


def crossing_time(problem, *, length: float | None = None, compliance: float = 0.0, fraction: float = MAIN_LOBE_FRACTION, runs: dict | None = None) -> float:
    """The first zero crossing [s] (:func:`first_zero_crossing`) of gauge 1's bending strain under the
    problem's history, at free length ``length`` [m] (None: the case's) and clamp ``compliance``
    [rad/(N·m)]; NaN when none within the problem's window. ``runs``: the beam runs of THIS problem
    already made, (length, compliance) → (time, bending strain), filled here (a run read at another
    ``fraction``, or met again by a search, is not stepped twice)."""
    key = (length, float(compliance))
    if runs is None or key not in runs:
        target = problem if length is None else at_free_length(problem, length)
        run = gauge_bending(beam_gauge_model(target, compliance), problem.load.history)
        if runs is None:
            return first_zero_crossing(*run, fraction)
        runs[key] = run
    return first_zero_crossing(*runs[key], fraction)


def equivalent_length(problem, compliance: float) -> float:
    """ΔL = c·EI [m]: the extra free length whose bending under a root moment M rotates it by M·c,
    with EI the smeared bending stiffness of the beam's width (E_x·h³/12·b)."""
    beam = problem.beam
    D = np.asarray(beam.layer_matrices()[0], float) if len(beam.layer_matrices()) == 1 else None
    if D is None:
        raise InputError("equivalent length: defined for a smeared (one-material) beam", "model")
    E = 1.0 / np.linalg.inv(D)[0, 0]  # σzz = τxz = 0 in a beam
    return compliance * E * beam.thickness**3 / 12 * beam.width


@dataclass(frozen=True)
class CrossingMatch:
    """The parameter (free length [m] or clamp compliance [rad/(N·m)]) whose crossing matches
    ``target`` [s]; ``value`` NaN when none in ``bracket`` does. ``crossing``: the crossing there [s];
    ``scanned``: (parameter, crossing) of the scan that bracketed it; ``evaluations``: beam runs."""

    parameter: str
    target: float
    value: float
    crossing: float
    bracket: tuple[float, float]
    scanned: tuple[tuple[float, float], ...]
    evaluations: int


def match_crossing(
    problem, parameter: str, target: float, bracket: tuple[float, float], *, points: int = 8, edge_steps: int = 6, runs: dict | None = None
) -> CrossingMatch:
    """The free length (``parameter="length"``, [m]) or clamp compliance (``"compliance"``, [rad/(N·m)])
    in ``bracket`` whose crossing of gauge 1 is ``target`` [s]. A scan of ``points`` values; where the
    main lobe appears or vanishes between two of them (a crossing on one side, none on the other) its
    edge is located by ``edge_steps`` bisections and added to the scan; then Brent's method on the
    first pair of scanned values whose crossings straddle the target (tolerance 1e-6 of the bracket).
    ``value`` NaN when no pair does. ``runs``: as :func:`crossing_time`'s (the problem's runs, shared;
    a point met twice is stepped once; ``evaluations`` counts the crossings asked for)."""
    if parameter not in ("length", "compliance"):
        raise InputError(f"parameter: {parameter!r} is not 'length' or 'compliance'", "parameter")
    from scipy.optimize import brentq

    count = [0]
    runs = {} if runs is None else runs

    def crossing(x):
        count[0] += 1
        return crossing_time(problem, length=x, runs=runs) if parameter == "length" else crossing_time(problem, compliance=x, runs=runs)

    scan = {float(x): crossing(float(x)) for x in np.linspace(*bracket, points)}
    xs = sorted(scan)
    for a, b in zip(xs[:-1], xs[1:]):
        if math.isfinite(scan[a]) != math.isfinite(scan[b]):
            good, bad = (a, b) if math.isfinite(scan[a]) else (b, a)
            for _ in range(edge_steps):
                mid = 0.5 * (good + bad)
                c = crossing(mid)
                good, bad = (mid, bad) if math.isfinite(c) else (good, mid)
                scan[mid] = c
    scanned = tuple(sorted(scan.items()))
    for (x0, c0), (x1, c1) in zip(scanned[:-1], scanned[1:]):
        if math.isfinite(c0) and math.isfinite(c1) and (c0 - target) * (c1 - target) <= 0:
            x = float(brentq(lambda v: crossing(v) - target, x0, x1, xtol=1e-6 * abs(bracket[1] - bracket[0])))
            c = crossing(x)
            if abs(c - target) <= MATCH_TOLERANCE:  # else a jump of the crossing (another lobe read) between x0 and x1
                return CrossingMatch(parameter, target, x, c, bracket, scanned, count[0])
    return CrossingMatch(parameter, target, math.nan, math.nan, bracket, scanned, count[0])


# --- a bar series made like the built-in synthetic one, with other constants ------------------------

MATCH_TOLERANCE = 2e-6  # s: a match must cross within this of the target (brentq brackets a jump as well as a root)
SERIES_ELEMENTS = 144  # the generator's bar mesh (finer than the series' 39: the records are not the reduction's model)
SERIES_STEP = 0.25e-6  # s: the generator's step
SERIES_WINDOW = 4.15e-3  # s: the generator's gauge model length
SERIES_SEED = 19880101  # the generator's seed: the same noise, offsets and clocks test by test
PRE_TRIGGER = 250e-6  # s of record before contact
SAMPLE_INTERVAL = 0.5e-6  # s
NOISE = 0.01  # σ of the noise as a share of the peak |strain|
OFFSET = 5e-6  # σ of the baseline offset (strain)
RECORD_MAX = 4.1e-3  # s: the longest record


@dataclass(frozen=True)
class SyntheticRecord:
    """A made record as :func:`softimpact.studies.series.reduce_series` reads one: time [s], strain, metadata."""

    time: np.ndarray
    signal: np.ndarray
    kind: str
    metadata: dict


def synthetic_series_records(series, laws) -> list[SyntheticRecord]:
    """Gauge records of the tests of ``series`` (its bar and gauge; per test mass, diameter, velocity),
    test i driven by ``laws[i]``'s pulse with its tail (a :class:`~softimpact.models.empirical.ScalingLaw`:
    eqs 4–7 and 15), made as tools/make_rubber_series.py made the built-in series (module docstring):
    with the built-in constants the records of its first tests are the built-in ones."""
    gauge = gauge_model(replace(series.bar, elements=SERIES_ELEMENTS), series.gauge_position, SERIES_STEP, SERIES_WINDOW)
    rng = np.random.default_rng(SERIES_SEED)
    out = []
    for test, law in zip(series.tests, laws):
        pulse = law.pulse(test.mass, test.diameter, test.velocity, tail=True)
        length = min(PRE_TRIGGER + pulse.duration * 0.8, RECORD_MAX)
        t, eps = synthetic_record(
            gauge,
            pulse,
            pre_trigger=PRE_TRIGGER,
            length=length,
            sample_interval=SAMPLE_INTERVAL,
            noise=NOISE,
            offset=float(rng.normal(0, OFFSET)),
            clock_start=float(rng.uniform(-0.5e-3, 2e-3)),
            rng=rng,
        )
        out.append(SyntheticRecord(t, eps, "strain", {"synthetic": f"{law.name}, alpha3 = {law.alpha3:.3f}"}))
    return out
