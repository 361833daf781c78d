"""What a chain command made (:class:`CommandResult`: its files, parsed) and a lab record (:class:`Record`)."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

from ...errors import InputError
from .._edge import _one_line, _write
from ._written import _axes, _frame, _read_only, _Written


@dataclass(frozen=True)
class CommandResult(_Written):
    """What a command made (:class:`softimpact.app.Outcome`): its files by name and its one line.

    Parameters
    ----------
    command : str
        The equivalent command line.
    outcome : softimpact.app.Outcome
        ``files`` (name → text or bytes; numbers in SI with unit-suffixed names), ``line``,
        ``inputs``, ``warnings``, ``gates``. A failed quality gate does not raise here (the
        command line exits 3); :meth:`write` marks it ``"status": "failed"`` in manifest.json.
    warnings : tuple of str
        The :class:`~softimpact.errors.SoftimpactWarning` s raised while the command ran, one line each
        (already warned at the call, as the outcome's own ``warnings`` were); manifest.json lists the
        outcome's, then these, as the command line does.
    """

    command: str
    outcome: object = field(repr=False, default=None)
    warnings: tuple = field(repr=False, compare=False, default=())

    @property
    def line(self) -> str:
        """The line the command prints."""
        return self.outcome.line

    def files(self, figures: bool = True):
        return {k: v for k, v in self.outcome.files.items() if figures or not k.endswith((".png", ".svg", ".pdf"))}

    def inputs(self):
        return tuple(self.outcome.inputs)

    def json(self, name: str) -> dict:
        """A JSON file of the outcome (``"scaling.json"``, ``"law.json"``, …), parsed."""
        return json.loads(self.outcome.files[name])

    def table(self, name: str):
        """A CSV file of the outcome (``"tests.csv"``, ``"history.csv"``, …) as a pandas DataFrame."""
        import io

        import pandas as pd

        return pd.read_csv(io.StringIO(self.outcome.files[name]))

    def summary(self) -> dict:
        return self.json("summary.json")

    def plot(self, ax=None):
        """The first figure of the outcome shown on ``ax`` (an image); returns the Axes."""
        import io

        import matplotlib.image as mpimg

        pngs = [k for k in self.outcome.files if k.endswith(".png")]
        if not pngs:
            raise InputError(f"{self.command}: made no figure (figures=False?)")
        ax = _axes(ax)
        ax.imshow(mpimg.imread(io.BytesIO(self.outcome.files[pngs[0]])))
        ax.set_axis_off()
        ax.set_title(pngs[0])
        return ax

    def write(self, out, *, figures: bool = True, force: bool = False) -> list[Path]:
        """Write the command's files and manifest.json into ``out`` (see :meth:`ImpactResult.write`)."""
        from ...gates import status

        gates = tuple(self.outcome.gates)
        manifest = {
            "status": status(gates, False),
            "accept_poor": False,
            "command": f"{self.command} (Python API)",
            "arguments": {},
            "warnings": [*map(_one_line, self.outcome.warnings), *self.warnings],  # the command line's order
            "gates": [g.as_dict() for g in gates],
        }
        return _write(out, self.files(figures), self.inputs(), manifest, force)


@dataclass(frozen=True)
class Record:
    """One channel of a lab record (:func:`read_record`).

    Parameters
    ----------
    time : numpy.ndarray
        [s], 1-D, increasing (negative before the trigger).
    signal : numpy.ndarray
        Same shape, in ``unit``.
    unit : str
        ``"V"``, ``"strain"``, ``"microstrain"`` or the file's own unit text.
    metadata : dict
        File, format, channel, sample rate [Hz], trigger, the header's items.

    Examples
    --------
    >>> import numpy as np
    >>> import softimpact as si
    >>> rec = si.Record(np.array([0.0, 1e-6]), np.array([1.0, 2.0]), "V")
    >>> rec.signal[0] = 5.0  # frozen: its arrays too
    Traceback (most recent call last):
    ...
    ValueError: assignment destination is read-only
    """

    time: object
    signal: object
    unit: str
    metadata: dict = field(default_factory=dict, compare=False)

    def __post_init__(self):
        _read_only((self.time, self.signal), 1)

    def to_frame(self):
        """The channel as a pandas DataFrame indexed by time [s]; its unit in ``df.attrs["units"]``."""
        return _frame({"time_s": self.time, "signal": self.signal}, {"signal": self.unit})

    def plot(self, ax=None):
        """The signal against time [µs]; returns the matplotlib Axes."""
        ax = _axes(ax)
        ax.plot(self.time * 1e6, self.signal)
        ax.set_xlabel("time [µs]")
        ax.set_ylabel(f"signal [{self.unit}]")
        return ax
