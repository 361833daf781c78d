"""The issue's full-size check: 8 × 8 in SS [90/0]5s plate, eq-15 pulse, against the Navier FSDT series.

The plate, load and gauges are symmetric about both mid-lines, so a quarter
(x, y ∈ [4, 8] in, ``symmetry`` supports on the mid-lines, the patch's quarter
at the corner) is the full plate at a quarter of the cost (checked to round-off
in ``tests/test_plate.py``). Errors in % of the Navier peaks over the window
(strain εx at 1 in / εy at 2 in; centre deflection over 0–1000 µs), dt = 0.25
µs, the series converged (79 and 239 terms agree to 2e-4 of the peaks):

=========================  ===========  ============  ==========
full-plate mesh            0–100 µs     0–1000 µs     deflection
=========================  ===========  ============  ==========
MITC4 64 × 64              3.7 / 6.1    21.6 / 29.7   1.5
MITC4 128 × 128            1.1 / 2.1    11.1 / 13.1   0.56
MITC4 192 × 192            0.5 / 1.0    6.2 / 6.2     0.25
MITC4 256 × 256                         3.6 / 3.8     0.14
MITC9 16 × 16              7.6 / 9.0    17.5 / 21.1   0.86
MITC9 24 × 24              3.8 / 3.6    10.7 / 10.6   0.32
MITC9 32 × 32              2.2 / 2.1    6.6 / 5.6     0.13
MITC9 48 × 48              1.0 / 0.9    1.8 / 1.7     0.02
MITC9 56 × 56                           1.2 / 0.9     0.01
MITC9 64 × 64              0.5 / 0.4    0.65 / 0.51   0.01
=========================  ===========  ============  ==========

The error grows with time: it is the phase error of the dispersive flexural
waves, accumulated over the reflections of 1000 µs. With the bilinear MITC4 it
falls at second order in h (an estimated 360 × 360 for 2 %); with the 9-node
MITC9 element (``softimpact.fem.plate``) at fourth order: 48 × 48 (27 455
DOF, as many as MITC4's 96 × 96) is within 2 % over the whole 0–1000 µs only
because its spatial error (2.1 %) and the time step's partly cancel; 56 × 56
meets the target with the spatial error alone (1.5 / 1.2 %), and is the mesh tested.
Time alone (the Navier modes stepped by average acceleration) costs 0.5 % at
dt = 0.25 µs, 5.5 / 5.0 % at 1 µs; the spatial error alone is the FE against
that time-stepped series (``plate_navier.newmark_modal_response``), and its
observed order is checked below.
"""

import numpy as np
import pytest

from softimpact.fem.newmark import SolverSpec
from softimpact.workflows.plate_impact import PlateGauge, PlateLoad, PlateModel, PlateProblem, PlateSpec

from _support import plate_navier as nav
from _support.constants import INCH
from _support.problems import PAPER_PULSE, SECTION, STACK, A

pytestmark = pytest.mark.slow

QUARTER = ("symmetry", "simply-supported", "symmetry", "simply-supported")
GAUGES = (PlateGauge("x1", (1 * INCH, 0.0), "bottom", "x", 0.031 * INCH), PlateGauge("y2", (0.0, 2 * INCH), "bottom", "y", 0.031 * INCH))
NAVIER_GAUGES = [(5 * INCH, 4 * INCH, "x", 0.031 * INCH), (4 * INCH, 6 * INCH, "y", 0.031 * INCH)]


def quarter_run(n, dt, duration, element="mitc9"):
    """Gauge strains and centre deflection of the quarter model with n × n elements (full plate 2n × 2n),
    sampled every microsecond."""
    problem = PlateProblem(
        PlateSpec(A / 2, A / 2, (n, n), STACK, QUARTER, element=element),
        PlateLoad((0.0, 0.0), 0.25 * INCH, PAPER_PULSE, grow=False),
        SolverSpec(dt, duration),
        GAUGES,
    )
    model = PlateModel(problem)
    r = model.direct(energy=False, snapshots=())
    every = int(round(1e-6 / dt))
    return model, r.strain[:, ::every], r.deflection[0, ::every]


def errors(strain, defl, ref):
    """Largest difference over the window, relative to the Navier peaks over 0–1000 µs."""
    d_ref, s_ref = ref
    k = strain.shape[1]
    es = np.max(np.abs(strain - s_ref[:, :k]), axis=1) / np.max(np.abs(s_ref), axis=1)
    ed = np.max(np.abs(defl - d_ref[0, :k])) / np.max(np.abs(d_ref[0]))
    return es, ed


@pytest.fixture(scope="module")
def navier():
    """The exact series and the series stepped like the FE (average acceleration, dt = 0.25 µs), sampled every µs."""
    times = np.arange(1001) * 1e-6
    args = (SECTION, A, A, (A / 2, A / 2), 0.25 * INCH, PAPER_PULSE, times, [(A / 2, A / 2)], NAVIER_GAUGES)
    return nav.transient(*args, terms=79), nav.transient(*args, terms=79, newmark_dt=0.25e-6)


def test_paper_plate_frequencies_within_1_percent():
    """First five frequencies on the 24 × 24 MITC9 mesh within 1 % (measured ≤ 0.02 %) of Navier FSDT."""
    problem = PlateProblem(
        PlateSpec(A, A, (24, 24), STACK, element="mitc9"), PlateLoad((A / 2, A / 2), 0.25 * INCH, PAPER_PULSE, grow=False), SolverSpec(1e-6, 1e-5)
    )
    exact = nav.frequencies(SECTION.D, SECTION.S, SECTION.I0, SECTION.I2, A, A, 5)
    assert np.max(np.abs(PlateModel(problem).frequencies(5) / exact - 1)) < 0.01


@pytest.fixture(scope="module")
def mesh_runs():
    """MITC9 quarter models of the 16², 24², 32², 48² and 56² full meshes, dt = 0.25 µs, 0–1000 µs."""
    return {2 * n: quarter_run(n, 0.25e-6, 1000e-6) for n in (8, 12, 16, 24, 28)}


def test_mitc9_spatial_error_falls_toward_fourth_order(mesh_runs, navier):
    """Against the series stepped like the FE (the spatial error alone), 0–1000 µs, on 16², 24², 32², 48²:
    the gauge-strain and centre-deflection errors fall at every refinement; the deflection's from 32² to
    48² at an observed order above 3.3 (measured 3.7; 2.5 and 2.9 on the coarser pairs: biquadratic,
    consistent mass, 4 asymptotically); the strains' (the largest error over a long window, where the
    accumulated phase error is still a sizeable part of a wavelength) at a fitted order above 2 over 24²–48²
    (measured 2.4 / 2.3; spatial errors 10.7 / 10.5 %, 6.8 / 5.7 %, 2.1 / 2.1 %, and on 56² 1.5 / 1.2 %)."""
    _, stepped = navier
    spatial = {n: errors(s, d, stepped) for n, (_, s, d) in mesh_runs.items()}
    ns = sorted(spatial)
    for a, b in zip(ns[:-1], ns[1:]):
        assert np.all(spatial[b][0] < spatial[a][0]) and spatial[b][1] < spatial[a][1]
    assert np.log(spatial[32][1] / spatial[48][1]) / np.log(48 / 32) > 3.3
    fit = [24, 32, 48]
    order = -np.polyfit(np.log(fit), np.log([spatial[n][0] for n in fit]), 1)[0]
    assert np.all(order > 2.0)


def test_paper_plate_within_2_percent_over_1000_us(mesh_runs, navier):
    """The issue's target over the whole run: on 56 × 56 MITC9 (quarter 28 × 28), dt = 0.25 µs, 0–1000 µs,
    the gauge strains within 2 % of their Navier peaks (measured 1.2 %, 0.9 %) and the centre deflection
    within 2 % (measured 0.01 %); and the spatial error alone (against the series stepped like the FE) also
    within 2 % (measured 1.5 / 1.2 %), so the target is not met by a cancellation. On 48 × 48 the total is
    1.81 / 1.73 % only because the spatial error (2.1 %) and the time step's (0.5 %) have opposite signs
    (consistent mass raises the frequencies, average acceleration lowers them)."""
    exact, stepped = navier
    _, s, d = mesh_runs[56]
    es, ed = errors(s, d, exact)
    assert np.all(es < 0.02) and ed < 0.02
    es, ed = errors(s, d, stepped)
    assert np.all(es < 0.02) and ed < 0.02
