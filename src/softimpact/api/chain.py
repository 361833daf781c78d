"""The chain of the paper in the notebook API: each function wraps its command's own function
(:mod:`softimpact.app`) and returns a :class:`~softimpact.api.results.CommandResult` — :func:`reduce`,
:func:`fit`, :func:`predict`, :func:`identify`, :func:`calibrate`, :func:`converge`, :func:`sweep` —
and :func:`read_record` reads one channel of a lab record."""

from __future__ import annotations

import warnings
from pathlib import Path

from ..errors import SoftimpactWarning
from ._edge import _Heard, _one_line, _text
from .results import CommandResult, Record

__all__ = ["reduce", "fit", "predict", "identify", "calibrate", "converge", "sweep", "read_record"]


def _command(command: str, call) -> CommandResult:
    """``call()``, an app command's :class:`~softimpact.app.Outcome`, as a CommandResult: the warnings raised
    while it ran kept and warned again at the user's line, then the outcome's own warnings warned (the
    command line shows both, in this order)."""
    with _Heard() as heard:
        outcome = call()
    with _Heard():
        for text in outcome.warnings:
            warnings.warn(_one_line(text), SoftimpactWarning, stacklevel=1)
    return CommandResult(command, outcome, tuple(heard.texts))


def reduce(series, *, figures: bool = True) -> CommandResult:
    """Reduce the bar strain records of a series to force histories and eq-15 pulse parameters (Fig 7).

    Parameters
    ----------
    series : str or Path
        A series file or a built-in series name (quantities with their units inside).
    figures : bool
        Draw the figures.

    Returns
    -------
    CommandResult
        ``table("tests.csv")``: per test peak force [N], times [s], impulse [N·s]; the files of
        ``softimpact reduce``.

    Raises
    ------
    softimpact.errors.InputError
        A missing or unreadable record.

    Examples
    --------
    >>> import softimpact as si
    >>> res = si.reduce("paper-silicone", figures=False)  # doctest: +SKIP
    """
    from ..app.series import reduce as command

    return _command("softimpact reduce", lambda: command(series_name=str(series), figures=figures))


def fit(series, *, figures: bool = True) -> CommandResult:
    """Reduce a series, then fit the scaling constants α1–α4 of eqs (4)–(7) (Table I).

    Parameters
    ----------
    series : str or Path
        A series file or a built-in series name.
    figures : bool
        Draw the figures (Figs 8–11).

    Returns
    -------
    CommandResult
        ``json("scaling.json")``: the constants (dimensionless exponents, SI prefactors).

    Raises
    ------
    softimpact.errors.InputError
        A missing or unreadable record.

    Examples
    --------
    >>> import softimpact as si
    >>> si.fit("paper-silicone").json("scaling.json")  # doctest: +SKIP
    """
    from ..app.series import fit as command

    return _command("softimpact fit", lambda: command(series_name=str(series), figures=figures))


def predict(
    *,
    velocity,
    projectile: str | None = None,
    mass=None,
    diameter=None,
    model: str = "empirical",
    constants: str | None = None,
    group: str = "pooled",
    tail: bool = False,
    material: str = "silicone rubber",
    target: str = "Al 6061-T6",
    bar: str | None = None,
    beam: str | None = None,
    units: str = "in-lbf-s",
    figures: bool = True,
) -> CommandResult:
    """Force history of a projectile at a velocity: the empirical model (eqs 4–7, 15), Hertz or Wilbeck.

    Parameters
    ----------
    velocity : str or pint.Quantity
        Impact velocity [velocity], e.g. ``"1166 in/s"``.
    projectile : str, optional
        A named projectile (``"rubber-1/2in"``), or give ``mass`` and ``diameter``.
    mass : str or pint.Quantity, optional
        Projectile mass [mass].
    diameter : str or pint.Quantity, optional
        Projectile diameter [length].
    model : str
        ``"empirical"``, ``"hertz"`` or ``"wilbeck"``.
    constants : str, optional
        Scaling constants: a preset or a scaling.json path.
    group : str
        Group of a scaling.json.
    tail : bool
        Empirical model: add the tail carrying the rest of eq (7)'s impulse.
    material, target : str
        Projectile and target materials (hertz, wilbeck).
    bar, beam : str, optional
        A bar or beam case driven by the predicted force.
    units : str
        Display units of the line and figure.
    figures : bool
        Draw the figure.

    Returns
    -------
    CommandResult
        ``table("history.csv")``: time_s and force_N (and strains); ``summary()``: peak force [N], …

    Raises
    ------
    softimpact.errors.InputError
        A missing unit, an unknown projectile or preset.

    Examples
    --------
    >>> import softimpact as si
    >>> res = si.predict(projectile="rubber-1/2in", velocity="1166 in/s", figures=False)
    >>> 100 < res.summary()["peak_force_N"] < 400  # N: Table II gives 44 lbf = 196 N
    True
    """
    from ..app.predict import predict as command

    outcome = lambda: command(  # noqa: E731
        projectile=projectile,
        mass=_text(mass, "mass", "mass"),
        diameter=_text(diameter, "length", "diameter"),
        velocity=_text(velocity, "velocity", "velocity"),
        model=model,
        constants=constants,
        group=group,
        tail=tail,
        material=material,
        target=target,
        bar_case=bar,
        beam_case=beam,
        system=units,
        figures=figures,
    )
    return _command("softimpact predict", outcome)


def identify(series, *, figures: bool = True) -> CommandResult:
    """Identify a soft projectile's contact law from a series of bar tests (law.json).

    Parameters
    ----------
    series : str or Path
        A series file or a built-in series name.
    figures : bool
        Draw the figures.

    Returns
    -------
    CommandResult
        ``json("law.json")``: the law's parameters (SI) and the range identified on; pass
        the written law.json as ``law=`` to :func:`impact`.

    Raises
    ------
    softimpact.errors.InputError
        A missing or unreadable record.

    Examples
    --------
    >>> import softimpact as si
    >>> si.identify("paper-silicone").json("law.json")  # doctest: +SKIP
    """
    from ..app.identify import identify as command

    return _command("softimpact identify", lambda: command(series_name=str(series), figures=figures))


def calibrate(
    case,
    *,
    measured=None,
    velocity=None,
    method: str = "least-squares",
    contact_radius=None,
    contact_time=None,
    fit_radius: bool = False,
    projectile: str = "rubber-1/2in",
    constants: str | None = None,
    budget: float = 20.0,
    figures: bool = True,
) -> CommandResult:
    """Force history that makes a beam's computed gauge strains match measured ones.

    Parameters
    ----------
    case : str or Path
        A beam case (with ``measured`` and ``velocity``) or a calibration series.
    measured : str or Path, optional
        CSV of measured strains: ``time_s`` and ``strain_<gauge>`` columns.
    velocity : str or pint.Quantity, optional
        Impact velocity [velocity].
    method : str
        ``"least-squares"`` (eq 15), ``"paper"`` or ``"deconvolve"``.
    contact_radius : str or pint.Quantity, optional
        r0 [length] (default the case's).
    contact_time : str or pint.Quantity, optional
        First contact on the record's clock [time].
    fit_radius : bool
        Least squares: fit r0 too.
    projectile, constants : str
        The bar-model start.
    budget : float
        Seconds that refining the model may cost.
    figures : bool
        Draw the figures.

    Returns
    -------
    CommandResult
        ``json("calibration.json")``: the fitted pulse (N, s) and its standard errors.

    Raises
    ------
    softimpact.errors.InputError
        A missing file or unit.

    Examples
    --------
    >>> import softimpact as si
    >>> si.calibrate("paper-calibration-series")  # doctest: +SKIP
    """
    from ..app.calibrate import calibrate_command

    outcome = lambda: calibrate_command(  # noqa: E731
        case=str(case),
        measured=None if measured is None else str(measured),
        velocity=_text(velocity, "velocity", "velocity"),
        method=method,
        contact_radius=_text(contact_radius, "length", "contact_radius"),
        contact_time=_text(contact_time, "time", "contact_time"),
        fit_radius=fit_radius,
        projectile=projectile,
        constants=constants,
        figures=figures,
        budget=budget,
    )
    return _command("softimpact calibrate", outcome)


def converge(case, *, levels: int = 3, ratio: int = 2, history: int | None = None, figures: bool = True) -> CommandResult:
    """Discretisation error of a bar, beam, plate or impact case by systematic refinement (Richardson).

    Parameters
    ----------
    case : str or Path
        A case file or built-in name.
    levels : int
        Number of discretisations (2 to 5): the case's own, then refined by ``ratio`` each.
    ratio : int
        Refinement ratio between levels (elements × ratio, time step / ratio).
    history : int, optional
        Beam cases: row N of the case's ``[[load.table]]``.
    figures : bool
        Draw the figures.

    Returns
    -------
    CommandResult
        ``table("convergence.csv")``: per output the observed order, values (SI, unit-suffixed
        names), extrapolation, GCI.

    Raises
    ------
    softimpact.errors.InputError
        A bad case or a refinement too large for the machine.

    Examples
    --------
    >>> import softimpact as si
    >>> si.converge("paper-calibration", levels=2)  # doctest: +SKIP
    """
    from ..app.converge import converge as command

    return _command("softimpact converge", lambda: command(case=str(case), levels=levels, ratio=ratio, history=history, figures=figures))


def sweep(spec, *, out, workers: int | None = 0, scheduler: str | None = None, figures: bool = True) -> CommandResult:
    """Grids and Monte Carlo runs of a case as a sweep spec says, locally or on Dask.

    Parameters
    ----------
    spec : str or Path
        A sweep spec file (TOML).
    out : str or Path
        Folder of the checkpoints (``out/checkpoints``): the same call resumes where it stopped.
        The spec's quantities carry their units; the results are SI.
    workers : int, optional
        Local Dask worker processes; 0 (default here): a plain loop, no Dask; None: the machine's cores.
    scheduler : str, optional
        Address of a running Dask scheduler.
    figures : bool
        Draw the figures.

    Returns
    -------
    CommandResult
        ``outcome.files["runs.parquet"]`` (a row per run) and ``summary()`` (statistics).

    Raises
    ------
    softimpact.errors.InputError
        A bad spec.

    Examples
    --------
    >>> import softimpact as si
    >>> si.sweep("my-sweep.toml", out="sweep-out")  # doctest: +SKIP
    """
    from ..app.sweep import sweep as command

    return _command("softimpact sweep", lambda: command(spec=str(spec), out_dir=str(out), workers=workers, scheduler=scheduler, figures=figures))


def read_record(path, *, channel: str | int | None = None) -> Record:
    """Read one channel of a lab record file (TDMS, MAT, HDF5, CSV, Tektronix, …).

    Parameters
    ----------
    path : str or Path
        The record file; its format is detected from extension and first bytes.
    channel : str or int, optional
        A channel name (``"group/channel"`` or ``"channel"``), an index, or None for a file of one channel.

    Returns
    -------
    Record
        ``time`` [s], ``signal`` in ``unit`` (V, strain, microstrain, …), ``metadata``.

    Raises
    ------
    softimpact.errors.InputError
        An unreadable file, an unknown channel, no time base.

    Examples
    --------
    >>> import softimpact as si
    >>> rec = si.read_record("scope.csv", channel="CH1")  # doctest: +SKIP
    """
    from ..input.records import read_lab_record

    r = read_lab_record(Path(path), channel)
    return Record(r.time, r.signal, r.unit, dict(r.metadata))
