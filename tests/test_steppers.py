"""The one coupled stepper (fem.stepping) and its implementations by name (fem.steppers.STEPPERS)."""

import math

import numpy as np
import pytest
from scipy.special import beta as beta_function

from softimpact.errors import ContactOutgrewRoom, InputError
from softimpact.fem.impact import ContactStructure, ImpactHistory, LawCapabilities, contact_intervals
from softimpact.fem.kernels import ContactKernels
from softimpact.fem.newmark import NewmarkParameters
from softimpact.fem.steppers import STEPPERS
from softimpact.fem.stepping import CoupledStepper
from softimpact.models.contact_laws import HertzLaw, HuntCrossleyLaw, SoftProjectileLaw, ViscoelasticSoftLaw
from softimpact.models.protocols import HistoryLaw

K_HERTZ, R_SPHERE = 5.0e9, 6.35e-3  # N/m^1.5, m: a steel ball on a stiff target (the scale of the paper's cases)
MASS, VELOCITY = 8.4e-3, 1.5  # kg, m/s


def _two_masses(nodes=(0.0,), spacing=None) -> ContactStructure:
    """A struck mass m1 on a spring k1 to a second mass m2 on a spring k2 to the ground (dense, 2 DOFs); with
    ``spacing``, the struck surface is ``nodes`` loadable points that all move with m1 (one DOF repeated)."""
    m1, m2, k1, k2 = 0.02, 0.05, 4.0e6, 2.0e6
    M = np.diag([m1, m2])
    K = np.array([[k1, -k1], [-k1, k1 + k2]])
    x = np.asarray(nodes, float)
    return ContactStructure(
        M=M, K=K, surface_x=x, surface_dofs=np.zeros(x.size, int), load_sign=1.0, center=0.0, approach_row=np.array([1.0, 0.0]), outputs=np.eye(2)
    )


class _PlainHertz:
    """Hertz's law written as the five members of ContactLaw only: no optional capability declared."""

    def __init__(self, K, R):
        self.K, self.R = K, R

    def force(self, alpha, rate=0.0):
        return self.K * alpha**1.5 if alpha > 0.0 else 0.0

    def stiffness(self, alpha, rate=0.0):
        return 1.5 * self.K * alpha**0.5 if alpha > 0.0 else 0.0

    def damping(self, alpha, rate=0.0):
        return 0.0

    def radius(self, alpha):
        return math.sqrt(self.R * alpha) if alpha > 0.0 else 0.0

    def energy(self, alpha):
        return self.K * alpha**2.5 / 2.5 if alpha > 0.0 else 0.0


class _RigidWall(CoupledStepper):
    """The shared loop against an immovable target: no free response, no compliance, nothing to load."""

    value = None
    half_spacing = math.inf

    def __init__(self, law, mass, velocity, time_step, steps):
        super().__init__(law, mass, velocity, time_step, steps)
        self.params, self.compliance = NewmarkParameters(), self

    def __call__(self, r):
        return 0.0, 0.0  # h_s = c·G·s: a rigid wall does not move

    def free_approach(self, k):
        return 0.0

    def apply(self, k, f, r):
        pass

    def history(self, last):
        nan = np.full(last + 1, np.nan)
        t = np.arange(last + 1) * self.dt
        arr = [np.array(v[: last + 1]) for v in (self.F, self.al, self.ald, self.rad, self.x, self.xv, self.cwork, self.cen)]
        F, al, ald, rad, x, xv, cw, ce = arr
        return ImpactHistory(t, F, al, ald, rad, x, xv, 0 * t, np.zeros((0, t.size)), nan, nan, nan, cw, ce, nan, self.newton_iterations, 0)


def test_the_shared_loop_on_a_rigid_wall_gives_hertz_closed_form():
    """On an immovable target the loop reproduces Hertz's rigid-wall impact: α_max = (5mV²/(4K))^(2/5) and
    duration 2·(α_max/V)·∫₀¹(1 − s^(5/2))^(-1/2) ds = (4/5)·B(2/5, 1/2)·α_max/V (Hertz 1882; Goldsmith 1960, Impact, eq 4.17)."""
    alpha_max = (5.0 * MASS * VELOCITY**2 / (4.0 * K_HERTZ)) ** 0.4
    duration = 0.8 * beta_function(0.4, 0.5) * alpha_max / VELOCITY
    dt = duration / 4000
    h = _RigidWall(HertzLaw(K_HERTZ, R_SPHERE), MASS, VELOCITY, dt, 4400).run()
    assert np.max(h.approach) == pytest.approx(alpha_max, rel=1e-6)
    first = contact_intervals(h.time, h.force, h.approach)[0]
    assert first.duration == pytest.approx(duration, rel=1e-6)
    assert h.impactor_velocity[-1] == pytest.approx(-VELOCITY, rel=1e-6)  # elastic: the ball rebounds at its impact speed


@pytest.mark.parametrize("law", [HertzLaw(K_HERTZ, R_SPHERE), HuntCrossleyLaw(K_HERTZ, R_SPHERE, 0.6, VELOCITY)], ids=["hertz", "hunt-crossley"])
def test_the_steppers_by_name_agree_and_conserve_momentum(law):
    """Direct stepping and contact kernels, chosen by name, give one force history (to 1e-9 of the peak), and
    the impactor's momentum change equals the contact impulse ∫F dt (trapezoid, the rule of the integration)."""
    s = _two_masses()
    dt, steps = 0.2e-6, 1500
    kernels = ContactKernels(s, dt, steps)
    runs = {
        name: STEPPERS[name](s, law, MASS, VELOCITY, dt, steps, engine=kernels if name == "kernels" else None, energy=False).run()
        for name in ("direct", "kernels")
    }
    direct, kern = runs["direct"], runs["kernels"]
    peak = np.max(direct.force)
    assert peak > 0 and np.max(np.abs(direct.force - kern.force)) <= 1e-9 * peak
    impulse = np.sum(0.5 * (direct.force[1:] + direct.force[:-1])) * dt
    assert MASS * (VELOCITY - direct.impactor_velocity[-1]) == pytest.approx(impulse, rel=1e-10)


def test_a_law_with_no_optional_capability_runs_the_same():
    """A law written as ContactLaw's five members only (no ``response``, no ``radius_power``: the Newton takes
    a central difference of the radius) gives HertzLaw's history to the Newton tolerance, through both steppers."""
    assert LawCapabilities.of(_PlainHertz(K_HERTZ, R_SPHERE)) == LawCapabilities(False, None)
    assert LawCapabilities.of(HertzLaw(K_HERTZ, R_SPHERE)) == LawCapabilities(False, 0.5)
    s = _two_masses(nodes=np.linspace(-2e-3, 2e-3, 41))  # a line patch the contact disc spreads over
    dt, steps = 0.2e-6, 800
    kernels = ContactKernels(s, dt, steps)
    for name in ("direct", "kernels"):  # the linear structures' steppers ("von-karman" steps a PlateVK: tests/test_plate_vk_impact.py)
        runs = [
            STEPPERS[name](s, law, MASS, VELOCITY, dt, steps, engine=kernels if name == "kernels" else None, energy=False).run()
            for law in (HertzLaw(K_HERTZ, R_SPHERE), _PlainHertz(K_HERTZ, R_SPHERE))
        ]
        assert np.max(runs[0].contact_radius) > 0.1e-3  # the disc reaches past the nearest node
        assert np.max(np.abs(runs[0].force - runs[1].force)) <= 1e-9 * np.max(runs[0].force)


@pytest.mark.parametrize("name", ["direct", "kernels"])
def test_a_contact_outgrowing_its_nodes_is_a_typed_error(name):
    """A contact disc wider than the loadable nodes raises ContactOutgrewRoom (an InputError) on either stepper."""
    s = _two_masses(nodes=np.linspace(-0.05e-3, 0.05e-3, 5))
    dt, steps = 0.2e-6, 400
    engine = ContactKernels(s, dt, steps) if name == "kernels" else None
    with pytest.raises(ContactOutgrewRoom, match="runs past the loadable surface nodes"):
        STEPPERS[name](s, HertzLaw(K_HERTZ, R_SPHERE), MASS, VELOCITY, dt, steps, engine=engine, energy=False).run()
    assert issubclass(ContactOutgrewRoom, InputError)


def test_kernels_keep_one_smaller_structure():
    """The kernels return their own structure at their reach, build a smaller reach's once and reuse it, and
    replace it by the next smaller reach's (no caller writes into the kernels)."""
    s = _two_masses()
    kernels = ContactKernels(s, 1e-6, 10, reach=2e-3)
    built = []

    def build(reach):
        built.append(reach)
        return _two_masses()

    assert kernels.structure_for(2e-3, build) is s and built == []
    first = kernels.structure_for(1e-3, build)
    assert kernels.structure_for(1e-3, build) is first and built == [1e-3]
    assert kernels.structure_for(0.5e-3, build) is not first and built == [1e-3, 0.5e-3]


def test_the_kernel_stepper_refuses_energies():
    """Contact kernels have no structure state: asking them for energies is an InputError, not NaNs in silence."""
    s = _two_masses()
    with pytest.raises(InputError, match="energies"):
        STEPPERS["kernels"](s, HertzLaw(K_HERTZ, R_SPHERE), MASS, VELOCITY, 1e-6, 10, energy=True)


@pytest.mark.parametrize(
    "law",
    [
        HertzLaw(K_HERTZ, R_SPHERE),
        HuntCrossleyLaw(K_HERTZ, R_SPHERE, 0.6, VELOCITY),
        SoftProjectileLaw(MASS, 2 * R_SPHERE, VELOCITY, 0.5, 1.2, 0.3),
        ViscoelasticSoftLaw(SoftProjectileLaw(MASS, 2 * R_SPHERE, VELOCITY, 0.5, 1.2, 0.3), 2.0, 0.5).for_time_step(1e-6),
    ],
    ids=["hertz", "hunt-crossley", "soft", "viscoelastic"],
)
def test_declared_capabilities_hold(law):
    """What a law declares holds: a = c·α^n with its ``radius_power`` n (a(4α)/a(α) = 4^n), and its ``response``
    is (force, stiffness, damping), the stiffness being ∂F/∂α by a central difference."""
    branch = law.branch(law.initial_state()) if isinstance(law, HistoryLaw) else law
    caps = LawCapabilities.of(branch)
    alpha, rate = 1e-5, 0.3
    if caps.radius_power is not None:
        assert branch.radius(4 * alpha) / branch.radius(alpha) == pytest.approx(4**caps.radius_power, rel=1e-12)
    h = 1e-6 * alpha
    slope = (branch.force(alpha + h, rate) - branch.force(alpha - h, rate)) / (2 * h)
    assert branch.stiffness(alpha, rate) == pytest.approx(slope, rel=1e-6)
    if caps.responds:
        assert branch.response(alpha, rate) == (branch.force(alpha, rate), branch.stiffness(alpha, rate), branch.damping(alpha, rate))
