"""The results of a beam or plate under a prescribed load (:class:`BeamResult`, :class:`PlateResult`) and of a
static plate (:class:`StaticPlateResult`)."""

from __future__ import annotations

from dataclasses import dataclass, field

from ._written import _axes, _frame, _read_only, _unit_of, _Written


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
        from ...output.beam import beam_files

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
        from ...cases.run import execute
        from ...output.fields import sampled_steps, write_fields

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
        from ...output.plate import plate_files

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
        from ...cases.run import execute
        from ...output.fields import keeps, kept_frames, sampled_steps, write_fields

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
        from ...output.plate import plate_static_files

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

        from ...units import display

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
