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

A package: :mod:`~softimpact.workflows.beam.problem` (the beam, its load, gauges, solver and checks),
:mod:`~softimpact.workflows.beam.linear` (the assembled linear model and its result) and
:mod:`~softimpact.workflows.beam.nonlinear` (its total Lagrangian form, ``kinematics = "von-karman"``).
``softimpact.workflows.beam_impact`` still names the same objects.
"""

from .linear import OUTPUTS, BeamModel, BeamResult
from .nonlinear import BeamTLModel, GreenLagrangeMesh
from .problem import LAMINATE_MODELS, BeamGauge, BeamLoad, BeamProblem, BeamSpec, check_problem, isotropic_matrix

__all__ = [
    "LAMINATE_MODELS",
    "OUTPUTS",
    "BeamGauge",
    "BeamSpec",
    "BeamLoad",
    "BeamProblem",
    "BeamModel",
    "BeamResult",
    "BeamTLModel",
    "GreenLagrangeMesh",
    "isotropic_matrix",
    "check_problem",
]
