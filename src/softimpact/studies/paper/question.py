"""The paper report's question section's computations: the predictive intervals of the identified law at the tested
impacts, and the what-if's two laws, identified from the built-in series' 1/2-in tests as they are (α3 = 0.25) and
made again with the tables' α3 (each a task of the report)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..tasks import once
from .thresholds import paper_identification

__all__ = ["WHAT_IF_PROJECTILE", "TABLES", "tables_alpha3", "paper_predictions", "what_if_law"]

WHAT_IF_PROJECTILE = "rubber-1/2in"  # the beams' ball: the what-if's bar tests are its tests of the built-in series
TABLES = (("long", "paper-long-calibration", "II"), ("short", "paper-short-calibration", "III"))


def tables_alpha3() -> float:
    """The α3 for which Table I's bar law of the 1/2-in ball gives the tables' t_F0: t_F0 = α3·α2·d/V (eqs 5-6)
    solved for α3 on each row of Tables II and III (t_F0·V nearly constant there), averaged."""
    from ...input.series import load_calibration_series
    from ...models.empirical import PRESETS, PROJECTILES

    P = PROJECTILES[WHAT_IF_PROJECTILE]
    a2 = PRESETS[P.law].alpha2
    rows = np.concatenate([np.array(load_calibration_series(name).reference) for _, name, _ in TABLES])
    return float(np.mean(rows[:, 2] * rows[:, 0] / (a2 * P.diameter)))


@once
def paper_predictions():
    """The identified law's predictive intervals of F0, t_F0, T, I at the tested impacts
    (:func:`~softimpact.workflows.identification.predict_pulses`), once per run."""
    from ...workflows.identification import predict_pulses

    rod, tests, law, _, cl = paper_identification()
    return predict_pulses(law, tests, rod, cl)


@once
def what_if_law(made: bool) -> tuple:
    """(law, largest |closure t_F0 error|) identified (:func:`~softimpact.workflows.identification.identify_series`)
    from the built-in series' 1/2-in tests as they are (``made`` False: α3 = 0.25) or made again by the series'
    generator with the tables' α3 (:func:`tables_alpha3`; ``made`` True), once per run."""
    from ...fem.bar import Rod
    from ...input.series import load_series
    from ...input.series_records import read_series_records
    from ...models.empirical import PRESETS, PROJECTILES
    from ...workflows.identification import identify_series
    from ..references import synthetic_series_records
    from ..series import reduce_series

    series = load_series("paper-rubber-series")
    P = PROJECTILES[WHAT_IF_PROJECTILE]
    half = replace(series, tests=tuple(t for t in series.tests if abs(t.diameter - P.diameter) < 1e-9))
    if made:
        records = synthetic_series_records(half, [replace(PRESETS[P.law], alpha3=tables_alpha3())] * len(half.tests))
    else:
        records, _ = read_series_records(half)
    _, law, _, cl = identify_series(Rod.of(series.bar), reduce_series(half, records))
    return law, float(np.max(np.abs(cl.peak_time_errors)))
