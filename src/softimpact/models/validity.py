"""Validity envelopes: where a model a result rests on stops being trustworthy, with the numbers.

Each check returns ratios (the quantity over its limit's scale) and flags (one sentence each,
with the numbers and the limit's reason); :func:`warn` turns flags into
:class:`~softimpact.errors.SoftimpactWarning` s (``softimpact: warning:`` lines), and
:meth:`Validity.summary` is summary.json's ``"validity"``: the ratios and the flags.

Limits, each with its reason:

- :data:`HERTZ_APPROACH_OVER_DIAMETER` = 0.1. Hertz replaces the sphere by a paraboloid and the
  bodies by half-spaces, which holds for a contact radius a ≪ R. For a sphere on a flat
  α = a²/R, so α/d = (a/R)²/2: α/d = 0.1 is a/R ≈ 0.45, where the paraboloid's gap is already
  5 % short of the sphere's ((a/R)²/4) and the half-space assumption strained. For the Hertz
  family only (hertz, hertz-unloading, hunt-crossley); a soft projectile's identified law is
  fitted to its own flattening.
- contact radius ≤ the projectile's radius, for the Hertz family (the laws whose derivation assumes a small
  contact): no sphere touches over more than its own radius; and on a bar, ≤ the bar's radius (the contact
  would overhang the bar's end). An identified law is fitted to its balls' own flattening: its envelope is what
  it was identified on (:func:`identified_contact_validity`: the approach over the diameter its tests reached),
  not a small-contact relation; a crushing sphere's cap cannot pass its radius by construction.
- :data:`DEFLECTION_OVER_THICKNESS` = 0.5. Linear plate (and beam) theory neglects the membrane
  stretching of the mid-surface, which stiffens the plate as (w/h)²: for a clamped circular plate
  under uniform pressure w + 0.488·w³/h² = q·a⁴/(64D) (Timoshenko & Woinowsky-Krieger 1959, §97),
  so at w/h = 0.5 the linear deflection is 12 % too large, and it grows fast beyond (a beam
  whose ends cannot draw in likewise).
- an identified law or empirical constants used outside the velocities, diameters, masses
  and projectile densities they were fitted on (more than :data:`RANGE_SLACK` beyond the range;
  the density by more than :data:`DENSITY_SLACK`: another material).
- strains past the ply allowables: a maximum-strain index above 1 (first-ply failure: the
  linear elastic answer past it is not the structure's).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

from ..errors import SoftimpactWarning

__all__ = [
    "HERTZ_APPROACH_OVER_DIAMETER",
    "HERTZ_FAMILY",
    "DEFLECTION_OVER_THICKNESS",
    "RANGE_SLACK",
    "DENSITY_SLACK",
    "Validity",
    "FLAG_LABELS",
    "contact_validity",
    "deflection_validity",
    "range_flags",
    "allowable_flags",
    "surface_strain_bound",
    "gauge_allowable_flags",
    "warn",
    "ValidityWarning",
]

HERTZ_APPROACH_OVER_DIAMETER = 0.1  # α/d: a/R ≈ 0.45 (module docstring)
HERTZ_FAMILY = ("hertz", "hertz-unloading", "hunt-crossley")
DEFLECTION_OVER_THICKNESS = 0.5  # w/h: membrane stiffening 12 % on a clamped plate (module docstring)
RANGE_SLACK = 0.10  # beyond ±10 % of a fitted range: an extrapolation
DENSITY_SLACK = 0.20  # a projectile density more than 20 % off the fitted ones: another material

# Each kind of flag by a short name (:attr:`Validity.names`) and a few words: a sweep counts its runs per name.
FLAG_LABELS = {
    "hertz_approach": f"approach > {HERTZ_APPROACH_OVER_DIAMETER:g} d (Hertz)",
    "contact_past_projectile_radius": "contact radius > the projectile's radius",
    "contact_past_bar_radius": "contact radius > the bar's radius",
    "deflection_past_linear": f"w/h > {DEFLECTION_OVER_THICKNESS:g}",
    "extrapolated_velocity": "velocity outside the fitted range",
    "extrapolated_diameter": "diameter outside the fitted range",
    "extrapolated_mass": "mass outside the fitted range",
    "extrapolated_density": "density off the fitted projectiles'",
    "strains_past_allowables": "strains past the ply allowables",
    "gauge_strain_past_allowables": "a gauge strain past the ply allowables",
    "contact_past_run_end": "a contact not ended, or one to come, at the run's end",
    "threshold_at_range_floor": "threshold at or below the lowest velocity searched",
    "elastic_past_yield": "an elastic metal past yield",
    "process_zone_unresolved": "a cohesive process zone over fewer than 3 node spacings",
    "plastic_strain_past_elongation": "plastic strain past the elongation at break (the skin may tear)",
    "force_unresolved_in_time": "the contact force zigzags from step to step (time step too long)",
    "cohesive_front_unresolved_in_time": "a delamination front crossed more than one node spacing in a step",
}


@dataclass(frozen=True)
class Validity:
    """Ratios of a run against its models' limits (name → number) and the flags they raise; ``names``:
    each flag's kind (a key of :data:`FLAG_LABELS`, same order; empty for a Validity rebuilt from a summary)."""

    values: dict
    flags: tuple[str, ...] = ()
    names: tuple[str, ...] = ()

    def __add__(self, other: Validity) -> Validity:
        return Validity({**self.values, **other.values}, self.flags + other.flags, self.names + other.names)

    def summary(self) -> dict:
        """summary.json's ``"validity"``: the ratios, then ``flags`` (a list of sentences, empty when all hold)."""
        return {**{k: float(v) for k, v in self.values.items()}, "flags": list(self.flags)}


def contact_validity(law_name: str, max_approach: float, max_radius: float, diameter: float, bar_radius: float | None = None) -> Validity:
    """Approach [m] and contact radius [m] of a contact law against the projectile's diameter [m]
    (and the bar's radius [m] on a bar)."""
    v = {"approach_over_diameter": max_approach / diameter, "contact_radius_over_projectile_radius": max_radius / (diameter / 2)}
    flags, names = [], []
    if law_name in HERTZ_FAMILY and v["approach_over_diameter"] > HERTZ_APPROACH_OVER_DIAMETER:
        flags.append(
            f"{law_name}: the approach reaches {v['approach_over_diameter']:.3g} of the projectile's diameter ({max_approach:.4g} m of "
            f"{diameter:.4g} m), past the {HERTZ_APPROACH_OVER_DIAMETER:g} where Hertz's small-contact assumption (a << R) holds"
        )
        names.append("hertz_approach")
    if law_name in HERTZ_FAMILY and v["contact_radius_over_projectile_radius"] > 1.0:
        flags.append(_past_radius(law_name, max_radius, diameter))
        names.append("contact_past_projectile_radius")
    if bar_radius is not None:
        v["contact_radius_over_bar_radius"] = max_radius / bar_radius
        if max_radius > bar_radius:
            flags.append(f"{law_name}: the contact radius {max_radius:.4g} m exceeds the bar's radius {bar_radius:.4g} m (the contact overhangs the bar's end)")
        names.append("contact_past_bar_radius")
    return Validity(v, tuple(flags), tuple(names))


def _past_radius(law_name: str, max_radius: float, diameter: float) -> str:
    """The flag of a contact radius [m] past the projectile's radius (``diameter`` [m] / 2)."""
    return (
        f"{law_name}: the contact radius reaches {max_radius / (diameter / 2):.3g} times the projectile's radius "
        f"({max_radius:.4g} m against {diameter / 2:.4g} m): no sphere touches over more than its own radius"
    )


def deflection_validity(what: str, max_deflection: float, thickness: float) -> Validity:
    """Peak deflection [m] of a linear plate or beam model against its thickness [m]."""
    r = abs(max_deflection) / thickness
    flags = ()
    if r > DEFLECTION_OVER_THICKNESS:
        flags = (
            f"{what}: the deflection reaches {r:.3g} times the thickness ({abs(max_deflection):.4g} m, h {thickness:.4g} m), past the "
            f"{DEFLECTION_OVER_THICKNESS:g} where linear theory holds (membrane stretching stiffens it as (w/h)^2)",
        )
    return Validity({"deflection_over_thickness": r}, flags, ("deflection_past_linear",) * len(flags))


def range_flags(what: str, checks) -> Validity:
    """``checks``: (quantity, value, (lo, hi), unit) tuples of a fitted model; a flag for each value more
    than :data:`RANGE_SLACK` outside its range (:data:`DENSITY_SLACK` for a density)."""
    values, flags, names = {}, [], []
    for name, value, (lo, hi), unit in checks:
        slack = DENSITY_SLACK if name == "density" else RANGE_SLACK
        key = name.replace(" ", "_")
        values[f"{key}_over_fitted_min"], values[f"{key}_over_fitted_max"] = value / lo, value / hi
        if not (1 - slack) * lo <= value <= (1 + slack) * hi:
            flags.append(f"{what}: {name} {value:.4g} {unit} lies outside the {lo:.4g}-{hi:.4g} {unit} it was fitted on: an extrapolation")
            names.append(f"extrapolated_{key}")
    return Validity(values, tuple(flags), tuple(names))


def allowable_flags(where: str, max_strain_index: float, key: str = "max_strain_index") -> Validity:
    """A maximum-strain index (strain over the ply's allowable; 1 = first-ply failure) at ``where``, reported as ``key``."""
    flags = ()
    if math.isfinite(max_strain_index) and max_strain_index > 1.0:
        flags = (
            f"{where}: strains reach {max_strain_index:.3g} times the ply allowables (maximum-strain index): the ply has failed "
            "and the elastic answer past that is not the structure's",
        )
    return Validity({key: max_strain_index}, flags, ("strains_past_allowables",) * len(flags))


def zone_flags(where: str, zone: float, spacing: float, floor: int = 3) -> Validity:
    """A cohesive process zone of length ``zone`` [m] over a node spacing ``spacing`` [m]: spanning fewer than ``floor``
    spacings, the growth the run shows is the mesh's (a coarse mesh delays onset and growth), not the law's."""
    r = zone / spacing
    flags = ()
    if r < floor * (1.0 - 1e-9):  # Turon's strengths set the zone to exactly ``floor`` spacings: round-off is not a shortfall
        flags = (
            f"{where}: the process zone ({zone * 1e3:.3g} mm) spans {r:.2g} node spacings of {spacing * 1e3:.3g} mm, fewer than {floor}: the "
            f"delamination's onset and growth are the mesh's; grade the mesh to {zone / floor * 1e3:.3g} mm (a near field) or use Turon's strengths (turon = true)",
        )
    return Validity({"process_zone_spacings": r}, flags, ("process_zone_unresolved",) * len(flags))


def yield_flags(where: str, von_mises_over_yield: float) -> Validity:
    """An elastic run of a metal whose largest von Mises stress over its yield stress (``von_mises_over_yield``) passes 1:
    past yield the elastic answer is not the structure's."""
    flags = ()
    if math.isfinite(von_mises_over_yield) and von_mises_over_yield > 1.0:
        flags = (
            f"{where}: the von Mises stress reaches {von_mises_over_yield:.3g} times the yield stress in an elastic run: past yield the "
            "elastic answer is not the structure's (run it elastic-plastic: plasticity = true, the default for a metal)",
        )
    return Validity({"von_mises_over_yield": von_mises_over_yield}, flags, ("elastic_past_yield",) * len(flags))


def tearing_flags(where: str, max_plastic_strain: float, elongation: float | None) -> Validity:
    """An elastic–plastic run whose largest equivalent plastic strain passes the metal's elongation at break: the model has
    no fracture, and the skin may have torn."""
    if elongation is None or not math.isfinite(max_plastic_strain):
        return Validity({})
    r = max_plastic_strain / elongation
    flags = ()
    if r > 1.0:
        flags = (
            f"{where}: the equivalent plastic strain reaches {max_plastic_strain:.3g}, {r:.3g} times the elongation at break "
            f"({elongation:.3g}): the skin may have torn, which the model (no fracture) cannot say",
        )
    return Validity({"plastic_strain_over_elongation": r}, flags, ("plastic_strain_past_elongation",) * len(flags))


def surface_strain_bound(ply) -> float:
    """A normal strain in any direction on a ply's face past which the ply has surely failed by maximum
    strain: ε_θ = ε1 cos²θ + ε2 sin²θ + γ12 sinθ cosθ is at most max(ε1a, ε2a) + γ12a/2 in magnitude
    while every index is ≤ 1 (ε1a = max(X_t, X_c)/E1, ε2a = max(Y_t, Y_c)/E2, γ12a = S/G12, the
    allowables of :func:`softimpact.models.failure.failure_indices`). For a gauge of unknown ply state."""
    import numpy as np

    from .laminate import ply_stiffness, reduced_stiffness

    X = ply.strength
    Q = reduced_stiffness(ply_stiffness(ply))
    S = np.linalg.inv(Q)
    return max(max(X.Xt, X.Xc) * S[0, 0], max(X.Yt, X.Yc) * S[1, 1]) + X.S12 / Q[2, 2] / 2


def gauge_allowable_flags(where: str, ply, peak_strain: float) -> Validity:
    """A gauge's peak |strain| against :func:`surface_strain_bound` of the ply (a flag: the ply has failed there)."""
    bound = surface_strain_bound(ply)
    r = abs(peak_strain) / bound
    flags = ()
    if r > 1.0:
        flags = (
            f"{where}: a strain of {abs(peak_strain):.4g} is past the ply allowables ({bound:.4g} is the most any direction reaches "
            "before a maximum-strain index passes 1): the ply has failed and the linear elastic answer past that is not the structure's",
        )
    return Validity({"gauge_strain_over_allowable_bound": r}, flags, ("gauge_strain_past_allowables",) * len(flags))


class ValidityWarning(SoftimpactWarning):
    """A validity flag as a warning: its text, and its kind in ``flag`` (a key of :data:`FLAG_LABELS`, or "")."""

    def __init__(self, text: str, flag: str = ""):
        super().__init__(text)
        self.flag = flag


def warn(validity: Validity) -> None:
    """Each flag as a :class:`~softimpact.errors.SoftimpactWarning` (shown as its text) carrying the flag's
    kind in ``.flag`` (:attr:`Validity.names`): a sweep counts its runs by kind instead of repeating the texts."""
    names = validity.names if len(validity.names) == len(validity.flags) else ("",) * len(validity.flags)
    for f, name in zip(validity.flags, names):
        warnings.warn(ValidityWarning(f, name), stacklevel=2)


# --- Ice and gelatin projectiles (models/crushing_law.py, models/hydrodynamic_law.py) ---

HYDRO_RELEASE_DEPTH_OVER_DIAMETER = 0.05  # s_c/d: the shock-detachment estimate a_c = R·V/U_s takes a shallow cap (s << d)

FLAG_LABELS.update(
    {
        "extrapolated_strain_rate": "crushing strain rate outside the strength law's measured range",
        "hydrodynamic_deep_release": f"shock release depth > {HYDRO_RELEASE_DEPTH_OVER_DIAMETER:g} d (hydrodynamic law)",
    }
)


def ice_strength_validity(diameter: float, velocity: float, strength) -> Validity:
    """The crushing law's strain rate V/d [1/s] against the range its strength law was measured on
    (``strength.rate_range``, e.g. Jones 1997: 0.1-10 1/s): hail at 10-100 m/s crushes at 1e2-1e4 1/s, so the
    published quasi-dynamic laws are extrapolated there and the flag says by how much."""
    rate = velocity / diameter
    return range_flags(f"the crushing strength ({strength.source or 'strength law'})", [("strain rate", rate, strength.rate_range, "1/s")])


def hydrodynamic_validity(diameter: float, velocity: float, hugoniot) -> Validity:
    """The hydrodynamic law's shock phase: the release depth s_c = d·V²/(4·U_s²) over d (its detachment
    estimate holds for a shallow cap, :data:`HYDRO_RELEASE_DEPTH_OVER_DIAMETER`), and V/c0 reported."""
    us = hugoniot.shock_speed(velocity)
    depth = velocity**2 / (4.0 * us * us)
    v = {"release_depth_over_diameter": depth, "velocity_over_sound_speed": velocity / hugoniot.c0}
    flags = ()
    if depth > HYDRO_RELEASE_DEPTH_OVER_DIAMETER:
        flags = (
            f"hydrodynamic: the shock releases at a depth of {depth:.3g} d (V {velocity:.4g} m/s, U_s {us:.4g} m/s), past the "
            f"{HYDRO_RELEASE_DEPTH_OVER_DIAMETER:g} d where the shallow-cap estimate of its detachment holds",
        )
    return Validity(v, flags, ("hydrodynamic_deep_release",) * len(flags))


__all__ += ["HYDRO_RELEASE_DEPTH_OVER_DIAMETER", "ice_strength_validity", "hydrodynamic_validity"]


# --- A coupled impact's envelopes, composed once (the impact command's and the threshold maps' rows) ---


def coupled_validity(problem, result, max_strain_index: float | None = None) -> Validity:
    """The envelopes of a coupled impact run, in the impact command's order: the contact law's approach and contact
    radius against the impactor's diameter (:func:`contact_validity`), the law's own envelope
    (:func:`softimpact.models.contact_laws.law_validity`), the target's peak deflection under the impact point against its
    thickness (``problem.target.validity``: its theory's; none past the linear limit for a von Kármán target) and,
    with ``max_strain_index`` (the run's maximum-strain index over the target's damage points), the strains against
    the ply allowables (:func:`allowable_flags`). ``problem``: an impact problem (``law_name``, ``law``, ``impactor``,
    ``target``); ``result``: its coupled result (``approach`` [m], ``contact_radius`` [m] and ``target_displacement`` [m] histories)."""
    import numpy as np

    from .contact_laws import law_validity

    d = problem.impactor.diameter
    v = contact_validity(problem.law_name, float(np.max(result.approach)), float(np.max(result.contact_radius)), d)
    v += law_validity(problem.law, problem.impactor.velocity)
    v += problem.target.validity(float(np.max(np.abs(result.target_displacement))))
    if max_strain_index is not None:
        v += allowable_flags("the target's plies", max_strain_index)
    return v + run_end_validity(result, problem.law, d) + force_step_validity(result.force, float(result.time[1] - result.time[0]))


ZIGZAG_SWING = 0.05  # a step-to-step reversal of the force larger than this fraction of its peak ...
ZIGZAG_STEPS = 5  # ... at this many steps or more ...
ZIGZAG_SHARE = 0.05  # ... and at one in twenty of the steps in contact: the force is not resolved by the time step


def force_step_validity(force, dt: float) -> Validity:
    """A flag when a coupled run's contact force ``force`` (per step of ``dt`` [s]) zigzags from step to step: at
    :data:`ZIGZAG_STEPS` or more steps, and at :data:`ZIGZAG_SHARE` of the steps with a force, the force reverses (its
    increments change sign) by a second difference |F_{k+1} − 2F_k + F_{k−1}| over :data:`ZIGZAG_SWING` of the peak
    (measured: the 1.8-kg bird at 150 m/s on the 4-mm elastic aluminium plate at 2 µs, 166 of 1052 steps, swings up
    to 0.67 of the peak; the elastic-plastic bird-al-skin at 8 µs, 7 of 200 steps up to 0.1, its peak within 1 % of
    the 2-µs run's: not flagged). A history the step resolves is smooth at the
    step's scale (its second difference ~ F·(π·dt/T)² for a pulse of duration T: 1e-3 of the peak at 100 steps a
    pulse), so a persistent zigzag is the structure's unresolved high modes read through the contact law — the force
    then moves with the time step (the bird on a flexible plate: docs/hail-and-bird.md). A single kink (a contact's
    start or end, a crush's end) does not count as persistent."""
    import numpy as np

    f = np.asarray(force, float)
    peak = float(np.max(np.abs(f))) if f.size else 0.0
    if f.size < 3 or peak <= 0.0:
        return Validity({})
    inc = np.diff(f)
    swing = np.abs(np.diff(inc)) / peak
    zig = (inc[:-1] * inc[1:] < 0.0) & (swing > ZIGZAG_SWING)
    n = int(np.count_nonzero(zig))
    if n < max(ZIGZAG_STEPS, ZIGZAG_SHARE * np.count_nonzero(f)):
        return Validity({})
    flag = (
        f"the contact force zigzags from step to step at {n} steps (swings up to {float(np.max(swing[zig])):.2g} of its peak, "
        f"steps of {dt * 1e6:.3g} us): the time step does not resolve the target's response under this contact law and the force "
        "depends on it; halve solver.time_step and compare the peak"
    )
    return Validity({}, (flag,), ("force_unresolved_in_time",))


def front_step_validity(areas: dict, time, spacing: float) -> Validity:
    """A flag when a delamination front outruns the time step: per interface (``areas``: name → delaminated area [m²]
    per time of ``time`` [s]) the largest advance of its front in one step, ΔA/(P·h) node spacings (``spacing`` h [m],
    P = 2·sqrt(π·A) the perimeter of a disc of the area after the step — the shortest, so the advance an upper bound
    for an elongated region). The damage is raised after each step from that step's openings (lagged: one step
    behind, fem.cohesive_plate), so a front crossing more than one node spacing a step fails several rows of nodes at
    once without the load they shed reaching their neighbours within it: the area then moves with the step (measured on
    examples/11's plate: 154 mm² at 1 µs, 293 mm² at 0.5 µs). Value ``front_spacings_per_step`` (the largest)."""
    import numpy as np

    worst, where, when = 0.0, None, None
    t = np.asarray(time, float)
    for name, a in areas.items():
        a = np.asarray(a, float)
        grown = np.diff(a)
        perimeter = 2.0 * np.sqrt(np.pi * np.maximum(a[1:], 0.0))
        ok = (grown > 0.0) & (perimeter > 0.0)
        if not ok.any():
            continue
        advance = np.where(ok, grown / np.where(ok, perimeter, 1.0) / spacing, 0.0)
        k = int(np.argmax(advance))
        if advance[k] > worst:
            worst, where, when = float(advance[k]), name, float(t[k + 1])
    if where is None:
        return Validity({})
    flags = ()
    if worst > 1.0:
        flags = (
            f"the cohesive interfaces: the delamination front at {where} advanced {worst:.2g} node spacings in one step (at {when * 1e6:.4g} us; "
            f"nodes {spacing * 1e3:.3g} mm apart): the step does not resolve its growth (the damage lags a step) and the delaminated "
            "areas move with it; halve solver.time_step and compare the areas",
        )
    return Validity({"front_spacings_per_step": worst}, flags, ("cohesive_front_unresolved_in_time",) * len(flags))


def run_end_validity(result, law=None, diameter: float | None = None) -> Validity:
    """A flag when a coupled run ends before its contacts do (``time[-1]``): the first contact not ended
    (``contact_duration`` NaN: its peak force, impulse and the target's peaks cover the run only), a later one not ended
    (the last of ``contacts`` without an end: the total impulse and the target's peaks cover the run only), or, every
    contact ended, the impactor still moving toward the target (``final_velocity`` > 0) where ``law`` can still press
    (its force a little past the final approach is not zero: not a sphere already crushed or flowed through, of
    ``diameter`` [m]): another contact may come."""
    end = float(result.time[-1])
    if not math.isfinite(result.contact_duration):
        what = "the first contact had not ended at the end of the run ({:.4g} us): its peak force, impulse and the target's peaks"
    elif result.contacts and not math.isfinite(result.contacts[-1].end):
        k, start = len(result.contacts), result.contacts[-1].start * 1e6
        what = f"contact {k} (from {start:.4g} us) had not ended at the end of the run ({{:.4g}} us): the total impulse and the target's peaks"
    elif result.final_velocity > 0.0 and _can_press(law, float(result.approach[-1]), diameter, float(result.impactor.velocity)):
        v, k = float(result.final_velocity), len(result.contacts)
        what = (
            f"the impactor still moves toward the target at the end of the run ({{:.4g}} us, {v:.3g} m/s after {k} contact"
            f"{'s' if k != 1 else ''}): another contact may come; the total impulse and the target's peaks"
        )
    else:
        return Validity({})
    return Validity({}, (what.format(end * 1e6) + " cover the run only and may come later; lengthen the run",), ("contact_past_run_end",))


def _can_press(law, approach: float, diameter: float | None, velocity: float) -> bool:
    """Whether ``law`` gives a force a little past ``approach`` [m] (a hundredth of ``diameter`` further, closing at
    ``velocity`` [m/s]); True where that cannot be asked (no law, or no memoryless force)."""
    force = getattr(law, "force", None)
    if force is None or diameter is None:
        return True
    try:
        return force(max(approach, 0.0) + 0.01 * diameter, abs(velocity)) > 0.0
    except TypeError:  # a law whose force takes a state (memory): assume it can
        return True


def range_floor_validity(threshold: float, lo: float) -> Validity:
    """A flag when a threshold velocity is the lowest velocity its search tried (``lo`` [m/s]): the index already reached 1
    there, so the threshold is at or below ``lo``, not found (a map's V* and FTE are then upper bounds)."""
    if not (math.isfinite(threshold) and threshold <= lo):
        return Validity({})
    return Validity(
        {},
        (
            f"the threshold is at or below the lowest velocity searched ({lo:.4g} m/s): the index reaches 1 there already; V* and the energy are upper bounds: lower the search's lowest velocity (lo)",
        ),
        ("threshold_at_range_floor",),
    )


def identified_range_validity(ranges: dict | None, velocity: float, diameter: float, mass: float | None, what: str) -> Validity:
    """An identified law used on an impactor (velocity [m/s], diameter [m], mass [kg] or None) against the tests it was
    identified on (``ranges``: its law.json's ``identified_on``, with ``velocity_m_s``, ``diameter_m`` and optionally
    ``projectile`` ``mass_kg`` and ``density_kg_m3`` ranges; None: nothing recorded, nothing checked): :func:`range_flags`
    of each (an ``extrapolated_*`` flag beyond :data:`RANGE_SLACK`, the density beyond :data:`DENSITY_SLACK`)."""
    if ranges is None:
        return Validity({})
    # a law measured on the material (two-bar tests) records no velocity, diameter or mass: only what it holds is checked
    given = (("velocity", velocity, "velocity_m_s", "m/s"), ("diameter", diameter, "diameter_m", "m"))
    checks = [(name, value, ranges[key], unit) for name, value, key, unit in given if key in ranges]
    proj = ranges.get("projectile")
    if proj is not None and mass is not None:
        density = mass / (math.pi / 6 * diameter**3)
        given = (("mass", mass, "mass_kg", "kg"), ("density", density, "density_kg_m3", "kg/m^3"))
        checks += [(name, value, proj[key], unit) for name, value, key, unit in given if key in proj]
    return range_flags(f"the impactor for {what}", checks)


__all__ += ["coupled_validity", "run_end_validity", "range_floor_validity", "identified_range_validity"]


# --- Models past their range where a number is reported (issue 42): plate theory on a thick plate, von Karman's strains ---

PLATE_THICKNESS_OVER_SPAN = 0.1  # h/a: plate theories neglect the through-thickness normal stress, an error of order (h/a)^2
SMALL_STRAIN_LIMIT = 0.02  # von Karman's strain drops the in-plane rotation term u,x^2/2, about eps/2 of the strain: 1 % at 2 %

FLAG_LABELS.update(
    {
        "plate_thicker_than_span_tenth": f"laminate thicker than {PLATE_THICKNESS_OVER_SPAN:g} of the span (plate theory)",
        "strain_past_small_strain": f"mid-surface strain > {SMALL_STRAIN_LIMIT:.0%} (von Karman's small strain)",
        "criterion_outside_regime": "a quasi-static delamination threshold on a wave-controlled or intermediate impact",
    }
)


def plate_span(length_x: float, length_y: float, supports) -> float:
    """A plate's shorter span [m] between its edges (x0, x1, y0, y1 ``supports``): a half or quarter model's length
    doubled across each symmetry edge (the whole plate's)."""
    x0, x1, y0, y1 = supports
    return min(length_x * (2 if "symmetry" in (x0, x1) else 1), length_y * (2 if "symmetry" in (y0, y1) else 1))


def plate_thickness_validity(thickness: float, span: float) -> Validity:
    """A plate theory's (FSDT's) envelope in its geometry: the laminate's ``thickness`` [m] over the plate's shorter
    ``span`` [m] (the length between its edges). Past :data:`PLATE_THICKNESS_OVER_SPAN` the plate is thick: the
    through-thickness normal stress and the sections' warping that a plate theory neglects are no longer small (their
    share grows as (h/a)²), so its deflections and strains are not the structure's. The ratio is reported, the flag raised past it."""
    r = thickness / span
    flags = ()
    if r > PLATE_THICKNESS_OVER_SPAN:
        flags = (
            f"plate theory (FSDT): the laminate is {r:.3g} of the plate's shorter span (h {thickness:.4g} m, span {span:.4g} m), past the "
            f"{PLATE_THICKNESS_OVER_SPAN:g} where a plate theory holds (a thick plate: its through-thickness stress is neglected); "
            "check the laminate's thickness (an inline ply's thickness is one ply's)",
        )
    return Validity({"thickness_over_span": r}, flags, ("plate_thicker_than_span_tenth",) * len(flags))


def small_strain_validity(what: str, max_strain: float) -> Validity:
    """The largest principal mid-surface strain of a von Kármán plate against :data:`SMALL_STRAIN_LIMIT`: its strain
    measure keeps the transverse rotations' w,x²/2 and drops the in-plane ones' u,x²/2, about ε/2 of the strain itself,
    and its laminate is linear elastic; past the limit neither is small, whatever the deflection."""
    flags = ()
    if math.isfinite(max_strain) and abs(max_strain) > SMALL_STRAIN_LIMIT:
        flags = (
            f"{what}: the mid-surface strain reaches {abs(max_strain):.3g} ({abs(max_strain):.1%}), past the {SMALL_STRAIN_LIMIT:.0%} where von "
            "Karman's strains (which drop the in-plane rotations' terms) and a linear elastic laminate hold",
        )
    return Validity({"max_membrane_strain": abs(max_strain)}, flags, ("strain_past_small_strain",) * len(flags))


__all__ += ["PLATE_THICKNESS_OVER_SPAN", "SMALL_STRAIN_LIMIT", "plate_span", "plate_thickness_validity", "small_strain_validity"]


FLAG_LABELS["extrapolated_approach"] = "approach past what the identified law's tests reached"


def identified_contact_validity(ranges: dict | None, max_approach: float, diameter: float, max_radius: float | None = None) -> Validity:
    """An identified law's geometric envelope: the run's largest approach over the impactor's ``diameter`` [m] against
    the largest its bar tests reached (law.json's ``identified_on.approach_over_diameter``, the range of each test's
    largest), flagged more than :data:`RANGE_SLACK` beyond it: the law's force there is an extrapolation of its fit.
    A law.json that does not record it (written before it was kept) cannot be checked so: its contact radius
    ``max_radius`` [m] is then held to the ball's radius, as a small-contact law's is (:func:`contact_validity`)."""
    reached = (ranges or {}).get("approach_over_diameter")
    if reached is None:
        if max_radius is None or max_radius <= diameter / 2:
            return Validity({})
        return Validity(
            {}, (_past_radius("identified (its law.json records no approach it was identified to)", max_radius, diameter),), ("contact_past_projectile_radius",)
        )
    r = max_approach / diameter
    hi = float(reached[1])
    flags = ()
    if r > (1 + RANGE_SLACK) * hi:
        flags = (
            f"the identified law: the approach reaches {r:.3g} of the impactor's diameter, past the {hi:.3g} its bar tests reached: "
            "its force there is an extrapolation of the fit",
        )
    return Validity({"approach_over_identified_max": r / hi}, flags, ("extrapolated_approach",) * len(flags))


__all__ += ["identified_contact_validity"]
