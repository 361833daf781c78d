"""The one exception type for bad input, raised at every layer.

The core (models, fem, workflows) names the *argument* that is wrong — its
Python name, in ``argument`` — and knows nothing of file formats. The input
layer maps arguments to the keys of its files (``solver.time_step``), and the
command line turns the error into a one-line message and exit code 2.
"""

__all__ = ["InputError", "CheckFailed"]


class InputError(ValueError):
    """Bad input: the message names the key (or argument) and the value.

    ``argument``: the parameter of the core object that was refused, so that an
    edge can name it in its own terms (None where the message already does).
    """

    def __init__(self, message: str, argument: str | None = None):
        super().__init__(message)
        self.argument = argument


class CheckFailed(RuntimeError):
    """A run finished but its answer failed a quality check (exit code 3)."""
