"""Former home of the cohesive plate: :mod:`softimpact.workflows.plate.cohesive`."""

from .plate.cohesive import CohesivePlateModel, CohesivePlateProblem, _TopView, interface_label  # noqa: F401
