"""The elastic–plastic plate (fem/plate_plastic.py, stepped by fem/nonlinear.py) loaded impulsively and struck by a
heavy mass, far past elastic, against the rigid-plastic string (tests/_support/rigid_plastic.py: closed forms derived
there; N. Jones's, which issue 40 asks for, were sought and not retrieved, so none of his equations, ranges or stated
agreement with tests is used).

The case: a strip of span L = 200 mm and thickness h = 2 mm clamped at both ends, the ends immovable in their plane, in
cylindrical bending (symmetry edges in y: plane strain), of the reference's illustrative Al 2024-T3-like metal made
perfectly plastic (E 73 GPa, ν 0.33, ρ 2780 kg/m³, σ_y 345 MPa, H = 0: the string's assumption). The package's model:
:class:`~softimpact.fem.plate_plastic.PlasticPlate` (MITC9, 8 layers × 2 points, von Kármán) on the half span,
12 elements by one across a 5-mm width, stepped by :class:`~softimpact.fem.nonlinear.NonlinearNewmark` (2 µs for the
impulses, 3 µs for the mass) for three times the string's stop time, then
sprung back to rest by :func:`~softimpact.fem.nonlinear.relax`. The impulse is the initial velocity V_0 of every free
transverse DOF; the mass G (per metre of width, ten times the strip's mass ρhL) is lumped on the first element (a band
of half-width 8.3 mm) with the strip's own mass there, all of it given V_0.

The regime: the strings' deflections are 10–16 thicknesses, the energies 9–20 times the membrane's elastic capacity
U_e = ½N_0ε_eL (rigid-plastic theory's premise: plastic work ≫ elastic energy; measured plastic work ≥ 98.7 % of the
initial kinetic energy), the mass ratio G/(ρhL) = 10 (the mode approximation within 1.7 % of the quasi-static string).

Measured (the string's W_f; the tolerance, half a thickness, is the bending capacity's estimated lowering of W,
derived in the support module; the mass's adds the mode approximation's own correction, 0.49 mm):

===================  ==========  ==========  ==============  ===================  ==============================
case                 W_f [mm]    peak [mm]   t_peak / t_f    permanent [mm]       string's permanent [mm]
===================  ==========  ==========  ==============  ===================  ==============================
impulse 80 m/s       21.13       21.02       1.04            18.11                18.69 (√(W_f² − ε_eL²/2))
impulse 120 m/s      31.70       31.02       1.02            29.55                30.13
mass 10 ρhL, 36 m/s  29.58       30.53       0.96            28.31                27.89
===================  ==========  ==========  ==============  ===================  ==============================

The independent elastic–plastic code (tests/_support/plastic_reference.py, Kirchhoff strip, 16 elements) gives at
120 m/s a peak of 30.70 mm and a permanent deflection of 28.89 mm: the package's are 1.0 % and 2.3 % larger.

Seen, not asserted: the energy balance of the impulsive runs closes to only 1–2 % of the initial kinetic energy at
2 µs and 2.5 % at 3 µs (at 120 m/s the plastic work counted exceeds the kinetic energy by 0.2 %; the mass run's
balance closes within 0.3 %), where the coupled impacts of tests/test_metal_impact.py close within 1e-3: an impulse
strains the whole strip plastically within a few steps; the error falls with the step, its source not pinned down.
At 3 µs the 80-m/s run failed a Newton step; the springback (relax) from the end of a 120-m/s run (3 µs) on the
catalogue's hardening Al 2024-T3 failed (a line-search trial the J2 return map could not follow).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
import pytest
import scipy.sparse

from softimpact.fem.nonlinear import NonlinearNewmark, relax
from softimpact.fem.plate import Plate, W
from softimpact.fem.plate_plastic import PlasticPlate
from softimpact.models.plasticity import J2PlaneStress, LinearHardening
from softimpact.models.plate_laminate import isotropic_section

from _support import plastic_reference as ref
from _support import rigid_plastic as rp

METAL = ref.Metal(73e9, 0.33, 2780.0, 345e6, 0.0)  # the reference's illustrative Al 2024-T3, perfectly plastic
SPAN, THICKNESS, WIDTH = 0.2, 2e-3, 0.005  # [m]: L/h = 100; the strip's width, one element across
MASS_PER_AREA = METAL.density * THICKNESS
N0 = rp.plane_strain_yield_force(METAL.yield_stress, THICKNESS)
STRIP_SUPPORTS = ("symmetry", "clamped", "symmetry", "symmetry")  # x = 0 (mid-span), x = L/2, y = 0, y = WIDTH
ELEMENTS = 12  # along the half span
IMPULSE_STEP, MASS_STEP = 2e-6, 3e-6  # [s]: 132 steps to the impulse's t_f (3 µs failed a Newton step at 80 m/s), 443 to the mass's
RUN_FOR = 3.0  # stop times: the strip has stopped yielding well before (its last tenth is elastic ringing)
MASS_RATIO = 10.0  # G / (ρhL)
TOLERANCE = rp.BENDING_DEFLECTION * THICKNESS  # [m]: the bending capacity's estimated lowering of W


class StripRun(NamedTuple):
    """The package's strip: its largest centre deflection ``peak`` [m] at ``time_of_peak`` [s], the ``permanent`` one
    after the run and the springback, the initial kinetic energy ``work_in`` and the ``plastic_work`` [J/m]."""

    peak: float
    time_of_peak: float
    permanent: float
    work_in: float
    plastic_work: float


def _strip_model() -> PlasticPlate:
    section = isotropic_section(METAL.youngs_modulus, METAL.poisson_ratio, METAL.density, THICKNESS)
    plate = Plate(SPAN / 2, WIDTH, ELEMENTS, 1, section, STRIP_SUPPORTS, element="mitc9")
    material = J2PlaneStress(METAL.youngs_modulus, METAL.poisson_ratio, LinearHardening(METAL.yield_stress, 0.0))
    return PlasticPlate(plate, material, kinematics="von-karman", in_plane="immovable")


def package_strip(velocity: float, *, mass: float = 0.0) -> StripRun:
    """The package's strip (module docstring) given ``velocity`` [m/s] everywhere (``mass`` 0: the impulse) or struck by
    ``mass`` [kg per metre of width] lumped on the first element; run for :data:`RUN_FOR` of the string's stop time."""
    pp = _strip_model()
    if mass:
        band = SPAN / 2 / ELEMENTS
        lumped = pp.load_vector(lambda x, y: (x < band * (1 + 1e-9)).astype(float)) * (mass / 2 / band)  # the half model's G/2
        dofs = np.flatnonzero(lumped > 0)
        pp.M = (pp.M + scipy.sparse.csr_matrix((lumped[dofs], (dofs, dofs)), shape=pp.M.shape)).tocsr()
        v0 = np.zeros(pp.n)
        v0[dofs] = velocity
        stop = rp.mass_string(mass, velocity, SPAN, THICKNESS, METAL.density, N0).stop_time
        dt = MASS_STEP
    else:
        full = np.zeros(pp.fe.basis.N)
        full[pp.fe.basis.nodal_dofs[W]] = velocity
        v0 = full[pp.free]
        stop = rp.impulsive_string(velocity, SPAN, THICKNESS, METAL.density, N0).stop_time
        dt = IMPULSE_STEP
    centre = pp.deflection(0.0, 0.0)
    run = NonlinearNewmark(pp, dt, rtol=1e-8, max_iterations=40).run(None, int(round(RUN_FOR * stop / dt)), rows=centre[None, :], v0=v0)
    w = run.outputs[0]
    k = int(np.argmax(w))
    rest, _ = relax(pp, run.u)
    per_metre = 2 / WIDTH  # the half span's, on WIDTH, to the whole strip's per metre of width
    return StripRun(float(w[k]), float(run.t[k]), float(centre @ rest), float(run.kinetic[0]) * per_metre, pp.plastic_work * per_metre)


def string_permanent(deflection: float) -> float:
    """The string's deflection less its membrane's elastic springback (rigid_plastic.elastic_springback)."""
    return rp.elastic_springback(deflection, SPAN, N0, THICKNESS, METAL.youngs_modulus, METAL.poisson_ratio)


# ---- the closed forms, checked without the package ----------------------------------------------------------------


def test_the_impulsive_string_is_the_wave_solution():
    """The string's leapfrog scheme at c·Δt = Δx (exact on the grid for m w_tt = N_0 w_xx) from a uniform V_0: every
    point's slope only grows (each stretches: the rigid-plastic solution), and at t_f = L/(2c) the whole string is at
    rest as the triangle of centre deflection V_0 L/(2c), to round-off; its plastic work is the initial kinetic energy
    to the small-slope approximation's (W/L)² (2.5e-2 here)."""
    velocity, cells = 120.0, 200
    limit = rp.impulsive_string(velocity, SPAN, THICKNESS, METAL.density, N0)
    c = math.sqrt(N0 / MASS_PER_AREA)
    dt = SPAN / cells / c
    prev, now = np.zeros(cells + 1), np.full(cells + 1, velocity * dt)
    prev[[0, -1]] = now[[0, -1]] = 0.0
    slope = np.abs(np.diff(now))
    for _ in range(cells // 2 - 1):
        nxt = np.zeros_like(now)
        nxt[1:-1] = now[2:] + now[:-2] - prev[1:-1]
        assert np.all(np.abs(np.diff(nxt)) >= slope - 1e-12 * velocity * dt)  # round-off
        prev, now, slope = now, nxt, np.abs(np.diff(nxt))
    nxt = np.zeros_like(now)
    nxt[1:-1] = now[2:] + now[:-2] - prev[1:-1]
    assert np.abs(nxt - prev).max() / (2 * dt) < 1e-9 * velocity  # at rest at t_f = (cells/2)·Δt
    assert now[cells // 2] == pytest.approx(limit.deflection, rel=1e-12)
    assert cells // 2 * dt == pytest.approx(limit.stop_time, rel=1e-12)
    kinetic = 0.5 * MASS_PER_AREA * velocity**2 * SPAN
    assert rp.string_plastic_work(limit.deflection, SPAN, N0) == pytest.approx(kinetic, rel=(limit.deflection / SPAN) ** 2)


def test_the_mass_string_tends_to_the_quasi_static_one():
    """The mode approximation of the struck string tends to the quasi-static string V_0 √(GL/(4N_0)) as G/(ρhL) grows
    (its correction falls as the strip's share ρhL/(3G)); at the tests' ratio, 10, it is 1.7 % short of it."""
    quasi = [rp.mass_string(r * MASS_PER_AREA * SPAN, 36.0, SPAN, THICKNESS, METAL.density, N0) for r in (10.0, 1e6)]
    assert quasi[1].uncertainty / quasi[1].deflection < 1e-6
    assert quasi[0].uncertainty / (quasi[0].deflection + quasi[0].uncertainty) == pytest.approx(1 - math.sqrt(10 / (10 + 1 / 3)), rel=1e-12)


# ---- the package's strip --------------------------------------------------------------------------------------------

IMPULSES = (80.0, 120.0)  # [m/s]: the strings' W_f 10.6 h and 15.8 h
STRUCK = (MASS_RATIO * MASS_PER_AREA * SPAN, 36.0)  # G [kg/m], V_0 [m/s]: W_f 14.8 h


@pytest.fixture(scope="module")
def impulsive_runs() -> dict[float, StripRun]:
    return {v: package_strip(v) for v in IMPULSES}


@pytest.fixture(scope="module")
def struck_run() -> StripRun:
    return package_strip(STRUCK[1], mass=STRUCK[0])


@pytest.mark.slow
@pytest.mark.parametrize("velocity", IMPULSES)
def test_the_impulse_is_past_elastic(impulsive_runs, velocity):
    """Inside rigid-plastic theory's premise: the initial kinetic energy is 9 and 20 times the membrane's elastic
    capacity and at least 98 % of it goes into plastic work (98.7 % and 100.2 % counted); the strip ends on the side it
    was pushed to (not the anomalous rebound through to the other side that Symonds & Yu 1985 describe, J. Appl.
    Mech. 52:517, abstract)."""
    run = impulsive_runs[velocity]
    assert run.work_in > 8 * rp.elastic_capacity(SPAN, N0, THICKNESS, METAL.youngs_modulus, METAL.poisson_ratio)
    assert run.plastic_work > 0.98 * run.work_in
    assert run.permanent > 0.5 * run.peak


@pytest.mark.slow
@pytest.mark.parametrize("velocity", IMPULSES)
def test_impulsive_peak_is_the_strings_deflection(impulsive_runs, velocity):
    """The peak centre deflection is the string's W_f = V_0 L/(2c) within half a thickness, the bending capacity's
    estimated lowering (measured: −0.11 mm of 21.13 at 80 m/s, −0.68 mm of 31.70 at 120 m/s)."""
    limit = rp.impulsive_string(velocity, SPAN, THICKNESS, METAL.density, N0)
    assert impulsive_runs[velocity].peak == pytest.approx(limit.deflection, abs=TOLERANCE)


@pytest.mark.slow
@pytest.mark.parametrize("velocity", IMPULSES)
def test_the_strip_stops_when_the_string_does(impulsive_runs, velocity):
    """The centre stops at the string's t_f = L/(2c) within 10 % (1.04 and 1.02 t_f measured): the hinges running in from the
    supports meet there, where an elastic strip would still be rising (its quarter period is 3.4 t_f)."""
    limit = rp.impulsive_string(velocity, SPAN, THICKNESS, METAL.density, N0)
    assert impulsive_runs[velocity].time_of_peak == pytest.approx(limit.stop_time, rel=0.1)


@pytest.mark.slow
@pytest.mark.parametrize("velocity", IMPULSES)
def test_impulsive_dent_is_the_string_less_its_springback(impulsive_runs, velocity):
    """The permanent centre deflection is the string's less its membrane's elastic springback, √(W_f² − ε_eL²/2),
    within half a thickness (measured −0.58 mm of 18.69 at 80 m/s, −0.58 mm of 30.13 at 120 m/s)."""
    limit = rp.impulsive_string(velocity, SPAN, THICKNESS, METAL.density, N0)
    assert impulsive_runs[velocity].permanent == pytest.approx(string_permanent(limit.deflection), abs=TOLERANCE)


@pytest.mark.slow
def test_impulsive_strip_matches_the_independent_code(impulsive_runs):
    """At 120 m/s the independent elastic–plastic code (Kirchhoff strip, 16 elements, 8 layers, 2 µs) gives the same
    peak within 3 % and the same permanent deflection within 5 % (the package's +1.0 % and +2.3 %: the
    discretisations, each within 2 % of its refinement in the reference's own test, and the FSDT plate's shear)."""
    r = ref.strip(ref.Impulse(120.0), length=SPAN, thickness=THICKNESS, metal=METAL, elements=16, layers=8, dt=2e-6)
    assert r.settled and not r.snapped_through
    assert impulsive_runs[120.0].peak == pytest.approx(r.peak_centre_deflection, rel=0.03)
    assert impulsive_runs[120.0].permanent == pytest.approx(r.permanent_centre_deflection, rel=0.05)


@pytest.mark.slow
def test_struck_strip_is_the_mass_string(struck_run):
    """Struck at mid-span by ten times its mass at 36 m/s (energy 19 times the elastic capacity, plastic work ≥ 98 % of
    the kinetic energy, 99.0 % counted): the peak is the mode approximation's W_f within half a thickness plus the
    approximation's own correction (+0.94 mm of 29.58 measured, 1.49 allowed), reached at its stop time within 10 %
    (0.96 measured), and the permanent deflection is the string's less its springback within the same (+0.42 mm of
    27.89)."""
    mass, velocity = STRUCK
    limit = rp.mass_string(mass, velocity, SPAN, THICKNESS, METAL.density, N0)
    assert struck_run.work_in > 8 * rp.elastic_capacity(SPAN, N0, THICKNESS, METAL.youngs_modulus, METAL.poisson_ratio)
    assert struck_run.plastic_work > 0.98 * struck_run.work_in
    assert struck_run.peak == pytest.approx(limit.deflection, abs=TOLERANCE + limit.uncertainty)
    assert struck_run.time_of_peak == pytest.approx(limit.stop_time, rel=0.1)
    assert struck_run.permanent == pytest.approx(string_permanent(limit.deflection), abs=TOLERANCE + limit.uncertainty)
