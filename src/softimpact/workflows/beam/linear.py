"""The linear beam: :class:`BeamModel`, the assembled plane model with its stepper, patch and output rows (direct
stepping, or the response engine's impulse responses), and its :class:`BeamResult`."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...errors import InputError
from ...fem.contact import output_groups, plane_contact_structure
from ...fem.energies import Energies
from ...fem.linear import LinearModel
from ...fem.loads import PatchLoad
from ...fem.plane import PlaneModel
from ...models.laminate import engineering_constants, plane_matrix
from .problem import BeamProblem

__all__ = ["BeamModel", "BeamResult", "OUTPUTS"]

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
    displacement: np.ndarray | None = None  # (n_dofs, n), reduced DOFs, direct stepping only
    energies: Energies | None = None  # kinetic, strain, work [J] at the steps energies.step, direct stepping only


class BeamModel(LinearModel):
    """Assembled beam with its stepper, patch and output rows, for one (mesh, dt): the plane model
    as a :class:`softimpact.fem.linear.LinearModel` (the structure protocol)."""

    def __init__(self, problem: BeamProblem, patch_radius: float | None = None, outputs: str = "all", damage: bool = False):
        """``patch_radius``: the widest contact radius the model must load (for fits of r0);
        ``damage``: the contact structure also outputs the ``"damage"`` group (:meth:`BeamProblem.damage_gauges`).
        ``outputs``: "all" (gauge strains, bending strains, deflection under the load) or
        "strain" (the gauge strains only: the response engine then costs one right-hand
        side per gauge instead of two per gauge and one; bending and deflection are NaN)."""
        if outputs not in OUTPUTS:
            raise InputError(f"outputs: {outputs!r} is not one of {', '.join(OUTPUTS)}", "outputs")
        self.problem, self.outputs = problem, outputs
        self.damage = problem.damage_gauges() if damage else ()
        self.plane = pm = PlaneModel(problem.beam.plane_beam())
        a, b = problem.beam.damping
        C = None if a == 0 and b == 0 else a * pm.M + b * pm.K
        top_x = pm.node_x[pm.top_nodes]
        patch = PatchLoad(top_x, problem.load.position, patch_radius or problem.load.contact_radius)
        # Patch loads push the top face down (−z).
        load_dofs = np.array([pm.dof(node, 1) for node in pm.top_nodes[patch.nodes]])
        rows = []
        for g in problem.gauges:
            other = "top" if g.surface == "bottom" else "bottom"
            rows.append(pm.surface_strain(g.position, g.surface, g.length))
            if outputs == "all":
                rows.append(pm.surface_strain(g.position, other, g.length))
        if outputs == "all":
            rows.append(pm.displacement(problem.load.position, "top", 1))
        O = np.array(rows) if rows else np.zeros((0, pm.n))
        super().__init__(pm.M, pm.K, C, problem.solver, load_dofs, -1.0, O, patch, problem.load.contact_radius, stepper=self._structure_stepper(C))

    def _structure_stepper(self, C):
        """The stepper of the structure (None: the linear Newmark stepper; a nonlinear model's its own)."""
        return None

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

    def respond(self, history=None, radius: float | None = None) -> BeamResult:
        """Gauge strains for a force history through the response engine."""
        F = self.force_samples(history)
        strain, bending, defl = self._split(self.respond_outputs(F, radius))
        return BeamResult(self.problem, self.solver.times(), F, strain, bending, defl)

    def direct(
        self, history=None, progress=None, energy: bool = True, displacement: bool = True, energy_samples: int = 200, radius: float | None = None
    ) -> BeamResult:
        """Direct Newmark stepping of all DOFs (:meth:`LinearModel.march`); with ``energy``, the
        energy balance, its kinetic and strain energies at about ``energy_samples`` evenly spaced
        steps (``energies.step``); with ``displacement``, the whole displacement history (for deformed
        shapes: n_dofs × n_steps floats; without it only the outputs are kept); ``radius``: r0 of
        this history (default the problem's contact radius)."""
        F = self.force_samples(history)
        keep = np.arange(self.steps + 1) if displacement else ()
        y, energies, saved = self.march(F, radius, energy, energy_samples, keep, progress)
        strain, bending, defl = self._split(y)
        return BeamResult(self.problem, self.solver.times(), F, strain, bending, defl, saved if displacement else None, energies)

    def contact_structure(self, point: float, reach: float):
        """The beam struck downward on its top face at ``point`` [m] (:func:`softimpact.fem.contact.plane_contact_structure`),
        with the gauge strains (each on its own face) as outputs, then the ``"damage"`` group's, and the model's damping."""
        pm, gauges = self.plane, self.problem.gauges + self.damage
        outputs = np.array([pm.surface_strain(g.position, g.surface, g.length) for g in gauges]).reshape(len(gauges), pm.n)
        return plane_contact_structure(pm, point, reach, outputs, tuple(g.name for g in gauges), self.C, self.contact_groups())

    def contact_groups(self) -> dict[str, tuple[int, ...]]:
        """``"gauges"`` (the problem's) and ``"damage"`` (:meth:`BeamProblem.damage_gauges`, when built with it)."""
        return output_groups(gauges=len(self.problem.gauges), damage=len(self.damage))

    @property
    def mesh(self):
        """The plane-strain mesh (:class:`~softimpact.fem.plane.PlaneModel`: ``expand``, ``field_frames``)."""
        return self.plane

    def _drop_mesh(self, light) -> None:
        light.plane = None

    def moduli(self) -> dict:
        """Effective engineering constants and the plane matrix of the (smeared) material."""
        spec = self.problem.beam
        if spec.stack is None:
            return {"E": spec.material.youngs_modulus, "nu": spec.material.poisson_ratio}
        out = {k: float(v) for k, v in engineering_constants(spec.stack.effective()).items()}
        out["plane_matrix_Pa"] = plane_matrix(spec.stack.effective(), spec.plane).tolist()
        out["bending_stiffness_per_width_N_m"] = {k: float(v) for k, v in spec.stack.bending_stiffness(spec.plane).items()}
        return out
