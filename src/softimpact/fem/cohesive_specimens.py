"""Delamination specimens of stacked cohesive beams (:mod:`softimpact.fem.cohesive_beam`), SI, beam theory of
the arms; the LEFM closed forms the tests use are in :mod:`softimpact.models.delamination`: :func:`dcb` (mode I),
:func:`enf` (mode II, three-point bending), :func:`mmb` (Reeder & Crews' mixed-mode bending lever, a rigid lever
modelled by its kinematics), and :func:`tip_control` (a crack-tip control that passes snap-backs)."""

from __future__ import annotations

import numpy as np
import scipy.sparse.linalg

from ..models.cohesive import BilinearCohesive
from .cohesive_beam import Arm, BeamStack, CohesiveInterfaces, Specimen, T, U, W, beam_stiffness, dof

__all__ = ["dcb", "enf", "mmb", "tip_control"]


def _mesh(length: float, a0: float, h_el: float, *, refine: tuple[float, float] | None = None, coarse: float = 4.0) -> np.ndarray:
    """Nodes on [0, length] with a node at the crack tip a0, elements of size ``h_el`` on ``refine`` (x0, x1)
    and ``coarse``× larger elsewhere."""
    x0, x1 = refine if refine is not None else (0.0, length)
    x0, x1 = max(0.0, min(x0, a0)), min(length, max(x1, a0))
    parts = []

    def seg(p, q, hh):
        if q - p <= 0:
            return np.array([p])
        m = max(1, int(np.ceil((q - p) / hh - 1e-9)))
        return np.linspace(p, q, m + 1)

    parts.append(seg(0.0, x0, coarse * h_el))
    parts.append(seg(x0, a0, h_el))
    parts.append(seg(a0, x1, h_el))
    parts.append(seg(x1, length, coarse * h_el))
    x = np.unique(np.round(np.concatenate(parts), 15))
    return x


def _stack(x, E, h, width, law, a0, points, closure="contact") -> BeamStack:
    cracked = (0.5 * (x[:-1] + x[1:]) < a0)[None, :]
    return BeamStack(x, (Arm(E, h), Arm(E, h)), width, law, cracked, points, closure)


def dcb(
    *, E: float, h: float, width: float, length: float, a0: float, law: BilinearCohesive, element: float, points: int = 3, control: str = "load", refine=None
) -> Specimen:
    """Double cantilever beam: two arms of thickness ``h`` [m] (each), pre-crack from x = 0 to ``a0``; the arms'
    ends at x = 0 pulled apart. Load-point displacement = opening w_top(0) − w_bottom(0); force = the pull P.
    Held: u_top(0), u_bottom(0) and w_top(length), which remove the three rigid motions and nothing more (a
    statically determinate support of a self-equilibrated load: every reaction is zero)."""
    x = _mesh(length, a0, element, refine=refine)
    st = _stack(x, E, h, width, law, a0, points)
    n = st.size
    g = np.zeros(n)
    g[dof(st, 0, 0, W)], g[dof(st, 1, 0, W)] = 1.0, -1.0
    fixed = np.array([dof(st, 0, 0, U), dof(st, 1, 0, U), dof(st, 0, len(x) - 1, W)])
    ctrl = g if control == "load" else tip_control(st, a0, opening=1.0)
    return Specimen(st, fixed, g, ctrl, "DCB")


def enf(
    *, E: float, h: float, width: float, half_span: float, a0: float, law: BilinearCohesive, element: float, points: int = 3, control: str = "load", refine=None
) -> Specimen:
    """End-notched flexure: span 2·``half_span`` = 2L simply supported under the lower arm at x = 0 and 2L, pre-crack
    from x = 0 to ``a0``, the load at midspan on the upper arm, downward. Load-point displacement = −w_top(L).
    ``control`` "load" (that displacement) or "sliding" (the sliding at the pre-crack tip, monotone through a
    snap-back). The faces are tied in the normal direction (``closure="tied"``): the arms stay in contact."""
    L = half_span
    x = _mesh(2 * L, a0, element, refine=refine)
    if not np.any(np.isclose(x, L)):
        x = np.unique(np.concatenate([x, [L]]))
    st = _stack(x, E, h, width, law, a0, points, closure="tied")
    n = st.size
    mid = int(np.argmin(np.abs(x - L)))
    g = np.zeros(n)
    g[dof(st, 0, mid, W)] = -1.0
    fixed = np.array([dof(st, 1, 0, W), dof(st, 1, len(x) - 1, W), dof(st, 1, 0, U)])
    ctrl = g if control == "load" else tip_control(st, a0, sliding=1.0)
    return Specimen(st, fixed, g, ctrl, "ENF")


def mmb(
    *,
    E: float,
    h: float,
    width: float,
    half_span: float,
    a0: float,
    lever: float,
    law: BilinearCohesive,
    element: float,
    points: int = 3,
    control: str = "load",
    refine=None,
) -> Specimen:
    """Mixed-mode bending (Reeder & Crews 1990): the ENF set-up plus a rigid lever hinged to the upper arm at x = 0,
    bearing on the upper arm at midspan x = L and loaded by P at ``lever`` = c beyond midspan. Small rotations
    of the lever give its load point's downward displacement c/L·w_top(0) − (c + L)/L·w_top(L): the upper arm
    is pulled up by P·c/L at x = 0 and pushed down by P·(c + L)/L at midspan. ``control`` "load" (that
    displacement) or "tip" (the opening plus the sliding at the pre-crack tip, monotone through a snap-back).
    The lever holds the crack open (P_I > 0 for c > L/3): no contact is modelled (``closure="none"``); the
    smallest opening of the separated faces (:attr:`Curve.min_separated_opening`) tells whether that held."""
    L, c = half_span, lever
    x = _mesh(2 * L, a0, element, refine=refine)
    if not np.any(np.isclose(x, L)):
        x = np.unique(np.concatenate([x, [L]]))
    st = _stack(x, E, h, width, law, a0, points, closure="none")
    n = st.size
    mid = int(np.argmin(np.abs(x - L)))
    g = np.zeros(n)
    g[dof(st, 0, 0, W)] = c / L
    g[dof(st, 0, mid, W)] = -(c + L) / L
    fixed = np.array([dof(st, 1, 0, W), dof(st, 1, len(x) - 1, W), dof(st, 1, 0, U)])
    if control == "load":
        ctrl = g
    else:  # |δ_n| + |δ_s| at the tip: each component turned by its sign under the initial, elastic response
        opening, sliding = tip_control(st, a0, opening=1.0), tip_control(st, a0, sliding=1.0)
        u = _elastic_response(st, fixed, g)
        ctrl = np.sign(opening @ u) * opening + np.sign(sliding @ u) * sliding
    return Specimen(st, fixed, g, ctrl, "MMB")


def _elastic_response(st: BeamStack, fixed, load) -> np.ndarray:
    """DOFs under the unit load ``load`` on the initial tangent (undamaged interfaces, the pre-crack open)."""
    ifc = CohesiveInterfaces.of(st)
    f, K, _ = ifc.assemble(np.zeros(st.size), ifc.initial_damage())
    K = (beam_stiffness(st) + K).tocsr()
    free = np.setdiff1d(np.arange(st.size), fixed)
    u = np.zeros(st.size)
    u[free] = scipy.sparse.linalg.spsolve(K[free][:, free].tocsc(), np.asarray(load, float)[free])
    return u


def tip_control(st: BeamStack, xc: float, *, opening: float = 0.0, sliding: float = 0.0) -> np.ndarray:
    """The DOF vector giving opening·δ_n + sliding·δ_s of interface 0 at the node nearest x = ``xc``
    (δ_n = w_top − w_bot, δ_s = u_top + h/2·θ_top − u_bot + h/2·θ_bot): a local control for the pre-crack tip."""
    node = int(np.argmin(np.abs(np.asarray(st.x) - xc)))
    c = np.zeros(st.size)
    c[dof(st, 0, node, W)] += opening
    c[dof(st, 1, node, W)] -= opening
    c[dof(st, 0, node, U)] += sliding
    c[dof(st, 0, node, T)] += sliding * st.arms[0].thickness / 2
    c[dof(st, 1, node, U)] -= sliding
    c[dof(st, 1, node, T)] += sliding * st.arms[1].thickness / 2
    return c
