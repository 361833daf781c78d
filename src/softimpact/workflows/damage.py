"""Damage screening of a laminated beam run: first-ply failure at the gauge sections
and the Davies–Zhang delamination index under the load.

At a gauge section the plane model gives the axial strain on both faces; the
section is taken as CLT kinematics (ε_x linear through the thickness between
the two faces, the plane model's own assumption away from the load), with
ε_y = 0 across the width for plane strain or N_y = M_y = 0 for plane stress.
Each ply's stresses at its faces then give the indices of
:mod:`softimpact.models.failure`; a section's index is the worst ply's (found at
the extreme faces of each fibre angle, :func:`extreme_faces`).

On a plate (:func:`plate_damage`) a point's in-plane strain tensor (ε_x, ε_y,
γ_xy) on each face comes from three direction strains (x, y and 45°:
γ_xy = 2ε_45 − ε_x − ε_y); the two faces give the mid-plane strains and
curvatures, and the indices are taken at both faces of every ply
(:func:`ply_faces`).

Delamination onset of a coupled impact (:func:`impact_damage`): Olsson's quasi-static threshold F_d from the
laminate's bending stiffnesses D and the ply's G_IIc (:func:`softimpact.models.delamination.onset_thresholds`)
against the peak force, the response regime by the impactor-to-target mass ratio
(:func:`softimpact.models.delamination.response_regime`, with the stand-in bounds
:data:`~softimpact.models.delamination.REGIME_BOUNDS`: Olsson's were not retrieved), the interlaminar shear at
each interface between plies of different orientation, and a one-line verdict.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..models.delamination import REGIME_BOUNDS, REGIME_BOUNDS_NOTE, onset_thresholds, response_regime
from ..models.failure import (
    CRITERIA,
    PlyStrength,
    davies_zhang_force,
    failure_indices,
    interlaminar_shear,
    ply_stresses,
)
from ..models.laminate import Stack, abd, engineering_constants
from ._damage_plies import PlyFailure, delamination_growth, delamination_shapes, plies_failed, ply_faces, residual_bending

__all__ = [
    "DamageResult",
    "section_strains",
    "extreme_faces",
    "ply_faces",
    "strain_tensor",
    "beam_damage",
    "plate_damage",
    "delamination_force",
    "olsson_force",
    "Interface",
    "mean_shear_resultant",
    "Onset",
    "onset",
    "damage_unavailable",
    "damage_refusal",
    "PointDamage",
    "PlyFailure",
    "plies_failed",
    "residual_bending",
    "ImpactDamage",
    "point_damage",
    "impact_damage",
    "face_points",
    "coupled_damage",
    "delamination_growth",
    "delamination_shapes",
]


@dataclass(frozen=True)
class DamageResult:
    """Index histories: ``ply[criterion]`` shape (n_gauges, n_t), worst ply of each gauge
    section; ``delamination`` shape (n_t,), F(t)/P_c; ``threshold_force`` P_c [N]."""

    ply: dict
    delamination: np.ndarray
    threshold_force: float

    def peaks(self) -> dict[str, float]:
        out = {k: float(v.max()) if v.size else 0.0 for k, v in self.ply.items()}
        out["delamination"] = float(self.delamination.max())
        return out


def section_strains(stack, plane: str, top: np.ndarray, bottom: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Mid-plane strains and curvatures (3, n) from the face strains ε_x (n,) of a section."""
    h = stack.thickness
    n = np.size(top)
    e0, k = np.zeros((3, n)), np.zeros((3, n))
    e0[0] = 0.5 * (top + bottom)
    k[0] = (top - bottom) / h
    if plane == "stress":
        # Free across the width: N_y = N_xy = M_y = M_xy = 0 given ε_x0 and κ_x.
        A, B, D = abd(stack.ply_stiffnesses(), [stack.ply.thickness] * len(stack.angles))
        K = np.block([[A, B], [B, D]])
        known, free = [0, 3], [1, 2, 4, 5]
        u = -np.linalg.solve(K[np.ix_(free, free)], K[np.ix_(free, known)] @ np.vstack((e0[0], k[0])))
        e0[1], e0[2], k[1], k[2] = u
    return e0, k


def extreme_faces(stack) -> tuple[np.ndarray, tuple]:
    """Heights [m] and angles of the highest and lowest ply face of each fibre angle.

    Along z the strains are affine, so any index convex in the ply stresses (maximum
    strain, Tsai–Wu's 1/R: gauge functions of convex envelopes) is largest at the
    extreme faces of the plies of one angle; Hashin's modes are convex on either side
    of σ = 0 and continuous there when τ12 = 0 (0°/90° plies in a beam), so for them too.
    Two points per angle instead of two per ply.
    """
    t, h = stack.ply.thickness, stack.thickness
    tops = h / 2 - t * np.arange(len(stack.angles))
    z, angles = [], []
    for a in dict.fromkeys(stack.angles):
        mine = tops[np.asarray(stack.angles) == a]
        z += [mine.max(), mine.min() - t]
        angles += [a, a]
    return np.array(z), tuple(angles)


def beam_damage(stack, strength: PlyStrength, plane: str, face: np.ndarray, other: np.ndarray, surfaces, force: np.ndarray) -> DamageResult:
    """Indices at the gauge sections; ``face``/``other`` (n_gauges, n_t) the axial strain on the
    gauge's face and the opposite one, ``surfaces`` each gauge's face, ``force`` (n_t,) [N]."""
    if not isinstance(stack, Stack):
        raise InputError("damage screening needs a layup (ply stacking), not ply fractions", "stack")
    z, angles = extreme_faces(stack)
    ply = {c: np.zeros(face.shape) for c in CRITERIA}
    for g, surface in enumerate(surfaces):
        top, bottom = (other[g], face[g]) if surface == "bottom" else (face[g], other[g])
        e0, k = section_strains(stack, plane, top, bottom)
        strain, stress = ply_stresses(stack.ply, angles, e0, k, z)
        idx = failure_indices(stack.ply, strength, strain, stress)
        for c in CRITERIA:
            ply[c][g] = idx[c].max(axis=0)
    pc = delamination_force(stack, strength.GIIc)
    return DamageResult(ply, np.asarray(force, float) / pc, pc)


def strain_tensor(ex, ey, e45) -> np.ndarray:
    """In-plane strains (ε_x, ε_y, γ_xy), shape (3, ...), from the normal strains in x, y and at 45°
    (ε_θ = ε_x cos²θ + ε_y sin²θ + γ_xy sinθ cosθ)."""
    ex, ey, e45 = (np.asarray(e, float) for e in (ex, ey, e45))
    return np.stack((ex, ey, 2 * e45 - ex - ey))


def plate_damage(stack, strength: PlyStrength, top: np.ndarray, bottom: np.ndarray, force: np.ndarray) -> DamageResult:
    """Indices at points of a plate: ``top``/``bottom`` (n_points, 3, n_t) the in-plane strains
    (ε_x, ε_y, γ_xy) on the top (z = +h/2) and bottom face, ``force`` (n_t,) [N]. FSDT
    kinematics: ε(z) = ε0 + z·κ with ε0 the faces' mean and κ their difference over h."""
    if not isinstance(stack, Stack):
        raise InputError("damage screening needs a layup (ply stacking), not ply fractions", "stack")
    top, bottom = np.asarray(top, float), np.asarray(bottom, float)
    z, angles = ply_faces(stack)
    ply = {c: np.zeros((top.shape[0], top.shape[-1])) for c in CRITERIA}
    for p in range(top.shape[0]):
        e0 = 0.5 * (top[p] + bottom[p])
        k = (top[p] - bottom[p]) / stack.thickness
        strain, stress = ply_stresses(stack.ply, angles, e0, k, z)
        idx = failure_indices(stack.ply, strength, strain, stress)
        for c in CRITERIA:
            ply[c][p] = idx[c].max(axis=0)
    pc = delamination_force(stack, strength.GIIc)
    return DamageResult(ply, np.asarray(force, float) / pc, pc)


def damage_unavailable(stack, where: str) -> str | None:
    """Why a laminate gives no damage outputs (one line naming what to give), or None when it does:
    a smeared ply blend has no stacking, and a ply without strengths needs them
    (:func:`softimpact.models.failure.strength_of`; ``where``: the ply's key in the case)."""
    from ..models.failure import strength_of

    if stack is None:
        return f"{where}: damage outputs need a laminate (an isotropic material has no ply strengths)"
    if not isinstance(stack, Stack):
        return f"{where}: damage outputs need a layup (ply stacking), not ply fractions"
    try:
        strength_of(stack.ply, where)
    except InputError as exc:
        return str(exc)
    return None


def damage_refusal(target, prefix: str = "") -> str | None:
    """:func:`damage_unavailable` for a target (a beam or plate problem, :class:`~softimpact.models.protocols.Target`):
    its laminate's ply named by the target's ``laminate_key`` after ``prefix`` (an impact case's "target.case: ")."""
    return damage_unavailable(target.stack, f"{prefix}{target.laminate_key}")


@functools.lru_cache(maxsize=64)  # pure function of frozen inputs; a sweep asks again for every run
def delamination_force(stack, GIIc: float) -> float:
    """Davies–Zhang threshold [N] of the laminate, with its smeared in-plane E1 and ν12."""
    ec = engineering_constants(stack.effective())
    return davies_zhang_force(ec["E1"], ec["nu12"], stack.thickness, GIIc)


@functools.lru_cache(maxsize=64)  # as delamination_force: a sweep asks again for every run
def olsson_force(stack, GIIc: float) -> float:
    """Olsson's quasi-static delamination threshold F_d [N] of a layup from its bending stiffnesses D
    (:func:`softimpact.models.delamination.onset_thresholds`: D* then π·sqrt(32·D*·G_IIc/9))."""
    return onset_thresholds(stack, GIIc).olsson


@dataclass(frozen=True)
class Interface:
    """The largest interlaminar shear [Pa] over the run at the interface between plies ``upper`` and ``lower``
    (1 = the top ply) of fibre angles ``angles`` [°], at ``z`` [m] from the mid-plane."""

    upper: int
    lower: int
    angles: tuple[float, float]
    z: float
    shear_max: float
    shear_mean: float | None = None  # over the disc (plate) or the length (beam) ``mean_radius`` around the load
    mean_radius: float | None = None

    def summary(self) -> dict:
        """summary.json's entry: {between, z_m, shear_max_Pa, shear_mean_Pa, shear_mean_radius_m}."""
        a, b = (f"{x:g}" for x in self.angles)
        out = {"between": f"plies {self.upper}/{self.lower} ({a}/{b})", "z_m": self.z, "shear_max_Pa": self.shear_max}
        if self.shear_mean is not None:
            out.update(shear_mean_Pa=self.shear_mean, shear_mean_radius_m=self.mean_radius)
        return out


@dataclass(frozen=True)
class Onset:
    """Delamination onset of an impact: Olsson's threshold ``threshold_force`` F_d [N] against ``peak_force`` [N],
    and the response ``regime`` by ``mass_ratio`` M_i/M_p of the impactor's mass to the target's ``target_mass``
    [kg] (None without the impactor's mass), with the bounds used and their standing (``regime_note``)."""

    threshold_force: float
    peak_force: float
    regime: str | None = None
    mass_ratio: float | None = None
    target_mass: float | None = None
    regime_note: str = REGIME_BOUNDS_NOTE

    @property
    def ratio(self) -> float:
        """Peak force over Olsson's F_d: delamination onset at 1."""
        return self.peak_force / self.threshold_force


def onset(stack, GIIc: float, peak_force: float, impactor_mass: float | None = None, target_mass: float | None = None) -> Onset:
    """:class:`Onset` of an impact of ``peak_force`` [N] on ``stack``; the regime when both masses [kg] are given
    (:func:`~softimpact.models.delamination.response_regime` with :data:`~softimpact.models.delamination.REGIME_BOUNDS`)."""
    regime = ratio = None
    if impactor_mass is not None and target_mass is not None:
        lo, hi = REGIME_BOUNDS
        regime = response_regime(impactor_mass, target_mass, wave_below=lo, quasi_static_above=hi)
        ratio = impactor_mass / target_mass
    return Onset(olsson_force(stack, GIIc), float(peak_force), regime, ratio, target_mass)


@dataclass(frozen=True)
class PointDamage:
    """Peak indices at one point (load point or gauge) over both faces of every ply and the run:
    ``peak[criterion]``, and where it was reached, ``ply[criterion]`` (1 = the top ply) and
    ``face[criterion]`` ("top" or "bottom" face of that ply)."""

    peak: dict
    ply: dict
    face: dict


VERDICT_PLIES = 3  # failed plies the verdict names (summary.json's plies_failed lists them all)


@dataclass(frozen=True)
class ImpactDamage:
    """Damage of a coupled impact: first-ply failure by point, the Davies–Zhang threshold
    force P_c [N] against the peak contact force [N], and the interlaminar shear under the load
    (largest stress [Pa] over the interfaces and the run, its quadratic delamination-onset index,
    the interface's height [m] from the mid-plane)."""

    points: dict  # name → PointDamage
    threshold_force: float
    peak_force: float
    interlaminar_shear_max: float
    interlaminar_index_max: float
    interlaminar_z: float
    onset: Onset | None = None
    interfaces: tuple[Interface, ...] = ()  # between plies of different orientation, top first
    plies_failed: tuple[PlyFailure, ...] = ()  # by Hashin's modes, in the order they failed
    residual_bending: tuple[float, float] = (1.0, 1.0)  # D11, D22 after the ply discount over the intact ones

    def first_ply_failure(self) -> tuple[str, float]:
        """The criterion with the largest first-ply failure index over the points, and that index."""
        worst = {c: max(p.peak[c] for p in self.points.values()) for c in CRITERIA}
        c = max(CRITERIA, key=worst.__getitem__)
        return c, worst[c]

    def verdict(self) -> str:
        """One line: the response regime, onset (peak force over Olsson's F_d) and the first-ply failure index."""
        c, fpf = self.first_ply_failure()
        parts = []
        if self.onset is not None:
            o = self.onset
            if o.regime is not None:
                parts.append(f"{o.regime} response (M_i/M_p {o.mass_ratio:.3g})")
            caveat = "" if o.regime in (None, "quasi-static") else ", a quasi-static threshold outside its regime"
            onset_word = "delamination onset reached" if o.ratio >= 1 else "below delamination onset"
            parts.append(f"{onset_word}: F_max/F_d (Olsson) {o.ratio:.2f}{caveat}")
        parts.append(f"first-ply failure {'reached' if fpf >= 1 else 'not reached'}: {c.replace('_', ' ')} {fpf:.2f}")
        if self.plies_failed:
            shown = ", ".join(f.phrase() for f in self.plies_failed[:VERDICT_PLIES])
            more = len(self.plies_failed) - VERDICT_PLIES
            parts.append(f"plies failed (Hashin's first mode): {shown}" + (f" and {more} more" if more > 0 else ""))
            d11, d22 = self.residual_bending
            parts.append(f"bending stiffness left after the ply discount D11 {d11:.0%}, D22 {d22:.0%}")
        else:
            parts.append("no ply failed by Hashin's modes")
        return "; ".join(parts)

    def summary(self) -> dict:
        """summary.json's ``damage``: the worst over the points per criterion, delamination onset (Davies–Zhang,
        Olsson, the regime, the interfaces' shear) and the verdict, then each point, SI."""
        out = {c: max(p.peak[c] for p in self.points.values()) for c in CRITERIA}
        out.update(
            delamination=self.peak_force / self.threshold_force,
            threshold_force_N=self.threshold_force,
            interlaminar_shear_max_Pa=self.interlaminar_shear_max,
            interlaminar_index=self.interlaminar_index_max,
            interlaminar_interface_z_m=self.interlaminar_z,
        )
        if self.onset is not None:
            o = self.onset
            out.update(olsson_threshold_force_N=o.threshold_force, peak_over_olsson=o.ratio)
            if o.regime is not None:
                out.update(regime=o.regime, impactor_over_target_mass=o.mass_ratio, target_mass_kg=o.target_mass, regime_note=o.regime_note)
        out["interfaces"] = [i.summary() for i in self.interfaces]
        out["interface_shear_max_Pa"] = max((i.shear_max for i in self.interfaces), default=0.0)
        out["interface_shear_mean_max_Pa"] = max((i.shear_mean or 0.0 for i in self.interfaces), default=0.0)
        out["plies_failed"] = [f.summary() for f in self.plies_failed]
        out["residual_D11_ratio"], out["residual_D22_ratio"] = self.residual_bending
        out["verdict"] = self.verdict()
        for name, p in self.points.items():
            out[name] = {**p.peak, "worst_ply": {c: {"ply": p.ply[c], "face": p.face[c]} for c in CRITERIA}}
        return out


def point_damage(stack, strength: PlyStrength, e0: np.ndarray, k: np.ndarray) -> PointDamage:
    """Indices at both faces of every ply from mid-plane strains and curvatures (3, n_t)."""
    z, angles = ply_faces(stack)
    strain, stress = ply_stresses(stack.ply, angles, e0, k, z)
    idx = failure_indices(stack.ply, strength, strain, stress)
    peak, ply, face = {}, {}, {}
    for c in CRITERIA:
        v = idx[c].max(axis=-1) if idx[c].ndim > 1 else idx[c]  # (2·n_plies,): over the run
        j = int(np.argmax(v))
        peak[c], ply[c], face[c] = float(v[j]), j // 2 + 1, ("top", "bottom")[j % 2]
    return PointDamage(peak, ply, face)


def mean_shear_resultant(force, contact_radius, radius: float, width: float | None) -> np.ndarray:
    """The transverse shear resultant [N/m] averaged around the load, by equilibrium under Hertz's pressure
    p ∝ sqrt(1 − r²/a²) on the contact disc of radius a = ``contact_radius`` (≤ ``radius``), per sample of ``force`` [N].

    Plate (``width`` None): the radial resultant q(r) = F(r)/(2πr), F(r) the load inside r (F·(1 − (1 − r²/a²)^{3/2})
    inside the disc), averaged over the disc of radius R: (1/πR²)∫₀^R q·2πr dr = F·(R − 3πa/16)/(πR²).
    Beam of width b: the line load (3F/4a)(1 − x²/a²) (the disc's pressure summed across the width) gives the shear
    force V(x) = (F/2)(3ξ − ξ³)/2, ξ = x/a, then F/2 beyond the disc; its mean over 0 ≤ x ≤ R, per unit width:
    F·(R − 3a/8)/(2bR). Both stay finite as a → 0 (F/(πR), F/(2b)), unlike the resultant at the disc's edge,
    F/(2πa) on a plate."""
    F, a = np.abs(np.asarray(force, float)), np.asarray(contact_radius, float)
    if np.any(a > radius * (1 + 1e-12)):
        raise InputError(f"the averaging radius {radius:g} m must cover the contact disc (largest radius {float(np.max(a)):g} m)", "radius")
    if width is None:
        return F * (radius - 3 * np.pi * a / 16) / (np.pi * radius**2)
    return F * (radius - 3 * a / 8) / (2 * width * radius)


# Directions [°] of the radial shear resultant checked under a plate's load (the largest is kept).
RADIAL_DIRECTIONS = (0.0, 45.0, 90.0, 135.0)


def impact_damage(
    stack,
    strength: PlyStrength,
    points: dict,
    force: np.ndarray,
    contact_radius: np.ndarray,
    width: float | None,
    peak_force: float | None = None,
    *,
    impactor_mass: float | None = None,
    target_mass: float | None = None,
    time: np.ndarray | None = None,
) -> ImpactDamage:
    """Damage of a coupled impact.

    ``points``: name → (mid-plane strains, curvatures), each (3, n_t) (:func:`section_strains`
    for a beam section, the faces' mean and difference over h on a plate); ``force`` (n_t,) [N];
    ``contact_radius`` (n_t,) [m]; ``width`` [m] of a beam, None on a plate; ``peak_force`` [N] the
    peak set against the Davies–Zhang and Olsson thresholds (default the largest sample of ``force``);
    ``impactor_mass`` and ``target_mass`` [kg] give the response regime (:func:`onset`); ``time`` (n_t,) [s] the
    times at which the plies failed (:func:`plies_failed`).

    Interlaminar shear under the load (:func:`softimpact.models.failure.interlaminar_shear`) from
    the transverse shear resultant beside the load: on a beam q = F/(2b), the load shared by the
    two sides (the impact regime: flexural waves leave both ways; a load at an end sends all of F
    one way); on a plate q = F/(2π·a) at the edge of the contact disc of radius a (axisymmetric
    equilibrium), a no less than h/2 (Saint-Venant: the shear spreads over about the thickness),
    taken along :data:`RADIAL_DIRECTIONS`. Per interface the largest shear over those directions; the
    ``interfaces`` kept are those between plies of different fibre angle, where delaminations run (the
    largest shear of all, at the mid-plane of a symmetric layup, often lies between two plies of one angle).
    """
    force = np.asarray(force, float)
    out = {name: point_damage(stack, strength, e0, k) for name, (e0, k) in points.items()}
    radius_hist = np.asarray(contact_radius, float) * np.ones_like(force)
    if width is not None:
        q, dirs = np.max(np.abs(force)) / (2 * width), (0.0,)
    else:
        a = np.maximum(radius_hist, stack.thickness / 2)
        q, dirs = float(np.max(np.abs(force) / (2 * np.pi * a))), RADIAL_DIRECTIONS
    # The converged measure: the resultant averaged over the disc (length) covering the widest contact and one
    # laminate thickness beyond it (Saint-Venant), fixed for the run.
    mean_radius = float(np.max(radius_hist, initial=0.0)) + stack.thickness
    q_mean = float(np.max(mean_shear_resultant(force, radius_hist, mean_radius, width), initial=0.0))
    best = (0.0, 0.0, 0.0)
    per_interface = np.zeros(len(stack.angles) - 1)
    per_interface_mean = np.zeros_like(per_interface)
    z = np.zeros_like(per_interface)
    for d in dirs:
        ils = interlaminar_shear(stack.ply, stack.angles, strength, d)
        if ils.z.size == 0:
            continue
        unit = np.hypot(ils.tau_xz, ils.tau_yz)
        tau = unit * q
        per_interface, z = np.maximum(per_interface, tau), ils.z
        per_interface_mean = np.maximum(per_interface_mean, unit * q_mean)
        j = int(np.argmax(ils.index))
        best = max(best, (float(ils.index[j] * q), float(tau.max()), float(ils.z[j])))
    angles = stack.angles
    interfaces = tuple(
        Interface(i + 1, i + 2, (float(angles[i]), float(angles[i + 1])), float(z[i]), float(per_interface[i]), float(per_interface_mean[i]), mean_radius)
        for i in range(len(angles) - 1)
        if angles[i] != angles[i + 1]
    )
    peak = float(np.max(force) if peak_force is None else peak_force)
    failed = plies_failed(stack, strength, points, time)
    return ImpactDamage(
        out,
        delamination_force(stack, strength.GIIc),
        peak,
        best[1],
        best[0],
        best[2],
        onset(stack, strength.GIIc, peak, impactor_mass, target_mass),
        interfaces,
        failed,
        residual_bending(stack, failed),
    )


def face_points(stack, faces: dict, plane: str | None) -> dict:
    """Mid-plane strains and curvatures (3, n) per point from its two faces' strains, ``faces``: name →
    (top, bottom). A face strain is either the axial ε_x (n,) of a beam section (``plane`` "strain" or
    "stress" across the width, :func:`section_strains`) or the normal strains along x, y and 45° (3, n) of
    a plate point (``plane`` None: the in-plane tensors, :func:`strain_tensor`, mean and difference over h)."""
    out = {}
    for name, (top, bottom) in faces.items():
        if plane is not None:
            out[name] = section_strains(stack, plane, top, bottom)
        else:
            t, b = strain_tensor(*top), strain_tensor(*bottom)
            out[name] = (0.5 * (t + b), (t - b) / stack.thickness)
    return out


def coupled_damage(target, result, points: tuple[str, ...] | None = None, *, impactor_mass: float | None = None) -> ImpactDamage:
    """Damage of a coupled impact (:func:`impact_damage`) on ``target`` (a :class:`~softimpact.models.protocols.Target`
    whose laminate has strengths) from ``result`` (a CoupledResult with its ``"damage"`` output group): first-ply
    failure at the target's damage points (``points``: only these, e.g. ("at_load",)), Davies–Zhang and Olsson
    against the largest refined peak of every contact, interlaminar shear under the load, and with
    ``impactor_mass`` [kg] the response regime (against the target's ``mass``)."""
    names, rows = result.groups["damage"]
    faces = target.damage_faces(result.strain, dict(zip(names, rows)))
    if points is not None:
        faces = {p: faces[p] for p in points}
    plane, width = target.damage_section
    stack = target.stack
    peak = max(c.peak_force for c in result.contacts)  # every contact's refined peak (parabola through the top samples)
    target_mass = target.mass if impactor_mass is not None else None
    return impact_damage(
        stack,
        stack.ply.strength,
        face_points(stack, faces, plane),
        result.force,
        result.contact_radius,
        width,
        peak,
        impactor_mass=impactor_mass,
        target_mass=target_mass,
        time=result.time,
    )


def metal_damage(target, result, rest: dict | None) -> dict:
    """summary.json's ``damage`` of an impact on a metal plate (``target.material`` a
    :class:`~softimpact.models.metals.Metal`). Elastic–plastic (``rest``: the plate's state at rest after the run,
    :meth:`softimpact.workflows.plate.NonlinearPlateModel.rest`): the dent (the permanent deflection under the impact
    point), the plastic zone's area, the plastic work and the largest equivalent plastic strain, with the plastic
    work's history from ``result``'s ``"columns"`` group. Elastic (``rest`` None): the largest von Mises stress over
    the yield stress at the damage points (both faces, every time), from the ``"damage"`` group's face strains."""
    from ..models.plasticity import von_mises

    metal, h = target.material, target.thickness
    if rest is not None:
        dent = rest["dent_depth_m"]
        cols = dict(zip(*result.groups["columns"])) if "columns" in result.groups else {}
        work = cols.get("plastic_work_J")
        first = None if work is None or not np.any(work > 0) else float(result.time[np.flatnonzero(work > 0)[0]])
        words = (
            f"dent {dent * 1e3:.3g} mm deep ({dent / h:.3g} of the thickness), plastic zone {rest['plastic_zone_area_m2'] * 1e6:.4g} mm², "
            f"plastic work {rest['plastic_work_J']:.4g} J"
            if rest["plastic_work_J"] > 0
            else "no yield: the plate stayed elastic (no dent)"
        )
        return {
            **rest,
            "yield_onset_time_s": first,
            "dent_note": "permanent mid-surface deflection under the impact point, positive into the plate, against the plate's rest before "
            "the impact: the equilibrium at zero load reached from the run's end with its plastic strains (the motion let die away)",
            "plasticity": f"J2 with {metal.hardening.describe()} ({metal.hardening_source}); rate: {metal.rate_source}",
            "verdict": words,
        }
    names, rows = result.groups["damage"]
    faces = target.damage_faces(result.strain, dict(zip(names, rows)))
    Q = metal.plasticity().elastic
    peak = 0.0
    for top, bottom in faces.values():
        for face in (top, bottom):
            peak = max(peak, float(von_mises(strain_tensor(*face).T @ Q.T).max()))
    ratio = peak / metal.yield_stress
    words = f"elastic run: the von Mises stress reaches {ratio:.3g} times the yield stress at the damage points"
    return {"max_von_mises_Pa": peak, "max_von_mises_over_yield": ratio, "verdict": words + (" (past yield: a dent is likely)" if ratio > 1 else "")}
