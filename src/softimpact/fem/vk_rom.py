"""A reduced-order von Kármán plate for coupled impact: load-dependent Ritz vectors for the bending, the membrane
condensed statically (exactly, as quadratic modal derivatives), a cubic modal restoring force, and the contact
point's residual static flexibility added, so that a coupled run costs a fraction of a second.

The full model is :class:`softimpact.fem.plate_vk.PlateVK` (its free DOFs split into the bending set b: w, φx, φy
and the membrane set m: u, v). For a laminate without bending–extension coupling (B = 0, a symmetric stack) the
linear stiffness and the mass do not couple the sets, and the membrane strain ε0 = ε_L(u_m) + ε_N(w) enters the
energy as ½∫ε0ᵀ A ε0. The reduction:

1. **Bending basis** Φ (n_b, r): the load-dependent Ritz vectors of the contact point (Wilson, Yuan & Dickens'
   construction, cited from the method's standard name; a Krylov space of K_bb⁻¹ M_bb started at K_bb⁻¹ c, c the approach row), M-orthonormalised and
   turned into the Rayleigh–Ritz modes of the space (Φᵀ M Φ = I, Φᵀ K Φ = Λ diagonal). The first vector is the
   contact point's static deflection: the static correction of the contact load is in the basis.
2. **Membrane, condensed** with the in-plane inertia neglected (in-plane waves are far faster than bending ones):
   for w = Φq the in-plane equilibrium K_mm u_m = −∫B_mᵀ A ε_N(w) is linear in the pairs q_i q_j, so
   u_m = Σ_{i≤j} q_i q_j Ψ_ij with K_mm Ψ_ij = −g_ij, g_ij the membrane nodal forces of the pair's ε_N
   (static modal derivatives of the in-plane field: one solve a pair). This is the exact minimum of the energy
   over u_m for the given w (the energy is quadratic in u_m), so the reduced energy is

       Π(q) = ½ qᵀ Λ q + ½ Σ_{ijkl} Γ_ijkl q_i q_j q_k q_l,   Γ from G = G_N + Gᵀ_g Ψ over the pairs,

   G_N the pairs' ∫ε_Nᵀ A ε_N (the element rule of :class:`~softimpact.fem.plate_vk.PlateVK`), and its gradient
   and Hessian are a cubic force and its tangent (:meth:`PlateVKROM.force`, two products with (r², r²) tables).
   Only the first ``nonlinear`` Krylov vectors (the static deflection under the ball and its first dynamic
   corrections: the stretching is local to the contact as much as global) carry these terms, a = Tq their
   coordinates; the other Ritz coordinates stay linear (their pairs would cost r⁴ a product).
   The coefficients are those of the stiffness evaluation procedure (STEP) and implicit condensation of
   non-intrusive nonlinear reduced models (Muravyov & Rizzi 2003; Hollkamp & Gordon 2008: cited from the methods'
   standard names), here computed from the element integrals rather than fitted to static solves of the full
   model; with the static condensation of the in-plane field they are exact for a flat structure (Vizzaccaro et al.,
   "Non-intrusive reduced order modelling for the dynamics of geometrically nonlinear flat structures using
   three-dimensional finite elements", arXiv:2009.11377, 2020: static condensation and static modal derivatives
   give the converged STEP solution for flat structures).
3. **The contact point kept exact**: the part of the contact disc's static flexibility the basis misses,
   z = K_bb⁻¹ c − Φ Λ⁻¹ Φᵀ c (nodal values on the disc, :class:`~softimpact.fem.impact.PatchCompliance`), is added
   to the approach as a residual compliance (the mode-acceleration idea), and likewise for the outputs (gauge
   strains); zero for the point force the first Ritz vector carries, small for a grown disc.

:class:`ReducedVonKarmanStepper` steps the impactor and the reduced plate as :class:`~softimpact.fem.vk_stepping.VonKarmanStepper`
does the full one: one Newton a step over the modal coordinates (dense r × r) with the contact condensed on each
iteration's linearised plate and solved by the contact Newton's bracket, the :class:`~softimpact.fem.stepping.CoupledStepper`
loop around it. Restricted to laminates without B coupling and
to memoryless contact laws.
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import lu_factor, lu_solve

from ..errors import InputError, SolverFailed
from .direct import structure_history
from .impact import ContactStructure, ImpactHistory, PatchCompliance, newton_contact
from .newmark import NewmarkParameters, spd_factor
from .plate import PHI_X, PHI_Y, U, V, W
from .plate_vk import PlateVK, VonKarmanNewmark
from .stepping import CoupledStepper, check_time_step

__all__ = ["PlateVKROM", "ReducedVonKarmanStepper", "reduced_plate"]

# Defaults from benchmarks/bench_vk_rom.py on the 48 × 48 MITC9 plate at 1500 in/s (w/h 0.7; BENCHMARKS.md): 80 and 24
# put the peak force 1.8 % and the contact time 0.1 % from the full run's at 0.44 s CPU a run; 60 and 16 cost less
# (0.33 s) but miss the contact time by 2.6 %; the error does not fall monotonically with either.
VECTORS = 80  # Ritz vectors (the contact's dynamic compliance converges slowly with them)
NONLINEAR = 24  # the first Krylov vectors (static deflection and its dynamic corrections) that carry the von Kármán terms
CHUNK = 256  # elements per block while the pair integrals are summed (memory: pairs × CHUNK × nq × 3 floats)
INDEPENDENT = 1e-8  # a Krylov vector whose M-norm falls below this fraction after orthogonalisation ends the space


class PlateVKROM:
    """The reduced von Kármán plate (module docstring) of ``vk`` struck along its approach row ``c`` (n,):
    ``vectors`` Ritz vectors; ``C`` the full damping (n, n) or None (projected on the basis).

    Attributes: ``r`` (coordinates), ``basis`` Φ (n, r) over ``vk``'s free DOFs (zero on the membrane set),
    ``lam`` Λ (r,) [1/s²], ``c`` (r,) the approach row on the coordinates, ``residual`` (n,) the static flexibility
    K⁻¹c the basis misses, ``C`` (r, r) or None, ``pairs`` (P, 2) and ``psi`` (n_m, P) the membrane's modal
    derivatives, ``build_seconds``."""

    def __init__(self, vk: PlateVK, c: np.ndarray, vectors: int = VECTORS, nonlinear: int = NONLINEAR, C=None):
        import time

        t0 = time.perf_counter()
        if not isinstance(vk, PlateVK):
            raise InputError("the reduced von Karman plate is built from a PlateVK")
        if vk.coupled:
            raise InputError("the reduced von Karman plate needs a laminate without bending-extension coupling (B = 0): step the full plate")
        if not (isinstance(vectors, (int, np.integer)) and vectors >= 2):
            raise InputError(f"vectors must be an integer of at least 2, got {vectors!r}")
        self.vk, self.n = vk, vk.n
        comp = vk.free % 5  # the plate numbers DOFs 5·node + component
        self.bset = np.flatnonzero(np.isin(comp, (W, PHI_X, PHI_Y)))
        self.mset = np.flatnonzero(np.isin(comp, (U, V)))
        c = np.asarray(c, float)
        Kbb, Mbb = vk.K[self.bset][:, self.bset].tocsc(), vk.M[self.bset][:, self.bset].tocsr()
        Kb = spd_factor(Kbb)
        X = self._ritz(Kb, Mbb, c[self.bset], vectors)
        lam, Y = np.linalg.eigh(X.T @ (Kbb @ X))  # X is M-orthonormal: the Rayleigh–Ritz modes of its span
        phi_b = X @ Y
        self.r = phi_b.shape[1]
        self.lam = lam
        self.basis = np.zeros((self.n, self.r))
        self.basis[self.bset] = phi_b
        self.c = self.basis.T @ c
        zc = np.zeros(self.n)
        zc[self.bset] = Kb.solve(c[self.bset])
        self.residual = zc - self.basis @ (self.c / lam)  # K⁻¹c − ΦΛ⁻¹Φᵀc
        self._Kb = Kb
        self.C = None if C is None else self.basis.T @ (C @ self.basis)
        self.rn = min(int(nonlinear), self.r)
        self.T = Y[: self.rn].copy()  # (rn, r): the first rn Ritz vectors' coordinates a = T q, which carry the von Kármán terms
        self._membrane(X[:, : self.rn])
        self.build_seconds = time.perf_counter() - t0

    @staticmethod
    def _ritz(Kb, Mbb, c: np.ndarray, count: int) -> np.ndarray:
        """Load-dependent Ritz vectors (n_b, ≤ count), M-orthonormal: K⁻¹c, then K⁻¹M of the last, each
        orthogonalised twice against the others (classical Gram–Schmidt in the M inner product)."""
        X = np.zeros((c.size, count))
        x = Kb.solve(c)
        k = 0
        while k < count:
            norm0 = np.sqrt(x @ (Mbb @ x))
            for _ in range(2):
                x = x - X[:, :k] @ (X[:, :k].T @ (Mbb @ x))
            norm = np.sqrt(x @ (Mbb @ x))
            if not norm > INDEPENDENT * norm0:
                break
            X[:, k] = x / norm
            k += 1
            x = Kb.solve(Mbb @ X[:, k - 1])
        return X[:, :k]

    def _membrane(self, phi_b: np.ndarray) -> None:
        """The pairs' membrane forces g, derivatives Ψ and the quartic energy's tables (module docstring)."""
        vk, r = self.vk, phi_b.shape[1]
        I, J = np.triu_indices(r)
        self.pairs = np.stack([I, J], 1)
        half = np.where(I == J, 0.5, 1.0)  # ε_N(Σ q_i w_i) = Σ_{i≤j} q_i q_j e_ij: ½ on the squares
        P = I.size
        full = np.zeros((vk.fe.basis.N, r))
        full[vk.free[self.bset]] = phi_b
        wdofs = vk._gdofs[:, 2]  # (ne, npe): the w DOFs of each element (components U, V, W when B = 0)
        mpos = np.full(vk.fe.basis.N + 1, -1)
        mpos[vk.free[self.mset]] = np.arange(self.mset.size)
        A = vk._A
        ne = wdofs.shape[0]
        g = np.zeros((self.mset.size, P))
        GN = np.zeros((P, P))
        for e0 in range(0, ne, CHUNK):
            sl = slice(e0, min(ne, e0 + CHUNK))
            Dx, Dy, wq = vk._Dx[sl], vk._Dy[sl], vk._wq[sl]
            we = full[wdofs[sl]]  # (nc, npe, r)
            wx, wy = np.einsum("eqp,epr->eqr", Dx, we), np.einsum("eqp,epr->eqr", Dy, we)
            e = np.stack([wx[..., I] * wx[..., J], wy[..., I] * wy[..., J], wx[..., I] * wy[..., J] + wx[..., J] * wy[..., I]], -1) * half[:, None]
            Ae = (e @ A.T) * wq[..., None, None]  # (nc, nq, P, 3): A ε_N of each pair, weighted
            GN += np.einsum("eqpi,eqsi->ps", e, Ae, optimize=True)
            fu = np.einsum("eqn,eqp->enp", Dx, Ae[..., 0]) + np.einsum("eqn,eqp->enp", Dy, Ae[..., 2])
            fv = np.einsum("eqn,eqp->enp", Dy, Ae[..., 1]) + np.einsum("eqn,eqp->enp", Dx, Ae[..., 2])
            for f, dofs in ((fu, vk._gdofs[sl, 0]), (fv, vk._gdofs[sl, 1])):
                rows = mpos[dofs.ravel()]
                keep = rows >= 0
                np.add.at(g, rows[keep], f.reshape(-1, P)[keep])
        Kmm = vk.K[self.mset][:, self.mset].tocsc()
        self.psi = -spd_factor(Kmm).solve(g).reshape(self.mset.size, P)
        G = GN + g.T @ self.psi  # ½ sᵀ G s: the condensed membrane energy of the pairs s = (q_i q_j)
        pidx = np.zeros((r, r), int)
        pidx[I, J] = pidx[J, I] = np.arange(P)
        h = np.where(np.eye(r, dtype=bool), 1.0, 0.5)  # Σ_ij q_i q_j e'_ij with e'_ij = e_ij/2 off the diagonal
        gamma = h[:, :, None, None] * h[None, None] * G[pidx[:, :, None, None], pidx[None, None]]
        self._g1 = gamma.reshape(r * r, r * r)  # Γ_(ab)(kl)
        self._G, self._gp = G, np.where(I == J, 1.0, 0.5)[:, None] * G  # N over the pairs: N_(ab) = Σ_(k≤l) h_ab G a_k a_l
        self._g2 = gamma.transpose(0, 2, 1, 3).reshape(r * r, r * r)  # Γ_(ab)(jl) = Γ_ajbl

    # ---- the reduced model ----------------------------------------------------------------
    def nonlinear_force(self, q: np.ndarray) -> np.ndarray:
        """∂Π/∂q − Λq (r,): on a = Tq, 2 N(a) a with N_ab = Σ Γ_abkl a_k a_l, carried to q by Tᵀ (module docstring)."""
        a = self.T @ q
        I, J = self.pairs[:, 0], self.pairs[:, 1]
        N = np.empty((self.rn, self.rn))
        N[I, J] = N[J, I] = self._gp @ (a[I] * a[J])  # the symmetric N from its pairs (a quarter of the r⁴ product)
        return self.T.T @ (2.0 * (N @ a))

    def nonlinear_tangent(self, q: np.ndarray) -> np.ndarray:
        """The Jacobian of :meth:`nonlinear_force` (r, r): Tᵀ(2N + 4 Σ_jl Γ_ajbl a_j a_l)T."""
        rn, T = self.rn, self.T
        a = T @ q
        A = np.outer(a, a).ravel()
        return T.T @ ((2.0 * (self._g1 @ A) + 4.0 * (self._g2 @ A)).reshape(rn, rn) @ T)

    def force(self, q: np.ndarray) -> np.ndarray:
        """∂Π/∂q (r,)."""
        return self.lam * q + self.nonlinear_force(q)

    def tangent(self, q: np.ndarray) -> np.ndarray:
        """∂²Π/∂q², dense (r, r)."""
        return np.diag(self.lam) + self.nonlinear_tangent(q)

    def energy(self, q: np.ndarray) -> float:
        """Π(q) [J]: the strain energy of the plate at d(q) (:meth:`expand`)."""
        sp = self.products(q)
        return 0.5 * float(self.lam @ (q * q)) + 0.5 * float(sp @ (self._G @ sp))

    def expand(self, q: np.ndarray) -> np.ndarray:
        """The plate's displacement d(q) over ``vk``'s free DOFs: Φq on the bending set, Σ q_i q_j Ψ_ij on the membrane set."""
        d = self.basis @ q
        d[self.mset] = self.psi @ self.products(q)
        return d

    def products(self, q: np.ndarray) -> np.ndarray:
        """The pairs a_i a_j, i ≤ j < rn, of a = Tq (P,)."""
        a = self.T @ q
        return a[self.pairs[:, 0]] * a[self.pairs[:, 1]]

    def outputs(self, O: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Rows ``O`` (k, n) of the full plate seen on the coordinates: (O Φ (k, r), O_m Ψ (k, P), the static
        flexibility of the rows the basis misses, K⁻¹O_bᵀ − ΦΛ⁻¹ΦᵀOᵀ (n, k))."""
        O = np.atleast_2d(np.asarray(O, float))
        lin = O @ self.basis
        Ob = O[:, self.bset]
        z = np.zeros((self.n, O.shape[0]))
        if O.shape[0]:
            z[self.bset] = self._Kb.solve(Ob.T.copy()).reshape(self.bset.size, O.shape[0])
        return lin, O[:, self.mset] @ self.psi, z - self.basis @ (lin.T / self.lam[:, None])


def reduced_plate(engine, approach_row: np.ndarray, vectors: int = VECTORS, nonlinear: int = NONLINEAR) -> PlateVKROM:
    """The reduced plate of a von Kármán plate's stepper ``engine`` (its :class:`~softimpact.fem.plate_vk.VonKarmanNewmark`,
    a model's ``stepper``) struck along ``approach_row`` (n,), the stepper's damping projected: what
    :class:`ReducedVonKarmanStepper` builds for one run, built here once for every run of that plate and impact point (the
    approach row is the point's, whatever the ball). An InputError for any other stepper (a linear structure's, a
    large-deflection beam's) or a laminate with bending-extension coupling."""
    if not (isinstance(engine, VonKarmanNewmark) and isinstance(engine.model, PlateVK)):
        raise InputError("the reduced von Karman model needs a plate with von Karman kinematics (its VonKarmanNewmark stepper)")
    return PlateVKROM(engine.model, approach_row, vectors, nonlinear, C=engine.C)


class _CondensedCompliance:
    """h(r) = c·z + h_res(r): the reduced plate's compliance to a unit force over the iteration's disc (fixed for the
    iteration) plus the disc's residual flexibility (:class:`~softimpact.fem.impact.PatchCompliance`)."""

    value = None

    def __init__(self, modal: float, residual: PatchCompliance):
        self.modal, self.residual, self.half_spacing = modal, residual, residual.half_spacing

    def __call__(self, r: float) -> tuple[float, float]:
        h, dh = self.residual(r)
        return self.modal + h, dh


class ReducedVonKarmanStepper(CoupledStepper):
    """:class:`CoupledStepper` of a von Kármán plate on its reduced model ``engine`` (a :class:`PlateVKROM`, built once
    and reused by every run of the plate and impact point; or the full plate's
    :class:`~softimpact.fem.plate_vk.VonKarmanNewmark`, whose reduced plate is then built here, for this run; module
    docstring): ``structure`` the full plate's :class:`ContactStructure` (its disc, approach row and outputs);
    ``energy``: the reduced plate's kinetic and strain energies (the residual flexibility's ½h F² included; the
    in-plane kinetic energy neglected); ``snapshots``: step indices at which to keep d(q) over the free DOFs.
    ``rtol``: the step's Newton tolerance on the residual (of the forces in balance)."""

    def __init__(
        self,
        structure: ContactStructure,
        law,
        mass: float,
        velocity: float,
        time_step: float,
        steps: int,
        newmark: NewmarkParameters = NewmarkParameters(),
        *,
        engine: PlateVKROM | VonKarmanNewmark | None = None,
        stop_after: float | None = None,
        energy: bool = True,
        snapshots=(),
        rtol: float = 1e-9,
        max_iterations: int = 30,
    ):
        super().__init__(law, mass, velocity, time_step, steps, stop_after)
        if isinstance(engine, VonKarmanNewmark):  # the full plate's stepper (run_impact's engine): its reduced plate, built here
            check_time_step(engine.dt, self.dt)
            engine = reduced_plate(engine, structure.approach_row)
        if not isinstance(engine, PlateVKROM):
            raise InputError("the reduced von Karman stepper needs the plate's PlateVKROM (or its VonKarmanNewmark) as its engine")
        if self.memory:
            raise InputError(f"a contact law with memory ({type(law).__name__}) on the reduced von Karman plate is not implemented: use a memoryless law")
        if structure.patch is None:
            raise InputError("the reduced von Karman stepper loads a plate's contact disc: the structure has no patch")
        if structure.M.shape[0] != engine.n:
            raise InputError(f"the reduced plate was built for {engine.n} DOFs, the structure has {structure.M.shape[0]}")
        if not np.allclose(engine.basis.T @ np.asarray(structure.approach_row, float), engine.c, rtol=1e-12, atol=0.0):
            raise InputError("the reduced plate was built for another impact point (its approach row differs)")
        self.rom, self.params, self.energy = engine, newmark, energy
        self.rtol, self.max_iterations = rtol, max_iterations
        rom, dt, b, g = engine, self.dt, newmark.beta, newmark.gamma
        self.a0, self.a1, self.a2, self.a3 = 1.0 / (b * dt * dt), g / (b * dt), 1.0 / (b * dt), 1.0 / (2.0 * b) - 1.0
        self.dofs = np.asarray(structure.surface_dofs, int)
        self.sign = float(structure.load_sign)
        self.patch = structure.patch
        self.cr = rom.c
        self.Bs = rom.basis[self.dofs]  # (p, r): the disc's nodal loads on the coordinates
        self._keff = np.diag(rom.lam + self.a0) + (0.0 if rom.C is None else self.a1 * rom.C)
        Cfull = structure.C
        if (Cfull is None) != (rom.C is None):
            raise InputError("the reduced plate's damping and the structure's differ (build the PlateVKROM with the structure's C)")
        self.extra_h = PatchCompliance(self.patch, self.sign * rom.residual[self.dofs])  # the residual flexibility of the disc
        # the loop's compliance: any positive one (as the full plate's stepper): the reduced plate's effective one plus the residual
        zr = np.linalg.solve(self._keff, self.cr)
        self.compliance = PatchCompliance(self.patch, self.sign * (rom.basis[self.dofs] @ zr + rom.residual[self.dofs]))
        self.O_lin, self.O_pair, zo = rom.outputs(structure.outputs)
        self.O_res = self.sign * zo[self.dofs]  # (p, k): outputs per unit load on each disc node, the part the basis misses
        self._keep_snapshots(snapshots, rom.n)
        self.structure_iterations = 0

    def _begin(self) -> None:
        super()._begin()
        r = self.rom.r
        self._structure_records(self.O_lin.shape[0])
        self.q, self.qv, self.qa = np.zeros(r), np.zeros(r), np.zeros(r)
        self.g_prev, self.rho_prev = np.zeros(r), 0.0
        self._ala = 0.0
        self.structure_iterations = 0

    def _contact(self, q: np.ndarray, x_pred: float, qq: float, index: int):
        """(α, F, r, h) of the impactor against the reduced plate held at ``q`` (zero force where apart), h the disc's
        residual compliance at r."""
        top = x_pred - float(self.cr @ q)
        if top <= 0.0:
            return top, 0.0, 0.0, 0.0
        a, f, r, _ = newton_contact(self.law, self.extra_h, self.hm, self.kappa, qq, top, top, index, self.dt, caps=self.caps)
        if f <= 0.0:
            return a, 0.0, 0.0, 0.0
        return a, f, r, self.extra_h(r)[0]

    def _condensed_force(self, free: np.ndarray, z: np.ndarray, x_pred: float, qq: float, guess: float, index: int) -> float:
        """F' of α = x̃ − β·dt²·F'/m − c·(free + F'·z) − h_res(r)·F', F' = P(α, κα + q): the contact Newton against the
        reduced plate's compliance c·z over this iteration's disc plus the residual flexibility the basis misses."""
        top = x_pred - float(self.cr @ free)
        if top <= 0.0:
            return 0.0
        comp = _CondensedCompliance(max(float(self.cr @ z), 0.0), self.extra_h)
        _, f, _, _ = newton_contact(self.law, comp, self.hm, self.kappa, qq, top, min(guess, top), index, self.dt, caps=self.caps)
        return f

    def free_approach(self, k: int) -> float:
        """The coupled step to k + 1 (one Newton over q and the contact); w̃ = c·q* + h(r*)F* − h_s(r*)F*."""
        dt, b = self.dt, self.params.beta
        x_pred = self.x[k] + dt * self.xv[k] + self.c2 * (-self.F[k] / self.mass)
        qq = self.r1 * self.ald[k] + self.r2 * self._ala - self.kappa * self.al[k]
        q, v, a, rom, C = self.q, self.qv, self.qa, self.rom, self.rom.C
        q1 = q + dt * v + dt * dt * (0.5 - b) * a
        p = self.a0 * q + self.a2 * v + self.a3 * a
        if C is not None:
            gm = self.params.gamma
            p = p - C @ (v + dt * (1 - gm) * a - dt * gm * (self.a0 * q + self.a2 * v + self.a3 * a))
        scale = max(np.linalg.norm(p), 1e-300)
        lu, last, guess, best = None, np.inf, x_pred, None
        for it in range(1, self.max_iterations + 1):
            a_c, f, r, h = self._contact(q1, x_pred, qq, k + 1)
            res = p - self._keff @ q1 - rom.nonlinear_force(q1)
            br = self.sign * (self.patch.shares(r)[0] @ self.Bs)  # a unit force over the disc (the nearest node where apart)
            if f > 0.0:
                res += f * br
                guess = a_c
            norm = np.linalg.norm(res)
            if it == 1:
                scale = max(scale, norm)
            elif norm <= self.rtol * scale:
                break
            if best is not None and norm > best[1] and it < self.max_iterations:
                # The residual rose past the best iterate's: a step across a kink of the contact law (its strength's ramp,
                # a crush that stops) can make full steps cycle between two iterates. Backtrack: half the step from the best.
                q1 = 0.5 * (best[0] + q1)
                continue
            best = (q1, norm)
            # The von Kármán terms' Jacobian at the step's first iterate, factored and kept while the residual falls
            # fast (a step moves it little); refreshed at the current iterate when it does not (large deflection).
            if lu is None or norm > 0.5 * last:
                lu = lu_factor(self._keff + rom.nonlinear_tangent(q1), check_finite=False)
            last = norm
            # The contact condensed on the linearised plate, as the full plate's step does: q = free + F'·z, F' the root of
            # the contact law against the compliance c·z plus the disc's residual one (the contact Newton's bracket: a
            # crush that stops, whose force falls steeply to zero, does not make the iterations cycle).
            z = lu_solve(lu, br, check_finite=False)
            free = q1 + lu_solve(lu, res, check_finite=False) - f * z
            q1 = free + self._condensed_force(free, z, x_pred, qq, guess, k + 1) * z
        else:
            raise SolverFailed(
                f"the reduced von Karman plate's Newton iteration did not converge at t = {(k + 1) * dt:.6g} s (step {k + 1}) in "
                f"{self.max_iterations} iterations (residual {norm / scale:.3g} of its scale): step the full plate (nonlinear_stepping "
                f"'von-karman') or a smaller time step"
            )
        self.structure_iterations += it - 1  # (f, r, h: the contact at the converged q1, from its last evaluation)
        a1 = self.a0 * (q1 - q) - self.a2 * v - self.a3 * a
        v1 = v + dt * ((1 - self.params.gamma) * a + self.params.gamma * a1)
        self._step = (q1, v1, a1, f, r, h)
        return float(self.cr @ q1) + (h * f - self.compliance(r)[0] * f if f > 0.0 else 0.0)

    def apply(self, k: int, f: float, r: float) -> None:
        """The coupled step's state at k + 1 (the loop's f agrees with F* to the contact Newton's tolerance)."""
        q1, v1, a1, f_star, r_star, h = self._step
        k1, rom = k + 1, self.rom
        s = self.patch.shares(r_star)[0] if f_star > 0.0 else np.zeros(self.dofs.size)
        rho = h * f_star  # the residual static deflection under the disc
        self.w[k1] = float(self.cr @ q1) + rho
        self.y[:, k1] = self.O_lin @ q1 + self.O_pair @ rom.products(q1) + f_star * (s @ self.O_res)
        g = f_star * self.sign * (s @ self.Bs)
        dw = 0.5 * (g + self.g_prev) @ (q1 - self.q) + 0.5 * (self.F[k] + f) * (rho - self.rho_prev)
        self.work[k1] = self.work[k] + dw
        self.mism[k1] = self.mism[k] + dw - 0.5 * (self.F[k] + f) * (self.w[k1] - self.w[k])
        if self.energy:
            self.ek[k1] = 0.5 * float(v1 @ v1)
            self.es[k1] = rom.energy(q1) + 0.5 * h * f_star * f_star
        self.q, self.qv, self.qa, self.g_prev, self.rho_prev = q1, v1, a1, g, rho
        if k1 in self.slot:
            self.saved[:, self.slot[k1]] = rom.expand(q1)

    def approach_acceleration(self, k: int, a_new: float, impactor_acceleration: float) -> float:
        """α̈_{k+1} by Newmark's rule on α (the base loop's), kept for the next coupled step."""
        self._ala = super().approach_acceleration(k, a_new, impactor_acceleration)
        return self._ala

    def history(self, last: int) -> ImpactHistory:
        return structure_history(self, last, self.structure_iterations)
