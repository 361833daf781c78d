"""The coupled steppers by name, one table (as scipy's ``METHODS`` of ``solve_ivp``): each an implementation
of :class:`softimpact.fem.stepping.CoupledStepper` with one signature,
``STEPPERS[name](structure, law, mass, velocity, time_step, steps, newmark, *, engine, stop_after, energy,
snapshots)`` then ``.run()``:

- ``"direct"``: :class:`softimpact.fem.direct.DirectStepper`, the structure stepped by Newmark with the
  impactor (``engine``: its factored :class:`softimpact.fem.newmark.NewmarkStepper`); energies and
  snapshots; the reference.
- ``"kernels"``: :class:`softimpact.fem.kernel_stepping.KernelStepper`, the scalar contact equation against
  the structure's impulse responses (``engine``: its :class:`softimpact.fem.kernels.ContactKernels`);
  milliseconds a run once built, equal to direct stepping to round-off, no structure energies.
- ``"von-karman"``: :class:`softimpact.fem.vk_stepping.VonKarmanStepper`, any nonlinear structure of the one
  engine (:mod:`softimpact.fem.nonlinear`: a plate with von Kármán kinematics, an elastic–plastic plate, sublaminates
  tied by cohesive interfaces, a plane beam in total Lagrangian form; ``engine``: its
  :class:`softimpact.fem.nonlinear.NonlinearNewmark`): one Newton over the structure and the contact a step, the
  structure's internal state committed after it; energies (dissipated included), the structure's recorded scalars
  and snapshots.
- ``"von-karman-rom"``: :class:`softimpact.fem.vk_rom.ReducedVonKarmanStepper`, the same plate on its reduced
  nonlinear model (``engine``: its :class:`softimpact.fem.vk_rom.PlateVKROM`, built once by
  :func:`softimpact.fem.vk_rom.reduced_plate`, as a threshold map's structure does; or the plate's
  VonKarmanNewmark, the reduced model then built for the run): a fraction of a second a run.
- ``"cohesive"``: the same stepper under the name the cohesive targets gave it before the engine was one.
"""

from __future__ import annotations

from .direct import DirectStepper
from .kernel_stepping import KernelStepper
from .vk_rom import ReducedVonKarmanStepper
from .vk_stepping import VonKarmanStepper

__all__ = ["STEPPERS"]

STEPPERS = {
    "direct": DirectStepper,
    "kernels": KernelStepper,
    "von-karman": VonKarmanStepper,
    "von-karman-rom": ReducedVonKarmanStepper,
    "cohesive": VonKarmanStepper,
}
