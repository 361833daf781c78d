"""Rigid-perfectly-plastic closed forms for a strip struck at mid-span or loaded impulsively, at deflections many times
its thickness: the string limit (issue 40).

The structure: a strip of span L and thickness h in cylindrical bending (plane strain, ε_yy = 0; every quantity per
metre of width), clamped at both ends, the ends immovable in their plane (a skin bay between stiff frames), of a
rigid-perfectly-plastic metal of density ρ and yield stress σ_y. At a deflection W ≫ h it carries its load as a plastic
string: the membrane force is the plane-strain yield force

    N_0 = (2/√3) σ_y h        (von Mises with ε_yy = 0 in the plastic flow: σ_yy = σ_xx/2),

the same everywhere, and small slopes are assumed (the strip's membrane strain is ½w'², von Kármán's).

**Not Jones's.** Issue 40 asked for N. Jones's closed forms (*Structural Impact*, Cambridge UP: the impulsively loaded
and the mass-struck plate with finite-deflection effects), their ranges and the agreement with tests that he states.
They were sought (the stored public pages hold the opening pages of papers that quote them, not the equations) and
not retrieved, so nothing of his is used here: the forms below are derived in this module from first principles, and
their tolerances in the tests are the estimates of what each form neglects (below), not a published agreement.

Impulse (:func:`impulsive_string`). A uniform initial velocity V_0, the strip at rest in shape. With m = ρh and
c = √(N_0/m) the string obeys m w_tt = N_0 w_xx wherever it stretches; d'Alembert's solution with the odd, 2L-periodic
extension V̂ of V_0 is w(x, t) = (1/2c) ∫_{x−ct}^{x+ct} V̂(s) ds: two hinges run in from the supports at c, behind
them the strip lies still at the slope V_0/c, between them it translates flat at V_0. Every point's slope only grows
(0 → V_0/c), so every point stretches and the wave solution is the rigid-plastic one. At t_f = L/(2c) the hinges
meet at mid-span and the velocity ½[V̂(x + ct) + V̂(x − ct)] is zero everywhere (one argument in (0, L), the other in
its mirror): the strip stops as a triangle of centre deflection

    W_f = V_0 L/(2c) = (V_0 L/2) √(ρh/N_0),

its plastic work N_0·2W_f²/L (the stretch of the triangle, 2W²/L at small slopes) equal to the kinetic energy
½ m V_0² L, all of it (:func:`string_plastic_work`).

Mass (:func:`mass_string`). A mass G [kg per metre of width] at V_0 strikes mid-span, the strip at rest. One-mode
approximation with the triangle φ = 1 − 2|x|/L (the rest shape above, and the static string's under a central load):
the modal mass M* = G + mL/3, the modal velocity from the momentum M*·Ẇ_0 = G V_0, the plastic work 2N_0W²/L: a
linear "spring" 4N_0/L that dissipates all it takes, so

    W_f = G V_0 √(L / (4 N_0 M*)),        t_f = (π/2) √(M* L / (4 N_0)),

exact as G/(mL) → ∞ (the quasi-static string, W_f → V_0 √(GL/(4N_0))); its error is of the order of the strip's
share mL/(3G) (the correction √(G/M*) itself is taken as its uncertainty: :func:`mass_string`'s ``uncertainty``).

What the forms neglect (estimates derived here, the tests' tolerances):

- the bending capacity M_0 = N_0 h/4: on the triangle mechanism its hinges (two at the supports, one of twice the
  rotation at mid-span) turn by 4·(2W/L) in all and dissipate 8M_0W/L = 2N_0hW/L against the string's 2N_0W²/L, a
  share h/W, which lowers W by about h/2 (:data:`BENDING_DEFLECTION` of a thickness);
- elasticity: the elastic–plastic strip springs back as its membrane unloads, by the plane-strain elastic strain
  ε_e = N_0(1 − ν²)/(E h): the triangle's stretch 2W²/L shortens by ε_e L, so W_p = √(W_f² − ε_e L²/2)
  (:func:`elastic_springback`; the bending springback neglected); the membrane's elastic capacity
  U_e = ½ N_0 ε_e L measures how far a run is past elastic (:func:`elastic_capacity`);
- hardening (a hardening metal's membrane force at the strain ½(2W/L)² exceeds N_0: :func:`plane_strain_flow_force`
  gives the bracket) and strain rate.

Units SI: m, Pa, kg/m³, m/s, s; forces, energies and masses per metre of width.
"""

from __future__ import annotations

import math
from typing import NamedTuple

__all__ = [
    "BENDING_DEFLECTION",
    "StringLimit",
    "plane_strain_yield_force",
    "plane_strain_flow_force",
    "impulsive_string",
    "mass_string",
    "string_plastic_work",
    "elastic_springback",
    "elastic_capacity",
]

BENDING_DEFLECTION = 0.5  # of the thickness: the bending capacity's estimated lowering of W (module docstring)


class StringLimit(NamedTuple):
    """The rigid-plastic string's final centre deflection ``deflection`` [m] (its permanent one: the string stops and
    stays), the time it stops ``stop_time`` [s] after the load, and ``uncertainty`` [m], the form's own error estimate
    (0 for the impulse, exact within its assumptions; the mode approximation's correction for the mass)."""

    deflection: float
    stop_time: float
    uncertainty: float


def _positive(**values: float) -> None:
    for name, v in values.items():
        if not (math.isfinite(v) and v > 0):
            raise ValueError(f"{name} must be a positive finite number, got {v!r}")


def plane_strain_yield_force(yield_stress: float, thickness: float) -> float:
    """N_0 = (2/√3) σ_y h [N/m]: the membrane force of a von Mises strip yielding in plane strain."""
    _positive(yield_stress=yield_stress, thickness=thickness)
    return 2.0 / math.sqrt(3.0) * yield_stress * thickness


def plane_strain_flow_force(yield_stress: float, hardening_modulus: float, thickness: float, strain: float) -> float:
    """The membrane force [N/m] of a linearly hardening von Mises strip (σ_y + H ε̄ᵖ) stretched in plane strain to the
    axial strain ``strain``, counting it all plastic: ε̄ᵖ = (2/√3) ε_xx (plastic incompressibility with ε_yy = 0),
    N = (2/√3)(σ_y + H ε̄ᵖ) h. An upper estimate of the force a hardening string reaches at that strain."""
    if not (math.isfinite(strain) and strain >= 0):
        raise ValueError(f"strain must be a non-negative finite number, got {strain!r}")
    return plane_strain_yield_force(yield_stress + hardening_modulus * 2.0 / math.sqrt(3.0) * strain, thickness)


def impulsive_string(velocity: float, span: float, thickness: float, density: float, membrane_force: float) -> StringLimit:
    """The rigid-plastic string struck by a uniform initial ``velocity`` V_0 [m/s] (module docstring): W_f = V_0 L/(2c),
    c = √(N_0/(ρh)), stopping at t_f = L/(2c); ``membrane_force`` N_0 [N/m] (:func:`plane_strain_yield_force`)."""
    _positive(velocity=velocity, span=span, thickness=thickness, density=density, membrane_force=membrane_force)
    c = math.sqrt(membrane_force / (density * thickness))
    return StringLimit(velocity * span / (2.0 * c), span / (2.0 * c), 0.0)


def mass_string(mass: float, velocity: float, span: float, thickness: float, density: float, membrane_force: float) -> StringLimit:
    """The rigid-plastic string struck at mid-span by ``mass`` G [kg/m] at ``velocity`` V_0 [m/s], one-mode
    approximation (module docstring): W_f = G V_0 √(L/(4N_0 M*)), M* = G + ρhL/3, stopping at (π/2)√(M* L/(4N_0));
    ``uncertainty`` the mode approximation's correction W_q − W_f against the quasi-static W_q = V_0 √(GL/(4N_0))."""
    _positive(mass=mass, velocity=velocity, span=span, thickness=thickness, density=density, membrane_force=membrane_force)
    modal = mass + density * thickness * span / 3.0
    w = mass * velocity * math.sqrt(span / (4.0 * membrane_force * modal))
    quasi_static = velocity * math.sqrt(mass * span / (4.0 * membrane_force))
    return StringLimit(w, 0.5 * math.pi * math.sqrt(modal * span / (4.0 * membrane_force)), quasi_static - w)


def string_plastic_work(deflection: float, span: float, membrane_force: float) -> float:
    """N_0 times the stretch of the triangle of centre ``deflection`` [J/m]: N_0 (2√((L/2)² + W²) − L), which is
    2N_0W²/L at small slopes."""
    return membrane_force * (2.0 * math.hypot(span / 2.0, deflection) - span)


def elastic_springback(deflection: float, span: float, membrane_force: float, thickness: float, youngs_modulus: float, poisson_ratio: float) -> float:
    """The centre deflection [m] of the triangle of ``deflection`` W_f once its membrane has unloaded elastically from
    N_0 in plane strain: √(W_f² − ε_e L²/2), ε_e = N_0(1 − ν²)/(E h) (module docstring; bending springback neglected)."""
    eps = membrane_force * (1.0 - poisson_ratio**2) / (youngs_modulus * thickness)
    left = deflection**2 - eps * span**2 / 2.0
    if left <= 0:
        raise ValueError(f"a deflection of {deflection!r} m springs back flat: the string is not past elastic")
    return math.sqrt(left)


def elastic_capacity(span: float, membrane_force: float, thickness: float, youngs_modulus: float, poisson_ratio: float) -> float:
    """U_e = ½ N_0 ε_e L [J/m]: the elastic energy of the strip's membrane at N_0 in plane strain, the measure of how far
    an impact's energy is past the elastic strip's."""
    eps = membrane_force * (1.0 - poisson_ratio**2) / (youngs_modulus * thickness)
    return 0.5 * membrane_force * eps * span
