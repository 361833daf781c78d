"""The ``softimpact`` command line.

Every command takes ``--out DIR`` and writes nothing outside it; commands that
draw take ``--figures/--no-figures``. Bad input: a one-line reason on stderr,
exit code 2, nothing written.
"""

from __future__ import annotations

import functools
import sys
import time

import click
import numpy as np

from . import __version__
from .errors import InputError

__all__ = ["main"]


def _guarded(fn):
    """Turn :class:`InputError` into a one-line message and exit code 2."""

    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        try:
            return fn(*args, **kwargs)
        except InputError as exc:
            click.echo(f"softimpact: error: {exc}", err=True)
            sys.exit(2)

    return wrapper


def _out_option(command: str):
    return click.option(
        "--out",
        "out",
        type=click.Path(file_okay=False),
        default=f"softimpact-{command}",
        show_default=True,
        help="Folder for the outputs (created if needed; nothing is written elsewhere).",
    )


_figures_option = click.option("--figures/--no-figures", default=True, show_default=True, help="Draw PNG figures.")


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="softimpact")
def main():
    """Soft-projectile impact: bar and laminate FE, force reduction, scaling laws, calibration."""


@main.command("cases")
@_guarded
def cases_cmd():
    """List the built-in cases and series (usable by name)."""
    from .cases import builtin_cases, load_toml

    for name, path in builtin_cases().items():
        title = load_toml(path).get("title", "")
        click.echo(f"{name:24s} {title}")


@main.command("bar")
@click.argument("case")
@_out_option("bar")
@_figures_option
@_guarded
def bar_cmd(case, out, figures):
    """Longitudinal impact of a sphere on an instrumented bar (CASE: file or built-in name)."""
    from .cases import load_bar_case
    from .io import write_outputs
    from .report import bar_files
    from .workflows.bar_impact import simulate_impact, without_end_cap

    problem, path = load_bar_case(case)
    t0 = time.perf_counter()
    result = simulate_impact(problem)
    plain = simulate_impact(without_end_cap(problem)) if problem.bar.end_cap is not None else None
    files = bar_files(result, plain, figures)
    written = write_outputs(out, files, inputs=[path])
    click.echo(
        f"peak force {result.peak_force:.1f} N at {result.time_of_peak * 1e6:.1f} us, "
        f"contact {result.contact_duration * 1e6:.1f} us ({time.perf_counter() - t0:.2f} s); "
        f"{len(written)} files in {out}"
    )


def _series_progress(series, label):
    return click.progressbar(length=len(series.tests), label=label, file=sys.stderr)


@main.command("beam")
@click.argument("case")
@click.option("--history", type=int, default=None, help="Row N of the case's [[load.table]] (Tables II/III for the built-ins).")
@_out_option("beam")
@_figures_option
@_guarded
def beam_cmd(case, history, out, figures):
    """Transverse impact of a laminated beam (CASE: file or built-in name)."""
    from .cases import load_beam_case
    from .io import write_outputs
    from .report import beam_files
    from .workflows.beam_impact import BeamModel

    problem, path = load_beam_case(case, history)
    t0 = time.perf_counter()
    model = BeamModel(problem)
    with click.progressbar(length=problem.solver.steps, label="stepping", file=sys.stderr) as bar:
        last = [0]

        def progress(k):
            bar.update(k - last[0])
            last[0] = k

        result = model.direct(progress=progress)
        bar.update(problem.solver.steps - last[0])
    files = beam_files(model, result, figures)
    write_outputs(out, files, inputs=[path])
    peaks = ", ".join(f"{g.name} {eps[np.argmax(np.abs(eps))] * 1e6:.0f} µε" for g, eps in zip(problem.gauges, result.strain))
    click.echo(f"{model.plane.n} DOF, {problem.solver.steps} steps ({time.perf_counter() - t0:.1f} s); peak strains {peaks}; files in {out}")


@main.command("reduce")
@click.argument("series")
@_out_option("reduce")
@_figures_option
@_guarded
def reduce_cmd(series, out, figures):
    """Bar strain records of a SERIES file → force histories and pulse parameters."""
    from .io import json_text, write_outputs
    from .report import reduction_files

    spec, reduced = _reduce(series)
    files = reduction_files(spec, reduced, figures)
    files["summary.json"] = json_text({"series": str(spec.path), "synthetic": spec.synthetic, "reduced": sum(r.reduction is not None for r in reduced), "failed": {r.test.name: r.error for r in reduced if r.reduction is None}})
    write_outputs(out, files, inputs=[spec.path] + [t.record for t in spec.tests])
    click.echo(f"{sum(r.reduction is not None for r in reduced)} of {len(reduced)} records reduced; tests.csv in {out}")


def _reduce(series):
    """Read a series and reduce its records with a progress bar; warn about the bad ones."""
    from .cases import load_series
    from .runs import reduce_series

    spec = load_series(series)
    with _series_progress(spec, "reducing") as bar:
        reduced = reduce_series(spec, progress=lambda name: bar.update(1))
    bad = [r for r in reduced if r.reduction is None]
    for r in bad:
        click.echo(f"softimpact: warning: {r.error}", err=True)
    if len(bad) == len(reduced):
        raise InputError("no record of the series could be reduced")
    return spec, reduced


@main.command("fit")
@click.argument("series")
@_out_option("fit")
@_figures_option
@_guarded
def fit_cmd(series, out, figures):
    """Reduce a SERIES, then fit the scaling constants α1–α4 of eqs (4)–(7)."""
    from .io import write_outputs
    from .report import reduction_files, scaling_files
    from .runs import fit_series

    spec, reduced = _reduce(series)
    fits = fit_series(reduced)
    files = reduction_files(spec, reduced, figures)
    files.update(scaling_files(fits, spec.units, figures))
    write_outputs(out, files, inputs=[spec.path] + [t.record for t in spec.tests])
    for label, g in fits.items():
        a = {k: f.slope for k, f in g.origin.items()}
        click.echo(f"{label:>10s}: alpha1 {a['alpha1']:.3f}  alpha2 {a['alpha2']:.3f}  alpha3 {a['alpha3']:.3f}  alpha4 {a['alpha4']:.3f}  ({len(g.points)} tests)")
    click.echo(f"scaling.json in {out}")


@main.command("predict")
@click.option("--projectile", help="A named projectile (rubber-1/2in, rubber-3/8in), or give --mass and --diameter.")
@click.option("--mass", help='Projectile mass, e.g. "1.1 g".')
@click.option("--diameter", help='Projectile diameter, e.g. "0.5 in".')
@click.option("--velocity", required=True, help='Impact velocity, e.g. "1166 in/s".')
@click.option("--model", type=click.Choice(["empirical", "hertz", "wilbeck"]), default="empirical", show_default=True)
@click.option("--constants", help="Scaling constants: a preset (silicone-1/2in, silicone-3/8in) or a scaling.json from `softimpact fit`.")
@click.option("--group", default="pooled", show_default=True, help="Group of a scaling.json to use (a diameter such as '0.5 in', or pooled).")
@click.option("--tail/--no-tail", default=False, show_default=True, help="Empirical model: add the tail that carries the rest of eq (7)'s impulse.")
@click.option("--material", default="silicone rubber", show_default=True, help="Projectile material (hertz and wilbeck models).")
@click.option("--target", default="Al 6061-T6", show_default=True, help="Target material (hertz model).")
@click.option("--bar", "bar_case", help="Drive the bar of this bar case (file or built-in name) with the predicted force.")
@click.option("--beam", "beam_case", help="Drive this beam case (file or built-in name) with the predicted force.")
@click.option("--units", "system", type=click.Choice(["in-lbf-s", "SI"]), default="in-lbf-s", show_default=True)
@_out_option("predict")
@_figures_option
@_guarded
def predict_cmd(projectile, mass, diameter, velocity, model, constants, group, tail, material, target, bar_case, beam_case, system, out, figures):
    """Force history of a projectile at a velocity, from the empirical model (eqs 4-7, 15) or a classical one."""
    from .predict import predict

    files, note = predict(projectile, mass, diameter, velocity, model, constants, group, tail, material, target, bar_case, system, figures, beam_case)
    from .io import write_outputs

    write_outputs(out, files)
    click.echo(note + f"; files in {out}")


@main.command("calibrate")
@click.argument("case")
@click.option("--measured", type=click.Path(dir_okay=False), help="CSV of measured strains: time_s and strain_<gauge> columns.")
@click.option("--velocity", help='Impact velocity, e.g. "1166 in/s" (sets the bar-model start).')
@click.option("--method", type=click.Choice(["least-squares", "paper", "deconvolve"]), default="least-squares", show_default=True)
@click.option("--contact-radius", help='r0 from the imprint, e.g. "0.25 in" (default: the case\'s).')
@click.option("--contact-time", help="First contact on the record's clock, e.g. \"100 us\" (default: estimated).")
@click.option("--fit-radius/--no-fit-radius", default=False, show_default=True, help="Least squares: fit r0 too.")
@click.option("--projectile", default="rubber-1/2in", show_default=True, help="Projectile of the bar-model start.")
@click.option("--constants", help="Scaling constants of the start: a preset or a scaling.json (default: the projectile's).")
@_out_option("calibrate")
@_figures_option
@_guarded
def calibrate_cmd(case, measured, velocity, method, contact_radius, contact_time, fit_radius, projectile, constants, out, figures):
    """Force history that makes computed gauge strains match measured ones.

    CASE is a beam case (with --measured and --velocity) or a calibration series file.
    """
    from . import units
    from .cases import CalibrationTest, is_calibration_series, load_beam_case, load_calibration_series
    from .io import write_outputs
    from .report import calibration_files, series_calibration_files
    from .runs import calibrate_tests, calibration_model

    t0 = time.perf_counter()
    if is_calibration_series(case):
        if measured or velocity:
            raise InputError("--measured/--velocity: not used with a series file (its [[test]] entries give them)")
        series = load_calibration_series(case)
        problem, case_path = load_beam_case(series.case)
        radii = [t.contact_radius or problem.load.contact_radius for t in series.tests]
        model = calibration_model(problem, radii, fit_radius)
        with click.progressbar(length=len(series.tests), label="calibrating", file=sys.stderr) as bar:
            items = calibrate_tests(model, series.tests, series.projectile, series.constants, method, fit_radius, progress=lambda n: bar.update(1))
        for i in items:
            if i.calibration is None:
                click.echo(f"softimpact: warning: {i.error}", err=True)
        if all(i.calibration is None for i in items):
            raise InputError("no test of the series could be calibrated")
        files = series_calibration_files(model, series, items, figures)
        write_outputs(out, files, inputs=[series.path, case_path] + [t.measured for t in series.tests])
        click.echo(f"{sum(i.calibration is not None for i in items)} of {len(items)} tests calibrated ({time.perf_counter() - t0:.1f} s); calibration.json in {out}")
        return
    if not measured or not velocity:
        raise InputError("--measured and --velocity are required with a beam case")
    V = units.parse(velocity, "velocity", "--velocity")
    r0 = units.parse(contact_radius, "length", "--contact-radius") if contact_radius else None
    tc = units.parse(contact_time, "time", "--contact-time") if contact_time else None
    problem, case_path = load_beam_case(case)
    from pathlib import Path

    test = CalibrationTest(Path(measured).stem, Path(measured), V, r0, tc)
    model = calibration_model(problem, [r0 or problem.load.contact_radius], fit_radius)
    items = calibrate_tests(model, [test], projectile, constants, method, fit_radius)
    if items[0].calibration is None:
        raise InputError(items[0].error)
    files = calibration_files(model, items, figures, single=True)
    write_outputs(out, files, inputs=[case_path, Path(measured)])
    c = items[0].calibration
    se = c.standard_errors.get("peak_force")
    click.echo(
        f"{c.method}: F0 {c.peak_force:.1f} N{f' ± {se:.2g}' if se else ''}, tF0 {c.time_of_peak * 1e6:.1f} us, T {c.duration * 1e6:.1f} us "
        f"({c.message}); {time.perf_counter() - t0:.1f} s; files in {out}"
    )


@main.command("paper")
@_out_option("paper")
@_figures_option
@_guarded
def paper_cmd(out, figures):
    """The whole paper, end to end, on the built-in cases, into DIR/report.html."""
    from .paper import run_paper

    run_paper(out, figures, echo=click.echo)


if __name__ == "__main__":  # pragma: no cover
    main()
