"""The structure protocol (models.protocols.StructureModel), implemented once (fem.linear.LinearModel)
by the bar's rod, the plane beam and the plate: engine against direct stepping, energy balance."""

from dataclasses import replace

import numpy as np
import pytest

from softimpact.fem.bar import BarModel, Rod
from softimpact.fem.newmark import SolverSpec
from softimpact.input.bar_case import load_bar_case
from softimpact.input.beam_case import load_beam_case
from softimpact.models.laminate import PLIES, Stack, parse_layup
from softimpact.models.protocols import StructureModel
from softimpact.models.pulses import SkewedPulse
from softimpact.workflows.beam_impact import BeamModel
from softimpact.workflows.plate_impact import PlateGauge, PlateLoad, PlateModel, PlateProblem, PlateSpec

INCH = 0.0254
PULSE = SkewedPulse(300.0, 20e-6, 60e-6)  # eq (15): 300 N, peak at 20 µs, 60 µs long


def _bar():
    """The paper's bar (39 Hermite elements), gauges at a quarter and half its length, 0.5 µs steps."""
    problem, _ = load_bar_case("paper-calibration")
    bar = problem.bar
    return BarModel(Rod.of(bar), SolverSpec(0.5e-6, 200e-6), [bar.length / 4, bar.length / 2])


def _beam():
    """The paper's long beam on a coarse mesh, undamped, its pulse replaced by PULSE."""
    problem, _ = load_beam_case("paper-long-beam")
    beam = replace(problem.beam, nx=48, nz=4, damping=(0.0, 0.0))
    load = replace(problem.load, history=PULSE)
    return BeamModel(replace(problem, beam=beam, load=load, solver=SolverSpec(0.5e-6, 150e-6)))


def _plate():
    """An 8-in simply supported [90/0]5s plate, 8 × 8 MITC9, a growing patch, two gauges."""
    stack = Stack(PLIES["T300/934"], parse_layup("[90/0]5s"))
    gauges = (PlateGauge("x1", (5 * INCH, 4 * INCH), "bottom", "x"), PlateGauge("y2", (4 * INCH, 6 * INCH), "bottom", "y"))
    spec = PlateSpec(8 * INCH, 8 * INCH, (8, 8), stack)
    return PlateModel(PlateProblem(spec, PlateLoad((4 * INCH, 4 * INCH), 0.25 * INCH, PULSE, grow=True), SolverSpec(1e-6, 150e-6), gauges))


MODELS = {"bar": _bar, "beam": _beam, "plate": _plate}


@pytest.fixture(scope="module", params=sorted(MODELS))
def model(request):
    return MODELS[request.param]()


def test_every_structure_satisfies_the_protocol(model):
    """Bar, beam and plate models are StructureModels (runtime-checkable protocol) and know their true DOF count."""
    assert isinstance(model, StructureModel)
    assert model.size == model.M.shape[0] == model.K.shape[0]
    if isinstance(model, BarModel):
        assert model.size == 2 * (model.rod.elements + 1) == 80  # Hermite rod: u and du/dx per node (fem/bar.py)


def test_respond_equals_direct_stepping(model):
    """The response engine's outputs (convolution of impulse responses) equal direct Newmark stepping to 1e-9 of the peak."""
    F = model.force_samples(PULSE)
    by_engine = model.respond_outputs(F)
    by_stepping, _, _ = model.march(F, energy=False)
    assert np.max(np.abs(by_engine - by_stepping)) <= 1e-9 * np.max(np.abs(by_stepping))


def test_direct_stepping_balances_energy(model):
    """Undamped average acceleration: kinetic + strain energy equals the work of the loads to round-off, every step."""
    _, E, _ = model.march(model.force_samples(PULSE), energy=True)
    assert np.array_equal(E.step, np.arange(model.steps + 1))
    assert np.max(np.abs(E.balance_error)) < 1e-10 * np.max(np.abs(E.work))


def test_light_copy_for_workers_pickles_small_and_responds_the_same(model):
    """for_workers() drops matrices, mesh and factor (which does not pickle): its pickle is the engine's kernels and
    little else (under 1 MB more), and it gives the same response."""
    import pickle

    if isinstance(model, BarModel):
        F = model.force_samples(PULSE)
        light = model.for_workers()
        assert light.stepper is None and light.M is None
        assert np.array_equal(light.respond_outputs(F), model.respond_outputs(F))
        return
    reference = model.respond(PULSE).strain
    light = model.for_workers()
    size = len(pickle.dumps(light))
    assert light.stepper is None and light.M is None and light.K is None
    assert np.array_equal(pickle.loads(pickle.dumps(light)).respond(PULSE).strain, reference)
    kernels = light._engine.kernel.nbytes + (0 if light._engine._start is None else sum(k.nbytes for k in light._engine._start if k is not None))
    assert size < kernels + 1e6


def test_laws_pulses_and_patches_satisfy_their_protocols():
    """Every contact law, the eq-15 pulse and both contact patches (line, plate disc) satisfy the protocols of models.protocols."""
    from softimpact.fem.impact import ContactPatch as LinePatch
    from softimpact.fem.plate_loads import CircularPatch, DiscShares
    from softimpact.models.contact_laws import HertzLaw, HuntCrossleyLaw, YangSunLaw
    from softimpact.models.materials import lookup
    from softimpact.models.protocols import ContactLaw, ContactPatch, HistoryLaw, Pulse

    hertz = HertzLaw.sphere_on_flat(0.008, lookup("steel"), lookup("Al 6061-T6"))
    assert isinstance(hertz, ContactLaw) and isinstance(HuntCrossleyLaw(hertz.K, hertz.R, 0.5, 2.0), ContactLaw)
    assert isinstance(YangSunLaw(hertz, 1e-5), HistoryLaw)
    assert isinstance(PULSE, Pulse)
    plate = _plate()
    assert isinstance(LinePatch(np.array([0.0, 1e-3, 2e-3]), 1e-3), ContactPatch)
    assert isinstance(DiscShares(CircularPatch(plate.fe, (4 * INCH, 4 * INCH), 0.5 * INCH)), ContactPatch)
