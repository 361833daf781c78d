"""The frozen results of the notebook API: what a run or a command made, with ``.plot``, ``.write``,
``.summary``, ``.to_frame`` and (beam, plate, impact) ``.write_fields``.

Why pandas and not xarray for the tabular view: every history here has one dimension,
time, so a DataFrame indexed by time holds it exactly; pandas is what users of lab
data already know, and the CSV files of the contract read back into the same frame.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import InputError
from ._edge import _one_line, _write

__all__ = ["ImpactResult", "BeamResult", "PlateResult", "StaticPlateResult", "BarResult", "CommandResult", "Record"]


# --- results ----------------------------------------------------------------------------------------


class _Written:
    """What every result offers on top of its numbers: the command's files, written or parsed."""

    command = "softimpact"
    warnings: tuple[str, ...] = ()  # the SoftimpactWarnings of the run, one line each (as manifest.json lists them)

    def files(self, figures: bool = True) -> dict[str, bytes | str]:  # pragma: no cover - each result has its own
        raise NotImplementedError

    def inputs(self) -> tuple[Path, ...]:
        return ()

    def summary(self) -> dict:
        """The numbers of the command's summary.json (SI, unit-suffixed keys), as the command line writes them."""
        return json.loads(self.files(figures=False)["summary.json"])

    def write(self, out, *, figures: bool = True, force: bool = False) -> list[Path]:
        """Write the command's files into ``out`` with their manifest.json (the command line's contract).

        Parameters
        ----------
        out : str or Path
            Folder (created if needed); files of an earlier softimpact run there that this run
            does not rewrite are removed, anything else is left alone.
        figures : bool
            Draw the PNG figures too.
        force : bool
            Replace files in ``out`` that no softimpact run wrote.

        Returns
        -------
        list of Path
            The files written (manifest.json not included).
        """
        from ..gates import status

        manifest = {
            "status": status((), False),
            "accept_poor": False,
            "command": f"{self.command} (Python API)",
            "arguments": {},
            "warnings": list(self.warnings),
            "gates": [],
        }
        return _write(out, self.files(figures), self.inputs(), manifest, force)


def _frame(columns: dict, units_of: dict, index: str = "time_s"):
    """A DataFrame of ``columns`` indexed by the column ``index`` (time, ``time_s``, by default), with ``df.attrs["units"]``.

    pandas, not xarray: every history has one dimension (time), which a DataFrame index holds
    exactly, and pandas is what users of lab data know (the ``table`` extra)."""
    try:
        import pandas as pd
    except ImportError:  # pragma: no cover - depends on the environment
        raise ImportError("to_frame needs pandas: pip install 'softimpact[table]'") from None
    cols = dict(columns)
    key = cols.pop(index)
    df = pd.DataFrame(cols, index=pd.Index(key, name=index))
    df.attrs["units"] = {index: units_of.get(index, "s" if index == "time_s" else "1"), **{k: units_of.get(k, "") for k in cols}}
    return df


def _unit_of(column: str) -> str:
    """The SI unit a contract column name ends in (``contact_force_N`` → ``N``)."""
    for suffix, unit in (("_m_s", "m/s"), ("_N_s", "N*s"), ("_N", "N"), ("_J", "J"), ("_m", "m"), ("_s", "s")):
        if column.endswith(suffix):
            return unit
    return "1"  # strains and other ratios


def _read_only(value, depth: int = 3) -> None:
    """Every numpy array reachable from ``value`` (through dataclass fields, tuples, lists and dict values,
    ``depth`` levels down) made read-only in place: a result is frozen, its arrays too (``res.force *= 2``
    raises instead of changing what ``write`` would write)."""
    import dataclasses

    if depth < 0 or value is None or isinstance(value, (str, bytes, int, float)):
        return
    if type(value).__module__ == "numpy" and hasattr(value, "setflags") and hasattr(value, "shape"):
        value.setflags(write=False)
    elif dataclasses.is_dataclass(value) and not isinstance(value, type):
        for f in dataclasses.fields(value):
            _read_only(getattr(value, f.name), depth - 1)
    elif isinstance(value, (tuple, list)):
        for v in value:
            _read_only(v, depth - 1)
    elif isinstance(value, dict):
        for v in value.values():
            _read_only(v, depth - 1)


def _axes(ax):
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots()
    return ax


@dataclass(frozen=True)
class ImpactResult(_Written):
    """A coupled impact on a beam or plate (:func:`impact`, or :func:`run` of an impact case).

    Parameters
    ----------
    problem : softimpact.workflows.coupled.ImpactProblem
        Every input in SI (target, impactor, law, solver, gauges).
    result : softimpact.fem.impact.CoupledResult
        The histories and first-contact scalars (SI, compression +).
    model : StructureModel, optional
        The assembled model that ran (reused by ``write_fields``).
    case_files : tuple of Path
        The case files read (never overwritten by ``write``).
    warnings : tuple of str
        The run's :class:`~softimpact.errors.SoftimpactWarning` s, one line each (already warned at
        the call; listed in manifest.json by ``write``, as the command line lists them).

    Attributes
    ----------
    peak_force : float
        [N] of the first contact; ``time_of_peak`` [s], ``contact_duration`` [s] (nan when
        not separated), ``impulse`` [N·s].
    time, force : numpy.ndarray
        (n_steps + 1,) [s], [N].
    strain : dict of str to numpy.ndarray
        Gauge strain histories (n_steps + 1,), tension +.
    """

    problem: object
    result: object
    model: object = field(repr=False, compare=False, default=None)
    case_files: tuple = field(repr=False, default=())
    warnings: tuple = field(repr=False, compare=False, default=())
    run_summary: dict = field(repr=False, compare=False, default=None)  # summary.json's content (cases.run.Run.summary)
    units: str = field(repr=False, default="in-lbf-s")  # the display system of figures and tables (a case's ``units``): the numbers stay SI
    command = "softimpact impact"

    def __post_init__(self):
        _read_only(self.result)

    peak_force = property(lambda self: self.result.peak_force, doc="Peak force of the first contact [N].")
    time_of_peak = property(lambda self: self.result.time_of_peak, doc="Time of the peak force [s] from first contact.")
    contact_duration = property(lambda self: self.result.contact_duration, doc="Duration of the first contact [s] (nan: not separated).")
    impulse = property(lambda self: self.result.impulse, doc="Impulse of the first contact [N·s].")
    time = property(lambda self: self.result.time, doc="Time [s], (n_steps + 1,).")
    force = property(lambda self: self.result.force, doc="Contact force [N], compression +, (n_steps + 1,).")

    @property
    def strain(self) -> dict:
        """Gauge strain histories by gauge name, each (n_steps + 1,), tension +."""
        strain = dict(zip(self.result.strain_names, self.result.strain))  # the gauges only: the damage strains are another output group
        _read_only(strain)
        return strain

    def inputs(self):
        return tuple(self.case_files)

    def files(self, figures: bool = True):
        """The files of ``softimpact impact`` (history.csv, summary.json, figures), by name."""
        from ..output.impact import impact_files

        return impact_files(self.problem, self.result, figures, model=self.model, summary=self.run_summary, units=self.units)

    def to_frame(self):
        """The histories of history.csv as a pandas DataFrame indexed by time [s]; units in ``df.attrs["units"]``.

        pandas rather than xarray: one dimension (time), and users know it (the ``table`` extra)."""
        from ..output.impact import impact_columns

        cols = impact_columns(self.result)
        return _frame(cols, {k: _unit_of(k) for k in cols})

    def plot(self, ax=None):
        """The contact force against time, in the problem's display units; returns the matplotlib Axes."""
        from ..units import display

        ax = _axes(ax)
        fu, tu = display(self.units, "force"), display(self.units, "time")
        ax.plot(self.time * tu.factor, self.force * fu.factor)
        ax.set_xlabel(f"time [{tu.label}]")
        ax.set_ylabel(f"contact force [{fu.label}]")
        return ax

    def write_fields(self, path, *, frames: int = 200):
        """Displacement fields of the target over time as XDMF for ParaView (:func:`softimpact.output.fields.write_fields`).

        Parameters
        ----------
        path : str or Path
            The .xdmf file; its heavy data go beside it with the suffix .h5.
        frames : int
            At most this many time steps, evenly sampled (every k-th step).

        Returns
        -------
        numpy.ndarray
            The step indices written.
        """
        from ..output.fields import write_fields

        return write_fields(path, self.model, self._snapshots(frames))

    def _snapshots(self, frames: int):
        """The frames of the fields: from the run if it kept them, else from the case run again through
        :func:`~softimpact.cases.run.execute` (the one run path the command's ``--fields`` takes) on the same model."""
        from ..cases.run import execute
        from ..output.fields import keeps, kept_frames, sampled_steps

        steps = sampled_steps(self.problem.solver.steps, frames)
        if keeps(self.result, steps):
            return kept_frames(self.result, steps)
        run = execute(self.problem, fields=True, frames=frames, model=self.model, damage=False, energy=False)
        return kept_frames(run.result, run.kept)


@dataclass(frozen=True)
class _Prescribed(_Written):
    """What a beam and a plate result share: a structure under a prescribed force history."""

    problem: object
    result: object
    model: object = field(repr=False, compare=False, default=None)
    case_files: tuple = field(repr=False, default=())
    warnings: tuple = field(repr=False, compare=False, default=())
    run_summary: dict = field(repr=False, compare=False, default=None)  # summary.json's content (cases.run.Run.summary)
    units: str = field(repr=False, default="in-lbf-s")  # the display system of figures and tables (a case's ``units``): the numbers stay SI

    def __post_init__(self):
        _read_only(self.result)

    time = property(lambda self: self.result.time, doc="Time [s], (n_steps + 1,).")
    force = property(lambda self: self.result.force, doc="Applied force [N], (n_steps + 1,).")

    @property
    def strain(self) -> dict:
        """Gauge strain histories by gauge name, each (n_steps + 1,), tension +."""
        return {g.name: eps for g, eps in zip(self.problem.gauges, self.result.strain)}

    def inputs(self):
        return tuple(self.case_files)


@dataclass(frozen=True)
class BeamResult(_Prescribed):
    """A beam under a prescribed force history (:func:`run` of a beam case; ``softimpact beam``).

    Parameters
    ----------
    problem : softimpact.workflows.beam_impact.BeamProblem
        Every input in SI.
    result : softimpact.workflows.beam_impact.BeamResult
        time [s], force [N], strain (n_gauges, n_steps + 1), deflection [m], displacement.
    model : StructureModel, optional
        The assembled model that ran (reused by ``write_fields``).
    case_files : tuple of Path
        The case files read (never overwritten by ``write``).
    warnings : tuple of str
        The run's :class:`~softimpact.errors.SoftimpactWarning` s, one line each (already warned at
        the call; listed in manifest.json by ``write``, as the command line lists them).
    """

    command = "softimpact beam"

    def files(self, figures: bool = True):
        """The files of ``softimpact beam``, by name."""
        from ..output.beam import beam_files

        return beam_files(self.model, self.result, figures, summary=self.run_summary, units=self.units)

    def to_frame(self):
        """Force and gauge strains as a pandas DataFrame indexed by time [s]; units in ``df.attrs["units"]``."""
        cols = {"time_s": self.time, "force_N": self.force, **{f"strain_{k}": v for k, v in self.strain.items()}}
        return _frame(cols, {k: _unit_of(k) for k in cols})

    def plot(self, ax=None):
        """The gauge strains against time [µs, µε]; returns the matplotlib Axes."""
        ax = _axes(ax)
        for name, eps in self.strain.items():
            ax.plot(self.time * 1e6, eps * 1e6, label=name)
        ax.set_xlabel("time [µs]")
        ax.set_ylabel("strain [µε]")
        ax.legend()
        return ax

    def write_fields(self, path, *, frames: int = 200):
        """Displacement fields over time as XDMF for ParaView; see :meth:`ImpactResult.write_fields`."""
        from ..cases.run import execute
        from ..output.fields import sampled_steps, write_fields

        steps, result = sampled_steps(self.problem.solver.steps, frames), self.result
        if result.displacement is None:  # a run without its displacement: the case again, as ``--fields`` runs it
            run = execute(self.problem, fields=True, frames=frames, model=self.model, energy=False)
            steps, result = run.kept, run.result
        return write_fields(path, self.model, (steps, result.time[steps], result.displacement[:, steps]))


@dataclass(frozen=True)
class PlateResult(_Prescribed):
    """A plate under a prescribed force history (:func:`run` of a plate case; ``softimpact plate``).

    Parameters
    ----------
    problem : softimpact.workflows.plate.PlateProblem
        Every input in SI.
    result : softimpact.workflows.plate.PlateResult
        time [s], force [N], strain (n_gauges, n_steps + 1), deflection [m] (impact point first).
    model : StructureModel, optional
        The assembled model that ran (reused by ``write_fields``).
    case_files : tuple of Path
        The case files read (never overwritten by ``write``).
    warnings : tuple of str
        The run's :class:`~softimpact.errors.SoftimpactWarning` s, one line each (already warned at
        the call; listed in manifest.json by ``write``, as the command line lists them).
    """

    command = "softimpact plate"

    def files(self, figures: bool = True):
        """The files of ``softimpact plate``, by name."""
        from ..output.plate import plate_files

        return plate_files(self.model, self.result, figures, self.run_summary, units=self.units)

    def to_frame(self):
        """Force, deflection under the load and gauge strains, indexed by time [s]; units in ``df.attrs["units"]``."""
        cols = {"time_s": self.time, "force_N": self.force, "deflection_m": self.result.deflection[0], **{f"strain_{k}": v for k, v in self.strain.items()}}
        return _frame(cols, {k: _unit_of(k) for k in cols})

    def plot(self, ax=None):
        """The deflection under the load against time [µs, mm]; returns the matplotlib Axes."""
        ax = _axes(ax)
        ax.plot(self.time * 1e6, self.result.deflection[0] * 1e3)
        ax.set_xlabel("time [µs]")
        ax.set_ylabel("deflection under the load [mm]")
        return ax

    def write_fields(self, path, *, frames: int = 200):
        """Displacement fields over time as XDMF for ParaView; see :meth:`ImpactResult.write_fields`."""
        from ..cases.run import execute
        from ..output.fields import keeps, kept_frames, sampled_steps, write_fields

        steps = sampled_steps(self.problem.solver.steps, frames)
        if keeps(self.result, steps):
            return write_fields(path, self.model, kept_frames(self.result, steps))
        run = execute(self.problem, fields=True, frames=frames, model=self.model, energy=False)  # as ``--fields`` runs it
        return write_fields(path, self.model, kept_frames(run.result, run.kept))


@dataclass(frozen=True)
class StaticPlateResult(_Written):
    """A plate under a uniform pressure, solved statically (:func:`press`; :func:`run` of a plate case with
    ``[solver] analysis = "static"``; ``softimpact plate`` on it).

    Parameters
    ----------
    problem : softimpact.workflows.plate.PlateProblem
        Every input in SI (``pressure`` [Pa], ``load_steps``, ``kinematics``, ``in_plane``).
    result : softimpact.workflows.plate.PlateStaticResult
        Per load step the pressure [Pa], the largest deflection [m], Newton's iterations and residuals.
    model : PlateVK, optional
        The assembled plate that ran.
    case_files : tuple of Path
        The case files read (never overwritten by ``write``).
    warnings : tuple of str
        The run's :class:`~softimpact.errors.SoftimpactWarning` s, one line each.
    """

    problem: object
    result: object = field(repr=False)  # its final displacement is the whole plate's: not for a repr
    model: object = field(repr=False, compare=False, default=None)
    case_files: tuple = field(repr=False, default=())
    warnings: tuple = field(repr=False, compare=False, default=())
    run_summary: dict = field(repr=False, compare=False, default=None)  # summary.json's content (cases.run.Run.summary)
    units: str = field(repr=False, default="in-lbf-s")  # the display system of the written summary: the numbers stay SI
    command = "softimpact plate"

    def __post_init__(self):
        _read_only(self.result)

    max_deflection = property(
        lambda self: float(self.result.max_deflection[-1]), doc="Largest transverse deflection of the mid-surface [m] at the full pressure."
    )
    converged = property(lambda self: bool(self.result.converged), doc="Whether Newton converged at every load step.")

    def inputs(self):
        return tuple(self.case_files)

    def files(self, figures: bool = True):
        """summary.json of ``softimpact plate`` on a static case (no history, no figures)."""
        from ..output.plate import plate_static_files

        return plate_static_files(self.run_summary, self.units)

    def to_frame(self):
        """Pressure, largest deflection and Newton iterations per load step, indexed by the step (1, 2, …); units in ``df.attrs["units"]``."""
        import numpy as np

        r = self.result
        cols = {
            "load_step": np.arange(1, r.pressure.size + 1),
            "pressure_Pa": r.pressure,
            "max_deflection_m": r.max_deflection,
            "newton_iterations": r.iterations,
        }
        return _frame(cols, {"load_step": "1", "pressure_Pa": "Pa", "max_deflection_m": "m", "newton_iterations": "1"}, index="load_step")

    def plot(self, ax=None):
        """The largest deflection against the pressure, from the unloaded plate through each load step, in the display
        units (in-lbf-s: psi and in; SI: kPa and mm); returns the matplotlib Axes."""
        import numpy as np

        from ..units import display

        if self.units == "SI":
            (pf, pl), (wf, wl) = (1e-3, "kPa"), (1e3, "mm")
        else:
            p, w = display(self.units, "stress"), display(self.units, "length")
            (pf, pl), (wf, wl) = (p.factor, p.label), (w.factor, w.label)
        ax = _axes(ax)
        q = np.concatenate(([0.0], self.result.pressure))
        w = np.concatenate(([0.0], self.result.max_deflection))
        ax.plot(q * pf, w * wf, "o-", label=self.result.kinematics)
        ax.set_xlabel(f"pressure [{pl}]")
        ax.set_ylabel(f"largest deflection [{wl}]")
        ax.set_title(self.problem.title or "uniform pressure, static")
        ax.legend()
        return ax


@dataclass(frozen=True)
class BarResult(_Written):
    """A sphere on the instrumented bar (:func:`impact` on a :class:`Bar`, :func:`run` of a bar case).

    Parameters
    ----------
    problem : softimpact.workflows.bar_impact.BarImpactProblem
        Every input in SI.
    result : softimpact.workflows.bar_impact.BarImpactResult
        The coupled run (contact force [N], gauge strains, …).
    plain : BarImpactResult, optional
        The same run without the end cap.
    inferred : (numpy.ndarray, numpy.ndarray, str), optional
        Time [s], force [N] read from the first gauge, and its name.
    case_files : tuple of Path
        The case files read.
    warnings : tuple of str
        The run's :class:`~softimpact.errors.SoftimpactWarning` s, one line each (already warned at
        the call; listed in manifest.json by ``write``, as the command line lists them).
    """

    problem: object
    result: object
    plain: object = field(repr=False, default=None)
    inferred: object = field(repr=False, default=None)
    case_files: tuple = field(repr=False, default=())
    warnings: tuple = field(repr=False, compare=False, default=())
    units: str = field(repr=False, default="in-lbf-s")  # the display system of figures and tables (a case's ``units``): the numbers stay SI
    command = "softimpact bar"

    def __post_init__(self):
        _read_only((self.result, self.plain, self.inferred))

    peak_force = property(lambda self: self.result.peak_force, doc="Peak contact force [N].")
    time_of_peak = property(lambda self: self.result.time_of_peak, doc="Time of the peak force [s].")
    contact_duration = property(lambda self: self.result.contact_duration, doc="Contact duration [s].")
    time = property(lambda self: self.result.time, doc="Time [s], (n_steps + 1,).")
    force = property(lambda self: self.result.force, doc="Contact force [N], (n_steps + 1,).")

    @property
    def strain(self) -> dict:
        """Gauge strain histories by gauge name, each (n_steps + 1,)."""
        return dict(zip(self.result.strain_names, self.result.strain))

    def inputs(self):
        return tuple(self.case_files)

    def files(self, figures: bool = True):
        """The files of ``softimpact bar``, by name."""
        from ..output.bar import bar_files

        return bar_files(self.result, self.plain, self.inferred, figures, units=self.units)

    def to_frame(self):
        """Contact force and gauge strains indexed by time [s]; units in ``df.attrs["units"]``."""
        cols = {"time_s": self.time, "contact_force_N": self.force, **{f"strain_{k}": v for k, v in self.strain.items()}}
        return _frame(cols, {k: _unit_of(k) for k in cols})

    def plot(self, ax=None):
        """The contact force against time [µs, N]; returns the matplotlib Axes."""
        ax = _axes(ax)
        ax.plot(self.time * 1e6, self.force)
        ax.set_xlabel("time [µs]")
        ax.set_ylabel("contact force [N]")
        return ax


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
        from ..gates import status

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
