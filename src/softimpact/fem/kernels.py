"""Contact kernels: coupled impact on a linear structure as a Volterra problem.

A linear structure at rest, stepped by Newmark, answers a history of contact-patch
loads q_j = F_j·s(a_j) (p nodal shares, :mod:`softimpact.fem.impact`) with the
discrete convolution

    w_k = Σ_{j=1..k} g_{k−j}·q_j,      y_k = Σ_{j=1..k} H_{k−j}·q_j,

where w is the approach row's displacement (the mid-surface under the impactor),
y the outputs (gauge strains), and g_i (p,), H_i (q, p) the structure's discrete
impulse responses at lag i (:class:`softimpact.fem.response.ImpulseResponse`,
computed once by reciprocity: 1 + q right-hand sides a step). g_0 is the
direct stepper's c·G. A coupled run (:class:`softimpact.fem.kernel_stepping.KernelStepper`, one implementation
of the coupled loop :class:`softimpact.fem.stepping.CoupledStepper`) then steps only the scalar contact
equation of :func:`softimpact.fem.impact.integrate_impact`,

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
where the law offers it (:class:`softimpact.models.protocols.SettlingLaw`, e.g.
:class:`softimpact.models.contact_laws.ViscoelasticSoftLaw`).

A smaller impactor (a smaller contact reach, its loadable nodes among the kernels') runs on the same
kernels with its own patch (:meth:`ContactKernels.compliance_for`); the kernels know the widest reach they
were built for and keep the last smaller impactor's structure (:meth:`ContactKernels.structure_for`). Kernels pickle without the
factorised stepper and the mesh (to a Dask worker).

The structure's own energies (kinetic, strain, the work on the patch nodes) need
its state and are not computed here (NaN); the impactor's energy and the contact
work are.
"""

from __future__ import annotations

import copy
from concurrent.futures import ThreadPoolExecutor
from types import SimpleNamespace

import numpy as np
from scipy.fft import next_fast_len

from ..errors import InputError
from .compliance import MappedCompliance
from .compliance import compliance as _compliance
from .impact import ContactPatch, ContactStructure, ImpactHistory
from .newmark import NewmarkParameters, NewmarkStepper
from .response import ImpulseResponse
from .stepping import check_time_step

__all__ = ["ContactKernels"]

MARCH_THREADS = 16  # the kernel build's marches run at once, one per kernel row up to this many (_reciprocal_march)


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


class ContactKernels:
    """Discrete impulse responses of ``structure`` for one time step and run length, built once.

    ``approach`` (p, steps): g_i, the approach-row displacement at lag i per unit load on each
    patch node; ``outputs`` (q, p, steps): the output rows' (H_i). Any number of coupled runs
    (other impactors, velocities, laws) then reuse them: :meth:`run`. ``threads``: the build's marches run
    at once (:func:`_reciprocal_march`; None: one per row with a band factor, 1: one march, as a caller
    whose cores are already busy may prefer: threads on a busy core cost ≈ 7 % more than one march).
    ``reach``: the widest contact [m] the structure loads (its ``contact_structure(point, reach)``), so that
    a smaller impactor's structure can be told from the kernels' own (:meth:`structure_for`).
    """

    def __init__(
        self,
        structure: ContactStructure,
        time_step: float,
        steps: int,
        newmark: NewmarkParameters = NewmarkParameters(),
        stepper=None,
        threads: int | None = None,
        *,
        reach: float | None = None,
    ):
        if not (isinstance(steps, (int, np.integer)) and steps >= 1):
            raise InputError(f"steps must be a positive integer, got {steps!r}")
        dt = float(time_step)
        st = stepper or NewmarkStepper(structure.M, structure.K, dt, C=structure.C, params=newmark)
        check_time_step(st.dt, dt)
        self.structure, self.dt, self.steps, self.newmark = structure, dt, int(steps), st.params
        self.reach = reach  # the widest contact [m] ``structure`` loads (None: not given): smaller impactors run on them too
        self._structures: dict = {}  # {reach: structure} of the last smaller impactor (:meth:`structure_for`)
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

    @property
    def lagged(self) -> np.ndarray:
        """(steps, p): row i is g_i, the approach row's response at lag i per unit load on each patch node."""
        return self._lagged

    def structure_for(self, reach: float, build) -> ContactStructure:
        """The contact structure of an impactor whose contact reaches ``reach`` [m] on the kernels' target: the
        kernels' own at their :attr:`reach`, else ``build(reach)`` (the model's ``contact_structure`` at the
        impact point; its loadable nodes must be among the kernels', :meth:`compliance_for`), kept for the next
        run of that reach (the last one only: a sweep of diameters builds each once in turn)."""
        if reach == self.reach:
            return self.structure
        if reach not in self._structures:
            self._structures = {reach: build(reach)}
        return self._structures[reach]

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

    def contact_spectrum(self, Qr: np.ndarray, start: int, upto: int) -> np.ndarray:
        """The spectrum (1 + q, nfft/2 + 1) of the response of every kernel row (0: the approach row, 1…q: the
        outputs) to the loads of steps ``start`` … ``upto`` (``Qr``: the run's loads, newest first), at their
        place in the run: one transform of the patch nodes the contact loaded (a small contact loads few of
        them), one product with the kernels' cached spectra. Its inverse transform at index m − 1 is
        y_m = Σ_{start ≤ j ≤ upto} K_{m−j}·q_j (:meth:`response`); the run's outputs are the sum over its contacts."""
        N, nfft = self.steps, self._nfft
        loads = Qr[N - upto : N - start + 1]  # steps upto … start
        used = np.flatnonzero(np.any(loads != 0.0, axis=0))
        if used.size == 0:
            return np.zeros((self._Hk.shape[0], nfft // 2 + 1), complex)
        nodes = slice(used[0], used[-1] + 1)  # the loaded nodes' span (a view of the spectra, not a copy)
        placed = np.zeros((used[-1] + 1 - used[0], nfft))
        placed[:, start - 1 : upto] = loads[::-1, nodes].T  # q_j at index j − 1
        return np.einsum("qpk,pk->qk", self._Hk[:, nodes], np.fft.rfft(placed, axis=-1))

    def response(self, spectrum: np.ndarray | None) -> np.ndarray:
        """y (rows, steps + 1) from a response spectrum of :meth:`contact_spectrum`, y_0 = 0 (None: no load,
        every kernel row's response zero)."""
        if spectrum is None:
            return np.zeros((self._Hk.shape[0], self.steps + 1))
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
        comp = MappedCompliance(_compliance(patch, self._lagged[0][index]), index, dofs.size)
        self._mapped = (dofs, comp)
        return comp

    def run(self, law, mass: float, velocity: float, stop_after: float | None = None, structure: ContactStructure | None = None) -> ImpactHistory:
        """The coupled impact of a rigid impactor (``mass`` [kg], ``velocity`` [m/s] > 0 toward the
        structure) through contact ``law`` (a ContactLaw or HistoryLaw): the histories of
        :func:`softimpact.fem.impact.integrate_impact` for the same structure, step and run length,
        structure energies NaN (:class:`softimpact.fem.kernel_stepping.KernelStepper`). ``stop_after``: stop
        this long [s] after the impactor has left for good. ``structure``: the same target struck at the same
        point with a smaller contact reach (another impactor diameter, :meth:`compliance_for`); None: the
        kernels' own."""
        from .kernel_stepping import KernelStepper  # (it builds on this module: imported here, not above)

        stepper = KernelStepper(structure, law, mass, velocity, self.dt, self.steps, self.newmark, engine=self, stop_after=stop_after)
        return stepper.run()
