"""The one exception type for bad input, raised at every layer.

The command line turns it into a one-line message and exit code 2.
"""

__all__ = ["InputError"]


class InputError(ValueError):
    """Bad input: the message names the key (or argument) and the value."""
