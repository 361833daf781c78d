"""The plate workflow's former module: everything now lives in the package :mod:`softimpact.workflows.plate`
(problem, linear, nonlinear and cohesive models); these names stay importable from here."""

from .plate import *  # noqa: F403
from .plate import __all__  # noqa: F401
from .plate.problem import STATIC_ITERATIONS  # noqa: F401
