"""Exceptions and warnings shared by every layer, and the command line's exit codes.

The core (models, fem, workflows) names the *argument* that is wrong — its
Python name, in ``argument`` — and knows nothing of file formats. The input
layer maps arguments to the keys of its files (``solver.time_step``), and the
command line turns the error into a one-line message and an exit code:

- :class:`InputError` — bad input, nothing computed or written: exit 2.
  Two kinds are told apart by type: :class:`NoContactRoom` (no room for the contact about the
  impact point) and :class:`ContactOutgrewRoom` (a run's contact grew past its loadable nodes).
- :class:`CheckFailed` — the run finished but its answer failed a quality gate
  (:mod:`softimpact.gates`): exit 3, its diagnostics still written and marked
  ``"status": "failed"``.
- :class:`SolverFailed` — a solver did not converge (a contact Newton iteration): exit 3
  like a failed check, with a one-line reason (time, step, residual or bracket); nothing written.
- :class:`SoftimpactWarning` — a usable result that deserves a word (a coarse
  mesh, an ignored column): one ``softimpact: warning:`` line, exit unchanged.
"""

import warnings

__all__ = [
    "InputError",
    "TooLarge",
    "NoContactRoom",
    "ContactOutgrewRoom",
    "CheckFailed",
    "SolverFailed",
    "SoftimpactWarning",
    "HeldWarnings",
    "EXIT_INPUT",
    "EXIT_CHECK",
    "EXIT_INTERNAL",
]

EXIT_INPUT = 2  # bad input: a one-line reason, nothing written
EXIT_CHECK = 3  # ran, but the answer failed its checks (diagnostics written, marked failed)
EXIT_INTERNAL = 70  # an unexpected exception: a bug (EX_SOFTWARE of sysexits.h)


class InputError(ValueError):
    """Bad input: the message names the key (or argument) and the value.

    ``argument``: the parameter of the core object that was refused, so that an
    edge can name it in its own terms (None where the message already does).
    """

    def __init__(self, message: str, argument: str | None = None):
        super().__init__(message)
        self.argument = argument


class TooLarge(InputError):
    """A problem the memory/time guard refuses (:func:`softimpact.guards.require_resources`): still
    bad input (exit 2), told apart so that a study can say which smaller study fits."""


class NoContactRoom(InputError):
    """The contact patch or disc does not fit about the impact point (off the structure, or over a
    supported edge): still bad input (exit 2), told apart so that an impact run can name the case's
    impact position (:func:`softimpact.workflows.coupled.impact_model`)."""


class ContactOutgrewRoom(InputError):
    """The contact radius of a coupled run grew past the loadable surface nodes (or disc) about the
    impact point: bad input (exit 2), told apart so that an impact run can say the contact outgrew
    its room (:func:`softimpact.workflows.coupled.run_impact`)."""


class CheckFailed(RuntimeError):
    """A run finished but its answer failed a quality check (exit code 3).

    ``gates``: the :class:`softimpact.gates.Gate` objects that failed (their
    reasons make the message when none is given).
    """

    def __init__(self, gates=(), message: str | None = None):
        self.gates = tuple(gates)
        if message is None:
            message = "; ".join(g.reason for g in self.gates) or "the result failed its checks"
        super().__init__(message)


class SolverFailed(CheckFailed):
    """A solver gave up (exit code 3, as a failed check): the message says where (time, step) and
    how far it was from converging (residual, bracket), in one line. The command line writes summary.json with
    that reason and a manifest marked failed (no results: there are none)."""

    def __init__(self, message: str):
        super().__init__((), message)


class SoftimpactWarning(UserWarning):
    """A result the user may use, with a caveat shown as one line (never an exit code)."""


class HeldWarnings:
    """``with HeldWarnings() as w:`` — the :class:`SoftimpactWarning` s raised inside the block, every one (not
    once per code location), held in ``w.held`` (:class:`warnings.WarningMessage` records, in order) and not
    shown; any other warning is shown as usual when the block ends. The one mechanism of the edges that
    show or keep the core's warnings in their own way: the sweep (once each, counted per run) and the
    Python API (warned again at the user's line)."""

    def __enter__(self):
        self.held: list = []
        self._catching = warnings.catch_warnings(record=True)
        self._caught = self._catching.__enter__()
        warnings.simplefilter("always", SoftimpactWarning)
        return self

    def __exit__(self, *exc):
        self._catching.__exit__(*exc)
        for w in self._caught:
            if issubclass(w.category, SoftimpactWarning):
                self.held.append(w)
            else:
                warnings.warn_explicit(w.message, w.category, w.filename, w.lineno, source=w.source)
        return False
