"""The issue's full-size check: 8 × 8 in SS [90/0]5s plate, eq-15 pulse, against the Navier FSDT series.

The plate, load and gauges are symmetric about both mid-lines, so a quarter
(x, y ∈ [4, 8] in, ``symmetry`` supports on the mid-lines, the patch's quarter
at the corner) is the full plate at a quarter of the cost (checked to round-off
in ``tests/test_plate.py``). Measured against the Navier series (converged: 79
and 239 terms agree to 2e-4 of the peaks), dt = 0.25 µs, errors in % of the
peaks (strain εx at 1 in, εy at 2 in; centre deflection):

===============  =========  ==========  ===========  ============
full-plate mesh  0–100 µs   0–250 µs    0–1000 µs    deflection
===============  =========  ==========  ===========  ============
64 × 64          3.7 / 6.1  10.4 / 8.1  21.6 / 29.7  1.5
128 × 128        1.1 / 2.1  3.7 / 3.4   11.1 / 13.1  0.56
192 × 192        0.5 / 1.0  1.7 / 1.7   6.2 / 6.2    0.25
256 × 256                               3.6 / 3.8    0.14
===============  =========  ==========  ===========  ============

Time alone (the Navier modes stepped by average acceleration): 5.5 / 5.0 % over
0–1000 µs at dt = 1 µs, 1.5 / 1.9 % at 0.5 µs, 0.5 / 0.5 % at 0.25 µs. The FE
converges to the series at second order, and the error grows with time: it is
the phase error of the dispersive flexural waves (both mesh and step), which
accumulates over the reflections of 1000 µs. The 2 % target is met over the
loading phase (0–250 µs) at 192 × 192, dt = 0.25 µs; over 0–1000 µs the error
falls 192² → 256² at an observed order 1.8–1.9, so it needs a mesh of about
360 × 360 (the target is kept below as a strict xfail on 64²).
"""

import numpy as np
import plate_navier as nav
import pytest
from conftest import INCH
from test_plate import PAPER_PULSE, SECTION, STACK, A

from softimpact.fem.newmark import SolverSpec
from softimpact.workflows.plate_impact import PlateGauge, PlateLoad, PlateModel, PlateProblem, PlateSpec

pytestmark = pytest.mark.slow

QUARTER = ("symmetry", "simply-supported", "symmetry", "simply-supported")
GAUGES = (PlateGauge("x1", (1 * INCH, 0.0), "bottom", "x", 0.031 * INCH), PlateGauge("y2", (0.0, 2 * INCH), "bottom", "y", 0.031 * INCH))
NAVIER_GAUGES = [(5 * INCH, 4 * INCH, "x", 0.031 * INCH), (4 * INCH, 6 * INCH, "y", 0.031 * INCH)]


def quarter_run(n, dt, duration):
    """Gauge strains and centre deflection of the quarter model with n × n elements (full plate 2n × 2n),
    sampled every microsecond."""
    problem = PlateProblem(
        PlateSpec(A / 2, A / 2, (n, n), STACK, QUARTER),
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
    times = np.arange(1001) * 1e-6
    return nav.transient(SECTION, A, A, (A / 2, A / 2), 0.25 * INCH, PAPER_PULSE, times, [(A / 2, A / 2)], NAVIER_GAUGES, terms=79)


def test_paper_plate_frequencies_within_1_percent():
    """First five frequencies on the 64 × 64 full mesh within 1 % (measured ≤ 0.26 %) of Navier FSDT."""
    problem = PlateProblem(PlateSpec(A, A, (64, 64), STACK), PlateLoad((A / 2, A / 2), 0.25 * INCH, PAPER_PULSE, grow=False), SolverSpec(1e-6, 1e-5))
    exact = nav.frequencies(SECTION.D, SECTION.S, SECTION.I0, SECTION.I2, A, A, 5)
    assert np.max(np.abs(PlateModel(problem).frequencies(5) / exact - 1)) < 0.01


@pytest.fixture(scope="module")
def mesh_runs():
    """Quarter models of the 32², 48² and 64² full meshes, dt = 0.25 µs, 0–1000 µs."""
    return {n: quarter_run(n // 2, 0.25e-6, 1000e-6) for n in (32, 48, 64)}


def test_errors_fall_with_the_mesh_at_second_order(mesh_runs, navier):
    """dt = 0.25 µs, 0–1000 µs: on 32², 48², 64² (full) the gauge-strain and deflection errors fall
    at every refinement; over the first 100 µs (before the phase error builds up) the strain error
    falls 32² → 64² at an observed order above 1 (measured 1.5 / 1.1, pre-asymptotic: 1.8 / 1.5 from
    64² to 128² and 1.9 / 1.7 from 96² to 192², tending to the bilinear 2); the centre deflection is
    within 2 % of its peak over 0–1000 µs on 64² (measured 1.5 %)."""
    full = {n: errors(s, d, navier) for n, (_, s, d) in mesh_runs.items()}
    early = {n: errors(s[:, :101], d[:101], navier)[0] for n, (_, s, d) in mesh_runs.items()}
    assert np.all(full[48][0] < full[32][0]) and np.all(full[64][0] < full[48][0])
    assert full[48][1] < full[32][1] and full[64][1] < full[48][1]
    assert np.all(np.log2(early[32] / early[64]) > 1.0)
    assert full[64][1] < 0.02


@pytest.fixture(scope="module")
def converged_loading_phase():
    return quarter_run(96, 0.25e-6, 250e-6)


def test_paper_plate_within_2_percent_over_the_loading_phase(converged_loading_phase, navier):
    """The issue's target on 192 × 192 (quarter 96 × 96), dt = 0.25 µs, over the loading phase
    0–250 µs: gauge strains within 2 % of their Navier peaks (measured 1.7 %, 1.7 %), centre
    deflection within 2 % (measured 0.04 %)."""
    _, s, d = converged_loading_phase
    es, ed = errors(s, d, navier)
    assert np.all(es < 0.02) and ed < 0.02


@pytest.mark.xfail(
    strict=True,
    reason="phase error of the flexural waves accumulates over 1000 µs: 21.6 % / 29.7 % on 64², 6.2 % / 6.2 % "
    "on 192², 3.6 % / 3.8 % on 256² at dt = 0.25 µs (order 1.8: about 360 × 360 needed, beyond this suite's budget)",
)
def test_paper_plate_strains_within_2_percent_over_1000_us(mesh_runs, navier):
    """The issue's target over the whole 0–1000 µs run, on 64² (not met at an affordable mesh; see the module's table)."""
    _, s, d = mesh_runs[64]
    es, _ = errors(s, d, navier)
    assert np.all(es < 0.02)


def test_beam_as_plate_section_layered_beam_agrees_with_the_plate():
    """The paper report's beam-as-plate section: 2 beams × 4 histories × 2 gauges. The plane-strain
    beam with the real stacking (layered 2-D elasticity, an independent model) and the FSDT strip
    agree on the peak gauge strains within 7 % (measured ≤ 6.1 %) and within 1 % for history 1,
    while the smeared beam, 15 % too stiff in bending, is off by more than 7 % somewhere."""
    from softimpact.app.plate import beam_as_plate_section

    section = beam_as_plate_section(False, {})
    rows = section.tables[0][2]
    assert len(rows) == 16
    layered = np.array([float(r[4]) for r in rows])
    smeared = np.array([float(r[3]) for r in rows])
    assert np.all(np.abs(layered) < 7)
    assert np.all(np.abs([float(r[4]) for r in rows if "history 1" in r[0]]) < 1)
    assert np.max(np.abs(smeared)) > 7
