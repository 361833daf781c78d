"""The beam's workflow under its former name: :mod:`softimpact.workflows.beam` (a package: problem, linear and
nonlinear models) holds it; this module names the same objects for code that imports them from here."""

from .beam import (  # noqa: F401  (re-exported)
    LAMINATE_MODELS,
    OUTPUTS,
    BeamGauge,
    BeamLoad,
    BeamModel,
    BeamProblem,
    BeamResult,
    BeamSpec,
    BeamTLModel,
    GreenLagrangeMesh,
    check_problem,
    isotropic_matrix,
)
from .beam.problem import MIN_ELEMENTS_PER_PATCH, MIN_ELEMENTS_THROUGH  # noqa: F401  (re-exported)

__all__ = ["LAMINATE_MODELS", "BeamGauge", "BeamSpec", "BeamLoad", "BeamProblem", "BeamModel", "BeamResult", "isotropic_matrix", "check_problem"]
