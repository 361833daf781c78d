"""Transverse soft impact of a cantilevered laminated beam (paper Figs 16–22).

The laminate is homogenised (smeared) or kept ply group by ply group (layered),
meshed with four-node plane elements, loaded on its top face by the force
history spread over the contact patch of eqs (8)–(14), and integrated by
Newmark average acceleration. Gauges read the axial strain averaged over their
length on the top or bottom face.

The model is linear and time-invariant, so :class:`BeamModel` offers two ways to
the same strains: ``direct`` stepping (all DOFs, energies, deformed shapes) and
``respond`` through the response engine (impulse responses at the gauges,
computed once by reciprocity; milliseconds per force history).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from ..fem.loads import PatchLoad
from ..fem.newmark import NewmarkStepper, SolverSpec
from ..fem.plane import PlaneBeam, PlaneModel
from ..fem.response import ImpulseResponse
from ..models.laminate import Stack, engineering_constants, plane_matrix
from ..models.materials import Material
from ..units import INCH

__all__ = ["LAMINATE_MODELS", "BeamGauge", "BeamSpec", "BeamLoad", "BeamProblem", "BeamModel", "BeamResult", "isotropic_matrix"]

MIN_STEPS_PER_RISE = 4  # a pulse rising in fewer time steps than this is not resolved
LAMINATE_MODELS = ("smeared", "layered")  # homogenised through the thickness, or ply group by ply group


@dataclass(frozen=True)
class BeamGauge:
    """A strain gauge: centre [m] from the support at x = 0, face, length [m]."""

    name: str
    position: float
    surface: str = "bottom"
    length: float = 0.031 * INCH


@dataclass(frozen=True)
class BeamSpec:
    """The beam: free length [m] (support at x = 0), width [m], mesh, support, and
    either a laminate (``stack``, ``model`` smeared|layered) or an isotropic
    ``material`` with a ``thickness``."""

    length: float
    width: float
    nx: int = 200
    nz: int = 6
    support: str = "clamped-free"
    stack: Stack | None = None
    model: str = "smeared"
    material: Material | None = None
    material_thickness: float = 0.0
    plane: str = "strain"
    lumped: bool = False
    damping: tuple[float, float] = (0.0, 0.0)  # Rayleigh α [1/s], β [s]: C = αM + βK

    def __post_init__(self):
        if (self.stack is None) == (self.material is None):
            raise InputError("give exactly one of a laminate (stack) and an isotropic material", "stack")
        if self.model not in LAMINATE_MODELS:
            raise InputError(f"model: {self.model!r} is not one of {', '.join(LAMINATE_MODELS)}", "model")

    @property
    def thickness(self) -> float:
        return self.stack.thickness if self.stack is not None else self.material_thickness

    @property
    def density(self) -> float:
        return self.stack.ply.density if self.stack is not None else self.material.density

    def layer_matrices(self) -> tuple:
        """D of each element layer (bottom first), or one D for all."""
        if self.material is not None:
            return (isotropic_matrix(self.material, self.plane),)
        if self.model == "smeared":
            return (plane_matrix(self.stack.effective(), self.plane),)
        h, nz = self.thickness, self.nz
        return tuple(plane_matrix(self.stack.layer_stiffness(j * h / nz, (j + 1) * h / nz), self.plane) for j in range(nz))

    def plane_beam(self) -> PlaneBeam:
        return PlaneBeam(self.length, self.thickness, self.width, self.nx, self.nz, self.layer_matrices(), self.density, self.support, self.lumped)


def isotropic_matrix(m: Material, plane: str = "strain") -> np.ndarray:
    """D of an isotropic material in plane strain or plane stress."""
    E, nu = m.youngs_modulus, m.poisson_ratio
    G = E / (2 * (1 + nu))
    if plane == "strain":
        lam = E * nu / ((1 + nu) * (1 - 2 * nu))
        return np.array([[lam + 2 * G, lam, 0], [lam, lam + 2 * G, 0], [0, 0, G]])
    c = E / (1 - nu**2)
    return np.array([[c, c * nu, 0], [c * nu, c, 0], [0, 0, G]])


@dataclass(frozen=True)
class BeamLoad:
    """Impact point [m] on the top face, contact radius r0 [m], and the force history (a pulse)."""

    position: float
    contact_radius: float
    history: object


@dataclass(frozen=True)
class BeamProblem:
    """Everything that defines a beam run (SI); checks that the load, gauges and time step fit."""

    beam: BeamSpec
    load: BeamLoad
    solver: SolverSpec
    gauges: tuple[BeamGauge, ...]
    title: str = ""
    units: str = "in-lbf-s"

    def __post_init__(self):
        L = self.beam.length
        if not 0 < self.load.position < L:
            raise InputError(f"load position {self.load.position!r} m is not on the beam (0 to {L!r} m)", "position")
        for g in self.gauges:
            if not (0 <= g.position - g.length / 2 and g.position + g.length / 2 <= L):
                raise InputError(f"gauge {g.name!r}: position {g.position!r} m puts the gauge off the beam (0 to {L!r} m)", "gauges")
        rise = getattr(self.load.history, "time_of_peak", None)
        if rise is not None and rise < MIN_STEPS_PER_RISE * self.solver.time_step:
            raise InputError(
                f"time step {self.solver.time_step!r} s cannot resolve a pulse rising in {rise!r} s (need at most time_of_peak/{MIN_STEPS_PER_RISE})",
                "time_step",
            )


OUTPUTS = ("all", "strain")  # what a BeamModel observes (BeamModel's ``outputs``)


@dataclass(frozen=True)
class BeamResult:
    """Histories (time on the last axis) of a beam run."""

    problem: BeamProblem
    time: np.ndarray
    force: np.ndarray
    strain: np.ndarray  # (n_gauges, n): each gauge on its own face
    bending: np.ndarray  # (n_gauges, n): (ε_face − ε_opposite)/2
    deflection: np.ndarray  # (n,) m, z-displacement of the top face under the impact point (up +)
    displacement: np.ndarray | None = None  # (n_dofs, n) view, reduced DOFs, direct stepping only
    energy: dict = field(default_factory=dict)  # kinetic, strain, work [J] at the steps energy["step"], direct stepping only


class BeamModel:
    """Assembled beam with its stepper, patch and output rows, for one (mesh, dt)."""

    def __init__(self, problem: BeamProblem, patch_radius: float | None = None, outputs: str = "all"):
        """``patch_radius``: the widest contact radius the model must load (for fits of r0).
        ``outputs``: "all" (gauge strains, bending strains, deflection under the load) or
        "strain" (the gauge strains only: the response engine then costs one right-hand
        side per gauge instead of two per gauge and one; bending and deflection are NaN)."""
        if outputs not in OUTPUTS:
            raise InputError(f"outputs: {outputs!r} is not one of {', '.join(OUTPUTS)}", "outputs")
        self.problem, self.outputs = problem, outputs
        self.plane = PlaneModel(problem.beam.plane_beam())
        pm = self.plane
        M, K = pm.M, pm.K
        a, b = problem.beam.damping
        C = None if a == 0 and b == 0 else a * M + b * K
        self.stepper = NewmarkStepper(M, K, problem.solver.time_step, C=C, params=problem.solver.newmark)
        top_x = pm.node_x[pm.top_nodes]
        self.patch = PatchLoad(top_x, problem.load.position, patch_radius or problem.load.contact_radius)
        # Patch loads push the top face down (−z).
        self.load_dofs = np.array([pm.dof(node, 1) for node in pm.top_nodes[self.patch.nodes]])
        self.B = np.zeros((pm.n, self.load_dofs.size))
        self.B[self.load_dofs, np.arange(self.load_dofs.size)] = -1.0
        rows = []
        for g in problem.gauges:
            other = "top" if g.surface == "bottom" else "bottom"
            rows.append(pm.surface_strain(g.position, g.surface, g.length))
            if outputs == "all":
                rows.append(pm.surface_strain(g.position, other, g.length))
        if outputs == "all":
            rows.append(pm.displacement(problem.load.position, "top", 1))
        self.O = np.array(rows) if rows else np.zeros((0, pm.n))
        self._engine = None

    @property
    def steps(self) -> int:
        return self.problem.solver.steps

    def nodal_loads(self, force: np.ndarray, radius: float | None = None) -> np.ndarray:
        """Patch loads (p, n_t) for a force history sampled at the solver's times (r0 = ``radius``
        or the problem's contact radius)."""
        return self.patch.forces(force, self.problem.load.contact_radius if radius is None else radius)

    def gauge_rows(self) -> np.ndarray:
        """Indices of the gauge strain rows among the model's outputs (and the engine's kernel)."""
        ng = len(self.problem.gauges)
        return np.arange(ng) if self.outputs == "strain" else 2 * np.arange(ng)

    def _split(self, y: np.ndarray):
        ng = len(self.problem.gauges)
        if self.outputs == "strain":
            nan = np.full(y.shape[1:], np.nan)
            return y, np.full(y.shape, np.nan), nan
        face, other = y[0 : 2 * ng : 2], y[1 : 2 * ng : 2]
        return face, 0.5 * (face - other), y[2 * ng]

    def engine(self) -> ImpulseResponse:
        """The response engine (impulse responses of the outputs to each patch node), built once."""
        if self._engine is None:
            self._engine = ImpulseResponse.reciprocal(self.stepper, self.B, self.steps, self.O)
        return self._engine

    def force_samples(self, history=None) -> np.ndarray:
        h = self.problem.load.history if history is None else history
        return np.asarray(h(self.problem.solver.times()) if callable(h) else h, float)

    def respond(self, history=None, radius: float | None = None) -> BeamResult:
        """Gauge strains for a force history through the response engine."""
        F = self.force_samples(history)
        if F[0] != 0.0:
            raise InputError("the force must be zero at first contact (t = 0)", "history")
        y = self.engine().respond(self.nodal_loads(F, radius))
        strain, bending, defl = self._split(y)
        return BeamResult(self.problem, self.problem.solver.times(), F, strain, bending, defl)

    def direct(
        self, history=None, progress=None, energy: bool = True, displacement: bool = True, energy_samples: int = 200, radius: float | None = None
    ) -> BeamResult:
        """Direct Newmark stepping of all DOFs; with ``energy``, the energy balance;
        with ``displacement``, the whole displacement history (for deformed shapes:
        n_dofs × n_steps floats; without it only the outputs are kept); ``radius``:
        r0 of this history (default the problem's contact radius).

        Work done by the load is summed over every step as ½(f_k + f_{k+1})·(u_{k+1} − u_k),
        the rule under which average acceleration balances energy exactly; the
        kinetic and strain energies are evaluated at about ``energy_samples``
        evenly spaced steps (``energy["step"]``), which is what the balance check needs
        and keeps the quadratic forms off the stepping's critical path.
        """
        F = self.force_samples(history)
        st = self.stepper
        n, N = self.plane.n, self.steps
        loads = -self.nodal_loads(F, radius)  # (p, N+1): patch forces on the load DOFs (down)
        f0 = np.zeros(n)
        f0[self.load_dofs] = loads[:, 0]
        stride = max(1, N // max(1, energy_samples))
        sampled = np.unique(np.r_[np.arange(0, N + 1, stride), N]) if energy else np.zeros(0, int)
        u_all = np.zeros((N + 1, n)) if displacement else None
        y = np.zeros((N + 1, self.O.shape[0]))  # outputs, time-major
        u_load = np.zeros((N + 1, self.load_dofs.size))  # for the work done by the load
        u_samples, v_samples = np.zeros((sampled.size, n)), np.zeros((sampled.size, n))
        u, v = np.zeros(n), np.zeros(n)
        acc = st.initial_acceleration(u, v, f0)
        j = 1 if sampled.size and sampled[0] == 0 else 0  # the zero state is already stored
        for k in range(N):
            rhs = st.predictor(u, v, acc)
            rhs[self.load_dofs] += loads[:, k + 1]
            u1 = st.solve(rhs)
            v, acc = st.correct(u1, u, v, acc)
            u = u1
            y[k + 1] = self.O @ u
            u_load[k + 1] = u[self.load_dofs]
            if u_all is not None:
                u_all[k + 1] = u
            if j < sampled.size and sampled[j] == k + 1:
                u_samples[j], v_samples[j], j = u, v, j + 1
            if progress is not None and k % 100 == 0:
                progress(k)
        strain, bending, defl = self._split(y.T)
        energies = {}
        if energy:
            M, K = self.plane.M, self.plane.K
            kinetic = 0.5 * np.einsum("kn,kn->k", v_samples, (M @ v_samples.T).T)
            strain_energy = 0.5 * np.einsum("kn,kn->k", u_samples, (K @ u_samples.T).T)
            work = np.concatenate(([0.0], np.cumsum(0.5 * np.einsum("pk,kp->k", loads[:, :-1] + loads[:, 1:], np.diff(u_load, axis=0)))))
            energies = {"step": sampled, "kinetic": kinetic, "strain": strain_energy, "work": work[sampled]}
        return BeamResult(self.problem, self.problem.solver.times(), F, strain, bending, defl, None if u_all is None else u_all.T, energies)

    def moduli(self) -> dict:
        """Effective engineering constants and the plane matrix of the (smeared) material."""
        spec = self.problem.beam
        if spec.stack is None:
            return {"E": spec.material.youngs_modulus, "nu": spec.material.poisson_ratio}
        out = {k: float(v) for k, v in engineering_constants(spec.stack.effective()).items()}
        out["plane_matrix_Pa"] = plane_matrix(spec.stack.effective(), spec.plane).tolist()
        out["bending_stiffness_per_width_N_m"] = {k: float(v) for k, v in spec.stack.bending_stiffness(spec.plane).items()}
        return out
