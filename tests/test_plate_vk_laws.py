"""The rate-dependent sphere laws (ice crushing, the hydrodynamic law of gelatin) on the von Kármán plate: at small
load the coupled run equals the linear plate's direct run (membrane action of order (w/h)²), and at w/h > 1 the
crushing impact closes its energy balance (the law stores nothing: its work is all dissipated)."""

import numpy as np
import pytest

from softimpact.app.paper.hail import BASE_CASE, hail_plate_case
from softimpact.input.plate_case import plate_problem
from softimpact.input.toml import locate
from softimpact.models.crushing_law import CrushingLaw
from softimpact.models.hydrodynamic_law import HydrodynamicLaw
from softimpact.models.projectiles import projectile_material
from softimpact.studies.thresholds import structure
from softimpact.workflows.coupled import run_impact

DIAMETER = 25.4e-3  # m: a 1-in sphere
LAYUP = "[45/0/-45/90]s"


class _Sphere:
    """A material's sphere law as the threshold structures take it (``law(m, d, V)``)."""

    def __init__(self, material: str):
        self.material = material
        self.density = projectile_material(material).density

    def law(self, mass: float, diameter: float, velocity: float):
        kind = CrushingLaw if self.material == "ice" else HydrodynamicLaw
        return kind.of(self.material, diameter, mass, velocity)


def _run(material: str, kinematics: str, thickness: float, velocity: float, duration: float, rtol: float | None = None):
    """(problem, result) of a 1-in sphere of ``material`` on the hail panel of ``thickness`` [m] (4 × 4 MITC9, 2 µs)."""
    data = hail_plate_case(thickness, LAYUP, 4, duration)
    data["plate"]["kinematics"] = kinematics
    sphere = _Sphere(material)
    s = structure("panel", plate_problem(data, locate(BASE_CASE).parent), DIAMETER, sphere.density, 2e-6, duration, sphere)
    if rtol is not None:
        s.model.stepper.rtol = rtol  # the von Kármán Newton's tolerance below the comparison's
    problem = s.problem_at(sphere, DIAMETER, velocity)
    return problem, run_impact(problem, s.model, energy=True, method=s.stepping)[1]


@pytest.mark.parametrize("material, velocity", [("ice", 0.1), ("gelatin", 10.0)])
def test_sphere_laws_on_the_von_karman_plate_equal_the_linear_plate_at_small_load(material, velocity):
    """At w/h < 0.01 the force history on the von Kármán plate equals the linear plate's direct run within 1e-6 of its peak."""
    h = 4.66e-3
    _, lin = _run(material, "linear", h, velocity, 4e-4)
    _, vk = _run(material, "von-karman", h, velocity, 4e-4, rtol=1e-8)
    assert np.max(np.abs(vk.target_displacement)) / h < 0.01
    assert lin.peak_force > 0.0
    assert np.max(np.abs(vk.force - lin.force)) <= 1e-6 * lin.peak_force


def test_crushing_impact_on_the_von_karman_plate_closes_its_energy_balance():
    """Ice at 20 m/s on the 1.59-mm panel (w/h > 1, through the end of the crush): impactor KE + plate KE + strain energy + ∫F dα
    (the law's dissipated work, summed here from the force and approach) = KE0 + the patch's surface mismatch within 1e-4 of KE0."""
    problem, r = _run("ice", "von-karman", 1.59e-3, 20.0, 6e-4)
    assert np.max(np.abs(r.target_displacement)) / 1.59e-3 > 1.0
    assert r.separated  # the crush ended within the run
    m = problem.impactor.mass
    ke0 = 0.5 * m * 20.0**2
    dissipated = np.concatenate([[0.0], np.cumsum(0.5 * (r.force[1:] + r.force[:-1]) * np.diff(r.approach))])
    E = r.energies
    balance = 0.5 * m * r.impactor_velocity**2 + E.kinetic + E.strain + dissipated - ke0 - E.surface_mismatch
    assert np.max(np.abs(balance)) < 1e-4 * ke0
    assert 0.0 < dissipated[-1] < ke0
