"""Hail and bird: ice and gelatin projectiles, their crushing and hydrodynamic contact laws, and the threats.

Every expected number comes from outside the code under test: a closed form, a cited publication, or an
independent integration written here (scipy's solve_ivp on the projectile's own equations).
"""

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from softimpact.errors import InputError
from softimpact.fem.newmark import SolverSpec
from softimpact.input.bar_case import load_bar_case
from softimpact.models.crushing_law import CrushingLaw, centre_of_mass_advance, sphere_crush_depth
from softimpact.models.hydrodynamic_law import HydrodynamicLaw
from softimpact.models.materials import CATALOGUE, hexagonal_isotropic_moduli, sphere_mass
from softimpact.models.projectiles import JONES_1997_FRESHWATER, WILBECK_GELATIN, PowerLawStrength
from softimpact.models.protocols import ContactLaw
from softimpact.models.specimens import Impactor
from softimpact.models.threats import BIRD_MASSES, hail_terminal_velocity, sphere_diameter
from softimpact.models.validity import hydrodynamic_validity, ice_strength_validity
from softimpact.units import INCH
from softimpact.workflows.bar_impact import simulate_impact

ICE, GELATIN = CATALOGUE["ice"], CATALOGUE["gelatin"]
# The published bar tests of ice spheres on a rigid target ("Experiments on an ice ball impacting onto a rigid
# target", abstract at discovery.researcher.life): 31.8-50.8 mm, 13-105 m/s, impulse over momentum 0.8-1.12.
IMPULSE_BAND = (0.8, 1.12)
ICE_POINTS = [(0.0318, 13.0), (0.0318, 105.0), (0.0508, 13.0), (0.0508, 105.0)]


def _rigid(law, mass, velocity, t_end):
    """m·α̈ = −F(α, α̇) on a rigid target (α the approach), integrated by scipy until the impactor stops or the
    sphere is consumed (its centre of mass at the target, α = d/2)."""

    def rhs(t, y):
        return [y[1], -law.force(y[0], y[1]) / mass]

    def stopped(t, y):
        return y[1] - 1e-9 * velocity

    def consumed(t, y):
        return y[0] - 0.5 * law.diameter * (1 - 1e-7)

    stopped.terminal = consumed.terminal = True
    T = law.diameter / velocity
    return solve_ivp(
        rhs, (0.0, t_end), [0.0, velocity], method="LSODA", events=[stopped, consumed], rtol=1e-10, atol=1e-14, max_step=T / 1000, dense_output=True
    )


def _soft_missile(diameter, density, velocity, strength):
    """The sphere's soft-missile equations in the crushed length s (remainder m_r(s) = m − ρ·π·s²(3R − s)/3, a
    spherical cap's volume): m_r·s̈ = −A(s)·σ(ṡ/d), F = A(s)·(σ + ρ·ṡ²), A = π·s·(d − s). Returns (t, F)."""
    R = diameter / 2
    m = density * math.pi * diameter**3 / 6

    def sigma(v):
        return strength(v / diameter)[0] if strength is not None else 0.0

    def rhs(t, y):
        s, v = y
        mr = m - density * math.pi * s * s * (3 * R - s) / 3
        return [v, -math.pi * s * (diameter - s) * sigma(v) / mr]

    def stopped(t, y):
        return y[1] - 1e-9 * velocity

    def consumed(t, y):
        return y[0] - diameter * (1 - 1e-9)

    stopped.terminal = consumed.terminal = True
    T = diameter / velocity
    sol = solve_ivp(
        rhs, (0.0, 3 * T), [0.0, velocity], method="LSODA", events=[stopped, consumed], rtol=1e-10, atol=1e-14, max_step=T / 1000, dense_output=True
    )

    def force(t):
        s, v = sol.sol(t)
        return math.pi * s * (diameter - s) * (sigma(v) + density * v * v) if v > 0 else 0.0

    return sol, force


def test_isotropic_stiffness_gives_its_own_moduli():
    """The Voigt-Reuss-Hill average of an isotropic stiffness (c11 = c33 = λ + 2μ, c12 = c13 = λ, c44 = μ) is E = μ(3λ + 2μ)/(λ + μ), ν = λ/(2(λ + μ))."""
    lam, mu = 6.0e9, 3.5e9
    E, nu = hexagonal_isotropic_moduli(lam + 2 * mu, lam, lam, lam + 2 * mu, mu)
    assert E == pytest.approx(mu * (3 * lam + 2 * mu) / (lam + mu), rel=1e-12)
    assert nu == pytest.approx(lam / (2 * (lam + mu)), rel=1e-12)


def test_catalogue_ice_lies_between_voigt_and_reuss_bounds_of_gammon_constants():
    """Catalogue ice: density 916.7 kg/m³ (0 °C) and a Young's modulus between the Reuss and Voigt bounds of Gammon et al.'s c_ij (computed here)."""
    c11, c12, c13, c33, c44 = (139.29e8, 70.82e8, 57.65e8, 150.10e8, 30.14e8)
    c66 = (c11 - c12) / 2
    C = np.array(
        [[c11, c12, c13, 0, 0, 0], [c12, c11, c13, 0, 0, 0], [c13, c13, c33, 0, 0, 0], [0, 0, 0, c44, 0, 0], [0, 0, 0, 0, c44, 0], [0, 0, 0, 0, 0, c66]]
    )
    S = np.linalg.inv(C)
    kv, gv = (C[:3, :3].sum()) / 9, (np.trace(C[:3, :3]) - (c12 + 2 * c13) + 3 * (2 * c44 + c66)) / 15
    kr, gr = 1 / S[:3, :3].sum(), 15 / (4 * np.trace(S[:3, :3]) - 4 * (S[0, 1] + S[1, 2] + S[0, 2]) + 3 * (2 * S[3, 3] + S[5, 5]))
    e_voigt, e_reuss = 9 * kv * gv / (3 * kv + gv), 9 * kr * gr / (3 * kr + gr)
    assert e_reuss < ICE.youngs_modulus < e_voigt
    assert ICE.density == 916.7


def test_centre_of_mass_advance_is_the_remaining_mass_fraction_integrated():
    """dX/ds of the crush geometry is the uncrushed fraction 1 − V_cap(s)/V_sphere (a spherical cap's volume), and X(s) inverts."""
    d = 1.0
    s = np.linspace(0.01, 0.99, 50)
    remaining = 1 - (math.pi * s**2 * (1.5 * d - s) / 3) / (math.pi * d**3 / 6)
    h = 1e-6
    slope = (np.array([centre_of_mass_advance(x + h) for x in s]) - np.array([centre_of_mass_advance(x - h) for x in s])) / (2 * h)
    np.testing.assert_allclose(slope, remaining, rtol=1e-6)
    assert centre_of_mass_advance(1.0) == pytest.approx(0.5)  # the whole sphere at the target: its centre moved by R
    np.testing.assert_allclose([sphere_crush_depth(centre_of_mass_advance(x)) for x in s], s, rtol=1e-12)


@pytest.mark.parametrize("law", [CrushingLaw(0.05, 0.05, JONES_1997_FRESHWATER), HydrodynamicLaw(0.05, 0.05, 100.0)])
def test_laws_follow_the_contact_protocol_and_their_tangents_are_the_derivatives(law):
    """Both laws are ContactLaws: no force apart or receding, nothing stored, and ∂F/∂α, ∂F/∂α̇ equal central differences."""
    assert isinstance(law, ContactLaw)
    assert law.force(-1e-3, 50.0) == 0.0 and law.force(1e-3, -1.0) == 0.0 and law.energy(1e-3) == 0.0
    for alpha, rate in [(1e-4, 90.0), (4e-3, 60.0), (0.015, 20.0)]:
        h, g = 1e-7 * alpha, 1e-7 * rate
        dfa = (law.force(alpha + h, rate) - law.force(alpha - h, rate)) / (2 * h)
        dfr = (law.force(alpha, rate + g) - law.force(alpha, rate - g)) / (2 * g)
        assert law.stiffness(alpha, rate) == pytest.approx(dfa, rel=1e-5)
        assert law.damping(alpha, rate) == pytest.approx(dfr, rel=1e-5)


def test_fragment_flow_limit_is_the_momentum_flux_closed_form():
    """Without strength the crush is the momentum flux alone: F(t) = ρ·π·(d·V·t − V²t²)·V², lasting d/V, impulse m·V."""
    d, V = 0.0508, 60.0
    m = sphere_mass(ICE, d)
    law = CrushingLaw.of(ICE, d, m, V)
    law = replace(law, strength=None)
    sol = _rigid(law, m, V, 0.999 * d / V)
    t = np.linspace(0, 0.99 * d / V, 200)
    F = np.array([law.force(*sol.sol(ti)) for ti in t])
    closed = ICE.density * math.pi * (d * V * t - V**2 * t**2) * V**2
    np.testing.assert_allclose(F, closed, rtol=1e-6, atol=1e-9 * closed.max())
    assert sol.y[1, -1] == pytest.approx(0.0, abs=1e-3 * V)  # the centre of mass at rest once the sphere is consumed


@pytest.mark.parametrize("d, V", ICE_POINTS)
def test_crushing_law_is_the_soft_missile_solution(d, V):
    """The law's rigid impactor (the centre of mass) reproduces the soft-missile equations in the crushed length, integrated independently: force to 1e-5, same duration."""
    m = sphere_mass(ICE, d)
    law = CrushingLaw.of(ICE, d, m, V)
    sol = _rigid(law, m, V, 3 * d / V)
    ref, ref_force = _soft_missile(d, ICE.density, V, JONES_1997_FRESHWATER)
    t_end = min(sol.t[-1], ref.t[-1])
    assert sol.t[-1] == pytest.approx(ref.t[-1], rel=1e-4)
    t = np.linspace(0, 0.98 * t_end, 100)
    F = np.array([law.force(*sol.sol(ti)) for ti in t])
    Fr = np.array([ref_force(ti) for ti in t])
    np.testing.assert_allclose(F, Fr, rtol=1e-5, atol=1e-6 * Fr.max())


@pytest.mark.parametrize("d, V", ICE_POINTS)
def test_crushing_dissipates_the_kinetic_energy_and_does_not_rebound(d, V):
    """On a rigid target the crushing law's work ∫F dα is the initial kinetic energy minus the rebound's, and there is no rebound (final velocity 0, never negative)."""
    m = sphere_mass(ICE, d)
    law = CrushingLaw.of(ICE, d, m, V)
    sol = _rigid(law, m, V, 3 * d / V)
    alpha, rate = sol.y
    F = np.array([law.force(a, r) for a, r in zip(alpha, rate)])
    work = float(np.sum(0.5 * (F[1:] + F[:-1]) * np.diff(alpha)))
    assert rate.min() >= -1e-9 * V and rate[-1] == pytest.approx(0.0, abs=1e-6 * V)
    assert work == pytest.approx(0.5 * m * V**2 - 0.5 * m * rate[-1] ** 2, rel=1e-4)
    impulse = float(np.sum(0.5 * (F[1:] + F[:-1]) * np.diff(sol.t)))
    assert IMPULSE_BAND[0] <= impulse / (m * V) <= IMPULSE_BAND[1]


@pytest.mark.parametrize("d, V", [(0.0508, 105.0), (sphere_diameter(1.8, 950.0), 150.0)])
def test_gelatin_on_a_rigid_target_impulse_and_hugoniot_pressure(d, V):
    """A gelatin sphere (and the CS 25.631 1.8 kg bird as a sphere) on a rigid target: impulse within 3 % of m·V, peak pressure within 10 % of Wilbeck's ρ(c0 + k·V)·V."""
    m = sphere_mass(GELATIN, d)
    law = HydrodynamicLaw.of(GELATIN, d, m, V)
    sol = _rigid(law, m, V, 1.5 * d / V)
    t = sol.t
    F = np.array([law.force(a, r) for a, r in sol.y.T])
    pressure = np.array([f / (math.pi * law.radius(a) ** 2) if f > 0 else 0.0 for f, a in zip(F, sol.y[0])])
    impulse = float(np.sum(0.5 * (F[1:] + F[:-1]) * np.diff(t)))
    rho, c0, k = 950.0, 1482.9, 2.0  # Wilbeck's constants (saullocastro/birdpressure, Bird.py)
    assert impulse == pytest.approx(m * V, rel=0.03)
    assert pressure.max() == pytest.approx(rho * (c0 + k * V) * V, rel=0.10)
    assert t[F > 0][-1] == pytest.approx(d / V, rel=0.05)  # the flow lasts the length over the velocity


def _bar_run(law, d, V, duration, steps):
    """The bar workflow with ``law``: time step d/V/``steps`` (the crush's stop needs a fine step: at d/V/250 the
    trapezoidal rule overshoots it into a rebound of ~2 % of V at 13 m/s), run for ``duration``·d/V."""
    base, _ = load_bar_case("paper-calibration")
    # The paper's 36-in aluminium bar, made 2 in wide (no end cap) so the 31.8-50.8 mm spheres crush on its face;
    # the published tests' bar dimensions were not retrieved.
    bar = replace(base.bar, diameter=2.0 * INCH, end_cap=None)
    p = Impactor.solid(ICE, d, V)
    T = d / V
    problem = replace(base, bar=bar, projectile=p, law=law, solver=SolverSpec(T / steps, duration * T), snapshots=())
    return simulate_impact(problem), p


@pytest.mark.parametrize("d, V", ICE_POINTS)
def test_ice_sphere_on_the_bar_impulse_within_published_band(d, V):
    """An ice sphere crushing on the instrumented bar (the bar workflow, the crushing law object): impulse over m·V within the published 0.8-1.12, no rebound."""
    m = sphere_mass(ICE, d)
    r, p = _bar_run(CrushingLaw.of(ICE, d, m, V), d, V, 0.6, 1000)
    assert r.separated
    assert IMPULSE_BAND[0] <= r.impulse / (p.mass * V) <= IMPULSE_BAND[1]
    assert r.rebound_velocity >= -1e-3 * V  # no rebound (to the time discretisation)


@pytest.mark.parametrize("d, V", [(0.0318, 105.0), (0.0508, 13.0)])
def test_fragment_flow_on_the_bar_lasts_about_d_over_v(d, V):
    """Without crushing strength (the fragment-flow limit) an ice sphere on the bar: impulse over m·V within 0.8-1.12, contact duration within 30 % of d/V."""
    m = sphere_mass(ICE, d)
    r, p = _bar_run(replace(CrushingLaw.of(ICE, d, m, V), strength=None), d, V, 1.5, 250)
    assert IMPULSE_BAND[0] <= r.impulse / (p.mass * V) <= IMPULSE_BAND[1]
    assert r.contact_duration == pytest.approx(d / V, rel=0.30)


@pytest.mark.xfail(
    strict=True, reason="Jones 1997's intact-ice strength, extrapolated to impact rates, stops the sphere in 0.06-0.45 d/V (docs/hail-and-bird.md)"
)
@pytest.mark.parametrize("d, V", [(0.0318, 13.0), (0.0508, 105.0)])
def test_intact_strength_crush_lasts_about_d_over_v(d, V):
    """The done-when criterion for the crushing law with its catalogue strength: contact duration within 30 % of d/V (known to fail: the gap is documented)."""
    m = sphere_mass(ICE, d)
    law = CrushingLaw.of(ICE, d, m, V)
    sol = _rigid(law, m, V, 3 * d / V)
    assert sol.t[-1] == pytest.approx(d / V, rel=0.30)


def test_power_law_strength_is_jones_1997_in_its_range_and_ramps_to_zero_below():
    """σ_c = 8.9 MPa·ε̇^0.15 over 0.1-10 1/s (Jones 1997, freshwater ice): 8.9 MPa at 1/s, 12.57 MPa at 10/s; linear to zero below 0.1/s."""
    s = JONES_1997_FRESHWATER
    assert s(1.0)[0] == pytest.approx(8.9e6)
    assert s(10.0)[0] == pytest.approx(8.9e6 * 10**0.15)
    assert s(0.05)[0] == pytest.approx(0.5 * 8.9e6 * 0.1**0.15)
    assert s(0.0) == (0.0, 0.0)
    with pytest.raises(InputError, match="exponent"):
        PowerLawStrength(8.9e6, 1.5, (0.1, 10.0))


def test_hail_terminal_velocity_against_the_one_centimetre_stone():
    """The drag-law terminal velocity of a 1 cm stone is within 5 % of 13.9 m/s (Munich Re 1984: 1 cm falls at 50 km/h, quoted by hypertextbook.com)."""
    assert hail_terminal_velocity(0.01) == pytest.approx(50 / 3.6, rel=0.05)
    assert hail_terminal_velocity(0.04) / hail_terminal_velocity(0.01) == pytest.approx(2.0, rel=1e-12)  # V_t ∝ sqrt(D)


def test_bird_masses_are_the_rules_numbers():
    """The certification birds: 8 lb (14 CFR 25.631), 4 lb (25.775, 25.571), 1.8 kg (CS 25.631), 1.0 kg (29.631)."""
    masses = {b.rule: b.mass for b in BIRD_MASSES}
    assert masses["14 CFR 25.631"] == pytest.approx(8 * 0.45359237)
    assert masses["14 CFR 25.775"] == pytest.approx(4 * 0.45359237)
    assert masses["EASA CS 25.631"] == 1.8 and masses["14 CFR 29.631"] == 1.0


def test_validity_envelopes_flag_the_strength_extrapolation_and_pass_bird_speeds():
    """Hail at 13 m/s on a 50.8 mm stone crushes at 256 1/s, past Jones's 10 1/s: flagged; a bird at 150 m/s releases its shock at a shallow depth: not flagged."""
    v = ice_strength_validity(0.0508, 13.0, JONES_1997_FRESHWATER)
    assert v.names == ("extrapolated_strain_rate",) and v.values["strain_rate_over_fitted_max"] == pytest.approx(13.0 / 0.0508 / 10.0)
    h = hydrodynamic_validity(0.15, 150.0, WILBECK_GELATIN)
    assert h.flags == () and h.values["release_depth_over_diameter"] == pytest.approx(150**2 / (4 * (1482.9 + 2 * 150) ** 2))


def test_constructors_refuse_the_wrong_material():
    """The crushing law needs a strength (ice), the hydrodynamic law a Hugoniot (gelatin)."""
    with pytest.raises(InputError, match="crushing strength"):
        CrushingLaw.of(GELATIN, 0.05, 0.06, 50.0)
    with pytest.raises(InputError, match="Hugoniot"):
        HydrodynamicLaw.of("ice", 0.05, 0.06, 50.0)
    with pytest.raises(InputError, match="no crushing or flow data"):
        CrushingLaw.of(CATALOGUE["steel"], 0.05, 0.5, 50.0)
