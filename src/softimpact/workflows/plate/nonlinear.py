"""The nonlinear plate of the one engine as a structure model (:class:`NonlinearPlateModel`): von Kármán kinematics
and, for a metal, the elastic–plastic section (:mod:`softimpact.fem.plate_plastic`), stepped by the nonlinear
Newmark–Newton engine (:mod:`softimpact.fem.nonlinear`); :meth:`PlateProblem.model` builds it."""

from __future__ import annotations

import numpy as np

from ...errors import InputError
from ...fem.contact import output_groups, plate_reach
from ...fem.energies import Energies
from ...fem.plate import Plate
from ...fem.plate_loads import CircularPatch
from .problem import PlateProblem, PlateResult

__all__ = ["NonlinearPlateModel", "PlateVKModel"]


class _SupportedView:
    """The all-DOF PlateFE of a :class:`~softimpact.fem.plate_vk.PlateVK` ``vk`` seen with the plate's own supports
    (a contact disc mirrored on a symmetry edge carries its share) and ``vk``'s free DOFs (``n``, ``free``,
    :meth:`expand`): every other attribute is the FE's (its DOF numbering: full vectors)."""

    def __init__(self, vk, plate: Plate):
        self._fe, self.plate, self.n, self.free = vk.fe, plate, vk.n, vk.free

    def dof(self, node: int, component: int) -> int:
        """The full DOF number of a node's component (``vk``'s ``_index`` maps it to its own, −1 where fixed)."""
        return int(self._fe.basis.nodal_dofs[component, node])

    def expand(self, u: np.ndarray) -> np.ndarray:
        """Full DOF vector(s) (fixed DOFs zero) from ``vk``'s reduced ones; time on the last axis."""
        full = np.zeros((self._fe.basis.N,) + np.shape(u)[1:])
        full[self.free] = u
        return full

    def __getattr__(self, name):
        return getattr(self._fe, name)


class NonlinearPlateModel:
    """The plate with von Kármán kinematics (:mod:`softimpact.fem.plate_vk`): its
    :class:`~softimpact.fem.plate_vk.PlateVK` ``vk`` (membrane DOFs kept, in-plane edges as the problem's
    ``in_plane``) — for a plastic metal plate its :class:`~softimpact.fem.plate_plastic.PlasticPlate` —, its nonlinear
    Newmark ``stepper`` (:class:`~softimpact.fem.nonlinear.NonlinearNewmark`, modified Newton), the output rows (gauges,
    then the ``"damage"`` group, then the ``"columns"`` group: the scalars the plate records, its plastic work, plastic
    zone and largest plastic strain); a coupled impact's structure
    (:meth:`contact_structure`, over its free DOFs, stepped by :data:`softimpact.fem.steppers.STEPPERS`
    ``"von-karman"``) and a prescribed force history's (:meth:`direct`). ``fe``: the mesh with the plate's
    supports and ``vk``'s free DOFs (its ``expand`` maps snapshots to full vectors). No response engine or
    kernels: the structure is not linear."""

    coupled_stepper = "von-karman"

    @property
    def mesh(self):
        """The plate's mesh seen with its supports and ``vk``'s free DOFs (``fe``: ``expand``, ``field_frames``)."""
        return self.fe

    def __init__(self, problem: PlateProblem, damage: bool = False):
        from ...fem.plate_vk import PlateVK, VonKarmanNewmark
        from .problem import plastic_plate

        self.problem = problem
        self.damage = problem.damage_gauges() if damage else ()
        plate = problem.plate.plate()
        self.vk = vk = plastic_plate(problem) if problem.plastic else PlateVK(plate, problem.in_plane)
        self.fe = self._view = _SupportedView(vk, plate)
        a, b = problem.plate.damping
        self.C = None if a == 0 and b == 0 else (a * vk.M + b * vk.K).tocsr()
        self.solver = problem.solver
        self.stepper = VonKarmanNewmark(vk, problem.solver.time_step, self.C, problem.solver.newmark, tangent="modified")
        gauges = problem.gauges + self.damage
        self.column_names = tuple(vk.history_names)
        rows = [vk.surface_strain(*g.position, g.surface, g.direction, g.length) for g in gauges]
        rows += [np.zeros(vk.n)] * len(self.column_names)  # placeholders the stepper fills with the plate's recorded scalars
        self.O = np.array(rows).reshape(len(rows), vk.n)
        self._names = tuple(g.name for g in gauges) + self.column_names

    def rest(self) -> dict:
        """A plastic plate's state once its motion has died away, from the last run's end: the equilibrium at zero load
        with its plastic strains (:func:`softimpact.fem.nonlinear.relax`): ``dent_depth_m`` the permanent mid-surface
        deflection under the impact point (positive into the plate, against the plate's rest before the impact),
        ``permanent_deflection_max_m`` the largest over the plate, and the plastic work, zone and strain after it."""
        from ...fem.nonlinear import relax
        from ...fem.plate import W

        vk = self.vk
        u, _ = relax(vk, vk.displacement)
        w = vk.expand(u)[vk.fe.basis.nodal_dofs[W]]
        work, zone, strain = vk.history(u)
        return {
            "dent_depth_m": -float(vk.deflection(*self.problem.load.position) @ u),
            "permanent_deflection_max_m": float(np.abs(w).max()),
            "plastic_work_J": float(work) * self._whole,
            "plastic_zone_area_m2": float(zone) * self._whole,
            "max_equivalent_plastic_strain": float(strain),
        }

    @property
    def _whole(self) -> float:
        """The whole plate over the model (2 per symmetry edge: a half or quarter model)."""
        return 2.0 ** sum(s == "symmetry" for s in self.problem.plate.supports)

    @property
    def size(self) -> int:
        """The plate's free DOFs (membrane included)."""
        return self.vk.n

    @property
    def steps(self) -> int:
        return self.solver.steps

    def frequencies(self, count: int = 5) -> np.ndarray:
        """The ``count`` lowest natural frequencies [Hz] of small vibrations about the flat plate (its linear
        stiffness K, membrane DOFs included; shift-invert Lanczos)."""
        import scipy.sparse.linalg as spl

        if not (isinstance(count, int) and 1 <= count < self.size - 1):
            raise InputError(f"count must be an integer from 1 to {self.size - 2}, got {count!r}")
        vals = spl.eigsh(self.vk.K.tocsc(), k=count, M=self.vk.M.tocsc(), sigma=0.0, which="LM", tol=1e-10, return_eigenvectors=False)
        return np.sqrt(np.abs(np.sort(vals))) / (2 * np.pi)

    def direct(self, history=None, progress=None, energy: bool = True, snapshots=None) -> PlateResult:
        """The force history (default: the problem's) on the load's patch (eq 11, its radius growing by eq 10
        when the load says so) by nonlinear Newmark–Newton stepping (:class:`~softimpact.fem.plate_vk.VonKarmanNewmark`):
        gauge strains, deflections under the load and at the problem's points, with ``energy`` the balance
        (kinetic, the von Kármán strain energy, the loads' work by the trapezoidal rule) at every step;
        ``snapshots``: step indices at which to keep the displacement of the free DOFs (None: every step)."""
        p, vk, st, N = self.problem, self.vk, self.stepper, self.solver.steps
        h = p.load.history if history is None else history
        F = np.asarray(h(self.solver.times()) if callable(h) else h, float)
        patch = CircularPatch(self._view, p.load.position, p.load.contact_radius, grow=p.load.grow)
        dofs = vk._index[patch.dofs]
        if np.any(dofs < 0):
            raise InputError(f"load position {p.load.position!r} m: the load patch reaches a supported edge")
        loads = -patch.forces(F, p.load.contact_radius)  # (p, N + 1): the patch pushes the plate down (−z)
        gauges = len(p.gauges) + len(self.damage)
        rows = np.vstack([self.O[:gauges], *[vk.deflection(*xy)[None] for xy in (p.load.position,) + tuple(p.points)]])
        keep = np.arange(N + 1) if snapshots is None else np.asarray(snapshots, int)
        slot = {int(k): i for i, k in enumerate(keep)}
        saved = np.zeros((vk.n, keep.size))
        n = vk.n
        u, v = np.zeros(n), np.zeros(n)
        f = np.zeros(n)
        f[dofs] = loads[:, 0]
        a = st.initial_acceleration(u, v, f)
        y = np.zeros((rows.shape[0], N + 1))
        kinetic, strain, work = np.zeros(N + 1), np.zeros(N + 1), np.zeros(N + 1)
        vk.reset()
        strain[0] = vk.strain_energy(u)
        if 0 in slot:
            saved[:, slot[0]] = u
        for k in range(N):
            f1 = np.zeros(n)
            f1[dofs] = loads[:, k + 1]
            u1, v, a, _ = st.step(u, v, a, f1)
            a = st.commit(u1, a)
            work[k + 1] = work[k] + 0.5 * (loads[:, k] + loads[:, k + 1]) @ (u1[dofs] - u[dofs])
            u = u1
            y[:, k + 1] = rows @ u
            if energy:
                # the structure's energy: recoverable + dissipated (a plastic plate's plastic work), as the coupled stepper's
                kinetic[k + 1], strain[k + 1] = 0.5 * v @ (vk.M @ v), vk.strain_energy(u) + vk.dissipated_energy()
            if k + 1 in slot:
                saved[:, slot[k + 1]] = u
            if progress is not None and k % 100 == 0:
                progress(k)
        energies = Energies(np.arange(N + 1), kinetic, strain, work) if energy else None
        ng, nd = len(p.gauges), len(self.damage)
        return PlateResult(p, self.solver.times(), F, y[:ng], y[ng + nd :], saved, energies, keep, y[ng : ng + nd] if nd else None)

    def contact_structure(self, point: tuple[float, float], reach: float):
        """The plate struck downward on its top face at ``point`` (x, y) [m], contact discs up to ``reach`` [m]
        (as :func:`softimpact.fem.contact.plate_contact_structure`, over this model's free DOFs)."""
        from ...errors import NoContactRoom
        from ...fem.impact import ContactStructure
        from ...fem.plate_loads import DiscShares

        vk = self.vk
        patch = CircularPatch(self._view, point, reach, grow=True)
        dofs = vk._index[patch.dofs]
        if np.any(dofs < 0):
            raise NoContactRoom(f"contact patch about {tuple(point)!r} m reaches a supported edge")
        return ContactStructure(
            M=vk.M,
            K=vk.K,
            surface_x=vk.fe.node_xy()[0, patch.nodes],
            surface_dofs=dofs,
            load_sign=-1.0,  # w is up +, the impact pushes down
            center=float(point[0]),
            approach_row=-vk.deflection(*point),
            outputs=self.O,
            output_names=self._names,
            C=self.C,
            patch=DiscShares(patch),
            groups=self.contact_groups(),
        )

    def contact_groups(self) -> dict[str, tuple[int, ...]]:
        """``"gauges"`` (the problem's), ``"damage"`` (:meth:`PlateProblem.damage_gauges`, when built with it) and
        ``"columns"`` (the plate's recorded scalars, a plastic plate's)."""
        return output_groups(gauges=len(self.problem.gauges), damage=len(self.damage), columns=len(self.column_names))

    def contact_reach(self, point: tuple[float, float], diameter: float) -> float:
        """The impactor's diameter cut by the plate's edges (:func:`softimpact.fem.contact.plate_reach`)."""
        return plate_reach(self.fe, self.problem.plate.supports, point, diameter)


PlateVKModel = NonlinearPlateModel  # its name while von Kármán kinematics was its only nonlinearity
