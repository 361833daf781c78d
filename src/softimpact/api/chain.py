"""The chain of the paper in the notebook API: each function wraps its command's own function
(:mod:`softimpact.app`) and returns a :class:`~softimpact.api.results.CommandResult` — :func:`reduce`,
:func:`fit`, :func:`predict`, :func:`identify`, :func:`calibrate`, :func:`converge`, :func:`sweep` —
and :func:`read_record` reads one channel of a lab record."""

from __future__ import annotations

import warnings
from pathlib import Path

from ..app.options import CALIBRATE, CALIBRATE_BAR, CONVERGE, IDENTIFY, PREDICT, SERIES, SHPB, SWEEP
from ..errors import SoftimpactWarning
from ._edge import _Heard, _one_line, keywords
from ._options import given, python_terms, takes
from .results import CommandResult, Record

__all__ = ["reduce", "fit", "predict", "identify", "calibrate", "converge", "sweep", "read_record", "catalogue", "calibrate_bar", "shpb"]


def _command(command: str, call, table=()) -> CommandResult:
    """``call()``, an app command's :class:`~softimpact.app.Outcome`, as a CommandResult: the warnings raised
    while it ran kept and warned again at the user's line, then the outcome's own warnings warned (the
    command line shows both, in this order); its errors name the keywords of ``table`` (:func:`python_terms`)."""
    with _Heard() as heard, python_terms(table):
        outcome = call()
    with _Heard():
        for text in outcome.warnings:
            warnings.warn(_one_line(text), SoftimpactWarning, stacklevel=1)
    return CommandResult(command, outcome, tuple(heard.texts))


@takes(SERIES, "series")
def reduce(series, **options) -> CommandResult:
    """Reduce the bar strain records of a series to force histories and eq-15 pulse parameters (Fig 7).

    Parameters
    ----------
    series : str or Path
        A series file or a built-in series name (quantities with their units inside).
    {options}

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
    >>> res = si.reduce("paper-rubber-series", figures=False)
    >>> test = res.table("tests.csv").iloc[0]  # the 1/2-in ball at 1000 in/s
    >>> m, d, V = test["mass_kg"], test["diameter_m"], test["velocity_m_s"]
    >>> round(float(test["peak_force_N"] / (m * V**2 / (2 * d))), 1)  # alpha1 of eq (4); Table I: 4.25 for 1/2 in
    4.3
    """
    from ..app.series import reduce as command

    given_ = given(reduce, options)
    return _command("softimpact reduce", lambda: command(series_name=str(series), **given_), SERIES)


@takes(SERIES, "series")
def fit(series, **options) -> CommandResult:
    """Reduce a series, then fit the scaling constants α1–α4 of eqs (4)–(7) (Table I).

    Parameters
    ----------
    series : str or Path
        A series file or a built-in series name.
    {options}

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
    >>> alphas = si.fit("paper-rubber-series", figures=False).json("scaling.json")["groups"]["0.375 in"]
    >>> round(alphas["alpha1"]["value"], 1), round(alphas["alpha2"]["value"], 2)  # Table I, 3/8 in: 4.00, 1.03
    (4.0, 1.03)
    """
    from ..app.series import fit as command

    given_ = given(fit, options)
    return _command("softimpact fit", lambda: command(series_name=str(series), **given_), SERIES)


@takes(PREDICT)
def predict(**options) -> CommandResult:
    """Force history of a projectile at a velocity: the empirical model (eqs 4–7, 15), Hertz or Wilbeck.

    Parameters
    ----------
    {options}

    Returns
    -------
    CommandResult
        ``table("history.csv")``: time_s and force_N (and strains); ``summary()``: peak force [N], …

    Raises
    ------
    softimpact.errors.InputError
        A missing unit, an unknown projectile or preset (before anything is computed).

    Examples
    --------
    >>> import softimpact as si
    >>> res = si.predict(projectile="rubber-1/2in", velocity="1166 in/s", figures=False)
    >>> 100 < res.summary()["peak_force_N"] < 400  # N: Table II gives 44 lbf = 196 N
    True
    """
    from ..app.predict import predict as command

    given_ = given(predict, options)
    return _command("softimpact predict", lambda: command(**given_), PREDICT)


@takes(IDENTIFY, "series")
def identify(series, **options) -> CommandResult:
    """Identify a soft projectile's contact law from a series of bar tests (law.json): the visco-elastic
    soft law, or with ``law="crushing"`` an ice sphere's crushing strength law (its strength at a reference
    rate and its rate exponent, law.json's family "crushing").

    Parameters
    ----------
    series : str or Path
        A series file or a built-in series name.
    {options}

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
    >>> law = si.identify("paper-rubber-series", figures=False).json("law.json")
    >>> law["family"], [round(v / 0.0254) for v in law["identified_on"]["velocity_m_s"]]  # in/s: the series' tests
    ('soft-projectile', [1000, 5000])
    """
    from ..app.identify import identify as command

    given_ = given(identify, options)
    return _command("softimpact identify", lambda: command(series_name=str(series), **given_), IDENTIFY)


@takes(CALIBRATE, "case")
def calibrate(case, **options) -> CommandResult:
    """Force history that makes a beam's computed gauge strains match measured ones.

    Parameters
    ----------
    case : str or Path
        A beam case (with ``measured`` and ``velocity``) or a calibration series.
    {options}

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
    >>> from pathlib import Path
    >>> record = Path(si.__file__).parent / "data" / "series" / "paper-long-calibration" / "long-V1166.csv"
    >>> res = si.calibrate("paper-long-beam", measured=record, velocity="1166 in/s", budget=0, figures=False)
    >>> round(res.json("calibration.json")["tests"][0]["peak_force_N"] / 4.4482216152605)  # lbf; Table II, history 1: 44 lbf
    44
    """
    from ..app.calibrate import calibrate_command

    given_ = given(calibrate, options)
    return _command("softimpact calibrate", lambda: calibrate_command(case=str(case), **given_), CALIBRATE)


@takes(CONVERGE, "case")
def converge(case, **options) -> CommandResult:
    """Discretisation error of a bar, beam, plate or impact case by systematic refinement (Richardson).

    Parameters
    ----------
    case : str or Path
        A case file or built-in name.
    {options}

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
    >>> res = si.converge("paper-calibration", levels=2, figures=False)
    >>> "observed_order" in res.table("convergence.csv").columns
    True
    """
    from ..app.converge import converge as command

    given_ = given(converge, options)
    return _command("softimpact converge", lambda: command(case=str(case), **given_), CONVERGE)


@takes(SWEEP, "spec")
def sweep(spec, *, out, **options) -> CommandResult:
    """Grids and Monte Carlo runs of a case as a sweep spec says, locally or on Dask (by default on the
    machine's cores, as ``softimpact sweep``: a sweep is many independent runs; ``workers=0`` runs a plain loop).

    Parameters
    ----------
    spec : str or Path
        A sweep spec file (TOML).
    out : str or Path
        Folder of the checkpoints (``out/checkpoints``): the same call resumes where it stopped.
        The spec's quantities carry their units; the results are SI.
    {options}

    Returns
    -------
    CommandResult
        ``outcome.files["runs.parquet"]`` (a row per run) and ``summary()`` (statistics). With a threshold
        (a level ``threshold_against`` names, or the velocity level, and a damage index or an output with a limit
        in ``[sweep.limits]``): ``table("thresholds.csv")`` and ``summary()["thresholds"]``
        (``threshold_<quantity>_median_<unit>``, its 5-95 % band, ``limit``, ``runs_outside_validity``); with a
        ``damage.*`` size (or the spec's ``onset`` list): ``table("onsets.csv")`` and ``summary()["onsets"]``
        (``onset_<quantity>_median_<unit>`` and its bracket).

    Raises
    ------
    softimpact.errors.InputError
        A bad spec.

    Examples
    --------
    >>> import softimpact as si
    >>> import tempfile
    >>> from pathlib import Path
    >>> folder = Path(tempfile.mkdtemp())
    >>> _ = (folder / "spec.toml").write_text('''
    ... [sweep]
    ... case = "paper-calibration"
    ... method = "grid"
    ... outputs = ["peak_force_N"]
    ... [[sweep.parameter]]
    ... key = "projectile.velocity"
    ... values = ["40 in/s", "80 in/s"]
    ... [[sweep.parameter]]
    ... key = "solver.duration"
    ... value = "120 us"
    ... [[sweep.parameter]]
    ... key = "output.snapshots"
    ... value = ["60 us"]
    ... ''')
    >>> res = si.sweep(folder / "spec.toml", out=folder / "out", workers=0, figures=False)  # a plain loop: two runs need no Dask
    >>> import io
    >>> import pyarrow.parquet as pq
    >>> peaks = pq.read_table(io.BytesIO(res.outcome.files["runs.parquet"])).column("peak_force_N").to_pylist()
    >>> 2.0 <= peaks[1] / peaks[0] <= 2.3  # doubling V: F0 ~ V (the bar's impedance) to V^1.2 (Hertz, a rigid end)
    True
    """
    from ..app.sweep import sweep as command

    given_ = given(sweep, options)
    return _command("softimpact sweep", lambda: command(spec=str(spec), out_dir=str(out), **given_), SWEEP)


@keywords("si.read_record")
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
    >>> from pathlib import Path
    >>> rec = si.read_record(Path(si.__file__).parent / "data" / "series" / "paper-rubber-series" / "1_2in-1000.csv")
    >>> rec.unit, bool(rec.time[-1] < 1e-2)  # the file's µs read as seconds
    ('microstrain', True)
    """
    from ..input.records import read_lab_record

    r = read_lab_record(Path(path), channel)
    return Record(r.time, r.signal, r.unit, dict(r.metadata))


@keywords("si.catalogue")
def catalogue():
    """The catalogue: every named material, ply, projectile, projectile material, set of scaling constants,
    contact law and built-in case (the tables of ``softimpact catalogue`` and of the docs' catalogue page).

    Returns
    -------
    softimpact.app.catalogue.Catalogue
        Frozen; one :class:`~softimpact.app.catalogue.Table` per attribute (``materials``, ``plies``,
        ``projectiles``, ``projectile_materials``, ``scaling_constants``, ``contact_laws``, ``cases``), each
        with its ``columns``, their SI ``units`` and one tuple per entry in ``rows`` (its name first, its
        source last); ``to_frame(name)`` gives a table as a pandas DataFrame.

    Examples
    --------
    >>> import softimpact as si
    >>> cat = si.catalogue()
    >>> "steel" in cat.materials.names
    True
    """
    from ..app.catalogue import catalogue as build

    return build()


@takes(CALIBRATE_BAR, "calibration")
def calibrate_bar(calibration, **options) -> CommandResult:
    """Calibrate a lab's bar from its records: the wave speed c0 [m/s] from the echoes, Poisson's ratio from their
    dispersion, the gauge's position [m] and its gauge factor from known impacts, each with its 95 % interval.

    Parameters
    ----------
    calibration : str or Path
        A calibration file (the bar as known, its gauge and bridge, the shots) or a built-in name.
    {options}

    Returns
    -------
    CommandResult
        ``json("calibration.json")``: each constant (SI) with its 95 % half-width and its fit's residual;
        ``files()["bar.toml"]``: the bar file that bar cases and series read (``[bar] file = "bar.toml"``).

    Raises
    ------
    softimpact.errors.InputError
        A missing or unreadable record, or one without an echo to time.

    Examples
    --------
    >>> import softimpact as si
    >>> c = si.calibrate_bar("lab-bar-calibration", figures=False).json("calibration.json")["constants"]
    >>> abs(c["wave_speed_m_s"]["value"] - 5097.77) <= c["wave_speed_m_s"]["ci95_half_width"]  # the synthetic bar's hidden c0
    True
    """
    from ..app.calibrate_bar import calibrate_bar as command

    given_ = given(calibrate_bar, options)
    return _command("softimpact calibrate-bar", lambda: command(calibration=str(calibration), **given_), CALIBRATE_BAR)


@takes(SHPB, "series")
def shpb(series, **options) -> CommandResult:
    """Two-bar (split Hopkinson) tests: each test's stress [Pa], strain rate [1/s] and strain at the specimen, its
    equilibrium window, modulus and strength; across tests a rate-dependent strength with its intervals (law.json).

    Parameters
    ----------
    series : str or Path
        A two-bar series file (the bars, their gauges, the specimen, the tests) or a built-in name.
    {options}

    Returns
    -------
    CommandResult
        ``table("tests.csv")``: per test strength_Pa, strain_rate_1_s, modulus_Pa, the equilibrium window;
        ``json("law.json")``: the crushing law (strength at a reference rate, rate exponent, the rates measured).

    Raises
    ------
    softimpact.errors.InputError
        A missing or unreadable record, or records too short for the waves to pass their gauges.

    Examples
    --------
    >>> import softimpact as si
    >>> m = si.shpb("ice-shpb-series", figures=False).json("law.json")["parameters"]["rate_exponent"]
    >>> abs(m["value"] - 0.2) <= m["ci95_half_width"]  # the synthetic ice's hidden exponent, 0.2, within the interval
    True
    """
    from ..app.shpb import shpb as command

    given_ = given(shpb, options)
    return _command("softimpact shpb", lambda: command(series_name=str(series), **given_), SHPB)
