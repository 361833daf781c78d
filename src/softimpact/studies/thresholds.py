"""Threshold maps: the impact velocity at which a damage index first reaches 1, against the
impactor's diameter, per structure, from COUPLED impact with an identified contact law.

For one structure (a beam or plate case, its contact point and its mesh) the contact kernels
(:class:`softimpact.fem.kernels.ContactKernels`) are built once, for the widest impactor; each
coupled run on them then costs milliseconds, so the threshold velocity V* of every diameter is
found by root-finding on the velocity (Brent's method on ln I(V) against ln V, bracketed by a
geometric scan): I(V*) = 1, with I

- Tsai–Wu at the load point (the largest 1/R over both faces of every ply and the run,
  :func:`softimpact.workflows.damage.point_damage`), or
- Davies–Zhang delamination, the coupled peak force over the laminate's threshold force
  P_c = π·sqrt(8·E·h³·G_IIc/(9(1−ν²))) (:func:`softimpact.workflows.damage.delamination_force`), or
- Olsson's onset (:data:`ONSET`, the onset map), the coupled peak force over Olsson's quasi-static threshold
  F_d = π·sqrt(32·D*·G_IIc/9) from the laminate's bending stiffnesses (:func:`softimpact.workflows.damage.olsson_force`).

Each row states its validity: the impactor-to-target mass ratio at its diameter and the response regime it
falls in (:func:`softimpact.models.delamination.response_regime` with the stand-in bounds
:data:`~softimpact.models.delamination.REGIME_BOUNDS`; Olsson's were not retrieved): Olsson's F_d is a
quasi-static threshold, to be read as such only in the "quasi-static" rows.

The impactor is a ball of the identified law's projectile: mass m = ρ·π·d³/6 (the law's tests'
density), diameter d; the law is :meth:`IdentifiedLaw.law(m, d, V)` of each velocity (its
parameters scaled by d/d_ref, its velocity scaling in V).

Bands (:func:`threshold_map`) combine three sources, stated in each row:

(a) the law's uncertainty: V* again for each of ``draws`` parameter vectors drawn (Latin
    hypercube, fixed seed) from the law's covariance (its 95 % half-widths /1.96 on the diagonal
    when it has none), as a sweep's ``contact.parameters`` draws are
    (:class:`softimpact.input.sweep_spec.LawDraw`);
(b) material scatter: every strength of the ply (and √G_IIc, hence P_c and F_d) scaled by a common factor
    s ~ N(1, ``strength_cov``²). Tsai–Wu's 1/R is homogeneous of degree −1 in a common strength
    factor (F_i ∝ 1/S, F_ij ∝ 1/S²), the delamination indices F/P_c and F/F_d too, so I(V; s) = I(V; 1)/s and
    V*(s) solves I(V; 1) = s: with the local power I ∝ V^β at V* (β from two runs at V*·(1 ± 2 %)),
    V*(s) = V*·s^(1/β);
(c) the discretisation error: the map is computed on the finer of two meshes (element counts
    and step both refined by r = 2); the coarser gives V*_c at the law's mean, and the two-mesh
    GCI of the fine value, Fs·|V*_f − V*_c|/(r^p − 1) with Fs = 3 (Roache's factor for two
    meshes) and the formal order p = 2, widens the band on both sides.

The 5–95 % band is that of the law draws × strength factors (each law draw paired with every one
of ``strength_quantiles`` equally spaced normal quantiles of s), widened by (c). The median is
that of the law draws at s = 1.

Each row also states whether its threshold lies inside the models' validity: the coupled run of the law's mean
at the nominal V* (the map's own run there, kept from the root-finding) checked as the impact command checks a
single run (:func:`softimpact.models.validity.coupled_validity`): the approach and the contact radius against the
ball, the law's own envelope, the peak deflection under the impact point over the thickness (mid-surface; the linear
limit w/h = 0.5) and the maximum-strain index over the damage points against the ply allowables; and, as the command
warns when it reads an identified law, the ball's velocity, diameter, mass and density against the tests the law was
identified on (``extrapolated_*`` flags; those ratios are not columns). The ratios are
columns under the impact summary's names (``deflection_over_thickness``, ``contact_radius_over_projectile_radius``,
``max_strain_index``, ...), the flags raised by name (``validity_flags``, :data:`~softimpact.models.validity.FLAG_LABELS`)
and ``inside_validity`` whether none was.

Nonlinear maps: on a target whose kinematics is "von-karman" (:class:`ThresholdStructure` ``stepping``) no kernels are
built (they hold a linear structure's impulse responses) and every run is stepped directly by the target's nonlinear
stepper (:data:`softimpact.workflows.coupled.METHODS`); the thresholds come from the same root-finding on the law's mean.
Its bands cost a threshold per law draw; with ``band_from`` (the linear map's rows of the same structure, index and
diameters) the nonlinear row carries over the linear row's RELATIVE law and strength band instead (median, p05, p95 and
the law's 5–95 % as the same fractions of the nominal threshold), widened by its own two-mesh GCI, and says so
(``band_from`` "linear map"; "own draws" otherwise), and the linear row's β (the strengths' share moves as s^(1/β)).
That carry-over assumes the law's and the strengths' relative effect on V* is the same on both kinematics. A nonlinear
threshold then costs its root-finding (secant steps from the linear threshold: two or three runs), one run at V* for its
validity and the coarse mesh's root-finding: on the report's quarter plate (16 MITC4 elements a side, 2 µs, 200 steps)
a von Kármán run costs about 12 linear direct runs (0.84 s against 0.07 s of CPU), and a nonlinear threshold with its
coarse mesh's (8 a side, 4 µs) about 4 s of CPU (measured on a shared 2-core machine, 8 thresholds in 32 s).

Reduced stepping: :func:`structure`'s ``nonlinear_stepping`` says how a von Kármán PLATE's runs are stepped, "von-karman"
(the full plate, the default and the reference) or "von-karman-rom" (:mod:`softimpact.fem.vk_rom`: the plate's reduced
model, built ONCE per structure for its impact point, whose approach row is the same for every ball, and reused by every
run of the map: a fraction of a second a run after a build of a few seconds). Its stated error: the reduced run's peak
force +1.8 % from the full run's on the 48 × 48 plate at w/h 0.7 (BENCHMARKS.md); an index that follows the peak force
ε high, as V^β, then has its threshold (1 + ε)^(−1/β) times the full one's, about −ε/β. Measured
(``benchmarks/bench_vk_rom_map.py``): on that plate the steel ball's delamination threshold is 0.9 % below the full
map's (ε +0.94 % at V*, β 1.05), the row 65 times cheaper in CPU; on the tests' 10 × 10 quarter plate under a rubber
ball, 4·10⁻⁶ (ε −8·10⁻⁶, β 1.9; tests/test_rom_maps.py). The reduced model holds
only for a laminate without bending–extension coupling and a memoryless contact law (the identified law's Maxwell arm
is not): anything else is refused when the structure is built, with an InputError naming the option. On a linear target
the option has no effect (kernel runs). Each row says how its runs were stepped (``stepping``).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..fem.contact import group_outputs
from ..fem.newmark import SolverSpec
from ..models.delamination import REGIME_BOUNDS, criterion_validity, response_regime
from ..models.materials import Material
from ..models.specimens import Impactor
from ..models.validity import (
    Validity,
    coupled_validity,
    identified_contact_validity,
    identified_range_validity,
    plate_span,
    plate_thickness_validity,
    range_floor_validity,
)
from ..workflows.coupled import ImpactProblem, impact_kernels, run_impact
from ..workflows.damage import coupled_damage, delamination_force, olsson_force
from ..workflows.plate_impact import PlateProblem

__all__ = [
    "INDICES",
    "NONLINEAR_STEPPINGS",
    "ONSET",
    "ThresholdStructure",
    "MapRow",
    "structure",
    "damage_index",
    "threshold_velocity",
    "threshold_map",
    "law_draws",
    "gci_two_meshes",
    "run_validity",
    "stepped_run",
    "structure_run",
    "check_range",
    "check_map",
]

INDICES = ("tsai_wu", "delamination")  # the damage indices thresholded by default
ONSET = "olsson"  # the onset map's index: peak force over Olsson's F_d
NONLINEAR_STEPPINGS = ("von-karman", "von-karman-rom")  # a von Kármán target's runs: the full plate (the reference) or its reduced model


@dataclass(frozen=True)
class MapRow:
    """One point of a threshold map: structure, index, diameter d [m], mass m [kg]; the threshold
    velocity [m/s] at the law's mean (``nominal``), median and 5–95 % of the combined band
    (``p05``, ``p95``, widened by ``gci``); ``law_p05``/``law_p95`` the law's draws alone,
    ``beta`` the local power of I in V at the threshold, ``gci`` [m/s] the discretisation
    error, ``coarse`` [m/s] the threshold on the coarser mesh; ``draws`` and ``reached`` the law
    draws and how many reached 1 within the velocity range (NaN thresholds otherwise); ``mass_ratio`` and ``regime``
    the response regime; ``ratios`` and ``flags`` the validity of the law's mean run at ``nominal`` (module docstring;
    empty when no threshold), ``kinematics`` the target's, ``band_from`` where the band comes from ("own draws" or
    "linear map": then ``beta`` is the linear row's too), ``runs`` the runs the nominal root-finding took, ``stepping``
    how they were stepped ("kernels", "direct", "von-karman" or "von-karman-rom": the method of
    :func:`~softimpact.workflows.coupled.run_impact`)."""

    structure: str
    index: str
    diameter: float
    mass: float
    nominal: float
    median: float
    p05: float
    p95: float
    law_p05: float
    law_p95: float
    beta: float
    gci: float
    coarse: float
    draws: int
    reached: int
    mass_ratio: float = math.nan  # the impactor's mass over the target's (the row's validity)
    regime: str = ""  # its response regime (module docstring)
    ratios: dict = dataclasses.field(default_factory=dict)  # the nominal run's validity ratios at V* (summary names)
    flags: tuple[str, ...] = ()  # the validity flags it raises, by name (models.validity.FLAG_LABELS)
    kinematics: str = "linear"  # the target's: "linear" (kernel runs) or "von-karman" (stepped directly)
    band_from: str = "own draws"  # where the band comes from: "own draws", or "linear map" (relative widths carried over)
    runs: int = 0  # the coupled runs the nominal threshold took (its root-finding)
    stepping: str = ""  # how the map's runs were stepped: "kernels", "direct", "von-karman" or "von-karman-rom"

    @property
    def inside(self) -> bool | None:
        """Whether the nominal run at V* raises no validity flag; None when no threshold was reached (nothing checked)."""
        return None if not self.ratios else not self.flags

    def as_dict(self) -> dict:
        """The row under its CSV/JSON names (SI): the thresholds and band, then the validity columns."""
        return {
            "structure": self.structure,
            "index": self.index,
            "diameter_m": self.diameter,
            "mass_kg": self.mass,
            "threshold_velocity_nominal_m_s": self.nominal,
            "threshold_velocity_median_m_s": self.median,
            "threshold_velocity_p05_m_s": self.p05,
            "threshold_velocity_p95_m_s": self.p95,
            "law_p05_m_s": self.law_p05,
            "law_p95_m_s": self.law_p95,
            "index_power_beta": self.beta,
            "discretisation_error_m_s": self.gci,
            "threshold_velocity_coarse_mesh_m_s": self.coarse,
            "draws": self.draws,
            "draws_reaching_1": self.reached,
            "impactor_over_target_mass": self.mass_ratio,
            "regime": self.regime,
            "kinematics": self.kinematics,
            "stepping": self.stepping,
            "band_from": self.band_from,
            "nominal_threshold_runs": self.runs,
            **{k: float(v) for k, v in self.ratios.items()},
            "validity_flags": list(self.flags),
            "inside_validity": self.inside,
        }


@dataclass
class ThresholdStructure:
    """A structure ready for threshold runs: its impact problem, its model (with the target's
    ``"damage"`` output group) and its contact kernels (built once, for the widest diameter; None on a nonlinear
    target, whose runs are stepped directly); on a von Kármán plate with ``nonlinear_stepping`` "von-karman-rom", ``rom``
    its reduced model (:class:`~softimpact.fem.vk_rom.PlateVKROM`, built once, every run's engine; None otherwise).
    Not frozen: the kernels keep a cache of the smaller impactors' contact discs."""

    name: str
    problem: ImpactProblem
    model: object
    kernels: object
    density: float  # kg/m³ of the impactor
    nonlinear_stepping: str = "von-karman"  # a nonlinear target's runs (:data:`NONLINEAR_STEPPINGS`); unused on a linear one
    rom: object = None  # the reduced plate of "von-karman-rom" stepping

    @property
    def kinematics(self) -> str:
        """The target's kinematics: "linear", or "von-karman" (large deflection)."""
        return self.problem.target.kinematics

    @property
    def stepping(self) -> str:
        """How a direct run of this structure is stepped (:func:`~softimpact.workflows.coupled.run_impact`'s ``method``):
        "direct" on a linear target, its kinematics' own stepper ("von-karman") otherwise, or its reduced model
        ("von-karman-rom") when it has one."""
        if self.kinematics == "linear":
            return "direct"
        return "von-karman-rom" if self.rom is not None else self.kinematics

    def problem_at(self, law, diameter: float, velocity: float) -> ImpactProblem:
        """The problem for a ball of ``diameter`` [m] at ``velocity`` [m/s] under the identified ``law`` (an IdentifiedLaw)."""
        mass = self.density * math.pi / 6.0 * diameter**3
        imp = Impactor(mass, diameter, velocity)
        return dataclasses.replace(self.problem, impactor=imp, law=law.law(mass, diameter, velocity))


def structure(
    name: str, target, widest: float, density: float, time_step: float, duration: float, law, *, nonlinear_stepping: str = "von-karman"
) -> ThresholdStructure:
    """A :class:`ThresholdStructure` from a resolved target ``target`` (a :class:`~softimpact.models.protocols.Target`:
    its load position and contact radius used, its force history dropped, :meth:`~softimpact.models.protocols.Target.for_impact`;
    its kinematics kept: a "von-karman" target gets no kernels and steps every run),
    for balls up to ``widest`` [m] of ``density`` [kg/m³], stepped at ``time_step`` [s] for ``duration`` [s];
    ``law``: the identified law (its mean; any law serves for the build, the kernels hold none).
    ``nonlinear_stepping`` (:data:`NONLINEAR_STEPPINGS`): how a von Kármán target's runs are stepped, "von-karman" (the
    full plate) or "von-karman-rom" (its reduced model, built here once: a plate whose laminate has no bending–extension
    coupling, under a memoryless law; an InputError naming the option otherwise); no effect on a linear target."""
    if nonlinear_stepping not in NONLINEAR_STEPPINGS:
        raise InputError(f"nonlinear_stepping must be one of {', '.join(NONLINEAR_STEPPINGS)}, got {nonlinear_stepping!r}")
    resolved = target.for_impact(SolverSpec(time_step, duration), ())
    rubber = Material("ball", 5.0e6, 0.49, density, "threshold-map impactor (the law carries the contact)")
    mass = density * math.pi / 6.0 * widest**3
    problem = ImpactProblem(resolved, name, Impactor(mass, widest, 1.0), rubber, "identified", law.law(mass, widest, 1.0), name)
    if not resolved.has_damage_outputs:
        raise InputError(f"{name}: no damage outputs (the laminate needs a layup and a ply with strengths)")
    model = problem.model(damage=True)
    linear = resolved.kinematics == "linear"
    kernels = impact_kernels(problem, model) if linear else None  # a nonlinear target steps every run (module docstring)
    rom = None if linear else _reduced_model(name, problem, model, nonlinear_stepping)
    return ThresholdStructure(name, problem, model, kernels, density, nonlinear_stepping, rom)


def _reduced_model(name: str, problem: ImpactProblem, model, nonlinear_stepping: str):
    """The reduced plate of a nonlinear target (:func:`~softimpact.fem.vk_rom.reduced_plate`, at its impact point) when
    ``nonlinear_stepping`` asks for it, else None; an InputError naming the option where it cannot apply."""
    from ..fem.vk_rom import reduced_plate
    from ..models.protocols import HistoryLaw

    if nonlinear_stepping == "von-karman":
        return None
    where = f"{name}: nonlinear_stepping = 'von-karman-rom'"
    if isinstance(problem.law, HistoryLaw):
        raise InputError(f"{where} needs a memoryless contact law ({type(problem.law).__name__} has memory): use nonlinear_stepping = 'von-karman'")
    reach = model.contact_reach(problem.position, problem.impactor.diameter)
    try:
        return reduced_plate(model.stepper, model.contact_structure(problem.position, reach).approach_row)
    except InputError as exc:
        raise InputError(f"{where}: {exc}; use nonlinear_stepping = 'von-karman'") from None


def damage_index(problem: ImpactProblem, result, index: str, scale: float = 1.0) -> float:
    """The damage ``index`` of a coupled run (:data:`INDICES` or :data:`ONSET`; ``result`` with its ``"damage"``
    output group): Tsai–Wu at the load point, the Davies–Zhang delamination index (peak force / P_c) or Olsson's
    onset (peak force / F_d); ``scale`` multiplies every strength (and P_c, F_d): the index is divided by it
    (homogeneous of degree −1)."""
    stack = problem.target.stack
    if index in ("delamination", ONSET):
        peak = max(c.peak_force for c in result.contacts)
        threshold = delamination_force if index == "delamination" else olsson_force
        return peak / threshold(stack, stack.ply.strength.GIIc) / scale
    return coupled_damage(problem.target, result, ("at_load",)).points["at_load"].peak[index] / scale


def _method(s: ThresholdStructure, method: str) -> str:
    """The run method actually used: "kernels" on a linear structure, else the structure's direct stepping."""
    return "kernels" if method == "kernels" and s.kernels is not None else s.stepping


def structure_run(s: ThresholdStructure, law, diameter: float, velocity: float, method: str = "kernels"):
    """(problem, result) of one coupled run of structure ``s``: ball of ``diameter`` [m] at ``velocity`` [m/s] under
    ``law``, on its kernels ("kernels" on a linear structure) or stepped as the structure says (:attr:`ThresholdStructure.stepping`,
    its reduced plate reused), the result's output groups split (``"damage"`` among them)."""
    problem = s.problem_at(law, diameter, velocity)
    method = _method(s, method)
    engine = s.rom if method == "von-karman-rom" else None  # the reduced plate, built once for every run of the structure
    _, result = run_impact(problem, s.model, energy=False, method=method, kernels=s.kernels if method == "kernels" else None, engine=engine)
    return problem, group_outputs(result, s.model.contact_groups())


def stepped_run(problem: ImpactProblem):
    """One coupled run of ``problem`` stepped directly (no kernels) by its target's kinematics' stepper ("direct" on a
    linear target), with its ``"damage"`` output group: the result (a :class:`~softimpact.workflows.coupled.CoupledResult`)."""
    model = problem.model(damage=True)
    method = "direct" if problem.target.kinematics == "linear" else problem.target.kinematics
    _, result = run_impact(problem, model, energy=False, method=method)
    return group_outputs(result, model.contact_groups())


def run_validity(problem: ImpactProblem, result, identified=None) -> Validity:
    """The validity of one coupled run of a threshold map (``result`` with its ``"damage"`` output group), checked as
    the impact command checks its run (:func:`~softimpact.models.validity.coupled_validity`, the maximum-strain index
    over the target's damage points: :func:`~softimpact.workflows.damage.coupled_damage`'s, as in summary.json) and,
    with the ``identified`` law (an IdentifiedLaw), the impactor against the tests it was identified on, as the command
    warns when it reads the law (:func:`~softimpact.models.validity.identified_range_validity`)."""
    dmg = coupled_damage(problem.target, result, impactor_mass=problem.impactor.mass).summary()
    v = coupled_validity(problem, result, dmg["max_strain"])
    if isinstance(problem.target, PlateProblem):  # plate theory's geometry, as the impact command checks its plate target
        spec = problem.target.plate
        v += plate_thickness_validity(spec.total_thickness, plate_span(spec.length_x, spec.length_y, spec.supports))
    if identified is not None:
        i = problem.impactor
        ranges = identified_range_validity(identified.identified_on, i.velocity, i.diameter, i.mass, "the identified law")
        v += Validity({}, ranges.flags, ranges.names)  # its flags (the command's warnings); its ratios stay out of the row
        v += identified_contact_validity(identified.identified_on, float(np.max(result.approach)), i.diameter, float(np.max(result.contact_radius)))
    return v


def index_at(s: ThresholdStructure, law, diameter: float, velocity: float, index: str, method: str = "kernels", runs: dict | None = None) -> float:
    """The damage ``index`` of one coupled run: ball of ``diameter`` [m] at ``velocity`` [m/s]; ``method`` "kernels" or "direct".
    ``runs``: coupled runs already made, filled here ((structure, law, diameter, velocity, method) → run, the
    objects by identity: for one caller that keeps them alive), so a run every index reads is made once."""
    if runs is None:
        return damage_index(*structure_run(s, law, diameter, velocity, method), index)
    key = (id(s), id(law), diameter, velocity, _method(s, method))
    if key not in runs:
        runs[key] = structure_run(s, law, diameter, velocity, method)
    return damage_index(*runs[key], index)


def threshold_velocity(
    s: ThresholdStructure,
    law,
    diameter: float,
    index: str,
    lo: float,
    hi: float,
    rtol: float = 2e-4,
    guess: float | None = None,
    beta: float | None = None,
    method: str = "kernels",
    runs: dict | None = None,
    evaluated: list | None = None,
) -> float:
    """The velocity V* [m/s] in [``lo``, ``hi``] at which ``index`` first reaches 1 (kernel runs):
    a geometric scan (ratio 1.5) for the first level where I ≥ 1, then Brent's method on
    ln I(V) in ln V to relative tolerance ``rtol``. NaN when I < 1 up to ``hi``; ``lo`` when I ≥ 1 there.

    With a ``guess`` (a nearby threshold: the law's mean for one of its draws) and the local power
    ``beta`` of I in V there, secant steps on ln I against ln V from it first (two or three runs);
    the scan when they leave [lo, hi] or do not converge in 8 runs. A draw whose I crosses 1
    more than once in the range may then give a crossing other than the first: the
    indices here grow monotonically with V over the ranges used (they follow the peak force).
    ``method``: "kernels" (the runs of a map) or "direct" (each run stepped directly: the reference);
    ``runs``: as :func:`index_at`'s (the scans of two indices share their runs); ``evaluated``: a list the velocities
    evaluated are appended to (its length: the root-finding's cost in runs, some maybe shared through ``runs``).
    On a nonlinear structure (no kernels) ``method`` "kernels" steps each run directly (:attr:`ThresholdStructure.stepping`)."""
    from scipy.optimize import brentq

    def g(lnv):
        if evaluated is not None:
            evaluated.append(math.exp(lnv))
        return math.log(max(index_at(s, law, diameter, math.exp(lnv), index, method, runs), 1e-300))

    if guess is not None and beta is not None and math.isfinite(guess) and beta > 0:
        x0, g0 = math.log(guess), g(math.log(guess))
        x1 = x0 - g0 / beta
        for _ in range(7):
            if not math.log(lo) < x1 < math.log(hi):
                break
            if abs(x1 - x0) < rtol / 4:
                return math.exp(x1)
            g1 = g(x1)
            if g1 == g0:
                break
            x0, x1, g0 = x1, x1 - g1 * (x1 - x0) / (g1 - g0), g1

    a, ga = math.log(lo), g(math.log(lo))
    if ga >= 0:
        return lo
    while a < math.log(hi):
        b = min(a + math.log(1.5), math.log(hi))
        gb = g(b)
        if gb >= 0:
            return math.exp(brentq(g, a, b, xtol=rtol / 4, rtol=rtol / 4))
        a = b
    return math.nan


def check_range(lo: float, hi: float) -> None:
    """Refuse a velocity range a threshold cannot be searched in: 0 < lo < hi [m/s], both finite."""
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo < hi):
        raise InputError(f"threshold velocity range: need 0 < lo < hi (finite), got lo = {lo!r} m/s, hi = {hi!r} m/s", "lo")


def check_map(indices, diameters, known=(*INDICES, ONSET), **scalars) -> None:
    """Refuse, before any run, a map's arguments it would fail on or silently mis-read: an index not among ``known``
    (the nearest suggested), no diameter or one not positive and finite [m], and any of ``scalars`` (name → value:
    ``strength_cov``, ``draws``) not a finite non-negative number (a NaN scatter would give a NaN band)."""
    import difflib

    if isinstance(indices, str) or not len(indices):
        raise InputError(f"indices: expected a list of indices of {', '.join(known)}, got {indices!r}", "indices")
    for index in indices:
        if index not in known:
            near = difflib.get_close_matches(str(index), known, n=1, cutoff=0.6)
            raise InputError(
                f"indices: {index!r} is not an index of the maps ({f'did you mean {near[0]!r}? ' if near else ''}known: {', '.join(known)})", "indices"
            )
    if isinstance(diameters, str) or not len(diameters) or not all(isinstance(d, (int, float)) and math.isfinite(d) and d > 0 for d in diameters):
        raise InputError(f"diameters: expected positive finite diameters [m], got {diameters!r}", "diameters")
    for name, value in scalars.items():
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not (math.isfinite(value) and value >= 0):
            raise InputError(f"{name}: expected a finite number >= 0, got {value!r}", name)


def law_draws(law, draws: int, seed: int = 1) -> list:
    """``draws`` copies of the identified ``law`` with its spread parameters drawn (Latin hypercube,
    ``seed``) from its covariance, or its 95 % half-widths /1.96 when it has none; draws outside the
    law's admissible range (k_ref, p, theta_ref > 0; c_ref, kappa_ref ≥ 0) are clipped to it."""
    from scipy.stats import norm, qmc

    names = list(law.names)
    spread = [i for i, h in enumerate(law.half_widths) if h > 0]
    if not spread or draws < 1:
        return []
    if law.covariance is not None:
        C = np.asarray(law.covariance, float)[np.ix_(spread, spread)]
    else:
        C = np.diag((np.asarray(law.half_widths, float)[spread] / 1.96) ** 2)
    L = np.linalg.cholesky(0.5 * (C + C.T) + 1e-30 * np.eye(len(spread)))
    u = qmc.LatinHypercube(d=len(spread), seed=seed).random(draws)
    z = norm.ppf(u) @ L.T
    out = []
    for row in z:
        v = np.array(law.values, float)
        v[spread] += row
        for n, floor in (("k_ref", 1e-12), ("p", 1e-3), ("c_ref", 0.0), ("kappa_ref", 0.0), ("theta_ref", 1e-9)):
            if n in names:
                v[names.index(n)] = max(v[names.index(n)], floor)
        out.append(dataclasses.replace(law, values=v))
    return out


def gci_two_meshes(fine: float, coarse: float, r: float = 2.0, p: float = 2.0, fs: float = 3.0) -> float:
    """Two-mesh GCI [same unit] of the FINE value (Roache): Fs·|fine − coarse|/(r^p − 1); NaN if either is."""
    if not (math.isfinite(coarse) and math.isfinite(fine)):
        return math.nan
    return fs * abs(fine - coarse) / (r**p - 1.0)


def threshold_map(
    s: ThresholdStructure,
    law,
    diameters,
    lo: float,
    hi: float,
    draws: int = 8,
    strength_cov: float = 0.10,
    strength_quantiles: int = 9,
    coarse: ThresholdStructure | None = None,
    indices=INDICES,
    seed: int = 1,
    band_from: list[MapRow] | None = None,
) -> list[MapRow]:
    """The threshold map of structure ``s`` (module docstring): one :class:`MapRow` per index (``indices``: of
    :data:`INDICES` and :data:`ONSET`; ``(ONSET,)`` the onset map) and diameter [m], with its regime and its
    validity at the nominal threshold, velocity range [``lo``, ``hi``] m/s; ``coarse``: the same structure on the mesh
    (and step) coarser by 2, for the discretisation error (None: no estimate, ``gci`` NaN). ``band_from``: rows of
    a map of the same structure (the linear one) whose relative band this map carries over instead of drawing its own
    (module docstring; each index and diameter must have its row there); their thresholds also start the root-finding."""
    from scipy.stats import norm

    check_range(lo, hi)
    check_map(indices, diameters, strength_cov=strength_cov, draws=draws, strength_quantiles=strength_quantiles)
    drawn = law_draws(law, draws, seed) if band_from is None else []
    q = norm.ppf((np.arange(strength_quantiles) + 0.5) / strength_quantiles)
    factors = np.maximum(1.0 + strength_cov * q, 0.05)
    runs: dict = {}  # every coupled run of the map, for all its indices (the scans from lo are the same runs)
    return [_map_row(s, law, index, d, (lo, hi), coarse, drawn, factors, runs, band_from) for index in indices for d in diameters]


def _map_row(s: ThresholdStructure, law, index: str, d: float, bounds, coarse, drawn: list, factors, runs: dict, band_from) -> MapRow:
    """One row of :func:`threshold_map`: ``index`` at diameter ``d`` [m], velocities in ``bounds`` (lo, hi) [m/s], the
    law's ``drawn`` copies and the strength ``factors`` for its band (or the row of ``band_from`` carried over),
    ``runs`` the map's coupled runs (shared by its rows)."""
    lo, hi = bounds
    mass = s.density * math.pi / 6.0 * d**3
    ref = None if band_from is None else _row_of(band_from, index, d)
    evaluated: list = []
    guess = dict(guess=ref.nominal, beta=ref.beta) if ref is not None else {}
    nominal = threshold_velocity(s, law, d, index, lo, hi, runs=runs, evaluated=evaluated, **guess)
    beta, ratios, flags = (math.nan if ref is None else ref.beta), {}, ()
    if math.isfinite(nominal):
        if ref is None:  # (a carried band carries its β too: two runs fewer a threshold)
            i1, i2 = (index_at(s, law, d, nominal * f, index, runs=runs) for f in (0.98, 1.02))
            beta = math.log(i2 / i1) / math.log(1.02 / 0.98)
        validity = run_validity(*_cached_run(s, law, d, nominal, runs), law) + range_floor_validity(nominal, lo)
        ratios, flags = dict(validity.values), tuple(validity.names)
    coarse_v = threshold_velocity(coarse, law, d, index, lo, hi, guess=nominal, beta=beta, runs=runs) if coarse is not None else math.nan
    coarse_v = math.nan if coarse_v <= lo else coarse_v  # a coarse threshold at the floor is not found: no GCI from it
    gci = gci_two_meshes(nominal, coarse_v)
    widen = gci if math.isfinite(gci) else 0.0
    if ref is not None:
        count, reached = ref.draws, ref.reached if math.isfinite(nominal) else 0
        p05, p95, med, law_lo, law_hi = _carried_band(ref, nominal, widen)
    else:
        vs = np.array([threshold_velocity(s, lw, d, index, lo, hi, guess=nominal, beta=beta, runs=runs) for lw in drawn] or [nominal], float)
        count, reached, (p05, p95, med, law_lo, law_hi) = len(vs), int(np.isfinite(vs).sum()), _drawn_band(vs, beta, factors, widen)
    target = s.problem.target.mass
    regime = response_regime(mass, target, wave_below=REGIME_BOUNDS[0], quasi_static_above=REGIME_BOUNDS[1])
    if math.isfinite(nominal):  # a quasi-static threshold's row on a wave-controlled impact says so (criterion_outside_regime)
        flags += criterion_validity(regime, (index,)).names
    return MapRow(
        s.name, index, d, mass, nominal, med, p05, p95, law_lo, law_hi, beta, gci, coarse_v, count, reached, mass / target, regime, ratios, flags,
        s.kinematics, "own draws" if ref is None else "linear map", len(evaluated), _method(s, "kernels"),
    )  # fmt: skip


def _drawn_band(vs: np.ndarray, beta: float, factors: np.ndarray, widen: float) -> tuple[float, ...]:
    """(p05, p95, median, law p05, law p95) of the thresholds ``vs`` of the law's draws (NaN: above the range) combined
    with the strength factors (V*·s^(1/β), module docstring (b)), the 90 % band widened by ``widen`` on both sides;
    all NaN when no draw reached its threshold or β is not a positive number."""
    ok = vs[np.isfinite(vs)]
    if not (ok.size and math.isfinite(beta) and beta > 0):
        return (math.nan,) * 5
    combined = (ok[:, None] * factors[None, :] ** (1.0 / beta)).ravel()
    lo_b, hi_b = np.percentile(combined, [5, 95])
    law_lo, law_hi = np.percentile(ok, [5, 95])
    return float(lo_b - widen), float(hi_b + widen), float(np.median(ok)), float(law_lo), float(law_hi)


def _cached_run(s: ThresholdStructure, law, diameter: float, velocity: float, runs: dict):
    """The map's coupled run at ``velocity`` (made once: :func:`index_at`'s cache)."""
    index_at(s, law, diameter, velocity, INDICES[0], runs=runs)
    return runs[(id(s), id(law), diameter, velocity, _method(s, "kernels"))]


def _row_of(rows: list[MapRow], index: str, diameter: float) -> MapRow:
    """The row of ``rows`` for ``index`` and ``diameter`` [m] (to 1e-9 relative)."""
    for r in rows:
        if r.index == index and math.isclose(r.diameter, diameter, rel_tol=1e-9):
            return r
    raise InputError(f"band_from: no row for {index} at d = {diameter:.6g} m (the linear map must have the same indices and diameters)")


def _carried_band(ref: MapRow, nominal: float, widen: float) -> tuple[float, float, float, float, float]:
    """(p05, p95, median, law_p05, law_p95) [m/s] at ``nominal`` from the linear row ``ref``'s band relative to its own
    nominal threshold (its band before its GCI widening), widened by this map's ``widen`` [m/s] on both sides."""
    if not (math.isfinite(nominal) and math.isfinite(ref.nominal) and ref.nominal > 0):
        return (math.nan,) * 5
    w = ref.gci if math.isfinite(ref.gci) else 0.0
    rel = nominal / ref.nominal
    return (
        (ref.p05 + w) * rel - widen,
        (ref.p95 - w) * rel + widen,
        ref.median * rel,
        ref.law_p05 * rel,
        ref.law_p95 * rel,
    )
