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
