"""The linear plate (:class:`PlateModel`): linear and time-invariant, so two ways to the same outputs: ``direct``
stepping (all DOFs, energies) and ``respond`` through the response engine (impulse responses at the outputs,
computed once by reciprocity; milliseconds per force history)."""

from __future__ import annotations

import copy

import numpy as np

from ...errors import InputError
from ...fem.contact import output_groups, plate_contact_structure, plate_reach
from ...fem.linear import LinearModel
from ...fem.plate import PlateFE
from ...fem.plate_loads import CircularPatch
from .problem import PlateProblem, PlateResult

__all__ = ["PlateModel"]


class PlateModel(LinearModel):
    """Assembled plate with its stepper, contact patch and output rows, for one (mesh, dt): the
    plate as a :class:`softimpact.fem.linear.LinearModel` (the structure protocol)."""

    def __init__(self, problem: PlateProblem, patch_radius: float | None = None, damage: bool = False):
        """``patch_radius``: the widest contact radius the model must load (for fits of r0); ``damage``: it also
        outputs the ``"damage"`` group (:meth:`PlateProblem.damage_gauges`), after the gauges."""
        self.problem = problem
        self.damage = problem.damage_gauges() if damage else ()
        self.fe = fe = PlateFE(problem.plate.plate())
        a, b = problem.plate.damping
        C = None if a == 0 and b == 0 else a * fe.M + b * fe.K
        load = problem.load
        patch = CircularPatch(fe, load.position, patch_radius or load.contact_radius, grow=load.grow)
        rows = [fe.surface_strain(*g.position, g.surface, g.direction, g.length) for g in problem.gauges + self.damage]
        rows += [fe.deflection(*p) for p in (load.position,) + tuple(problem.points)]
        # Patch loads push the plate down (−z).
        super().__init__(fe.M, fe.K, C, problem.solver, patch.dofs, -1.0, np.array(rows), patch, load.contact_radius)

    def _split(self, y: np.ndarray):
        """(gauge strains, deflections, the damage group or None) of the output rows."""
        ng, nd = len(self.problem.gauges), len(self.damage)
        return y[:ng], y[ng + nd :], (y[ng : ng + nd] if nd else None)

    def respond(self, history=None, radius: float | None = None) -> PlateResult:
        """Gauge strains and deflections for a force history through the response engine.

        A patch of fixed radius loads one pattern scaled by F(t): the engine then combines its
        impulse responses over the patch once and convolves each output with F alone."""
        F = self.force_samples(history)
        if self.patch.grow:
            y = self.respond_outputs(F, radius)
        else:
            if F[0] != 0.0:
                raise InputError("the force must be zero at first contact (t = 0)", "history")
            r0 = self.load_radius if radius is None else radius
            y = self.engine().respond_pattern(self.nodal_loads(np.ones(1), r0)[:, 0], F)
        strain, defl, damage = self._split(y)
        return PlateResult(self.problem, self.solver.times(), F, strain, defl, damage=damage)

    def direct(self, history=None, progress=None, energy: bool = True, snapshots=None) -> PlateResult:
        """Direct Newmark stepping of all DOFs (:meth:`LinearModel.march`); with ``energy``, the
        energy balance at every step. ``snapshots``: step indices at which to keep the displacement
        of all DOFs (``None``: every step, memory n_dofs × n_steps)."""
        F = self.force_samples(history)
        keep = np.arange(self.steps + 1) if snapshots is None else np.asarray(snapshots, int)
        y, energies, saved = self.march(F, None, energy, None, keep, progress)
        strain, defl, damage = self._split(y)
        return PlateResult(self.problem, self.solver.times(), F, strain, defl, saved, energies, keep, damage)

    def contact_structure(self, point: tuple[float, float], reach: float):
        """The plate struck downward on its top face at ``point`` (x, y) [m], contact discs up to
        ``reach`` [m] (:func:`softimpact.fem.contact.plate_contact_structure`), the gauges as outputs, then the ``"damage"`` group's."""
        gauges = self.problem.gauges + self.damage
        return plate_contact_structure(self.fe, point, reach, self.O[: len(gauges)], tuple(g.name for g in gauges), self.C, self.contact_groups())

    def contact_groups(self) -> dict[str, tuple[int, ...]]:
        """``"gauges"`` (the problem's) and ``"damage"`` (:meth:`PlateProblem.damage_gauges`, when built with it)."""
        return output_groups(gauges=len(self.problem.gauges), damage=len(self.damage))

    def contact_reach(self, point: tuple[float, float], diameter: float) -> float:
        """The impactor's diameter cut by the plate's edges (:func:`softimpact.fem.contact.plate_reach`)."""
        return plate_reach(self.fe, self.problem.plate.supports, point, diameter)

    @property
    def mesh(self):
        """The plate's mesh (:class:`~softimpact.fem.plate.PlateFE`: ``expand``, ``field_frames``)."""
        return self.fe

    def _drop_mesh(self, light) -> None:
        light.fe = None
        light.patch = copy.copy(self.patch)
        light.patch.fe = None
