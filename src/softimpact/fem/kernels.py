"""Contact kernels: coupled impact on a linear structure as a Volterra problem.

A linear structure at rest, stepped by Newmark, answers a history of contact-patch
loads q_j = F_j·s(a_j) (p nodal shares, :mod:`softimpact.fem.impact`) with the
discrete convolution

    w_k = Σ_{j=1..k} g_{k−j}·q_j,      y_k = Σ_{j=1..k} H_{k−j}·q_j,

where w is the approach row's displacement (the mid-surface under the impactor),
y the outputs (gauge strains), and g_i (p,), H_i (q, p) the structure's discrete
impulse responses at lag i (:class:`softimpact.fem.response.ImpulseResponse`,
computed once by reciprocity: 1 + q right-hand sides a step). g_0 is the
direct stepper's c·G. A coupled run then steps only the scalar contact equation
of :func:`softimpact.fem.impact.integrate_impact`,

    R(α) = α − α̃ + F(α, α̇(α))·h(a(α)) = 0,   α̃ = x̃ − Σ_{j≤k} g_{k+1−j}·q_j,

with the same Newton iteration, so the histories equal direct coupled stepping to
round-off (the sums are taken in another order). The approach's rate and
acceleration follow from Newmark's rule applied to α itself (x and c·u each obey
it, so their difference does), which needs no structural state.

Cost. The build marches the structure with 1 + q right-hand sides (the approach row and the q
outputs, by reciprocity; :func:`_reciprocal_march`): with a band factor one march per row, run at once in
threads (the band solve releases the GIL), about 1.1–1.6 direct coupled runs on 2 free cores; with SuperLU's
sparse factor (large plates) one march solving all rows in one call a step, about 1.6–1.9 (BENCHMARKS.md).
A run costs milliseconds. The scalar state is plain Python floats. In the Newton iteration the patch
enters only through h_s(a) = c·G·s(a) and dh_s/da, evaluated without forming s, exactly: over the
nodes the disc reaches (the cosine line patch; after the first iterate h_s alone, the slope kept from
the first, :func:`softimpact.fem.impact.newton_contact`) or as the interpolation of the table's c·G·s_k
computed once (a plate's disc, whose shares interpolate a table); s itself is formed once per step, at
the root. A step whose force is zero at the bracket's top α̃ (a force clipped to
zero, as by a Maxwell arm's negative stress while unloading) has its root there and takes it without
a Newton solve. While in contact, the history sum runs over the current contact's steps only (one
contiguous dot product; the earlier contacts are a precomputed "old" response). When a contact ends,
the response to its loads is one FFT product with the kernels' cached spectra, kept for the outputs
(the run's outputs are the sum over its contacts: one inverse transform at the end). While apart, no
load is added, the impactor flies at constant speed, and the next contact is found by one vectorised
test; the steps between carry only the scalar recursions of α̇, α̈, and a law's memory in one call
where the law offers it (``apart``; ``settle`` gives a converged step's state, branch and energy at
once: :class:`softimpact.models.contact_laws.ViscoelasticSoftLaw`).

A smaller impactor (a smaller contact reach, its loadable nodes among the kernels') runs on the same
kernels with its own patch (:meth:`ContactKernels.compliance_for`). Kernels pickle without the
factorised stepper and the mesh (to a Dask worker).

The structure's own energies (kinetic, strain, the work on the patch nodes) need
its state and are not computed here (NaN); the impactor's energy and the contact
work are.
"""

from __future__ import annotations

import copy
import math
from bisect import bisect_left, bisect_right
from concurrent.futures import ThreadPoolExecutor
from types import SimpleNamespace

import numpy as np
from scipy.fft import next_fast_len

from ..errors import InputError
from ..models.protocols import HistoryLaw
from ..models.specimens import Impactor
from .impact import ContactPatch, ContactStructure, ImpactHistory, PatchCompliance, SeparationClock, newton_contact
from .newmark import NewmarkParameters, NewmarkStepper
from .plate_loads import DiscShares
from .response import ImpulseResponse

__all__ = ["ContactKernels"]

MARCH_THREADS = 16  # the kernel build's marches run at once, one per kernel row up to this many (_reciprocal_march)


class _LineCompliance:
    """h_s(r) = c·G·s(r) [m/N] and dh_s/dr [1/N] of the cosine line patch (:class:`ContactPatch`) as
    plain floats, exact. Over the nodes i0 … i1 − 1 the disc of radius r reaches, the outer ends are
    clipped to ±r (sin = ±1) and each inner segment end m_j is shared by two nodes, so

        h_s = ½·[c_{i0} + c_{i1−1} + Σ_j (c_j − c_{j+1})·sin(π·m_j/(2r))],
        dh_s/dr = −½·(π/(2r))/r·Σ_j (c_j − c_{j+1})·m_j·cos(π·m_j/(2r)),

    one sine and one cosine per reached node."""

    def __init__(self, patch: ContactPatch, cG: np.ndarray):
        self.patch, self.half_spacing = patch, float(patch.half_spacing)
        c = np.asarray(cG, float)
        self.lo, self.hi, self.c = patch.lo.tolist(), patch.hi.tolist(), c.tolist()
        self.dc = (c[:-1] - c[1:]).tolist()  # c_j − c_{j+1}: the weight of the end shared by nodes j and j + 1
        self.ends = [(d, m, d * m) for d, m in zip(self.dc, self.hi)]  # (weight, position, their product) of each inner segment end
        self.x0, self.x1 = self.extent = patch.extent
        self.point = self.c[patch.nearest]
        self._kept = None  # (r, i0, i1, π/(2r), the inner ends' sines) of the last :meth:`value`

    def __call__(self, r: float) -> tuple[float, float]:
        if r < self.half_spacing:
            return self.point, 0.0
        if -r < self.x0 - 1e-12 * r or r > self.x1 + 1e-12 * r:
            raise InputError(f"contact radius {r:.4g} m runs past the loadable surface nodes")
        i0, i1 = bisect_right(self.hi, -r), bisect_left(self.lo, r)
        w = math.pi / (2.0 * r)
        sin, cos = math.sin, math.cos
        h = self.c[i0] + self.c[i1 - 1]
        dh = 0.0
        for d, m, dm in self.ends[i0 : i1 - 1]:  # the inner segment ends the disc covers
            x = w * m
            h += d * sin(x)
            dh += dm * cos(x)
        return 0.5 * h, -0.5 * w * dh / r

    def value(self, r: float) -> float:
        """h_s(r) alone (the contact iteration's later iterates, :func:`newton_contact`), the same sum as
        :meth:`__call__`'s; its sines are kept for :meth:`load` at the same r (the converged iterate's)."""
        if r < self.half_spacing:
            return self.point
        if -r < self.x0 - 1e-12 * r or r > self.x1 + 1e-12 * r:
            raise InputError(f"contact radius {r:.4g} m runs past the loadable surface nodes")
        i0, i1 = bisect_right(self.hi, -r), bisect_left(self.lo, r)
        w = math.pi / (2.0 * r)
        sin = math.sin
        h = self.c[i0] + self.c[i1 - 1]
        sines = []
        keep = sines.append
        for d, m, _ in self.ends[i0 : i1 - 1]:
            x = sin(w * m)
            keep(x)
            h += d * x
        self._kept = (r, i0, i1, w, sines)
        return 0.5 * h

    def load(self, r: float, f: float, out: np.ndarray) -> None:
        """out ← f·s(r) (out zero on entry): the nodal loads of the converged step."""
        if r < self.half_spacing:
            out[self.patch.nearest] = f
            return
        lo, hi, sin = self.lo, self.hi, math.sin
        kept = self._kept
        if kept is not None and kept[0] == r:  # the sines of the inner ends, from :meth:`value` at this r
            _, i0, i1, w, inner = kept
        else:
            w = math.pi / (2.0 * r)
            i0, i1 = bisect_right(hi, -r), bisect_left(lo, r)
            inner = [sin(w * m) for m in hi[i0 : i1 - 1]]
        # the segment ends the disc covers, each shared by two nodes (lo[j + 1] is hi[j]), the outer two clipped to ±r
        half = 0.5 * f
        below = sin(w * min(max(lo[i0], -r), r))
        loads = []
        for above in inner:
            loads.append(half * (above - below))
            below = above
        loads.append(half * (sin(w * min(max(hi[i1 - 1], -r), r)) - below))
        out[i0:i1] = loads


class _TableCompliance:
    """h_s(r) and dh_s/dr of a plate's contact disc (:class:`DiscShares`): its shares are the linear
    interpolation of a table in r, so c·G·s(r) is the same interpolation of the table's c·G·s_k
    (each computed once, when first reached), exact to round-off."""

    def __init__(self, patch: DiscShares, cG: np.ndarray):
        self.patch, self.half_spacing, self.cG = patch, float(patch.half_spacing), np.asarray(cG, float)
        self.step, self.radius = patch.step, patch.patch.radius
        self.last = int(round(self.radius / self.step))  # TABLE − 1
        self.h: list = [None] * (self.last + 1)

    def _h(self, k: int) -> float:
        h = self.h[k]
        if h is None:
            h = self.h[k] = float(self.patch.row(k) @ self.cG)
        return h

    def __call__(self, r: float) -> tuple[float, float]:
        if r > self.radius * (1 + 1e-12):
            raise InputError(f"contact radius {r:.4g} m runs past the loadable disc ({self.radius:.4g} m)")
        pos = min(max(r / self.step, 0.0), self.last)
        k = min(int(pos), self.last - 1)
        frac = pos - k
        h0, h1 = self._h(k), self._h(k + 1)
        return h0 * (1 - frac) + h1 * frac, (h1 - h0) / self.step

    def load(self, r: float, f: float, out: np.ndarray) -> None:
        """out ← f·s(r): the nodal loads of the converged step."""
        out[:] = f * self.patch.shares(r)[0]


class _ShareCompliance(PatchCompliance):
    """:class:`softimpact.fem.impact.PatchCompliance` of any other patch, with the loads of a converged step."""

    def load(self, r: float, f: float, out: np.ndarray) -> None:
        """out ← f·s(r): the nodal loads of the converged step."""
        out[:] = f * self.patch.shares(r)[0]


class _Mapped:
    """A smaller structure's compliance on the kernels' patch columns ``index`` (its surface DOFs among
    the kernels'): h_s from its own patch, its loads written into those columns."""

    def __init__(self, comp, index: np.ndarray, width: int):
        self.comp, self.index, self.half_spacing, self.patch = comp, index, comp.half_spacing, comp.patch
        self._row = np.zeros(width)

    def __call__(self, r: float) -> tuple[float, float]:
        return self.comp(r)

    def load(self, r: float, f: float, out: np.ndarray) -> None:
        row = self._row
        row[:] = 0.0
        self.comp.load(r, f, row)
        out[self.index] = row[: self.index.size]


def _reciprocal_march(st: NewmarkStepper, rows: np.ndarray, dofs: np.ndarray, sign: float, steps: int, threads: int | None = None) -> np.ndarray:
    """The kernels (m, p, steps) of the m = 1 + q rows ``rows`` (m, n) for unit loads on the p surface DOFs
    ``dofs`` (direction ``sign``), by reciprocity: Newmark marches of the structure at rest under the loads
    f_1 = rowsᵀ at step 1 only (:func:`_march`). The rows are independent: they are split over ``threads``
    marches run at once. None: one per row (up to :data:`MARCH_THREADS`) where a band factor solves them
    (:attr:`NewmarkStepper.separate_solves`: m right-hand sides cost m solves together or apart, and the
    band solve releases the GIL), else one march (SuperLU solves several columns in one call for less than
    apart, BENCHMARKS.md). One march per row beats one per core: on 2 free cores, three one-row marches take
    about 1.5 marches' time, a two-row and a one-row march 2; on a busy core they cost about what one march
    of all rows costs. Each row's numbers are the same whatever the split (its column of each solve and
    product is computed alone: a test)."""
    rows = np.asarray(rows, float)
    if threads is None:
        threads = MARCH_THREADS if st.separate_solves else 1
    groups = np.array_split(np.arange(rows.shape[0]), max(1, min(rows.shape[0], threads)))
    if len(groups) == 1:
        return _march(st, rows, dofs, sign, steps)
    with ThreadPoolExecutor(len(groups)) as pool:
        parts = list(pool.map(lambda g: _march(st, rows[g], dofs, sign, steps), groups))
    return np.concatenate(parts, axis=0)


def _march(st: NewmarkStepper, rows: np.ndarray, dofs: np.ndarray, sign: float, steps: int) -> np.ndarray:
    """:func:`_reciprocal_march` of the rows ``rows`` in one march, their right-hand sides in one solve a
    step, the surface DOFs read after each step, kernel[:, :, i] = sign·u_{i+1}[dofs]ᵀ. The numbers of
    :meth:`ImpulseResponse.reciprocal` (``kernel``) to the last bit: the stepper's predictor
    u' = K_eff⁻¹·[M·(a0·u + a2·v + a3·a) + C·(a1·u + a4·v + a5·a)] and corrector a' = a0·(u' − u) − a2·v − a3·a,
    v' = v + a6·a + a7·a' in the same order, with a2·v formed once for both, the products in place, and
    the outputs read by index instead of a sparse product. The factor's solve is called uncounted
    (:meth:`NewmarkStepper.factor_solve`: marches may run in threads)."""
    f1 = np.asarray(rows, float).T.copy()  # (n, m)
    a0, a1, a2, a3, a4, a5, a6, a7 = st.a0, st.a1, st.a2, st.a3, st.a4, st.a5, st.a6, st.a7
    M, C, solve = st.M, st.C, st.factor_solve
    unit = a3 == 1.0  # average acceleration: a3·a is a
    seen = np.empty((steps, dofs.size, f1.shape[1]))  # time-major: each step writes one contiguous block
    u = solve(f1)  # from rest: u = K_eff⁻¹·f_1, a = a0·u, v = a7·a
    a = a0 * u
    v = a7 * a
    seen[0] = u[dofs]
    for k in range(1, steps):
        a2v = a2 * v
        z = a0 * u
        z += a2v
        z += a if unit else a3 * a
        rhs = M @ z
        if C is not None:
            rhs = rhs + C @ (a1 * u + a4 * v + a5 * a)
        u1 = solve(rhs)
        acc = u1 - u
        acc *= a0
        acc -= a2v
        acc -= a if unit else a3 * a
        v += a6 * a
        v += a7 * acc
        u, a = u1, acc
        seen[k] = u[dofs]
    return np.ascontiguousarray((sign * seen).transpose(2, 1, 0))


def _light(patch):
    """The patch without its mesh (a plate's disc keeps its tables and share; the mesh stays behind)."""
    inner = getattr(patch, "patch", None)
    if inner is None or getattr(inner, "fe", None) is None:
        return patch
    if hasattr(patch, "row"):  # every tabulated row now, while the mesh is at hand
        patch.table  # noqa: B018
    light = copy.copy(patch)
    light.patch = copy.copy(inner)
    light.patch.fe = None
    return light


def _compliance(patch, cG: np.ndarray):
    """The patch's h_s(r) = c·G·s(r) evaluator (chosen once per kernel build, not per step)."""
    if isinstance(patch, ContactPatch):
        return _LineCompliance(patch, cG)
    if isinstance(patch, DiscShares):
        return _TableCompliance(patch, cG)
    return _ShareCompliance(patch, cG)


class ContactKernels:
    """Discrete impulse responses of ``structure`` for one time step and run length, built once.

    ``approach`` (p, steps): g_i, the approach-row displacement at lag i per unit load on each
    patch node; ``outputs`` (q, p, steps): the output rows' (H_i). Any number of coupled runs
    (other impactors, velocities, laws) then reuse them: :meth:`run`. ``threads``: the build's marches run
    at once (:func:`_reciprocal_march`; None: one per row with a band factor, 1: one march, as a caller
    whose cores are already busy may prefer: threads on a busy core cost ≈ 7 % more than one march).
    """

    def __init__(
        self,
        structure: ContactStructure,
        time_step: float,
        steps: int,
        newmark: NewmarkParameters = NewmarkParameters(),
        stepper=None,
        threads: int | None = None,
    ):
        if not (isinstance(steps, (int, np.integer)) and steps >= 1):
            raise InputError(f"steps must be a positive integer, got {steps!r}")
        dt = float(time_step)
        st = stepper or NewmarkStepper(structure.M, structure.K, dt, C=structure.C, params=newmark)
        if not math.isclose(st.dt, dt, rel_tol=1e-12):
            raise InputError(f"stepper time step {st.dt!r} differs from time_step {dt!r}")
        self.structure, self.dt, self.steps, self.newmark = structure, dt, int(steps), st.params
        self.patch = ContactPatch(structure.surface_x, structure.center) if structure.patch is None else structure.patch
        dofs = np.asarray(structure.surface_dofs, int)
        n = st.n
        B = np.zeros((n, dofs.size))
        B[dofs, np.arange(dofs.size)] = float(structure.load_sign)
        rows = np.vstack([np.asarray(structure.approach_row, float)[None, :], np.asarray(structure.outputs, float).reshape(-1, n)])
        if st.dense:  # small models (a bar): the response engine's march, one product a step
            self.engine = ImpulseResponse.reciprocal(st, B, self.steps, rows)
            kernel = self.engine.kernel
        else:
            self.engine = None
            kernel = _reciprocal_march(st, rows, dofs, float(structure.load_sign), self.steps, threads)
            st.nsolve += self.steps * rows.shape[0]  # counted as right-hand sides: one a step per row (the marches' calls are uncounted)
        self.approach = kernel[0]  # (p, steps)
        self.outputs = kernel[1:]  # (q, p, steps)
        self._lagged = np.ascontiguousarray(self.approach.T)  # (steps, p): row i is g_i
        self._compliance = _compliance(self.patch, self._lagged[0])
        self._column = {int(d): i for i, d in enumerate(dofs)}
        self._mapped: tuple | None = None  # (surface DOFs, compliance) of the last smaller structure run
        self._nfft = next_fast_len(2 * self.steps - 1, real=True)  # no wrap-around (ImpulseResponse._spectrum)
        self._Hk = np.fft.rfft(kernel, self._nfft, axis=-1)  # the kernels' spectra: part of the build, not of the first run
        self.solves = st.nsolve

    @property
    def output_names(self) -> tuple[str, ...]:
        return tuple(self.structure.output_names)

    def __getstate__(self):
        """Kernels travel (to a Dask worker) without the engine's factorised stepper, the structure's
        matrices or the mesh: what a run needs, the kernels, their spectra and the patch's tables."""
        state = self.__dict__.copy()
        s = self.structure
        patch = _light(self.patch)
        state.update(
            engine=None,
            structure=SimpleNamespace(
                surface_x=s.surface_x,
                surface_dofs=s.surface_dofs,
                load_sign=s.load_sign,
                center=s.center,
                output_names=s.output_names,
                patch=None if s.patch is None else patch,
            ),
            patch=patch,
            _compliance=None,
            _mapped=None,
            _structures={},
        )
        return state

    def __setstate__(self, state):
        self.__dict__.update(state)
        self._compliance = _compliance(self.patch, self._lagged[0])

    def _contact_spectrum(self, Qr: np.ndarray, start: int, upto: int) -> np.ndarray:
        """The spectrum (1 + q, nfft/2 + 1) of the response of every kernel row (0: the approach row, 1…q: the
        outputs) to the loads of steps ``start`` … ``upto`` (``Qr``: the run's loads, newest first), at their
        place in the run: one transform of the patch nodes the contact loaded (a small contact loads few of
        them), one product with the kernels' cached spectra. Its inverse transform at index m − 1 is
        y_m = Σ_{start ≤ j ≤ upto} K_{m−j}·q_j (:meth:`_response`); the run's outputs are the sum over its contacts."""
        N, nfft = self.steps, self._nfft
        loads = Qr[N - upto : N - start + 1]  # steps upto … start
        used = np.flatnonzero(np.any(loads != 0.0, axis=0))
        if used.size == 0:
            return np.zeros((self._Hk.shape[0], nfft // 2 + 1), complex)
        nodes = slice(used[0], used[-1] + 1)  # the loaded nodes' span (a view of the spectra, not a copy)
        placed = np.zeros((used[-1] + 1 - used[0], nfft))
        placed[:, start - 1 : upto] = loads[::-1, nodes].T  # q_j at index j − 1
        return np.einsum("qpk,pk->qk", self._Hk[:, nodes], np.fft.rfft(placed, axis=-1))

    def _response(self, spectrum: np.ndarray) -> np.ndarray:
        """y (rows, steps + 1) from a response spectrum of :meth:`_contact_spectrum`, y_0 = 0."""
        y = np.zeros((spectrum.shape[0], self.steps + 1))
        y[:, 1:] = np.fft.irfft(spectrum, self._nfft, axis=-1)[:, : self.steps]
        return y

    def compliance_for(self, structure: ContactStructure | None):
        """The patch compliance of ``structure``: the kernels' own (None, or the same surface DOFs), or that
        of a structure on the same matrices whose loadable DOFs are among the kernels' (a smaller impactor's
        contact disc), mapped onto the kernels' columns (its own patch and shares: the run equals its direct run)."""
        if structure is None or structure is self.structure:
            return self._compliance
        dofs = np.asarray(structure.surface_dofs, int)
        if self._mapped is not None and np.array_equal(self._mapped[0], dofs):
            return self._mapped[1]
        own = np.asarray(self.structure.surface_dofs, int)
        if np.array_equal(dofs, own) and structure.patch is None and self.structure.patch is None:
            return self._compliance
        try:
            index = np.array([self._column[int(d)] for d in dofs], int)
        except KeyError:
            raise InputError("structure: its loadable surface DOFs are not all among the kernels' (build kernels for the wider contact)") from None
        patch = ContactPatch(structure.surface_x, structure.center) if structure.patch is None else structure.patch
        comp = _Mapped(_compliance(patch, self._lagged[0][index]), index, dofs.size)
        self._mapped = (dofs, comp)
        return comp

    def run(self, law, mass: float, velocity: float, stop_after: float | None = None, structure: ContactStructure | None = None) -> ImpactHistory:
        """The coupled impact of a rigid impactor (``mass`` [kg], ``velocity`` [m/s] > 0 toward the
        structure) through contact ``law`` (a ContactLaw or HistoryLaw): the histories of
        :func:`softimpact.fem.impact.integrate_impact` for the same structure, step and run length,
        structure energies NaN. ``stop_after``: stop this long [s] after the impactor has left for good.
        ``structure``: the same target struck at the same point with a smaller contact reach (another
        impactor diameter, :meth:`compliance_for`); None: the kernels' own.

        The scalar state is plain Python floats; while apart, the next contact is found by one
        vectorised test of the ballistic impactor against the structure's free response.
        """
        Impactor(mass, 1.0, velocity)  # validates mass and velocity (> 0, toward the structure): the direct path's rule
        dt, N = self.dt, self.steps
        mass, velocity = float(mass), float(velocity)
        if hasattr(law, "for_time_step"):
            law = law.for_time_step(dt)
        beta, gamma = self.newmark.beta, self.newmark.gamma
        comp = self.compliance_for(structure)
        g = self._lagged
        p = g.shape[1]
        hm = beta * dt * dt / mass
        kappa = gamma / (beta * dt)
        r1, r2 = 1.0 - gamma / beta, dt * (1.0 - gamma / (2.0 * beta))
        bdt2 = beta * dt * dt
        c2 = dt * dt * (0.5 - beta)

        F, al, ald, rad, x, xv, cwork, cen = ([0.0] * (N + 1) for _ in range(8))
        Qr = np.zeros((N + 1, p))  # Qr[N − j] = q_j = F_j·s_j: a contact's loads newest first, contiguous
        Qflat, gflat = Qr.ravel(), g.ravel()  # the same, as one run of lags × nodes each (views)
        dot = np.dot
        xv[0] = ald[0] = velocity
        xa = ala = 0.0
        memory = isinstance(law, HistoryLaw)  # (a protocol check: once, not per step)
        state = law.initial_state() if memory else None
        branch = law.branch(state) if memory else law
        # where the law offers them: its memory's free flight in one call, a converged step's state, branch and energy in one
        apart, settle = (getattr(law, "apart", None), getattr(law, "settle", None)) if memory else (None, None)
        load = comp.load
        responds = hasattr(branch, "response")  # (F, ∂F/∂α, ∂F/∂α̇) in one call
        old = [0.0] * (N + 1)  # response to the loads of the earlier contacts
        start = None  # first step of the current contact
        total = None  # the spectrum of the response to the loads of the contacts ended so far
        iterations, last = 0, N
        clock = None if stop_after is None else SeparationClock(stop_after)
        k = 0
        while k < N:
            if start is None and k > 0 and F[k] == 0.0 and al[k] <= 0.0:
                # apart (no force now or before: the impactor flies at constant speed): the next contact is
                # the first step whose predicted approach is positive, found at once; the steps between
                # only carry the scalar recursions of α̇, α̈ (and the law's memory).
                v = xv[k]
                ks = np.arange(k, N)
                pred = x[k] + (ks - k + 1) * (dt * v)
                tgt = pred - np.asarray(old[k + 1 : N + 1])
                hit = np.flatnonzero(tgt > 0.0)
                j = k + int(hit[0]) if hit.size else N
                n = j - k
                tgt = tgt[:n].tolist()
                rates = []
                a_prev, ad = al[k], ald[k]
                for a_new in tgt:  # α̇ and α̈ by Newmark's rules on α (as in contact, below)
                    q = r1 * ad + r2 * ala - kappa * a_prev
                    ala = (a_new - a_prev - dt * ad - c2 * ala) / bdt2
                    ad = kappa * a_new + q
                    rates.append(ad)
                    a_prev = a_new
                x[k + 1 : j + 1] = pred[:n].tolist()
                xv[k + 1 : j + 1] = [v] * n
                al[k + 1 : j + 1] = tgt
                ald[k + 1 : j + 1] = rates
                cwork[k + 1 : j + 1] = [cwork[k]] * n
                if apart is not None:
                    state, cen[k + 1 : j + 1] = apart(state, n)
                    branch = law.branch(state)
                elif memory:
                    for i in range(k + 1, j + 1):
                        cen[i] = branch.energy(al[i])
                        state = law.advance(state, al[i], ald[i])
                        branch = law.branch(state)
                # a law without memory stores nothing while apart (α ≤ 0): cen stays 0
                if clock is not None:
                    for i in range(k + 1, j + 1):
                        if clock.done(i * dt, al[i] < 0.0 and ald[i] < 0.0):
                            last = i
                            break
                if last < N:
                    break
                k = j
                if k >= N:
                    break
            # a law with memory: the branch of the state the last step left (built there, for its energy)
            ak, adk, fk = al[k], ald[k], F[k]
            x_pred = x[k] + dt * xv[k] + c2 * xa
            w_hist = old[k + 1]
            if start is not None:  # the current contact's loads, lags 1 … k + 1 − start: one dot product
                L = k + 1 - start
                w_hist += float(dot(gflat[p : (L + 1) * p], Qflat[(N - k) * p : (N - k + L) * p]))
            target = x_pred - w_hist
            q = r1 * adk + r2 * ala - kappa * ak
            if target <= 0.0:
                a_new, f, r = target, 0.0, 0.0
            elif fk == 0.0 and (branch.response(target, kappa * target + q)[0] if responds else branch.force(target, kappa * target + q)) == 0.0:
                # no force at the bracket's top α̃ (a force clipped to zero, as by the Maxwell arm's negative
                # stress while unloading): R(α̃) = 0 there, the root (R increases with α), without a Newton iteration
                a_new, f, r = target, 0.0, 0.0  # no contact disc where no force presses
            else:
                guess = 2.0 * ak - al[k - 1] if k >= 1 else target
                a_new, f, r, its = newton_contact(branch, comp, hm, kappa, q, target, guess, k + 1, dt, try_top=True)
                iterations += its
            if f != 0.0:
                load(r, f, Qr[N - k - 1])
                if start is None:
                    start = k + 1
            elif start is not None:  # contact ended: the free response to its loads, once
                spectrum = self._contact_spectrum(Qr, start, k)
                total = spectrum if total is None else total + spectrum
                old = (np.asarray(old) + self._response(spectrum[:1])[0]).tolist()
                start = None
            x[k + 1] = x_pred - hm * f
            xa1 = -f / mass
            xv[k + 1] = xv[k] + dt * ((1.0 - gamma) * xa + gamma * xa1)
            ad_new = kappa * a_new + q
            F[k + 1], al[k + 1], rad[k + 1], ald[k + 1] = f, a_new, r, ad_new
            # Newmark's displacement rule on α = x − c·u gives α̈ without the structure's state
            ala = (a_new - ak - dt * adk - c2 * ala) / bdt2
            cwork[k + 1] = cwork[k] + 0.5 * (fk + f) * (a_new - ak)
            if settle is not None:
                state, branch, cen[k + 1] = settle(state, a_new, ad_new)
            elif memory:
                cen[k + 1] = branch.energy(a_new)  # the step's branch: its stress at α_{k+1} is the converged σ_{k+1}
                state = law.advance(state, a_new, ad_new)
                branch = law.branch(state)
            else:
                cen[k + 1] = float(branch.energy(a_new))
            xa = xa1
            k += 1
            # moving apart: the impactor slower than the target point, ẋ < ẇ = ẋ − α̇
            if clock is not None and clock.done(k * dt, f == 0.0 and a_new < 0.0 and ad_new < 0.0):
                last = k
                break
        if start is not None:  # in contact at the end
            spectrum = self._contact_spectrum(Qr, start, N)
            total = spectrum if total is None else total + spectrum
        y = self._response(total) if total is not None else np.zeros((self._Hk.shape[0], N + 1))  # (1 + q, N + 1): approach row, then the outputs
        sl = slice(0, last + 1)
        nan = np.full(last + 1, np.nan)
        t = np.arange(N + 1) * dt

        def arr(v):
            return np.array(v[: last + 1])

        return ImpactHistory(
            time=t[sl],
            force=arr(F),
            approach=arr(al),
            approach_rate=arr(ald),
            contact_radius=arr(rad),
            impactor_displacement=arr(x),
            impactor_velocity=arr(xv),
            target_displacement=y[0, sl],
            outputs=y[1:, sl],
            structure_kinetic=nan,
            structure_strain=nan.copy(),
            structure_work=nan.copy(),
            contact_work=arr(cwork),
            contact_energy=arr(cen),
            surface_mismatch=nan.copy(),
            newton_iterations=iterations,
            solves=0,
        )
