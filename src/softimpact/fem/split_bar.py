"""Two-bar (split Hopkinson) set-up: incident bar, specimen and transmitted bar, as three Hermite rods in a row.

Each part is the rod of :mod:`softimpact.fem.bar` (scikit-fem's Hermite elements: u and du/dx at each node).
The parts are joined by their axial displacement only: at a junction the force E·A·u' is continuous
while the strain u' jumps with the area and the modulus (the note of :mod:`softimpact.fem.bar`), so each
side keeps its own strain DOF and the two axial DOFs become one. The joints carry tension as well as
compression (bars and specimen stay in contact: the analysis window ends before any unloading wave would
open them).

The bars are linear elastic. The specimen may flow (``SpecimenLaw``): an elastic–viscoplastic bar, with the
flow stress a function of the plastic strain rate,

    σ_f(ε̇_p) = σ_0 · (1 + ε̇_p/ε̇_0)^m,      |σ| ≤ σ_f,                                      (F)

perfectly plastic (yield σ_0) for m = 0, and ≈ σ_0·(ε̇_p/ε̇_0)^m, a power law, at rates well above ε̇_0. Its
internal force is integrated at three Gauss points per element (exact for the elastic stiffness:
u' is quadratic on a Hermite element), with a return mapping per point: the trial stress σ_tr = E(ε − ε_p),
and when |σ_tr| > σ_0 the plastic increment Δ solving |σ_tr| − E·Δ = σ_f(Δ/dt) (one root: the left
side falls and the right rises with Δ).

Time: Newmark's average acceleration (β = 1/4, γ = 1/2) with Newton's iteration each step on the consistent
tangent. The elastic effective matrix K + M/(β dt²) is factored once (:func:`softimpact.fem.newmark.spd_factor`);
the flowing Gauss points soften it by a low-rank term, solved by Woodbury's identity against K_eff⁻¹Pᵀ computed
once (P the Gauss points' strain rows): one back-substitution for an elastic step, two or three while the
specimen flows.

The load: a compressive force F(t) [N] on the incident bar's free end (x = 0), as a striker's pressure
would apply it. Positions on the incident bar from its loaded end, on the transmitted bar from the
specimen. Outputs: gauge strains (tension +), the forces on the specimen's two faces (compression +, from
the bars' own strain DOFs at the joints) and the specimen's mean strain (its faces' approach over its
length, compression +).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse

from ..errors import InputError
from .bar import Rod, assemble_rod
from .newmark import spd_factor

__all__ = ["SpecimenLaw", "SplitBar", "SplitBarResult", "simulate_split_bar"]

GAUSS = (np.array([-math.sqrt(0.6), 0.0, math.sqrt(0.6)]), np.array([5.0, 8.0, 5.0]) / 9.0)  # 3-point Gauss–Legendre on [−1, 1]
TOLERANCE = 1e-10  # Newton: stop when the update is this small against the displacement (the step's and the total)
MAX_ITERATIONS = 200
BETA, GAMMA = 0.25, 0.5  # Newmark's average acceleration


@dataclass(frozen=True)
class SpecimenLaw:
    """Flow of the specimen, eq. (F): ``yield_stress`` σ_0 [Pa] (None: elastic), ``rate_exponent`` m [-],
    ``reference_rate`` ε̇_0 [1/s]."""

    yield_stress: float | None = None
    rate_exponent: float = 0.0
    reference_rate: float = 1.0

    def __post_init__(self):
        if self.yield_stress is not None and not (math.isfinite(self.yield_stress) and self.yield_stress > 0):
            raise InputError(f"yield_stress must be positive, got {self.yield_stress!r}", "yield_stress")
        if not 0.0 <= self.rate_exponent < 1.0:
            raise InputError(f"rate_exponent must lie in [0, 1), got {self.rate_exponent!r}", "rate_exponent")
        if not self.reference_rate > 0:
            raise InputError(f"reference_rate must be positive, got {self.reference_rate!r}", "reference_rate")

    def flow_stress(self, rate):
        """σ_f [Pa] at the plastic strain rate(s) ``rate`` [1/s], eq. (F)."""
        return self.yield_stress * (1.0 + np.maximum(rate, 0.0) / self.reference_rate) ** self.rate_exponent


@dataclass(frozen=True)
class SplitBar:
    """The set-up: ``incident``, ``specimen`` and ``transmitted`` rods (:class:`softimpact.fem.bar.Rod`: length,
    area, E, ρ, elements), the specimen's flow ``law``."""

    incident: Rod
    specimen: Rod
    transmitted: Rod
    law: SpecimenLaw = SpecimenLaw()


@dataclass(frozen=True)
class SplitBarResult:
    """Histories on ``time`` [s] (from the load's start): ``incident_strain`` and ``transmitted_strain`` (n_gauges, n),
    tension +; ``front_force`` and ``back_force`` [N] on the specimen's faces, compression +; ``specimen_strain``
    its mean strain, compression +; ``iterations`` the Newton iterations of all steps."""

    time: np.ndarray
    incident_strain: np.ndarray
    transmitted_strain: np.ndarray
    front_force: np.ndarray
    back_force: np.ndarray
    specimen_strain: np.ndarray
    iterations: int


class _Assembly:
    """The three rods joined (module docstring): reduced matrices, the specimen's Gauss points, probes."""

    def __init__(self, setup: SplitBar):
        parts = [assemble_rod(r) for r in (setup.incident, setup.specimen, setup.transmitted)]
        sizes = [p.n for p in parts]
        offsets = np.cumsum([0, *sizes])
        n_full = int(offsets[-1])
        index = np.arange(n_full)
        # the incident's last axial DOF is the specimen's first; the specimen's last is the transmitted's first
        joints = [
            (offsets[0] + int(parts[0].axial_dofs[-1]), offsets[1] + int(parts[1].axial_dofs[0])),
            (offsets[1] + int(parts[1].axial_dofs[-1]), offsets[2] + int(parts[2].axial_dofs[0])),
        ]
        for keep, drop in joints:
            index[drop] = keep
        kept = np.unique(index)
        reduced = np.searchsorted(kept, index)
        self.n = kept.size
        self.T = scipy.sparse.csr_matrix((np.ones(n_full), (np.arange(n_full), reduced)), shape=(n_full, self.n))
        M = scipy.sparse.block_diag([p.M for p in parts]).tocsr()
        K_bars = scipy.sparse.block_diag([parts[0].K, scipy.sparse.csr_matrix(parts[1].K.shape), parts[2].K]).tocsr()
        self.M = (self.T.T @ M @ self.T).tocsr()
        self.K_bars = (self.T.T @ K_bars @ self.T).tocsr()
        spec = setup.specimen
        # the specimen's Gauss points: three per element, their weights (dx) and strain probe rows
        nodes = parts[1].nodes
        h = np.diff(nodes)
        xi, wi = GAUSS
        self.gauss_x = (0.5 * (nodes[:-1, None] + nodes[1:, None]) + 0.5 * h[:, None] * xi[None, :]).ravel()
        self.gauss_w = (0.5 * h[:, None] * wi[None, :]).ravel()
        self.P = self._embed(parts[1].strain_probe(self.gauss_x), offsets[1], n_full)
        self.spec_E, self.spec_A = spec.youngs_modulus, spec.area
        self.K_spec = (self.P.T @ scipy.sparse.diags(spec.youngs_modulus * spec.area * self.gauss_w) @ self.P).tocsr()
        self.parts, self.offsets, self.n_full = parts, offsets, n_full
        self.load_dof = int(reduced[offsets[0] + parts[0].axial_dofs[0]])
        self.front_dof = int(reduced[joints[0][0]])
        self.back_dof = int(reduced[joints[1][0]])
        self.front_strain = self._embed(parts[0].strain_probe([setup.incident.length]), offsets[0], n_full)
        self.back_strain = self._embed(parts[2].strain_probe([0.0]), offsets[2], n_full)

    def _embed(self, probe, offset, n_full):
        """A part's probe rows as rows over the reduced DOFs."""
        coo = scipy.sparse.coo_matrix(probe)
        full = scipy.sparse.csr_matrix((coo.data, (coo.row, coo.col + offset)), shape=(coo.shape[0], n_full))
        return (full @ self.T).tocsr()

    def probes(self, part: int, positions) -> scipy.sparse.csr_matrix:
        return self._embed(self.parts[part].strain_probe(positions), self.offsets[part], self.n_full)


def _return_map(law: SpecimenLaw, E: float, strain, plastic, dt: float, guess=None):
    """(stress, plastic strain, tangent dσ/dε) at the Gauss points after a step of ``dt`` from the committed ``plastic``
    strain (module docstring); elastic (tangent E) where the law has no yield stress or the trial stress is below σ_0.
    Flowing, the tangent is E·h/(E + h), h = σ_f'(ε̇_p)/dt (0 for a perfectly plastic point)."""
    trial = E * (strain - plastic)
    tangent = np.full(trial.shape, E)
    if law.yield_stress is None:
        return trial, plastic, tangent
    size = np.abs(trial)
    flowing = size > law.yield_stress
    if not flowing.any():
        return trial, plastic, tangent
    s = size[flowing]
    if law.rate_exponent == 0.0:
        delta = (s - law.yield_stress) / E
    else:
        delta = _viscoplastic_increment(law, E, s, dt, None if guess is None else guess[flowing])
    new_plastic = plastic.copy()
    new_plastic[flowing] += np.sign(trial[flowing]) * delta
    rate = delta / dt
    h = law.flow_stress(rate) * law.rate_exponent / (law.reference_rate + rate) / dt
    tangent[flowing] = E * h / (E + h)
    return E * (strain - new_plastic), new_plastic, tangent


def _viscoplastic_increment(law: SpecimenLaw, E: float, s, dt: float, guess):
    """The plastic increments Δ = ε̇_p·dt solving s − E·Δ = σ_f(Δ/dt) at trial stresses ``s`` > σ_0 (eq. F): Newton on
    q = ln ε̇_p of φ(q) = ln σ_f(e^q) − ln(s − E·dt·e^q), which rises monotonically and is nearly straight where the
    power law holds (ε̇_p ≫ ε̇_0); safeguarded by bisection in q; from the last step's rate (``guess``, Δ) where it flowed.
    m > 0 (the perfectly plastic increment is closed-form)."""
    top = (s - law.yield_stress) / (E * dt)  # φ > 0 there: σ_f(top) ≥ σ_0 = s − E·dt·top
    lo, hi = np.log(np.maximum(1e-12 * top, 1e-300)), np.log(top)
    # a point that flowed last step starts from its rate then; one just yielding from σ_f(ε̇_p) = s (the flow law alone)
    alone = law.reference_rate * ((s / law.yield_stress) ** (1.0 / law.rate_exponent) - 1.0)
    start = alone if guess is None else np.where(guess > 0, guess / dt, alone)
    q = np.clip(np.log(np.maximum(start, 1e-300)), lo, hi)
    for _ in range(100):
        r = np.exp(q)
        room = np.maximum(s - E * dt * r, 1e-300)
        phi = np.log(law.flow_stress(r)) - np.log(room)
        lo, hi = np.where(phi < 0, q, lo), np.where(phi < 0, hi, q)
        dphi = law.rate_exponent * r / (law.reference_rate + r) + E * dt * r / room
        nxt = q - phi / dphi
        nxt = np.where((nxt >= lo) & (nxt <= hi), nxt, 0.5 * (lo + hi))  # inclusive: a converged point sits on its bracket
        done = np.max(np.abs(nxt - q)) <= 1e-9  # a relative change of the rate: φ itself is exact to ~1e-12 only
        q = nxt
        if done:
            break
    return np.exp(q) * dt


def _tangent_solve(factor, woodbury, residual, softening):
    """K_t⁻¹·residual, K_t = K_eff − Pᵀ diag(d) P the effective tangent (d = A·w·(E − tangent) at the flowing points), by
    Woodbury's identity on the elastic factor: y = K_eff⁻¹ r, then y + Z_p (diag(1/d_p) − P_p Z_p)⁻¹ P_p y, Z = K_eff⁻¹ Pᵀ.
    ``woodbury``: (Z, the specimen's DOFs S, P restricted to them); P_p y and P_p Z_p need only S (P is zero elsewhere)."""
    y = factor.solve(residual)
    p = np.flatnonzero(softening > 0)
    if woodbury is None or p.size == 0:
        return y
    Z, S, PS = woodbury
    Pp = PS[p]
    small = np.diag(1.0 / softening[p]) - Pp @ Z[S][:, p]
    return y + Z[:, p] @ np.linalg.solve(small, Pp @ y[S])


def simulate_split_bar(setup: SplitBar, force, *, time_step: float, duration: float, incident_gauges=(), transmitted_gauges=()) -> SplitBarResult:
    """Step the set-up (module docstring) under the compressive ``force`` F(t) [N] (a callable) on the incident bar's
    free end, every ``time_step`` [s] for ``duration`` [s]; gauges at ``incident_gauges`` [m] from the loaded end
    and ``transmitted_gauges`` [m] from the specimen."""
    from threadpoolctl import threadpool_limits

    if not (time_step > 0 and duration > time_step):
        raise InputError(f"time_step {time_step!r} s and duration {duration!r} s must be positive, the duration longer", "time_step")
    a = _Assembly(setup)
    steps = int(round(duration / time_step))
    dt = duration / steps
    t = np.arange(steps + 1) * dt
    factor = spd_factor((a.K_bars + a.K_spec + a.M / (BETA * dt * dt)).tocsc())
    gauges = [a.probes(part, np.atleast_1d(np.asarray(g, float))) if len(g) else None for part, g in ((0, incident_gauges), (2, transmitted_gauges))]
    f_load = np.asarray([force(tt) for tt in t], float)
    woodbury = None
    if setup.law.yield_stress is not None:  # K_eff⁻¹ Pᵀ and P on the specimen's DOFs, for the flowing tangent
        P_dense = a.P.toarray()
        S = np.flatnonzero(np.any(P_dense != 0.0, axis=0))
        woodbury = (factor.solve(P_dense.T), S, P_dense[:, S])
    with threadpool_limits(1, user_api="blas"):  # small dense solves: threads would only wait for each other
        return _march(setup, a, factor, woodbury, f_load, t, gauges)


def _march(setup: SplitBar, a: _Assembly, factor, woodbury, f_load, t, gauges) -> SplitBarResult:
    """The time loop of :func:`simulate_split_bar`: Newmark's predictor, Newton on the consistent tangent, the outputs."""
    steps, dt = t.size - 1, float(t[1] - t[0])
    n, M, PT = a.n, a.M, a.P.T.tocsr()
    u, v, acc = np.zeros(n), np.zeros(n), np.zeros(n)
    plastic = np.zeros(a.gauss_x.size)
    last = np.zeros(a.gauss_x.size)  # each Gauss point's plastic increment of the last step: the next step's first guess
    scale = a.spec_A * a.gauss_w
    gi, gt = gauges
    out_i = np.zeros((0 if gi is None else gi.shape[0], steps + 1))
    out_t = np.zeros((0 if gt is None else gt.shape[0], steps + 1))
    front, back, mean = np.zeros(steps + 1), np.zeros(steps + 1), np.zeros(steps + 1)
    EA_i = setup.incident.youngs_modulus * setup.incident.area
    EA_t = setup.transmitted.youngs_modulus * setup.transmitted.area
    iterations = 0
    if f_load[0] != 0.0:  # acceleration at t = 0 from the load alone (the set-up at rest)
        rhs = np.zeros(n)
        rhs[a.load_dof] = f_load[0]
        acc = scipy.sparse.linalg.spsolve(M.tocsc(), rhs)
    for k in range(1, steps + 1):
        u_pred = u + dt * v + dt * dt * (0.5 - BETA) * acc
        v_pred = v + dt * (1 - GAMMA) * acc
        f_ext = np.zeros(n)
        f_ext[a.load_dof] = f_load[k]
        un = u_pred.copy()
        for _ in range(MAX_ITERATIONS):
            acc_new = (un - u_pred) / (BETA * dt * dt)
            stress, _, tangent = _return_map(setup.law, a.spec_E, a.P @ un, plastic, dt, last)
            residual = f_ext - M @ acc_new - a.K_bars @ un - PT @ (scale * stress)
            du = _tangent_solve(factor, woodbury, residual, scale * (a.spec_E - tangent))
            un = un + du
            iterations += 1
            if setup.law.yield_stress is None or np.linalg.norm(du) <= TOLERANCE * (np.linalg.norm(un - u) + np.linalg.norm(un)):
                break
        else:
            raise RuntimeError(f"split bar: the specimen's flow did not converge at t = {t[k] * 1e6:.3f} us")
        _, new_plastic, _ = _return_map(setup.law, a.spec_E, a.P @ un, plastic, dt, last)
        last, plastic = np.abs(new_plastic - plastic), new_plastic
        acc_new = (un - u_pred) / (BETA * dt * dt)
        v = v_pred + GAMMA * dt * acc_new
        u, acc = un, acc_new
        if gi is not None:
            out_i[:, k] = gi @ u
        if gt is not None:
            out_t[:, k] = gt @ u
        front[k] = -EA_i * float((a.front_strain @ u)[0])
        back[k] = -EA_t * float((a.back_strain @ u)[0])
        mean[k] = (u[a.front_dof] - u[a.back_dof]) / setup.specimen.length
    return SplitBarResult(t, out_i, out_t, front, back, mean, iterations)
