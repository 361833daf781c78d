"""The contact kernels' fast paths against the step-by-step computations they replace.

The Maxwell law's free flight (``apart``) and a converged step's update (``settle``) against its
``advance``/``branch``/``energy`` step by step (states to the last bit, energies to 1e-13); the build's reciprocal march against
the response engine's, to the last bit; a run whose force is clipped to zero while the bodies overlap
(the steps the kernels take without a Newton solve) against direct coupled stepping.
"""

from dataclasses import replace

import numpy as np
import pytest

from softimpact.fem.impact import integrate_impact
from softimpact.fem.kernels import ContactKernels, _reciprocal_march
from softimpact.fem.newmark import NewmarkStepper, SolverSpec
from softimpact.fem.response import ImpulseResponse
from softimpact.input.impact_case import load_impact_case
from softimpact.models.contact_laws import SoftProjectileLaw, ViscoelasticSoftLaw
from softimpact.workflows.coupled import impact_model

DT = 0.5e-6
MASS, DIAMETER, VELOCITY = 1.2e-3, 0.0127, 50.8  # a 1/2-in silicone-rubber ball at 2000 in/s


def _maxwell() -> ViscoelasticSoftLaw:
    """The identified law's form with tests/data/law-v-main.json's values at d_ref (a stiff, fast-relaxing arm)."""
    return ViscoelasticSoftLaw(SoftProjectileLaw(MASS, DIAMETER, VELOCITY, k=4.77, p=1.317, c=0.0), kappa=17.24, theta=0.1285).for_time_step(DT)


def _loaded_state(law):
    """A state after a few loading and unloading steps (arm strain and stress both nonzero)."""
    state = law.initial_state()
    for alpha in (2e-5, 8e-5, 1.5e-4, 1.2e-4):
        state = law.advance(state, alpha, 0.0)
    assert state.strain > 0.0 and state.stress != 0.0
    return state


def test_apart_equals_advancing_step_by_step():
    """States and contact energies of a flight apart (2006 steps) equal the step's branch energy, then advance, step by step, bit for bit."""
    law = _maxwell()
    start = _loaded_state(law)
    alphas = [-1e-6, -3e-6, 0.0, -2e-5, -1e-9, -4e-6] + [-1e-6] * 2000  # α ≤ 0: the bodies apart, a long flight
    state, energies = start, []
    for alpha in alphas:
        energies.append(law.branch(state).energy(alpha))
        state = law.advance(state, alpha, -1.0)
    fast, fast_energies = law.apart(start, len(alphas))
    assert (fast.strain, fast.stress) == (state.strain, state.stress)
    assert fast_energies == energies
    assert law.apart(start, 0) == (start, [])


def test_settle_equals_advance_branch_and_energy():
    """A converged step's state, branch and energy from settle equal advance, branch and the step's own branch's
    energy (its arm stress at α is the converged σ: ½·(mV²/d)·d·σ²/κ beside the elastic part), loading and unloading."""
    law = _maxwell()
    state = slow = law.initial_state()
    for alpha, rate in [(1e-5, 40.0), (6e-5, 30.0), (1.4e-4, 5.0), (1.3e-4, -8.0), (4e-5, -30.0), (-2e-6, -40.0), (3e-6, 10.0)]:
        state, branch, energy = law.settle(state, alpha, rate)
        step = law.branch(slow)
        slow = law.advance(slow, alpha, rate)
        reference = law.branch(slow)
        assert (state.strain, state.stress) == (slow.strain, slow.stress)
        assert energy == pytest.approx(step.energy(alpha), rel=1e-13, abs=1e-300)
        elastic = law.base.energy(alpha) if alpha > 0 else 0.0
        scale = law.base.mass * law.base.velocity**2 / law.base.diameter
        assert energy - elastic == pytest.approx(0.5 * scale * law.base.diameter * slow.stress**2 / law.kappa, rel=1e-9)
        assert branch == reference
        for probe in (2e-5, 1.5e-4):
            assert branch.response(probe, 12.0) == reference.response(probe, 12.0)


@pytest.fixture(scope="module")
def beam():
    """The long beam made coarse (40 × 4 Q4, the impact case's gauges), struck at its centre, 0.5 µs steps, 600 steps."""
    problem, _ = load_impact_case("paper-long-beam-impact")
    t = problem.target
    solver = SolverSpec(DT, 300e-6, problem.solver.newmark)
    problem = replace(problem, target=replace(t, beam=replace(t.beam, nx=40, nz=4), solver=solver))
    model = impact_model(problem)
    return model.contact_structure(problem.position, model.contact_reach(problem.position, problem.impactor.diameter)), solver


@pytest.mark.parametrize("damped", [False, True])
def test_build_march_equals_the_response_engine(beam, damped):
    """The build's kernels equal the response engine's reciprocal kernels bit for bit, without and with Rayleigh damping."""
    s, solver = beam
    if damped:
        s = replace(s, C=(200.0 * s.M + 1e-7 * s.K).tocsc())
    st = NewmarkStepper(s.M, s.K, solver.time_step, C=s.C, params=solver.newmark)
    kernels = ContactKernels(s, solver.time_step, solver.steps, solver.newmark, stepper=st)
    n, dofs = st.n, np.asarray(s.surface_dofs, int)
    B = np.zeros((n, dofs.size))
    B[dofs, np.arange(dofs.size)] = float(s.load_sign)
    rows = np.vstack([np.asarray(s.approach_row, float)[None, :], np.asarray(s.outputs, float)])
    engine = ImpulseResponse.reciprocal(st, B, solver.steps, rows)
    assert np.array_equal(kernels.approach, engine.kernel[0])
    assert np.array_equal(kernels.outputs, engine.kernel[1:])
    assert np.array_equal(kernels._Hk, engine._spectrum()[0])


@pytest.mark.parametrize("damped", [False, True])
def test_threaded_build_march_equals_the_response_engine(damped):
    """A model past the dense limit (the long beam at 60 × 4 Q4, 610 DOF: a band factor): the build's marches, one
    thread per kernel row (its default) or all rows in one march, equal the response engine's reciprocal kernels
    bit for bit, without and with Rayleigh damping."""
    problem, _ = load_impact_case("paper-long-beam-impact")
    t = problem.target
    solver = SolverSpec(DT, 60e-6, problem.solver.newmark)
    problem = replace(problem, target=replace(t, beam=replace(t.beam, nx=60, nz=4), solver=solver))
    model = impact_model(problem)
    s = model.contact_structure(problem.position, model.contact_reach(problem.position, problem.impactor.diameter))
    if damped:
        s = replace(s, C=(200.0 * s.M + 1e-7 * s.K).tocsc())
    st = NewmarkStepper(s.M, s.K, solver.time_step, C=s.C, params=solver.newmark)
    assert not st.dense and st.separate_solves  # a band factor, solved without the GIL: the threaded marches are taken
    n, dofs = st.n, np.asarray(s.surface_dofs, int)
    B = np.zeros((n, dofs.size))
    B[dofs, np.arange(dofs.size)] = float(s.load_sign)
    rows = np.vstack([np.asarray(s.approach_row, float)[None, :], np.asarray(s.outputs, float)])
    engine = ImpulseResponse.reciprocal(st, B, solver.steps, rows)
    assert np.abs(engine.kernel).max() > 0.0
    for threads in (None, 1, 2):  # one march per row, all rows in one march, an uneven two-and-one split
        kernel = _reciprocal_march(st, rows, dofs, float(s.load_sign), solver.steps, threads=threads)
        assert np.array_equal(kernel, engine.kernel)


def test_a_clipped_force_equals_direct_stepping(beam):
    """A soft ball whose Maxwell arm clips the force to zero while the bodies still overlap: the kernel run equals direct stepping to 1e-9 of the peak,
    and neither reports a contact disc while the clipped force is zero."""
    s, solver = beam
    law = _maxwell()
    st = NewmarkStepper(s.M, s.K, solver.time_step, C=s.C, params=solver.newmark)
    direct = integrate_impact(s, law, MASS, VELOCITY, solver.time_step, solver.steps, newmark=solver.newmark, stepper=st, energy=False)
    clipped = (direct.force == 0.0) & (direct.approach > 0.0)
    assert np.count_nonzero(clipped[1:]) >= 10  # the case exercises the steps taken without a Newton solve
    fast = ContactKernels(s, solver.time_step, solver.steps, solver.newmark, stepper=st).run(law, MASS, VELOCITY)
    peak = direct.force.max()
    assert np.max(np.abs(fast.force - direct.force)) <= 1e-9 * peak
    assert np.max(np.abs(fast.approach - direct.approach)) <= 1e-9 * np.max(np.abs(direct.approach))
    assert np.max(np.abs(fast.contact_energy - direct.contact_energy)) <= 1e-9 * np.max(direct.contact_energy)
    assert np.max(np.abs(fast.strain - direct.strain)) <= 1e-9 * np.max(np.abs(direct.strain))
    assert np.array_equal(fast.force > 0.0, direct.force > 0.0)
    # no contact disc where no force presses, the bodies overlapping or not; the disc's radius where it does
    for h in (fast, direct):
        assert np.all(h.contact_radius[h.force == 0.0] == 0.0) and np.all(h.contact_radius[h.force > 0.0] > 0.0)


def test_contact_energy_holds_the_arm_stress_the_force_implies(beam):
    """Direct coupled stepping with the Maxwell law: at every step in contact (F > 0) the contact energy minus the
    equilibrium part's elastic energy is the arm spring's ½·(mV²/d)·d·σ²/κ with σ = F/(mV²/d) − k(α/d)^p(1 + cα̇/V),
    the arm stress the force history itself implies (a record one relaxation step ahead would be σ·E: 3 % low here)."""
    s, solver = beam
    law = _maxwell()
    st = NewmarkStepper(s.M, s.K, solver.time_step, C=s.C, params=solver.newmark)
    r = integrate_impact(s, law, MASS, VELOCITY, solver.time_step, solver.steps, newmark=solver.newmark, stepper=st, energy=False)
    b = law.base
    scale = b.mass * b.velocity**2 / b.diameter
    on = r.force > 0.0
    a, rate = r.approach[on], r.approach_rate[on]
    sigma = r.force[on] / scale - b.k * (a / b.diameter) ** b.p * (1.0 + b.c * rate / b.velocity)
    elastic = b.k * scale * (a / b.diameter) ** b.p * a / (b.p + 1.0)
    arm = r.contact_energy[on] - elastic
    expected = 0.5 * scale * b.diameter * sigma**2 / law.kappa
    assert np.max(np.abs(arm - expected)) <= 1e-6 * np.max(expected)


@pytest.mark.parametrize("stop_after", [10e-6, 50e-6])
def test_runs_stop_at_the_same_step_after_separation(beam, stop_after):
    """With ``stop_after`` the kernel run ends at the same step as direct stepping (the impactor moving away for that long,
    through contact and through the kernels' vectorised flight apart), with the same forces up to there."""
    s, solver = beam
    law, steps = _maxwell(), 1200  # 600 µs: the ball leaves within it
    st = NewmarkStepper(s.M, s.K, solver.time_step, C=s.C, params=solver.newmark)
    direct = integrate_impact(s, law, MASS, VELOCITY, solver.time_step, steps, newmark=solver.newmark, stepper=st, energy=False, stop_after=stop_after)
    fast = ContactKernels(s, solver.time_step, steps, solver.newmark, stepper=st).run(law, MASS, VELOCITY, stop_after=stop_after)
    assert direct.time.size < steps + 1  # the run did stop early
    assert fast.time.size == direct.time.size
    assert np.max(np.abs(fast.force - direct.force)) <= 1e-9 * direct.force.max()


def test_line_patch_loads_from_kept_sines_equal_fresh_loads(beam):
    """The line patch's loads at r taken from the sines kept by value(r) equal loads computed afresh, and loads at
    another radius than the last value() ignore the kept sines (equal to a fresh patch's loads there)."""
    s, solver = beam
    kernels = ContactKernels(s, solver.time_step, solver.steps, solver.newmark)
    comp = kernels._compliance
    spacing = 2.0 * comp.half_spacing
    fresh = type(comp)(comp.patch, kernels._lagged[0])
    for r1, r2 in ((2.7 * spacing, 2.7 * spacing), (2.7 * spacing, 3.7 * spacing), (3.7 * spacing, 1.6 * spacing)):  # within the 4 spacings loadable
        assert comp.value(r1) == comp(r1)[0]
        kept, new = np.zeros(kernels._lagged.shape[1]), np.zeros(kernels._lagged.shape[1])
        comp.load(r2, 7.0, kept)
        fresh.load(r2, 7.0, new)
        assert np.array_equal(kept, new)
        assert abs(kept.sum() - 7.0) <= 1e-12 * 7.0  # the shares sum to one
