"""The ``softimpact`` command line: click only — arguments → app → outputs → one line.

Every command takes ``--out DIR`` and writes nothing outside it; commands that
draw take ``--figures/--no-figures``. Outputs are written atomically with a
``manifest.json`` (files and inputs with their SHA-256, version, status, the
command); a reused DIR loses the previous run's files that this run does not
rewrite, and nothing else.

Exit codes:

- 0 — done (warnings, if any, as ``softimpact: warning:`` lines on stderr);
- 2 — bad input, or a problem too large for the machine: a one-line reason on
  stderr, nothing computed, nothing written (``--out`` is checked writable
  before any computing);
- 3 — ran, but the answer failed its quality checks (:mod:`softimpact.gates`):
  a one-line reason, the diagnostics still written, marked ``"status": "failed"``
  in summary.json and manifest.json; ``--accept-poor`` turns this into exit 0
  with ``"status": "accepted-poor"``;
- 70 — an internal error (a bug): one line; ``softimpact --debug`` (or
  ``SOFTIMPACT_DEBUG=1``) shows the traceback.

``softimpact --ignore-limits`` (or ``SOFTIMPACT_IGNORE_LIMITS=1``) runs problems
the resource guard would refuse. Heavy modules are imported inside the
commands, so ``softimpact --help`` starts fast.
"""

from __future__ import annotations

import functools
import os
import sys
import warnings

import click

from . import __version__
from .app.options import CALIBRATE, CALIBRATE_BAR, CASE, CONVERGE, IDENTIFY, PREDICT, SERIES, SHPB, SWEEP
from .errors import EXIT_CHECK, EXIT_INPUT, EXIT_INTERNAL, CheckFailed, InputError, SoftimpactWarning, SolverFailed

__all__ = ["main"]

DEBUG_ENV = "SOFTIMPACT_DEBUG"  # set to 1 to see the traceback of an internal error


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


FORCE_ENV = "SOFTIMPACT_FORCE"  # set to 1 to let outputs replace files no earlier softimpact run wrote


def _forced() -> bool:
    """``softimpact --force`` (kept in the root context, not in the environment: one invocation only) or SOFTIMPACT_FORCE=1."""
    ctx = click.get_current_context(silent=True)
    if ctx is not None and ctx.find_root().params.get("force"):
        return True
    return os.environ.get(FORCE_ENV, "").strip() not in ("", "0")


def _claim_out(out, kwargs: dict):
    """Hold ``--out`` for the run, checked before any computing (output.files.claim_output):
    the files named by the command's arguments are its inputs, never counted as the user's outputs."""
    from pathlib import Path

    from .output.files import claim_output

    named = [v for v in kwargs.values() if isinstance(v, str) and v and Path(v).is_file()]
    return claim_output(out, force=_forced(), inputs=named)


def _guarded(fn):
    """Run a command so that it ends in one line and a documented exit code, never a traceback.

    InputError (and MemoryError, under ``--ignore-limits``) → exit 2; CheckFailed →
    exit 3; any other exception → exit 70 (traceback with ``--debug``). :class:`SoftimpactWarning` s raised anywhere
    below are shown as ``softimpact: warning:`` lines and kept for the manifest.
    """

    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        ctx = click.get_current_context(silent=True)
        shown = ctx.meta.setdefault("softimpact.warnings", []) if ctx is not None else []
        original = warnings.showwarning

        def show(message, category, filename, lineno, file=None, line=None):
            if issubclass(category, SoftimpactWarning):
                click.echo(f"softimpact: warning: {_one_line(message)}", err=True)
                shown.append(_one_line(message))
            else:
                original(message, category, filename, lineno, file, line)

        from .output.files import figure_format

        token = figure_format.set(ctx.meta.get("softimpact.figure_format", "png") if ctx is not None else "png")
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("always", SoftimpactWarning)
                warnings.showwarning = show
                if "out" not in kwargs:
                    return fn(*args, **kwargs)
                with _claim_out(kwargs["out"], kwargs):
                    return fn(*args, **kwargs)
        except InputError as exc:
            click.echo(f"softimpact: error: {_one_line(exc)}", err=True)
            sys.exit(EXIT_INPUT)
        except SolverFailed as exc:
            if "out" in kwargs:
                _write_failure(kwargs["out"], exc)
            click.echo(f"softimpact: solver failed: {_one_line(exc)} (summary.json says why, marked failed)", err=True)
            sys.exit(EXIT_CHECK)
        except CheckFailed as exc:
            click.echo(f"softimpact: check failed: {_one_line(exc)} (diagnostics written, marked failed; --accept-poor to accept)", err=True)
            sys.exit(EXIT_CHECK)
        except MemoryError:
            click.echo("softimpact: error: out of memory: the problem is too large for this machine (make it smaller)", err=True)
            sys.exit(EXIT_INPUT)
        except Exception as exc:
            if os.environ.get(DEBUG_ENV, "").strip() not in ("", "0"):
                raise
            click.echo(
                f"softimpact: internal error: {type(exc).__name__}: {_one_line(exc)} (a bug; `softimpact --debug ...` shows the traceback)",
                err=True,
            )
            sys.exit(EXIT_INTERNAL)
        finally:
            figure_format.reset(token)

    return wrapper


def _write_failure(out: str, exc: Exception) -> None:
    """A solver that gave up leaves its diagnostics as a failed check does (exit 3): summary.json with the status and
    the reason, and manifest.json marked failed, so the folder says what happened instead of holding nothing."""
    from .output.files import json_text, write_outputs

    ctx = click.get_current_context(silent=True)
    summary = {"status": "failed", "reason": _one_line(exc), "softimpact_version": __version__}
    manifest = {
        "status": "failed",
        "accept_poor": False,
        "command": ctx.command_path if ctx is not None else "softimpact",
        "arguments": dict(ctx.params) if ctx is not None else {},
        "warnings": list(ctx.meta.get("softimpact.warnings", [])) if ctx is not None else [],
        "gates": [],
    }
    try:
        write_outputs(out, {"summary.json": json_text(summary)}, manifest=manifest, force=_forced())
    except InputError:  # the folder refuses (a file of the user's): the one line still says why
        pass


class _Progress:
    """A click progress bar driven by the app's ``progress(done, total, label)`` callback."""

    def __init__(self):
        self.bar = None

    def __call__(self, done: int, total: int, label: str) -> None:
        if self.bar is None:
            self.bar = click.progressbar(length=total, label=label, file=sys.stderr)
            self.bar.__enter__()
        self.bar.label = label
        self.bar.update(done - self.bar.pos)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.__exit__(None, None, None)
            self.bar = None


def _finish(outcome, out: str, accept_poor: bool = False) -> None:
    """Write the outcome's files and manifest into ``out`` atomically, show its warnings and its line.

    If a quality gate of the outcome failed, the files are still written (status
    "failed" in the manifest) and :class:`CheckFailed` raised — unless
    ``accept_poor``, when the status is "accepted-poor" and the exit is 0.
    """
    from .gates import failed, status
    from .output.files import with_figure_format, write_outputs

    for w in outcome.warnings:
        click.echo(f"softimpact: warning: {_one_line(w)}", err=True)
    gates = tuple(outcome.gates)
    ctx = click.get_current_context(silent=True)
    manifest = {
        "status": status(gates, accept_poor),
        "accept_poor": accept_poor,
        "command": ctx.command_path if ctx is not None else "softimpact",
        "arguments": dict(ctx.params) if ctx is not None else {},
        "warnings": [*map(_one_line, outcome.warnings), *(ctx.meta.get("softimpact.warnings", []) if ctx is not None else [])],
        "gates": [g.as_dict() for g in gates],
    }
    files = with_figure_format(outcome.files, ctx.meta.get("softimpact.figure_format", "png") if ctx is not None else "png")
    written = write_outputs(out, files, inputs=outcome.inputs, manifest=manifest, force=_forced())
    bad = failed(gates)
    if bad and not accept_poor:
        raise CheckFailed(bad)
    if bad:
        click.echo(f"softimpact: warning: accepted with --accept-poor: {_one_line(CheckFailed(bad))}", err=True)
    click.echo(f"{outcome.line}; {len(written)} files in {out}")


def _run(command, out: str, accept_poor: bool = False, **kwargs) -> None:
    """Run an app command with a progress bar, then write its outcome (see :func:`_finish`)."""
    progress = _Progress()
    try:
        outcome = command(progress=progress, **kwargs)
    finally:
        progress.close()
    _finish(outcome, out, accept_poor)


@click.group(context_settings={"help_option_names": ["-h", "--help"], "max_content_width": 100})
@click.version_option(__version__, prog_name="softimpact")
@click.option("--ignore-limits", is_flag=True, default=False, help="Run problems the memory/time guard would refuse (or set SOFTIMPACT_IGNORE_LIMITS=1).")
@click.option("--debug", is_flag=True, default=False, help="Show the traceback of an internal error (or set SOFTIMPACT_DEBUG=1).")
@click.option(
    "--force", is_flag=True, default=False, help="Let outputs replace files in --out that no earlier softimpact run wrote (or set SOFTIMPACT_FORCE=1)."
)
def main(ignore_limits, debug, force):
    """Soft-projectile impact: bar and laminate FE, force reduction, scaling laws, calibration.

    CASE and SERIES are files or built-in names (see `softimpact cases`).
    Exit codes: 0 done; 2 bad input or a problem too large for the machine
    (one line, nothing written); 3 the answer failed its quality checks
    (diagnostics written, marked failed; --accept-poor to accept); 70 internal error.
    """
    from .guards import IGNORE_LIMITS_ENV

    if ignore_limits:
        os.environ[IGNORE_LIMITS_ENV] = "1"
    if debug:
        os.environ[DEBUG_ENV] = "1"


# --- the examples of the commands' --help (click's epilog) ----------------------------------------------

# name → (a file the example needs, as "name: one-line description" then its lines; or None) and the command
# line. tests/test_cli_examples.py runs every one (but paper's) as it is written here.
EXAMPLES = {
    "cases": (None, "softimpact cases"),
    "catalogue": (None, "softimpact catalogue"),
    "bar": (None, "softimpact bar paper-calibration --no-figures --out bar-out"),
    "beam": (None, "softimpact beam paper-long-beam --history 1 --no-figures --out beam-out"),
    "converge": (None, "softimpact converge paper-calibration --levels 2 --no-figures --out converge-out"),
    "sweep": (
        (
            "spec.toml: the 1/2-in rubber ball at two velocities on the built-in long beam",
            "[sweep]",
            'case = "paper-long-beam"',
            'method = "grid"',
            'outputs = ["peak_force_N", "strain_g1.peak"]',
            "[[sweep.parameter]]",
            'key = "load.history"',
            'value = { shape = "empirical", projectile = "rubber-1/2in", velocity = "1000 in/s" }',
            "[[sweep.parameter]]",
            'key = "load.history.velocity"',
            'values = ["1000 in/s", "3000 in/s"]',
        ),
        "softimpact sweep spec.toml --workers 0 --no-figures --out sweep-out",
    ),
    "plate": (None, "softimpact plate plate-ss-8in --no-figures --out plate-out"),
    "reduce": (None, "softimpact reduce paper-rubber-series --no-figures --out reduce-out"),
    "fit": (None, "softimpact fit paper-rubber-series --no-figures --out fit-out"),
    "predict": (None, 'softimpact predict --projectile rubber-1/2in --velocity "2000 in/s" --no-figures --out predict-out'),
    "calibrate": (None, "softimpact calibrate paper-long-calibration --no-figures --out calibrate-out"),
    "impact": (None, "softimpact impact paper-long-beam-impact --no-figures --out impact-out"),
    "identify": (None, "softimpact identify paper-rubber-series --no-figures --out identify-out"),
    "paper": (None, "softimpact paper --out paper-out"),
    "calibrate-bar": (None, "softimpact calibrate-bar lab-bar-calibration --no-figures --out calibrate-bar-out"),
    "shpb": (None, "softimpact shpb ice-shpb-series --no-figures --out shpb-out"),
}


# the top-level help's examples (``softimpact --help``): where to start, as typed, each one run by tests/test_cli_examples.py
MAIN_EXAMPLES = ("cases", "bar", "impact")
main.epilog = (
    "\b\nExamples:\n" + "\n".join(f"  {EXAMPLES[n][1]}" for n in MAIN_EXAMPLES) + "\n  softimpact COMMAND --help   (each command's options and its own example)"
)


def _epilog(name: str) -> str:
    """The ``Example:`` block of a command's --help (``\\b``: click keeps its lines as written)."""
    needs, line = EXAMPLES[name]
    if needs is None:
        return f"\b\nExample:\n  {line}"
    head, *body = needs
    return "\b\n" + f"Example ({head}):\n" + "".join(f"    {b}\n" for b in body) + f"  {line}"


# --- the shared options and the command factory ----------------------------------------------------

HISTORY_HELP = "Row N of the case's [[load.table]]."


def _out_option(command: str) -> click.Option:
    return click.Option(
        ["--out", "out"],
        type=click.Path(),  # checked by output.files.check_writable: one line, exit 2
        default=f"softimpact-{command}",
        show_default=True,
        help="Folder for the outputs (created if needed; nothing is written elsewhere).",
    )


class _TableOption(click.Option):
    """A click option whose help lists the rows of a table (``{projectiles}``), filled when the help is shown
    (:func:`softimpact.app.options.filled`: the tables' modules are imported then, not at every start)."""

    def get_help_record(self, ctx):
        from .app.options import filled

        self.help = filled(self.help)
        return super().get_help_record(ctx)


class _TableCommand(click.Command):
    """A click command whose help text lists the rows of a table (``{contact_laws}``), filled when the help is shown."""

    def format_help_text(self, ctx, formatter):
        from .app.options import filled

        self.help = filled(self.help)
        super().format_help_text(ctx, formatter)


def _option(o) -> click.Option:
    """The click option of an :class:`softimpact.app.options.Option`: ``--name`` (``--name/--no-name`` for a
    bool), its type or choices, default and help as the table writes them; its value reaches the command
    under the option's name."""
    if o.type is bool:
        return _TableOption([f"{o.flag}/--no-{o.flag[2:]}", o.name], default=o.default, show_default=True, help=o.help)
    if o.choices:
        kind = click.Choice(list(o.choices))
    elif o.file:
        kind = click.Path(dir_okay=False)
    else:
        kind = {str: click.STRING, int: click.INT, float: click.FLOAT}[o.type]
    return _TableOption([o.flag, o.name], type=kind, default=o.default, required=o.required, show_default=o.default is not None, help=o.help)


def _figures_option() -> click.Option:
    from .app.options import FIGURES

    return _option(FIGURES)


def _figure_format_option() -> click.Option:
    """``--figure-format``: kept in the context (not passed to the command), applied by :func:`_guarded` and :func:`_finish`."""

    def keep(ctx, param, value):
        ctx.meta["softimpact.figure_format"] = value
        return value

    return click.Option(
        ["--figure-format"],
        type=click.Choice(["png", "svg", "pdf"]),
        default="png",
        show_default=True,
        expose_value=False,
        callback=keep,
        help="Figures as PNG (120 dpi) or vector SVG or PDF.",
    )


def _history_option(help: str) -> click.Option:
    return click.Option(["--history"], type=int, default=None, help=help)


def _accept_poor_option() -> click.Option:
    return click.Option(
        ["--accept-poor"], is_flag=True, default=False, help="Exit 0 even when the answer fails its quality checks (marked accepted-poor in the outputs)."
    )


def _fields_option() -> click.Option:
    return click.Option(
        ["--fields"],
        is_flag=True,
        default=False,
        help="Also write fields.xdmf + fields.h5: displacement (beam: and strain) fields over time for ParaView, "
        "at most 200 evenly sampled steps (needs the fields extra: pip install 'softimpact[fields]').",
    )


def _command(
    name: str,
    short_help: str,
    *,
    options: tuple = (),
    history: str | None = None,
    figures: bool = True,
    accept_poor: bool | str = False,
    fields: bool = False,
):
    """Register ``softimpact NAME``: the function's own arguments and options (its click
    decorators), then the options of its table (``options``, :mod:`softimpact.app.options`; its
    ``figures`` is the shared one), then the shared ones in this order: ``--history`` (with that help text, when
    given), ``--out`` (default ``softimpact-NAME``), ``--figures/--no-figures``,
    ``--accept-poor`` (when asked for; ``accept_poor="before-out"`` lists it before ``--out``,
    where calibrate has always had it) and ``--fields`` (when asked for); the function runs under :func:`_guarded`."""

    def decorate(fn):
        command = main.command(name, cls=_TableCommand, short_help=short_help, epilog=_epilog(name))(_guarded(fn))
        command.params.extend(_option(o) for o in options if o.name != "figures")
        shared = [_history_option(history)] if history is not None else []
        if accept_poor == "before-out":
            shared.append(_accept_poor_option())
        shared.append(_out_option(name))
        if figures:
            shared += [_figures_option(), _figure_format_option()]
        if accept_poor is True:
            shared.append(_accept_poor_option())
        if fields:
            shared.append(_fields_option())
        command.params.extend(shared)
        return command

    return decorate


@main.command("cases", short_help="List the built-in cases and series.", epilog=_epilog("cases"))
@_guarded
def cases_cmd():
    """List the built-in cases and series, usable by name wherever a CASE or SERIES is asked for."""
    from .cases import builtin_listing

    for name, kind, title in builtin_listing():
        click.echo(f"{name:24s} {kind:7s} {title}")


@main.command("catalogue", short_help="List the named materials, plies, projectiles, contact laws and cases.", epilog=_epilog("catalogue"))
@_guarded
def catalogue_cmd():
    """List every named material, ply, projectile, projectile material, set of scaling constants,
    contact law and built-in case, each value in SI with its unit and each entry with its source
    (the same tables as ``si.catalogue()`` and the docs' catalogue page)."""
    from .app.catalogue import text

    click.echo(text().rstrip())


@_command("bar", "Sphere on the instrumented bar (Figs 4-6).", options=CASE)
@click.argument("case")
def bar_cmd(case, units, out, figures):
    """Longitudinal impact of a sphere on an instrumented bar (CASE: file or built-in name).

    Writes history.csv, summary.json, strain-along-bar.csv and, with figures,
    fig04-gauge-strain.png, fig05-contact-force.png, fig06-strain-along-bar.png, energy.png.
    """
    from .app.bar import bar

    _run(bar, out, case=case, units=units, figures=figures)


@_command(
    "beam",
    "Transverse impact of a laminated beam (Figs 16-22).",
    options=CASE,
    history="Row N of the case's [[load.table]] (Tables II/III for the built-ins).",
    fields=True,
)
@click.argument("case")
def beam_cmd(case, units, history, out, figures, fields):
    """Transverse impact of a laminated beam (CASE: file or built-in name).

    Writes history.csv, summary.json and, with figures, fig18-mesh.png,
    fig20-load-distribution.png, fig21-22-gauge-strains.png, deformed.png; with --fields,
    fields.xdmf and fields.h5 (ParaView).
    """
    from .app.beam import beam

    _run(beam, out, case=case, history=history, units=units, figures=figures, fields=fields)


@_command("converge", "Discretisation error of a case by systematic refinement.", options=CONVERGE)
@click.argument("case")
def converge_cmd(case, out, **options):
    """Run a bar, beam or plate CASE on refined meshes and time steps; estimate the observed
    order and the discretisation error of each output by Richardson extrapolation.

    Level 1 is the case as written; its error is the case's own distance from
    converged. Cost grows about as ratio^(dimensions + 1) per level: a beam's
    third level at ratio 2 costs some 30 times its first.

    Writes convergence.csv (one row per output: status, observed order, value and
    relative error per level, extrapolated value, GCI), summary.json and, with
    figures, convergence.png (error against refinement) and histories.png.
    """
    from .app.converge import converge

    _run(converge, out, case=case, **options)


@_command("sweep", "Grids and Monte Carlo of a case, local or on Dask.", options=SWEEP)
@click.argument("spec")
def sweep_cmd(spec, workers, scheduler, units, out, figures):
    """Runs of a case varied as the SPEC file says (grid, Monte Carlo, Latin hypercube).

    Writes runs.parquet (a row per run), summary.json (statistics, failures, rank
    correlations) and, for damage outputs against velocity, thresholds.csv and
    thresholds.png. Finished chunks are checkpointed in OUT/checkpoints: the same
    command started again resumes where it stopped.
    """
    from .app.sweep import sweep

    _run(sweep, out, spec=spec, out_dir=out, workers=workers, scheduler=scheduler, units=units, figures=figures)


@_command("plate", "Transverse impact of a laminated plate (FSDT).", options=CASE, history=HISTORY_HELP, fields=True)
@click.argument("case")
def plate_cmd(case, units, history, out, figures, fields):
    """Transverse impact of a laminated plate, FSDT MITC9 (or MITC4) elements (CASE: file or built-in name).

    Writes history.csv, summary.json and, with figures, plate-mesh.png,
    deflection.png, histories.png; with --fields, fields.xdmf and fields.h5 (ParaView).
    """
    from .app.plate import plate

    _run(plate, out, case=case, history=history, units=units, figures=figures, fields=fields)


@_command("reduce", "Bar strain records -> force histories (Fig 7).", options=SERIES, accept_poor=True)
@click.argument("series")
def reduce_cmd(series, units, out, figures, accept_poor):
    """Bar strain records of a SERIES file → force histories and pulse parameters.

    Writes tests.csv, history-<test>.csv per test, summary.json and, with figures,
    fig07-force-<test>.png per test (and dispersion-<test>.png with dispersion correction).
    """
    from .app.series import reduce

    _run(reduce, out, accept_poor, series_name=series, units=units, figures=figures)


@_command("fit", "Reduce a series, then fit alpha1-alpha4 (Table I).", options=SERIES, accept_poor=True)
@click.argument("series")
def fit_cmd(series, units, out, figures, accept_poor):
    """Reduce a SERIES, then fit the scaling constants α1–α4 of eqs (4)–(7).

    Writes the files of `reduce` (but summary.json), scaling.json and, with
    figures, fig08-peak-force.png, fig09-inverse-duration.png, fig10-skewness.png, fig11-impulse.png.
    """
    from .app.series import fit

    _run(fit, out, accept_poor, series_name=series, units=units, figures=figures)


@_command("predict", "Force history from a model, optionally driving a bar or beam.", options=PREDICT)
def predict_cmd(out, **options):
    """Force history of a projectile at a velocity, from the empirical model or a classical one.

    Writes history.csv (with the structure's gauge strains under --bar/--beam),
    summary.json and, with figures, force-history.png.
    """
    from .app.predict import predict

    _run(predict, out, **options)


@_command("calibrate", "Force history that makes computed strains match measured ones.", options=CALIBRATE, accept_poor="before-out")
@click.argument("case")
def calibrate_cmd(case, accept_poor, out, **options):
    """Force history that makes computed gauge strains match measured ones.

    CASE is a beam case (with --measured and --velocity) or a calibration series
    file. The model's discretisation error is estimated first (the case's mesh
    against one refinement) and the mesh refined within --budget; standard errors
    include that error as well as the noise. Writes calibration.json and history.csv (history-<test>.csv per test and
    tables.csv and scaling.json for a series) and, with figures, strains*.png, force*.png
    (and fig23-25-force-scaling.png for a series).
    """
    from .app.calibrate import calibrate_command

    _run(calibrate_command, out, accept_poor, case=case, **options)


@_command("impact", "Coupled impact of a rigid impactor on a beam or plate through a contact law.", options=CASE, fields=True)
@click.argument("case")
def impact_cmd(case, units, out, figures, fields):
    """Coupled impact of a rigid impactor on a beam or plate (CASE: file or built-in name), the
    contact force found each step from a contact law ({contact_laws}).

    Writes history.csv, summary.json and, with figures, force-history.png,
    approach.png, gauge-strains.png, energy.png (and on a plate plate-mesh.png, deflection.png);
    with --fields, fields.xdmf and fields.h5 (ParaView: the target's displacement over time).
    """
    from .app.impact import impact

    _run(impact, out, case=case, units=units, figures=figures, fields=fields)


@_command("identify", "A soft projectile's contact law from bar tests (law.json).", options=IDENTIFY, accept_poor=True)
@click.argument("series")
def identify_cmd(series, out, law, units, figures, accept_poor):
    """Identify one contact law of a SERIES of bar tests (file or built-in name): reduce the
    records, reconstruct force against approach, fit, then check by coupled bar simulations.

    Writes law.json (with predictive intervals), closure.csv, predictions.csv, approach-<test>.csv
    per test and, with figures, closure-forces.png and force-approach.png.
    """
    from .app.identify import identify

    _run(identify, out, accept_poor, series_name=series, law=law, units=units, figures=figures)


@_command("paper", "The whole paper, end to end, into report.html.")
def paper_cmd(out, figures):
    """The whole paper, end to end, on the built-in cases, into DIR/report.html.

    report.html embeds its figures (it opens on its own when mailed); every
    section's files are written beside it in a folder of its own.
    """
    from .app.paper import paper

    _run(paper, out, figures=figures)


@_command("calibrate-bar", "A lab's bar calibrated from its records into a bar file (bar.toml).", options=CALIBRATE_BAR, accept_poor=True)
@click.argument("calibration")
def calibrate_bar_cmd(calibration, units, out, figures, accept_poor):
    """Calibrate a lab's bar from the records of a CALIBRATION file (file or built-in name): the wave speed from
    the echoes' times, Poisson's ratio (or the effective radius) from their dispersion, the gauge's position, and
    the gauge factor from known impacts (a ball's momentum); each with its 95 % interval and its fit's residual.

    Writes bar.toml (a bar file that bar cases and series read: [bar] file = "bar.toml"), calibration.json,
    shots.csv and, with figures, echoes-<shot>.png and calibration.png. Exit 3 when the records disagree.
    """
    from .app.calibrate_bar import calibrate_bar

    _run(calibrate_bar, out, accept_poor, calibration=calibration, units=units, figures=figures)


@_command("shpb", "Two-bar (split Hopkinson) tests -> stress-strain curves at rate, a rate law.", options=SHPB, accept_poor=True)
@click.argument("series")
def shpb_cmd(series, units, out, figures, accept_poor):
    """Analyse the two-bar (split Hopkinson) tests of a SERIES file (file or built-in name): each record's waves
    moved to the specimen's faces, one-, two- and three-wave stress, strain rate and strain, the dynamic
    equilibrium check, the modulus and the strength at rate; across tests, a rate-dependent strength
    sigma = sigma_ref (rate/rate_ref)^m with its intervals and the range of rates measured.

    Writes tests.csv, curve-<test>.csv per test, summary.json, law.json (a crushing law for impact and bar cases,
    law = "identified", with three tests or more) and, with figures, stress-strain-<test>.png,
    equilibrium-<test>.png and rate-law.png.
    """
    from .app.shpb import shpb

    _run(shpb, out, accept_poor, series_name=series, units=units, figures=figures)


if __name__ == "__main__":  # pragma: no cover
    main()
