"""The plate workflow, one package: the problem (:mod:`.problem`: the plate, its load, gauges, solver, statics),
the linear model (:mod:`.linear`), the nonlinear model of the one engine (:mod:`.nonlinear`: von Kármán
kinematics, elastic–plastic metal sections) and the sublaminates tied by cohesive interfaces (:mod:`.cohesive`)."""

from .cohesive import CohesivePlateModel, CohesivePlateProblem, interface_label
from .linear import PlateModel
from .nonlinear import NonlinearPlateModel, PlateVKModel
from .problem import (
    ANALYSES,
    DAMAGE_DIRECTIONS,
    PlateGauge,
    PlateLoad,
    PlateProblem,
    PlateResult,
    PlateSpec,
    PlateStaticResult,
    check_problem,
    membrane_strain_index,
    solve_plate_static,
)

__all__ = [
    "ANALYSES",
    "DAMAGE_DIRECTIONS",
    "CohesivePlateModel",
    "CohesivePlateProblem",
    "NonlinearPlateModel",
    "PlateGauge",
    "PlateLoad",
    "PlateModel",
    "PlateProblem",
    "PlateResult",
    "PlateSpec",
    "PlateStaticResult",
    "PlateVKModel",
    "check_problem",
    "interface_label",
    "membrane_strain_index",
    "solve_plate_static",
]
