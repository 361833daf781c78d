"""Hail threshold maps on Rhymer's panels: the delamination-onset velocity of ice spheres against their
diameter, per panel thickness, from COUPLED impact with the crushing law, the critical force at that onset,
and the failure threshold energy FTE = ½·m·V*² against thickness over diameter h/D with its linear fit.

The panels (Rhymer, Kim & Roach, Composites Part A 43 (2012) 1134-1144, doi:10.1016/j.compositesa.2012.02.017,
abstract): T800/3900-2 carbon/epoxy tape, quasi-isotropic, three thicknesses 1.59, 3.11 and 4.66 mm, each struck
by ice spheres of 38.1, 50.8 and 61.0 mm. The panels are given as a function that builds each one's plate
target (the report's, :func:`softimpact.app.paper.hail.panel_target`, from a case file: studies read no files).
What was not retrieved, and what the report stands in for it:

- the ply: T800/3900-2 is not in the catalogue; the catalogue's IM7/8552 (intermediate-modulus fibre, toughened
  epoxy; its moduli, strengths and G_IIc) stands in, with the ply thickness set so the panel has Rhymer's thickness;
- the layups: 8, 16 and 24 plies, [45/0/-45/90]s, [45/0/-45/90]2s, [45/0/-45/90]3s (quasi-isotropic; the plies
  are then 0.199, 0.194 and 0.194 mm, the order of a tape ply), a choice;
- the panels' size and supports: the built-in hail-plate-qi case's 300 × 300 mm, simply supported, a choice.

Indices (:mod:`softimpact.studies.thresholds`, read-only, its :func:`~softimpact.studies.thresholds.threshold_velocity`
on its contact kernels): Olsson's onset, the coupled peak force over F_d = π·sqrt(32·D*·G_IIc/9) (:data:`ONSET`), and
Davies–Zhang's, the peak force over P_c (``"delamination"``), beside it. Both are the peak force over a force fixed
by the laminate alone, so the CRITICAL FORCE at the onset (the coupled peak force at V*) is that force whatever the
ice diameter: the diameter-independence Rhymer & Kim found (Computers, Materials & Continua 35 (2013) 87-117,
abstract) is built into this criterion, not predicted by it. What the model predicts is V*, hence FTE, and how
FTE goes with h/D.

Each row carries the validity of its run at V* (the single impact run's checks: the contact law's approach and
radius against the sphere, the crushing strength's strain rate against the range it was measured on, the
plate's deflection over its thickness; :func:`run_validity`), the sphere's mass over the panel's and the response
regime it falls in (as :mod:`~softimpact.studies.thresholds`' rows: Olsson's F_d is a quasi-static threshold), and
the discretisation error of V*: the two-mesh
GCI (:func:`~softimpact.studies.thresholds.gci_two_meshes`: safety factor 3, formal order 2, ratio 2) between the
map's mesh and one coarser by 2 in elements and step.

Large deflection: the panels' ``kinematics`` may be "von-karman" (:func:`hail_map`): no kernels then, every run (the
one at V* included) stepped by the nonlinear plate's own stepper, and with ``guesses`` (the linear map's rows) each
threshold's secant steps start from the linear V*, so a nonlinear threshold costs a few runs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from ..models.crushing_law import CrushingLaw
from ..models.delamination import REGIME_BOUNDS, criterion_validity, response_regime
from ..models.projectiles import projectile_material
from ..models.validity import range_floor_validity
from .thresholds import ONSET, check_map, check_range, gci_two_meshes, structure, structure_run, threshold_velocity

__all__ = [
    "RHYMER_THICKNESSES",
    "RHYMER_DIAMETERS",
    "RHYMER_LAYUPS",
    "STAND_IN_PLY",
    "HAIL_INDICES",
    "CatalogueIce",
    "HailRow",
    "FteFit",
    "hail_structures",
    "hail_map",
    "fte_fit",
    "run_validity",
]

RHYMER_THICKNESSES = (1.59e-3, 3.11e-3, 4.66e-3)  # m: Rhymer, Kim & Roach 2012 (abstract)
RHYMER_DIAMETERS = (38.1e-3, 50.8e-3, 61.0e-3)  # m: the same tests' ice spheres
RHYMER_LAYUPS = ("[45/0/-45/90]s", "[45/0/-45/90]2s", "[45/0/-45/90]3s")  # a choice: quasi-isotropic, 8, 16, 24 plies
STAND_IN_PLY = "IM7/8552"  # for T800/3900-2, not in the catalogue
HAIL_INDICES = (ONSET, "delamination")  # Olsson's onset, Davies–Zhang beside it
GUESS_POWER = 2.0  # the power of the index in V assumed by the first secant step from a guessed V* (the secant's own slope after it)


@dataclass(frozen=True)
class CatalogueIce:
    """The catalogue's ice as a law of the threshold maps (the interface of an identified law they read:
    ``law(m, d, V)`` and no spread parameters): the crushing law with the material's strength
    (Jones 1997, :data:`~softimpact.models.projectiles.JONES_1997_FRESHWATER`), or ``strength`` if given."""

    strength: object = None
    names: tuple = ()
    values: np.ndarray = field(default_factory=lambda: np.zeros(0))
    half_widths: np.ndarray = field(default_factory=lambda: np.zeros(0))
    covariance: None = None

    @property
    def density(self) -> float:
        return projectile_material("ice").density

    def law(self, mass: float, diameter: float, velocity: float) -> CrushingLaw:
        return CrushingLaw(mass, diameter, self.strength or projectile_material("ice").strength)


def hail_structures(
    panel_target, thickness: float, layup: str, law, meshes, duration: float, widest: float, kinematics: str = "linear", nonlinear_stepping: str = "von-karman"
):
    """(map mesh, coarse mesh) :class:`~softimpact.studies.thresholds.ThresholdStructure` of one panel:
    ``panel_target(thickness, layup, elements, duration, kinematics=...)`` the resolved plate target (a
    :class:`~softimpact.models.protocols.Target`; the report builds it from a case file,
    :func:`softimpact.app.paper.hail.panel_target`), ``meshes`` ((elements a side, time step [s]) coarse,
    fine); spheres up to ``widest`` [m] of ice; ``kinematics`` the panels' ("linear" or "von-karman"), and
    ``nonlinear_stepping`` how a von Kármán panel's runs are stepped (:func:`~softimpact.studies.thresholds.structure`:
    the full plate, or its reduced model, built once per mesh)."""
    out = []
    for n, dt in meshes:
        target = panel_target(thickness, layup, n, duration, kinematics=kinematics)
        out.append(structure(f"{thickness * 1e3:.2f} mm", target, widest, _density(law), dt, duration, law, nonlinear_stepping=nonlinear_stepping))
    return out[1], out[0]


def _density(law) -> float:
    """The spheres' density [kg/m³]: the catalogue's ice, for either law of the maps (:class:`CatalogueIce` is the
    catalogue's ice; an identified crushing law holds no density, and its tests' spheres were ice)."""
    return projectile_material("ice").density


def run_validity(problem, result):
    """The validity of one coupled run, composed as the single impact run composes it
    (:func:`softimpact.models.validity.coupled_validity`): the contact law's approach and contact radius against the
    sphere, the law's own envelope, the target's deflection against its thickness."""
    from ..models.validity import coupled_validity

    return coupled_validity(problem, result)


@dataclass(frozen=True)
class HailRow:
    """One point of a hail map: panel ``thickness`` [m], ice ``diameter`` [m] and ``mass`` [kg], ``index``; the onset
    velocity ``velocity`` [m/s] on the map's mesh (NaN above the range), ``coarse`` on the coarser, ``gci`` [m/s] its
    discretisation error; ``fte`` = ½·m·V*² [J]; ``peak_force`` [N] the coupled peak at V* (the critical force) and
    ``threshold_force`` [N] the index's own (F_d or P_c); ``validity`` the run's ratios and flags at V*."""

    thickness: float
    diameter: float
    mass: float
    index: str
    velocity: float
    coarse: float
    gci: float
    peak_force: float
    threshold_force: float
    validity: dict
    mass_ratio: float = math.nan  # the sphere's mass over the panel's
    regime: str = ""  # its response regime (:func:`~softimpact.models.delamination.response_regime`, stand-in bounds)
    kinematics: str = "linear"  # the panel's: "linear" or "von-karman"
    floored: bool = False  # the onset is the search's lowest velocity: at or below it, not found (flagged; not fitted)

    @property
    def fte(self) -> float:
        return 0.5 * self.mass * self.velocity**2

    @property
    def h_over_d(self) -> float:
        return self.thickness / self.diameter

    def as_dict(self) -> dict:
        v = {k: val for k, val in self.validity.items() if k != "flags"}
        return {
            "thickness_m": self.thickness,
            "diameter_m": self.diameter,
            "mass_kg": self.mass,
            "index": self.index,
            "h_over_d": self.h_over_d,
            "threshold_velocity_m_s": self.velocity,
            "threshold_velocity_coarse_mesh_m_s": self.coarse,
            "discretisation_error_m_s": self.gci,
            "fte_J": self.fte,
            "fte_discretisation_error_J": self.mass * self.velocity * self.gci if math.isfinite(self.gci) else math.nan,
            "critical_force_N": self.peak_force,
            "threshold_force_N": self.threshold_force,
            "impactor_over_target_mass": self.mass_ratio,
            "regime": self.regime,
            **{f"validity_{k}": float(val) for k, val in v.items()},
            "validity_flags": "; ".join(self.validity.get("flags", [])),
        }


def _threshold_force(s, index: str) -> float:
    from ..workflows.damage import delamination_force, olsson_force

    stack = s.problem.target.stack
    return (olsson_force if index == ONSET else delamination_force)(stack, stack.ply.strength.GIIc)


def hail_map(
    law,
    panel_target,
    thicknesses=RHYMER_THICKNESSES,
    diameters=RHYMER_DIAMETERS,
    layups=RHYMER_LAYUPS,
    meshes=None,
    duration: float = 1.5e-3,
    lo: float = 2.0,
    hi: float = 300.0,
    indices=HAIL_INDICES,
    rtol: float = 1e-3,
    kinematics: str = "linear",
    guesses=(),
    nonlinear_stepping: str = "von-karman",
):
    """The hail map (module docstring): one :class:`HailRow` per thickness, index and diameter, ice of ``law``
    (:class:`CatalogueIce` or an identified crushing law,
    :class:`~softimpact.workflows.identification.CrushingIdentifiedLaw`) on the panels of ``panel_target``
    (:func:`hail_structures`) between ``lo`` and ``hi`` m/s. ``meshes``: ((elements, step)
    coarse, fine), default ((4, 4 µs), (8, 2 µs)).

    ``kinematics``: the panels' ("linear", or "von-karman": large deflection; no kernels then, every run, the one at V*
    included, stepped by the panel's own stepper, :attr:`~softimpact.studies.thresholds.ThresholdStructure.stepping`).
    ``guesses``: rows of another map of the same panels (the linear map's): the V* of the row with the same thickness,
    diameter and index starts the threshold's secant steps (:func:`~softimpact.studies.thresholds.threshold_velocity`,
    first-step power :data:`GUESS_POWER`), in place of the scan from ``lo``. ``nonlinear_stepping``: a von Kármán
    panel's runs on the full plate ("von-karman") or on its reduced model ("von-karman-rom": the crushing law is
    memoryless and the quasi-isotropic panels have no bending–extension coupling; on the thinnest panel, 8 × 8 at
    2 µs, w/h 2-3, its peak force is the full plate's within 0.7 %, ``tests/test_rom_maps.py``)."""
    check_range(lo, hi)
    check_map(indices, diameters, known=(ONSET, "delamination"))
    if len(thicknesses) != len(layups):  # zip would drop the panels past the shorter list, silently
        raise InputError(f"thicknesses and layups: one layup per panel thickness, got {len(thicknesses)} thicknesses and {len(layups)} layups", "layups")
    if kinematics not in ("linear", "von-karman"):
        raise InputError(f"kinematics: {kinematics!r} is not one of linear, von-karman", "kinematics")
    meshes = meshes or ((4, 4e-6), (8, 2e-6))
    start = {(r.thickness, r.diameter, r.index): r.velocity for r in guesses if math.isfinite(r.velocity)}
    rows = []
    for h, layup in zip(thicknesses, layups):
        fine, coarse = hail_structures(panel_target, h, layup, law, meshes, duration, max(diameters), kinematics, nonlinear_stepping)
        runs: dict = {}
        for index in indices:
            for d in diameters:
                guess = start.get((h, d, index))
                v = threshold_velocity(fine, law, d, index, lo, hi, rtol=rtol, guess=guess, beta=GUESS_POWER if guess else None, runs=runs)
                vc = threshold_velocity(coarse, law, d, index, lo, hi, rtol=rtol, guess=v, beta=GUESS_POWER, runs=runs) if math.isfinite(v) else math.nan
                vc = math.nan if vc <= lo else vc  # a coarse onset at the floor is not found: no GCI from it
                mass = _density(law) * math.pi / 6.0 * d**3
                peak, validity = math.nan, {"flags": []}
                ratio = mass / fine.problem.target.mass
                regime = response_regime(mass, fine.problem.target.mass, wave_below=REGIME_BOUNDS[0], quasi_static_above=REGIME_BOUNDS[1])
                if math.isfinite(v):
                    problem, result = structure_run(fine, law, d, v)
                    peak = max(c.peak_force for c in result.contacts)
                    # the run's checks, and a quasi-static threshold applied outside its regime (criterion_outside_regime)
                    validity = (run_validity(problem, result) + range_floor_validity(v, lo) + criterion_validity(regime, (index,))).summary()
                row = HailRow(
                    h, d, mass, index, v, vc, gci_two_meshes(v, vc), peak, _threshold_force(fine, index), validity, ratio, regime, fine.kinematics, v <= lo
                )
                rows.append(row)
    return rows


@dataclass(frozen=True)
class FteFit:
    """FTE = slope·(h/D) + intercept [J], least squares over the rows, and its R²; ``n`` the points fitted."""

    slope: float
    intercept: float
    r2: float
    n: int


def fte_fit(rows, index: str = ONSET) -> FteFit:
    """The linear fit of FTE against h/D over the rows of ``index`` that reached their threshold inside the range searched
    (a row at its floor holds an upper bound only)."""
    pts = [(r.h_over_d, r.fte) for r in rows if r.index == index and math.isfinite(r.velocity) and not r.floored]
    if len(pts) < 3:
        return FteFit(math.nan, math.nan, math.nan, len(pts))
    x, y = np.array(pts).T
    slope, intercept = np.polyfit(x, y, 1)
    r2 = 1.0 - float(np.sum((y - (slope * x + intercept)) ** 2)) / float(np.sum((y - y.mean()) ** 2))
    return FteFit(float(slope), float(intercept), r2, len(pts))
