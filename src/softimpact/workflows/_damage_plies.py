"""The parts of the damage workflow (:mod:`softimpact.workflows.damage`) past first-ply failure: which plies failed, by
which of Hashin's modes and when (:func:`plies_failed`), the bending stiffness a ply discount leaves
(:func:`residual_bending`), and the delaminated areas of an impact on sublaminates tied by cohesive interfaces
(:func:`delamination_growth`). A private part of that workflow: it imports no other workflow.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..models.failure import HASHIN_MODES, PlyStrength, discounted_abd, hashin_modes, ply_stresses

__all__ = ["ply_faces", "PlyFailure", "plies_failed", "residual_bending", "delamination_growth"]


def ply_faces(stack) -> tuple[np.ndarray, tuple]:
    """Heights [m] and angles of both faces of every ply (top ply first).

    With in-plane shear the Hashin modes jump where σ1 or σ2 changes sign, so the
    extreme faces of one angle (:func:`extreme_faces`) need not hold their largest
    value; every ply's own faces are the points where its strains are extreme.
    """
    t, h = stack.ply.thickness, stack.thickness
    tops = h / 2 - t * np.arange(len(stack.angles))
    z = np.ravel(np.column_stack((tops, tops - t)))
    return z, tuple(a for a in stack.angles for _ in (0, 1))


@dataclass(frozen=True)
class PlyFailure:
    """The first failure of one ply by Hashin's modes over a run: ``ply`` (1 = the top ply) of fibre ``angle`` [°],
    the ``mode`` that reached 1 first (one of :data:`~softimpact.models.failure.HASHIN_MODES`; the largest of them if
    two did at the same sample), at ``sample`` of the run's histories, time ``time`` [s] (None without the times),
    at damage point ``point`` on ``face`` ("top" or "bottom") of the ply."""

    ply: int
    angle: float
    mode: str
    sample: int
    time: float | None
    point: str
    face: str

    def summary(self) -> dict:
        """summary.json's entry: {ply, angle_deg, mode, time_s, point, face}."""
        return {"ply": self.ply, "angle_deg": self.angle, "mode": self.mode, "time_s": self.time, "point": self.point, "face": self.face}

    def phrase(self) -> str:
        """ "ply 4 (90°) matrix tension at 0.153 ms"."""
        when = f"at {self.time * 1e3:.3g} ms" if self.time is not None else f"at sample {self.sample}"
        return f"ply {self.ply} ({self.angle:g}°) {self.mode.replace('_', ' ')} {when}"


def plies_failed(stack, strength: PlyStrength, points: dict, time: np.ndarray | None = None) -> tuple[PlyFailure, ...]:
    """Every ply that fails by one of Hashin's modes (:func:`~softimpact.models.failure.hashin_modes` reaching 1) at
    any of ``points`` (name → (mid-plane strains, curvatures), each (3, n_t)), both faces of the ply, with the mode
    that failed first and when (``time`` (n_t,) [s]); in the order they failed. No degradation follows: the run's
    stiffness stays the intact laminate's, so what comes after a ply's first failure is that of an intact ply."""
    z, angles = ply_faces(stack)
    first: dict[int, tuple] = {}  # ply index → (sample, −value, mode, point, face)
    for name, (e0, k) in points.items():
        _, stress = ply_stresses(stack.ply, angles, e0, k, z)
        modes = hashin_modes(strength, stress)
        v = np.stack([np.asarray(modes[m]).reshape(len(z), -1) for m in HASHIN_MODES])  # (4, 2·n_plies, n_t)
        failed = (v >= 1.0).any(axis=0)
        for j in np.flatnonzero(failed.any(axis=-1)):
            i = int(np.argmax(failed[j]))
            m = int(np.argmax(v[:, j, i]))
            key = (i, -float(v[m, j, i]), HASHIN_MODES[m], name, ("top", "bottom")[j % 2])
            if j // 2 not in first or key < first[j // 2]:
                first[j // 2] = key
    out = [
        PlyFailure(p + 1, float(stack.angles[p]), mode, i, None if time is None else float(np.asarray(time)[i]), name, face)
        for p, (i, _, mode, name, face) in first.items()
    ]
    return tuple(sorted(out, key=lambda f: (f.sample, f.ply)))


def residual_bending(stack, failed: tuple[PlyFailure, ...]) -> tuple[float, float]:
    """(D11, D22) of ``stack`` after the ply discount of the ``failed`` plies (:func:`~softimpact.models.failure.discounted_abd`:
    a matrix failure keeps the fibre, a fibre failure removes the ply) over the intact laminate's: what bending
    stiffness the run left. Not fed back into the run (its stiffness stays the intact laminate's)."""
    if not failed:
        return 1.0, 1.0
    D0 = discounted_abd(stack, {})[2]
    D = discounted_abd(stack, {f.ply: f.mode for f in failed})[2]
    return float(D[0, 0] / D0[0, 0]), float(D[1, 1] / D0[1, 1])


def delamination_growth(damage: dict | None, result) -> dict | None:
    """summary.json's ``damage`` of an impact on sublaminates tied by cohesive interfaces
    (:mod:`softimpact.fem.cohesive_plate`), from ``result``'s ``"columns"`` group: the delaminated area (damage 1;
    its final value is its largest, the damage being irreversible) and the process zone's largest area (0 < d < 1),
    summed over the interfaces and per interface, when each first appeared, the fracture energy dissipated and the
    energy the interfaces store at the end; the verdict gains the delaminated area. ``damage`` (the indices' block,
    or None) unchanged when the run had no cohesive interfaces."""
    groups = getattr(result, "groups", None) or {}
    if "columns" not in groups or "delaminated_area_m2" not in groups["columns"][0]:
        return damage
    cols = dict(zip(*groups["columns"]))
    t = result.time
    cracked, zone = cols["delaminated_area_m2"], cols["process_zone_area_m2"]

    def first(a):
        hit = np.flatnonzero(a > 0.0)
        return float(t[hit[0]]) if hit.size else None

    per = {}
    for name, values in cols.items():
        for q, key in (("delaminated_area_m2_", "delaminated_area_m2"), ("process_zone_area_m2_", "process_zone_area_max_m2")):
            if name.startswith(q):
                per.setdefault(name[len(q) :], {})[key] = float(values[-1] if key == "delaminated_area_m2" else np.max(values))
    out = dict(damage or {})
    out.update(
        delaminated_area_m2=float(cracked[-1]),
        process_zone_area_max_m2=float(np.max(zone)),
        process_zone_area_final_m2=float(zone[-1]),
        delamination_onset_time_s=first(cracked),
        damage_onset_time_s=first(zone + cracked),
        fracture_energy_dissipated_J=float(cols["fracture_energy_dissipated_J"][-1]),
        cohesive_stored_energy_J=float(cols["cohesive_stored_energy_J"][-1]),
        cohesive_interfaces=per,
        delaminated_area_note="summed over the cohesive interfaces (per interface in cohesive_interfaces), of the whole plate; "
        "delaminated: damage 1; process zone: 0 < damage < 1; nodal tributary areas",
    )
    mm2 = 1e6
    if cracked[-1] > 0:
        words = f"delaminated {cracked[-1] * mm2:.4g} mm² over {sum(v['delaminated_area_m2'] > 0 for v in per.values())} of {len(per)} cohesive interface(s)"
    elif np.max(zone) > 0:
        words = f"no delamination grew (cohesive damage began: process zone up to {np.max(zone) * mm2:.4g} mm²)"
    else:
        words = f"no cohesive damage at the {len(per)} interface(s)"
    out["verdict"] = f"{damage['verdict']}; {words}" if damage and damage.get("verdict") else words
    return out


def delamination_shapes(damage: dict, scan) -> dict:
    """``damage`` (of :func:`delamination_growth`) with what a C-scan shows (``scan``, a
    :class:`~softimpact.workflows.plate.cscan.CScan`): the projected area and each interface's shape; the verdict gains
    the projected area and the largest delamination's major axis against the fibres of the ply below it."""
    out = {**damage, **scan.summary()}
    grown = [i for i in scan.interfaces if i.area > 0.0]
    if grown:
        big = max(grown, key=lambda i: i.area)
        angle = (
            "no major axis (round)"
            if np.isnan(big.orientation_deg)
            else f"at {big.orientation_deg:.0f}° from x, {big.misalignment_deg:.0f}° from the {big.lower_ply_deg:g}° ply below"
        )
        words = (
            f"projected delamination {scan.projected_area * 1e6:.4g} mm²; largest at interface {big.words}: "
            f"{big.major_axis * 1e3:.3g} × {big.minor_axis * 1e3:.3g} mm, major axis {angle}"
        )
        out["verdict"] = f"{out['verdict']}; {words}" if out.get("verdict") else words
    return out
