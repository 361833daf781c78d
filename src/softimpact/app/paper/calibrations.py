"""The report's section on the calibrations of Tables II and III and the long-against-short comparison (paper Figs 23-25)."""

from __future__ import annotations

import re
from dataclasses import replace

import numpy as np

from ...cases.run import execute
from ...input.beam_case import load_beam_case
from ...input.records import read_strains
from ...input.scaling_constants import start_pulse
from ...input.series import CalibrationSeries, load_calibration_series
from ...models.empirical import PRESETS, PROJECTILES
from ...models.pulses import SkewedPulse
from ...output import plots
from ...output.calibration import SeriesComparison, calibration_section, series_calibration_files, tables_rows
from ...output.files import figure_bytes
from ...output.report import Section
from ...studies.calibration import CalibratedTest, calibrate_tests, calibration_model, scaling_points, series_fits
from ...studies.tasks import once
from ...workflows.beam_impact import BeamLoad, BeamModel
from ...workflows.calibration import Measured, calibrate
from ...workflows.scaling import fit_groups
from .notes import SYSTEM

__all__ = ["calibration_sections", "comparison"]


def calibration_sections(figures: bool, files: dict) -> list[Section]:
    """Each beam's calibration series (least squares, and the paper's procedure on the long beam's history 1),
    then the calibrated scaling beside the paper's tables."""
    sections = []
    groups = {}
    for beam in ("long", "short"):
        section, made, rows = beam_calibration(beam, figures)
        files.update(made)
        sections.append(section)
        groups.update(rows)
    if figures:
        files["calibration-fig23-25.png"] = figure_bytes(plots.beam_force_scaling(groups, SYSTEM))
        sections.append(
            Section(
                "Long against short beam (Figs 23-25)",
                [
                    "The shorter beam takes a lower, longer force at a given velocity (the paper's finding: flexural waves "
                    "reflected from the boundaries shape the force history). Filled: calibrated here; open: the paper's tables; "
                    "lines: fits through the origin of eqs (4)-(6), solid ours, dotted the paper's."
                ],
                [],
                [("calibration-fig23-25.png", "Figs 23-25: F0 against V², 1/T against V and tF0/T against V, long and short beams")],
            )
        )
    return sections


@once
def beam_calibration(beam: str, figures: bool) -> tuple[Section, dict, dict]:
    """One beam's calibration series ("long" or "short"), once per run (a task of the report): its section, its files
    and its rows of Figs 23-25 (calibrated and the paper's)."""
    files: dict = {}
    series = load_calibration_series(f"paper-{beam}-calibration")
    problem, _ = load_beam_case(series.case)
    models = calibration_model(problem, [t.contact_radius or problem.load.contact_radius for t in series.tests], False)
    items = calibrate_tests(models, series.tests, series.projectile, series.constants, "least-squares")
    truths = [SkewedPulse(r[1], r[2], r[3]) for r in series.reference] if len(series.reference) == len(items) else None
    prefix = f"calibration-{beam}/"
    fits = series_fits(series, items)
    files.update(series_calibration_files(models, series, items, fits, figures, prefix, truths))
    paper_method = None
    if beam == "long":
        # The paper's procedure on history 1, from the bar model with the Table's tF0/T (see NOTES).
        test = series.tests[0]
        bar = start_pulse(series.projectile, series.constants, test.velocity)
        ref = series.reference[0]
        start = SkewedPulse(bar.peak_force, ref[2] / ref[3] * bar.duration, bar.duration)
        t, strains = read_strains(test.measured)
        paper_method = calibrate(models(0), Measured(test.measured.name, t, strains), start, "paper", radius=test.contact_radius)
    compared = comparison(models.finest(), series, items, fits)
    section = calibration_section(models, series, items, compared, prefix, figures, paper_method)
    section.summary = [f0_summary(items, series, beam)]
    note = linear_theory_note(problem, items, beam)
    if note:
        section.paragraphs.insert(0, note)
        count = re.search(r"(\d+ of \d+) tests deflect", note)  # the note's own count
        section.qualified = f"{count.group(1) if count else 'some'} tests past linear theory's w/h = 0.5, see Warnings of the run"
    groups = {
        f"{beam} beam, calibrated": [r[:4] for r in tables_rows(items)],
        f"{beam} beam, Table {'II' if beam == 'long' else 'III'} (paper)": [r[:4] for r in series.reference],
    }
    return section, files, groups


def f0_summary(items: list[CalibratedTest], series: CalibrationSeries, beam: str) -> str:
    """The calibrated F0 of each test beside the paper's (Table II long, III short: ``series.reference``, the
    section's own table), in the report's units, and the largest relative difference."""
    from ...units import display

    fu = display(SYSTEM, "force")
    ref = {round(r[0], 6): r[1] for r in series.reference}
    pairs = [(i.calibration.peak_force, ref.get(round(i.test.velocity, 6))) for i in items if i.calibration is not None]
    shown = ", ".join(f"{f * fu.factor:.1f} ({'—' if p is None else f'{p * fu.factor:.1f}'})" for f, p in pairs)
    diffs = [abs(f / p - 1) for f, p in pairs if p]
    worst = f"; at most {max(diffs):.1%} apart" if diffs else ""
    table = "II" if beam == "long" else "III"
    return f"F0 of the {beam} beam's calibrations [{fu.label}], calibrated (paper's Table {table}): {shown or 'none calibrated'}{worst}"


def linear_theory_note(problem, items: list[CalibratedTest], beam: str) -> str:
    """The calibrated histories run through the beam as the ``beam`` command would check them: each test's
    deflection under the load against the thickness (linear theory's envelope,
    :func:`softimpact.models.validity.deflection_validity`). Every flag is warned (so the paper's manifest lists
    it) and the note beside the table says which tests leave the envelope; empty when none does."""
    from ...models.validity import DEFLECTION_OVER_THICKNESS, deflection_validity, warn

    ratios = []
    done = [item for item in items if item.calibration is not None]
    if not done:
        return ""
    # the calibration ladder's models output gauge strains only: the deflection under the load needs a model of its own
    model = BeamModel(problem, patch_radius=max(item.calibration.contact_radius for item in done))
    for item in done:
        load = BeamLoad(problem.load.position, item.calibration.contact_radius, item.calibration.pulse)
        res = execute(replace(problem, load=load), model=model, energy=False).result
        v = deflection_validity(f"calibration of the {beam} beam, test {item.test.name}", float(np.max(np.abs(res.deflection))), res.problem.beam.thickness)
        warn(v)
        if v.flags:
            ratios.append((item.test.name, v.values["deflection_over_thickness"]))
    if not ratios:
        return ""
    listed = ", ".join(f"{name} {r:.2f}" for name, r in ratios)
    return (
        f"Outside linear theory: under their calibrated histories {len(ratios)} of {len(items)} tests deflect the {beam} beam by more than "
        f"{DEFLECTION_OVER_THICKNESS:g} times its thickness (w/h: {listed}). The beam model is linear, so these histories and the "
        "constants fitted to them carry the model error of neglected membrane stiffening (it grows as (w/h)^2); the paper's own "
        "analysis shares this limit."
    )


def comparison(model: BeamModel, series: CalibrationSeries, items: list[CalibratedTest], fits) -> SeriesComparison:
    """The bar law's histories, the strains under the paper's histories and both scaling fits."""
    P = PROJECTILES[series.projectile]
    law = PRESETS[P.law]
    ref = {round(r[0], 6): r for r in series.reference}
    bar_models, strains = [], []
    for item in items:
        V = item.test.velocity
        bar_models.append(law.parameters(P.mass, P.diameter, V))
        r = ref.get(round(V, 6))
        if r is None:
            strains.append(None)
        else:
            res = model.respond(SkewedPulse(r[1], r[2], r[3]), r[4])
            strains.append(tuple(float(np.max(np.abs(s))) for s in res.strain))
    groups = {}
    if len(series.reference) >= 2:
        paper_rows = [(str(i), r[0], r[1], r[2], r[3]) for i, r in enumerate(series.reference)]
        groups["paper's table"] = next(iter(fit_groups(scaling_points(paper_rows, series.projectile)).values()))
    if fits is not None:
        groups["calibrated"] = next(iter(fits.values()))
    return SeriesComparison(tuple(bar_models), tuple(strains), groups, law)
