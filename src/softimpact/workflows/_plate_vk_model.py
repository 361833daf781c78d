"""Former home of the nonlinear plate model: :mod:`softimpact.workflows.plate.nonlinear`."""

from .plate.nonlinear import NonlinearPlateModel, PlateVKModel, _SupportedView  # noqa: F401
