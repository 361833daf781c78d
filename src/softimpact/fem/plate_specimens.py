"""Delamination specimens as plate strips: two sublaminates of :class:`~softimpact.fem.cohesive_plate.CohesivePlate`.

A specimen is a strip along x (its length) of width b along y, split at its mid-plane into two arms, each an FSDT
plate of :mod:`softimpact.fem.plate` (MITC9 by default), tied by the bilinear mixed-mode cohesive law through the
plate's own interface code: the same nodal integration, law and committed damage as an impact run's stacked plate.
The pre-crack is the initial damage 1 on the interface nodes with x < a0; loads are line loads over the width
(their consistent nodal forces: the tributary lengths of the edge's nodes, Newton–Cotes weights, as the
interface's areas); the rigid motions are removed by point constraints whose reactions vanish (a self-equilibrated
load, statically determinate supports). By default half the width is modelled: the strip is symmetric about
y = b/2 for an unrotated layup ([0]n: D16 = D26 = 0), its symmetry edge holds v = φy = 0.

The force λ of a :class:`PlateSpecimen` is the whole specimen's (the line load P/b over the modelled width);
its displacement :meth:`PlateSpecimen.displacement` is the whole specimen's work-conjugate one (gᵀu over the
share of the width modelled): the energies of the model divided by ``share`` are the whole specimen's.

- :func:`dcb`: the double cantilever beam (mode I): the arms' ends at x = 0 pulled apart; load-point displacement
  = the opening there, averaged over the width.
- :func:`mmb`: Reeder & Crews' mixed-mode bending, the lever modelled by its kinematics as in
  :func:`softimpact.fem.cohesive_specimens.mmb`: span 2L, the lower arm on line supports at x = 0 and 2L, the upper
  arm pulled up by P·c/L at x = 0 and pushed down by P·(c + L)/L at midspan; load-point displacement
  c/L·w_top(0) − (c + L)/L·w_top(L).

The mesh along x is graded (:func:`strip_grid`): ``element`` [m] over the zone where the crack runs, growing by
``GROWTH`` to ``coarse`` elsewhere.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..models.cohesive import BilinearCohesive
from ..models.laminate import Ply, Stack
from ..models.plate_laminate import plate_section
from .cohesive_plate import CohesivePlate
from .plate import PHI_X, Plate, U, V, W
from .quasistatic import QuasiStatic, QuasiStaticPath, linear_response, quasistatic_path

__all__ = [
    "GROWTH",
    "Critical",
    "PlateSpecimen",
    "ReleaseRates",
    "crack_front",
    "critical_load",
    "dcb",
    "mmb",
    "onset_force",
    "release_rates",
    "run",
    "strip_grid",
]

GROWTH = 1.3  # ratio of neighbouring elements' lengths outside the fine zone: a gentle grading
ONSET_MARGIN = 0.999  # of the elastic limit: the first increment of a critical-load path stays linear


def _graded(start: float, stop: float, first: float, largest: float) -> np.ndarray:
    """Points from ``start`` to ``stop`` (either order), the first interval ``first``, growing by GROWTH up to
    ``largest``, the intervals scaled to end at ``stop``."""
    span = abs(stop - start)
    if span <= 1e-12:
        return np.array([start])
    steps, h = [], first
    while sum(steps) < span * (1 - 1e-9):
        steps.append(min(h, largest))
        h *= GROWTH
    s = np.cumsum(steps) * span / sum(steps)
    return start + np.sign(stop - start) * np.concatenate(([0.0], s))


def strip_grid(length: float, fine: tuple[float, float], element: float, coarse: float, knots=()) -> np.ndarray:
    """Grid lines along x on [0, ``length``]: ``element`` on ``fine`` = (x0, x1), graded (GROWTH) to ``coarse``
    outside; the grid line nearest each of ``knots`` (a pre-crack tip, a load line) is moved onto it."""
    x0, x1 = (min(max(v, 0.0), length) for v in fine)
    if not (element > 0 and coarse >= element and x1 > x0):
        raise InputError(
            f"strip mesh: need element > 0, coarse >= element and a fine zone of positive length, got {element!r}, {coarse!r}, {fine!r}", "element"
        )
    n = max(1, int(np.ceil((x1 - x0) / element - 1e-9)))
    xs = np.unique(np.concatenate([_graded(x0, 0.0, element, coarse), np.linspace(x0, x1, n + 1), _graded(x1, length, element, coarse)]))
    for k in knots:
        xs[np.argmin(np.abs(xs - k))] = k
    return np.unique(xs)


@dataclass(frozen=True, eq=False)
class PlateSpecimen:
    """A cohesive plate strip with its load g (λ·g, λ the whole specimen's force [N]), control c, ``fixed`` stacked
    DOFs (held at zero), ``share`` the part of the width modelled, ``a0`` [m], ``name``."""

    model: CohesivePlate
    load: np.ndarray
    control: np.ndarray
    fixed: np.ndarray
    share: float
    a0: float
    name: str

    def displacement(self, u: np.ndarray) -> float:
        """The whole specimen's load-point displacement gᵀu/share [m]."""
        return float(self.load @ u) / self.share


def _plate(spec_ply: Ply, plies: int, width: float, xs, ny: int, half: bool, element: str) -> tuple[Plate, Stack]:
    stack = Stack(spec_ply, (0.0,) * (2 * plies))
    b = width / 2 if half else width
    ys = np.linspace(0.0, b, ny + 1)
    supports = ("free", "free", "free", "symmetry" if half else "free")
    plate = Plate(float(xs[-1]), b, xs.size - 1, ny, plate_section(stack), supports, True, tuple(xs), tuple(ys), element)
    return plate, stack


def _dof(model: CohesivePlate, layer: int, node: int, component: int) -> int:
    """The stacked position of ``component`` of ``node`` on sublaminate ``layer`` (InputError if it is fixed)."""
    local = model.layers[layer].dof(node, component)
    if local < 0:
        raise InputError(f"DOF {component} of node {node} of sublaminate {layer} is held by a support")
    return int(model.layer_dofs(layer)[local])


def _line(model: CohesivePlate, layer: int, x: float, component: int = W) -> np.ndarray:
    """Row over the stacked DOFs: the tributary-length fractions (summing to 1) of ``component`` on the node line
    nearest ``x`` of sublaminate ``layer`` (a uniform line load's consistent nodal shares)."""
    fe = model.layers[layer].fe
    i = int(np.argmin(np.abs(fe.node_xs - x)))
    nodes = fe.grid_node[i]
    weights = model.area[nodes] / model.area[nodes].sum()
    row = np.zeros(model.n)
    for node, wgt in zip(nodes, weights):
        row[_dof(model, layer, node, component)] += wgt
    return row


def _node(model: CohesivePlate, x: float, y: float) -> int:
    fe = model.layers[0].fe
    return int(fe.grid_node[np.argmin(np.abs(fe.node_xs - x)), np.argmin(np.abs(fe.node_ys - y))])


def _precrack(model: CohesivePlate, a0: float) -> None:
    """Damage 1 on the interface nodes with x < a0 (a tenth of a micrometre of round-off allowed)."""
    fe = model.layers[0].fe
    x = np.repeat(fe.node_xs, fe.node_ys.size)  # grid_node[i, j] = i·(ny + 1) + j
    damage = model.damage.copy()
    damage[:, x < a0 - 1e-10] = 1.0
    model.damage = damage


def dcb(
    ply: Ply,
    *,
    plies_per_arm: int,
    width: float,
    length: float,
    a0: float,
    law: BilinearCohesive,
    element: float,
    fine: tuple[float, float] | None = None,
    coarse: float | None = None,
    ny: int = 2,
    half: bool = True,
    plate_element: str = "mitc9",
) -> PlateSpecimen:
    """Double cantilever beam: [0] arms of ``plies_per_arm`` plies each, pre-crack from x = 0 to ``a0``, the arms' ends
    pulled apart by P (a line load P/b on each, up on the upper, down on the lower). ``fine`` (x0, x1): where the
    elements are ``element`` long (default a0 to a0 + 5 mm), ``coarse`` elsewhere (default 4 arm thicknesses);
    ``ny`` elements over the modelled width. Held (bottom arm, far end x = length): u, w, φx on the symmetry edge
    (``half``), or u, v, w, φx at y = 0 and u, w at y = b: the rigid motions and nothing more."""
    h = plies_per_arm * ply.thickness
    fine = (a0, a0 + 5e-3) if fine is None else fine
    xs = strip_grid(length, fine, element, 4 * h if coarse is None else coarse, knots=(a0,))
    plate, stack = _plate(ply, plies_per_arm, width, xs, ny, half, plate_element)
    model = CohesivePlate(plate, stack, (plies_per_arm,), law)
    _precrack(model, a0)
    share = 0.5 if half else 1.0
    g = share * (_line(model, 0, 0.0) - _line(model, 1, 0.0))
    b = plate.length_y
    if half:
        far = _node(model, length, b)
        fixed = [_dof(model, 1, far, c) for c in (U, W, PHI_X)]
    else:
        p, q = _node(model, length, 0.0), _node(model, length, b)
        fixed = [_dof(model, 1, p, c) for c in (U, V, W, PHI_X)] + [_dof(model, 1, q, c) for c in (U, W)]
    return PlateSpecimen(model, g, g, np.asarray(fixed), share, a0, "DCB")


def _tip(model: CohesivePlate, a0: float) -> tuple[np.ndarray, np.ndarray]:
    """Rows giving the width-averaged (opening, sliding along x) of the interface on the node line nearest a0."""
    t_up, t_lo = (lay.plate.section.thickness for lay in model.layers)
    opening = _line(model, 0, a0) - _line(model, 1, a0)
    sliding = _line(model, 0, a0, U) - t_up / 2 * _line(model, 0, a0, PHI_X) - _line(model, 1, a0, U) - t_lo / 2 * _line(model, 1, a0, PHI_X)
    return opening, sliding


def mmb(
    ply: Ply,
    *,
    plies_per_arm: int,
    width: float,
    half_span: float,
    a0: float,
    lever: float,
    law: BilinearCohesive,
    element: float,
    fine: tuple[float, float] | None = None,
    coarse: float | None = None,
    ny: int = 2,
    half: bool = True,
    control: str = "load",
    plate_element: str = "mitc9",
) -> PlateSpecimen:
    """Mixed-mode bending over the span 2L = 2·``half_span`` (module docstring), ``lever`` c [m], pre-crack to ``a0``.
    ``control``: ``"load"`` (the lever's load-point displacement) or ``"tip"`` (the width-averaged opening plus sliding
    at the pre-crack tip, each turned by its sign under the elastic response: monotone through a snap-back). Held:
    w on the lower arm's lines x = 0 and 2L (the supports), u (and v, u at y = b on the full width) at its far end."""
    if control not in ("load", "tip"):
        raise InputError(f"control must be 'load' or 'tip', got {control!r}", "control")
    L, c = half_span, lever
    h = plies_per_arm * ply.thickness
    fine = (a0, a0 + 5e-3) if fine is None else fine
    xs = strip_grid(2 * L, fine, element, 4 * h if coarse is None else coarse, knots=(a0, L))
    plate, stack = _plate(ply, plies_per_arm, width, xs, ny, half, plate_element)
    model = CohesivePlate(plate, stack, (plies_per_arm,), law)
    _precrack(model, a0)
    share = 0.5 if half else 1.0
    g = share * (c / L * _line(model, 0, 0.0) - (c + L) / L * _line(model, 0, L))
    fe = model.layers[1].fe
    lines = np.concatenate([fe.grid_node[0], fe.grid_node[-1]])
    fixed = [_dof(model, 1, node, W) for node in lines]
    b = plate.length_y
    far = _node(model, 2 * L, 0.0)
    fixed.append(_dof(model, 1, far, U))
    if not half:
        fixed += [_dof(model, 1, far, V), _dof(model, 1, _node(model, 2 * L, b), U)]
    fixed = np.asarray(fixed)
    ctrl = g
    if control == "tip":
        opening, sliding = _tip(model, a0)
        u = linear_response(model, g, fixed)
        ctrl = np.sign(opening @ u) * opening + np.sign(sliding @ u) * sliding
    return PlateSpecimen(model, g, ctrl, fixed, share, a0, "MMB")


def crack_front(spec: PlateSpecimen, damage: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(y [m] of the node lines across the width, crack length [m] (the largest x of a fully damaged node, cracked
    from x = 0), process-zone length [m] (the x-extent of the nodes with 0 < d < 1)) of the interface at ``damage``
    (interfaces, nodes)."""
    fe = spec.model.layers[0].fe
    d = np.asarray(damage)[0][fe.grid_node]  # (x lines, y lines)
    x = fe.node_xs
    cracked = np.cumprod(d >= 1.0, axis=0).astype(bool)
    tip = np.array([x[c].max() if c.any() else 0.0 for c in cracked.T])
    zone = []
    for j in range(d.shape[1]):
        z = x[(d[:, j] > 0) & (d[:, j] < 1.0)]
        zone.append(z.max() - z.min() if z.size > 1 else 0.0)
    return fe.node_ys.copy(), tip, np.asarray(zone)


def run(spec: PlateSpecimen, displacements, *, damage: str = "newton", damage_tol: float = 1e-4) -> QuasiStaticPath:
    """The quasi-static path of ``spec`` through the control values ``displacements`` (the whole specimen's load-point
    displacement [m] under load control; the tip's opening + sliding [m] under tip control)
    (:func:`~softimpact.fem.quasistatic.quasistatic_path`). The specimen's model carries the damage: a specimen runs
    once."""
    targets = np.asarray(displacements, float) * (spec.share if spec.control is spec.load else 1.0)
    return quasistatic_path(
        spec.model,
        targets,
        load=spec.load,
        control=spec.control,
        fixed=spec.fixed,
        damage=damage,
        damage_tol=damage_tol,
        trial_damage=trial_damage(spec.model),
    )


def trial_damage(model: CohesivePlate):
    """The damage ``model.commit(u)`` would store from ``d``, without storing it (its law at its openings)."""

    def trial(u: np.ndarray, d: np.ndarray) -> np.ndarray:
        return model.law.traction(model.opening(u), d.ravel()).damage.reshape(d.shape)

    return trial


@dataclass(frozen=True)
class Critical:
    """The peak of a specimen's load against its control: ``load`` P_c [N], the vertex of the parabola of the force against
    the control through the largest recorded force and its neighbours (the recorded largest, ``recorded``, lies below it
    by O(step²)), and ``displacement`` δ_c [m] there (the whole specimen's load-point displacement); ``path`` the path to where the force had
    fallen ``drop`` below its peak; ``zone`` the process-zone length [m] at the peak at mid-width (the symmetry
    edge, or the middle node line), ``crack`` the crack length there [m]; ``fallbacks`` the increments the Newton
    iterations left to the staggered passes (:class:`~softimpact.fem.quasistatic.QuasiStatic`)."""

    load: float
    displacement: float
    recorded: float
    path: QuasiStaticPath
    zone: float
    crack: float
    fallbacks: int = 0


def onset_force(spec: PlateSpecimen) -> float:
    """The force [N] at which the first intact interface point of ``spec`` reaches the law's onset along the elastic
    response (its mixed-mode onset displacement δ0(B) at the mixity B of the response there): up to it the path is
    linear, and a path started there integrates its work exactly."""
    model, law = spec.model, spec.model.law
    delta = model.opening(linear_response(model, spec.load, spec.fixed))
    intact = model.damage.ravel() < 1.0
    active = np.sqrt(np.maximum(delta[:, 0], 0.0) ** 2 + np.sum(delta[:, 1:] ** 2, axis=-1))
    ratio = np.where(intact & (active > 0), law.onset_displacement(law.mode_mixity(delta)) / np.where(active > 0, active, 1.0), np.inf)
    return float(ratio.min())


def critical_load(
    spec: PlateSpecimen,
    *,
    near: float,
    approach: int = 8,
    step: float = 0.01,
    increment: float | None = None,
    drop: float = 0.01,
    until: float | None = None,
    max_steps: int = 400,
    damage: str = "newton",
) -> Critical:
    """The peak of ``spec``'s load along its control (:class:`Critical`). The path goes in one increment to the elastic
    limit (:func:`onset_force`: linear up to it, its work exact), in ``approach`` equal increments on to the control the
    elastic response has at ``near`` [N] (an estimate below the peak), then by ``increment`` (control units; default
    ``step`` times that control, for load control) until the force has fallen ``drop`` below its largest value, and
    on to ``until`` (the whole specimen's load-point displacement [m] under load control, the tip's opening + sliding
    under tip control: the propagation branch) when given; InputError after ``max_steps`` increments without a peak."""
    if not (near > 0 and approach >= 1 and 0 < step < 1 and 0 < drop < 1 and max_steps >= 3):
        raise InputError(
            f"critical_load needs near > 0, approach >= 1, 0 < step < 1, 0 < drop < 1 and max_steps >= 3, got {near!r}, {approach!r}, {step!r}, {drop!r}, {max_steps!r}",
            "near",
        )
    per_newton = abs(float(spec.control @ linear_response(spec.model, spec.load, spec.fixed)))  # control per N, elastic
    first = ONSET_MARGIN * onset_force(spec) * per_newton
    start = max(near * per_newton, first)
    increment = step * start if increment is None else float(increment)
    if not increment > 0:
        raise InputError(f"increment must be positive, got {increment!r}", "increment")
    path = QuasiStatic(spec.model, load=spec.load, control=spec.control, fixed=spec.fixed, damage=damage, trial_damage=trial_damage(spec.model))
    path.advance(first)
    forces = [path.advance(v) for v in np.linspace(first, start, approach + 1)[1:]]
    scale = spec.share if spec.control is spec.load else 1.0  # ``until`` in the path's control units
    while forces[-1] > (1 - drop) * max(forces) or len(forces) < 3 or (until is not None and start + (len(forces) - approach) * increment < until * scale):
        if len(forces) > max_steps:
            raise InputError(f"{spec.name}: no peak of the load within {max_steps} increments of {increment:.3g} from {near} N", "near")
        forces.append(path.advance(start + (len(forces) - approach + 1) * increment))
    result = path.result()
    top = int(np.argmax(result.force))
    i = min(max(top, 1), result.force.size - 2)
    c, f = result.control[i - 1 : i + 2], result.force[i - 1 : i + 2]  # the control grows monotonically, the displacement need not
    a2, a1, a0 = np.polyfit(c, f, 2)
    cv = -a1 / (2 * a2) if a2 < 0 else c[1]
    displacement = np.interp(cv, c, result.displacement[i - 1 : i + 2]) / spec.share
    ys, tip, zone = crack_front(spec, result.damage[top])
    mid = int(np.argmin(np.abs(ys - (ys[-1] if spec.share < 1 else ys[-1] / 2))))
    return Critical(
        float(np.polyval((a2, a1, a0), cv)), float(displacement), float(result.force.max()), result, float(zone[mid]), float(tip[mid]), path.fallbacks
    )


@dataclass(frozen=True)
class ReleaseRates:
    """Energy release rates [J/m²] per unit load² [N²] along the crack front (the node line at the pre-crack tip, across
    the modelled width): ``y`` [m], ``mode_I``, ``mode_II``, ``mode_III`` (n_y,) each, and their averages over the
    front ``mean_I``, ``mean_II``, ``mean_III`` (weighted by the nodes' areas): :func:`release_rates`."""

    y: np.ndarray
    mode_I: np.ndarray
    mode_II: np.ndarray
    mode_III: np.ndarray
    mean_I: float
    mean_II: float
    mean_III: float

    @property
    def total(self) -> np.ndarray:
        """G_T(y) per unit load² (n_y,)."""
        return self.mode_I + self.mode_II + self.mode_III

    def critical_load(self, GIc: float, GIIc: float, eta: float, where: str = "mean") -> float:
        """The load [N] at which the B–K criterion G_T = G_Ic + (G_IIc − G_Ic)·(G_sh/G_T)^η is met (G_sh = G_II + G_III),
        by the front's mean (``"mean"``) or at its middle (``"middle"``: the node line's last node, the symmetry edge of
        a half-width model)."""
        if where == "mean":
            GI, Gsh = self.mean_I, self.mean_II + self.mean_III
        elif where == "middle":
            GI, Gsh = float(self.mode_I[-1]), float(self.mode_II[-1] + self.mode_III[-1])
        else:
            raise InputError(f"where must be 'mean' or 'middle', got {where!r}", "where")
        Gsh = max(Gsh, 0.0)  # round-off of a pure mode I
        GT = GI + Gsh
        return float(np.sqrt((GIc + (GIIc - GIc) * (Gsh / GT) ** eta) / GT))


def release_rates(spec: PlateSpecimen, extension: float) -> ReleaseRates:
    """The crack-closure energy release rates of ``spec`` per unit load², through the plate's own interface, for the
    crack grown from its pre-crack a0 by ``extension`` Δa [m] (the rates at a0 + Δa/2 to second order: build the
    specimen at a − Δa/2 for the rates at a). The elastic response u0 to λ = 1 at the committed damage (the
    pre-crack), the interface forces F_p = a_p·K·δ0_p of the intact nodes with a0 ≤ x < a0 + Δa (the penalty), then
    the response u1 with those nodes released (damage 1) and their openings δ1_p. At a fixed load the potential
    energy falls by ½·Σ_p F_p·δ1_p exactly (the released springs' forces before times their openings after:
    reciprocity between the two linear systems), the sum split by component into modes I (δ_n), II (sliding along x)
    and III (along y): Irwin's crack-closure integral over a finite extension. Per node line across the width, G(y)
    = ½·Σ F_p·δ1_p / Σ a_p over the line's released nodes. Δa must span several elements and the penalty's boundary
    layer (a single node line's release depends on both: tests/test_krueger.py). The model's damage is restored."""
    if not extension > 0:
        raise InputError(f"extension must be positive, got {extension!r} m", "extension")
    model = spec.model
    fe = model.layers[0].fe
    x = np.repeat(fe.node_xs, fe.node_ys.size)  # grid_node[i, j] = i·(ny + 1) + j
    band = np.flatnonzero((x >= spec.a0 - 1e-10) & (x < spec.a0 + extension - 1e-10))
    saved = model.damage.copy()
    try:
        u0 = linear_response(model, spec.load, spec.fixed)
        d0 = model.opening(u0)[band]  # interface 0: its points come first
        damage = saved.copy()
        damage[0, band] = 1.0
        model.damage = damage
        d1 = model.opening(linear_response(model, spec.load, spec.fixed))[band]
    finally:
        model.damage = saved
    a = model.area[band]
    work = 0.5 * model.law.K * a[:, None] * d0 * d1  # (points, 3): ½F·δ1 by component
    line = np.searchsorted(fe.node_ys, np.tile(fe.node_ys, fe.node_xs.size)[band] - 1e-12)  # the y line of each point
    ny = fe.node_ys.size
    per = np.stack([np.bincount(line, work[:, k], ny) for k in range(3)], -1) / np.bincount(line, a, ny)[:, None]
    mean = work.sum(0) / a.sum()
    return ReleaseRates(fe.node_ys.copy(), per[:, 0], per[:, 1], per[:, 2], float(mean[0]), float(mean[1]), float(mean[2]))
