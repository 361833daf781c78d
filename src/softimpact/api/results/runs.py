"""The results of a coupled impact (:class:`ImpactResult`) and of a bar run (:class:`BarResult`)."""

from __future__ import annotations

from dataclasses import dataclass, field

from ._written import _axes, _frame, _read_only, _unit_of, _Written


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
        from ...output.impact import impact_files

        return impact_files(self.problem, self.result, figures, model=self.model, summary=self.run_summary, units=self.units)

    def to_frame(self):
        """The histories of history.csv as a pandas DataFrame indexed by time [s]; units in ``df.attrs["units"]``.

        pandas rather than xarray: one dimension (time), and users know it (the ``table`` extra)."""
        from ...output.impact import impact_columns

        cols = impact_columns(self.result)
        return _frame(cols, {k: _unit_of(k) for k in cols})

    def plot(self, ax=None):
        """The contact force against time, in the problem's display units; returns the matplotlib Axes."""
        from ...units import display

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
        from ...output.fields import write_fields

        return write_fields(path, self.model, self._snapshots(frames))

    def _snapshots(self, frames: int):
        """The frames of the fields: from the run if it kept them, else from the case run again through
        :func:`~softimpact.cases.run.execute` (the one run path the command's ``--fields`` takes) on the same model."""
        from ...cases.run import execute
        from ...output.fields import keeps, kept_frames, sampled_steps

        steps = sampled_steps(self.problem.solver.steps, frames)
        if keeps(self.result, steps):
            return kept_frames(self.result, steps)
        run = execute(self.problem, fields=True, frames=frames, model=self.model, damage=False, energy=False)
        return kept_frames(run.result, run.kept)


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
        from ...output.bar import bar_files

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
