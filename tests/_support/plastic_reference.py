"""Independent elastic–plastic references for the metal-skin dent (issue 40): a strip in cylindrical bending
and an axisymmetric circular plate, Kirchhoff kinematics with von Kármán membrane strains, J2 plasticity
with linear isotropic hardening integrated through the thickness.

Written apart from the package (numpy only; nothing imported from softimpact) and deliberately with another
formulation than the package's plate (FSDT, MITC elements, Simo–Taylor's plane-stress return map): here the
structure is one-dimensional (the coordinate s runs from the centre, s = 0, to the support, s = a), w is a
C¹ cubic Hermite field (no transverse shear), u a quadratic field, and the return map is solved in the
principal axes of the two in-plane normal stresses.

Kinematics (z from the mid-surface, w positive along the load):

- strip (plane strain, per unit width, a = L/2, symmetric about mid-span):
  ε₁ = u' + ½w'² − z w'', ε₂ = 0 (ε_yy = 0 at every point), σ_zz = 0;
- circular plate (axisymmetric, a = R): ε₁ = ε_r = u' + ½w'² − z w'', ε₂ = ε_θ = u/r − z w'/r.

Both are written ε_i(z) = ε̄_i + z κ_i with the generalised strains (ε̄₁, ε̄₂, κ₁, κ₂) = (u' + ½w'², u/r, −w'', −w'/r)
(the strip has ε̄₂ = κ₂ = 0); ``kinematics="linear"`` drops ½w'². The stress resultants (N₁, N₂, M₁, M₂) =
∫ σ_i (1, z) dz are integrated by a composite two-point Gauss rule in ``layers`` equal layers (exact for the
elastic section and, with an even number of layers, for the fully plastic one; see :func:`through_thickness`).
The internal virtual work ∫ (N·δε̄ + M·δκ) dA, dA = 2 ds (the whole strip, per unit width) or 2πr ds (the plate),
gives the internal force and its tangent (material part BᵀCB plus the geometric part N₁ δw' w').

Inertia: the consistent mass ρh ∫ (δu u + δw w) dA; the rotary inertia ρh³/12 of the Kirchhoff section is left out
(a fraction of order (h/L)², 4·10⁻⁴ for the benchmark's plates), as is transverse shear (the FSDT plate's deflection
differs by a fraction of the same order).

Time integration: Newmark's average acceleration (β = ¼, γ = ½) with Newton iterations; for it the discrete
kinetic-energy change equals the trapezoidal work of the forces, so with the trapezoidal plastic work
W_p = Σ ½(σₙ + σₙ₊₁)·Δε_p and the elastic energy Ψ = ½ σ·C⁻¹σ the balance KE + Ψ + W_p (+ contact) = work in
closes to the second order in Δt (its defects: the von Kármán term ¼ ΔN₁(Δw')² of each step and point, and the
steps where a contact switches on or off).

Units SI: m, Pa, kg/m³, s; the strip's loads, energies and masses are per metre of width.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

__all__ = [
    "Metal",
    "ILLUSTRATIVE_AL_2024",
    "Pressure",
    "CentreDeflection",
    "Impulse",
    "MassImpact",
    "StaticResult",
    "DynamicResult",
    "return_map",
    "through_thickness",
    "section_response",
    "strip",
    "circular_plate",
    "first_yield_pressure_clamped_circular",
]

GAUSS_POINTS = 4  # per element along s: Hermite w'² is quartic, ρh·φφ of degree 6 (7 with the plate's r): exact
NEWTON_TOL = 1e-8  # relative residual at which an equilibrium iteration stops (round-off stalls near 1e-9 on fine meshes)
GROSS_FRACTION = 1e-3  # of the internal forces' gross size: a floor of the residual's scale (round-off where they cancel)
NEWTON_MAX = 40
CONTACT_STIFFNESS_FACTOR = 1000.0  # the default penalty of a mass impact, in units of the structure's static stiffness  # iterations before a step is cut (static) or the run fails (dynamic)
YIELD_TOL = 1e-12  # relative overstress below which a trial state counts as elastic (no flip-flop at f = 0)


@dataclass(frozen=True)
class Metal:
    """Isotropic elastic–plastic metal: E [Pa], ν, ρ [kg/m³], σ_y0 [Pa], linear hardening H [Pa] in
    σ_y(ε̄_p) = σ_y0 + H ε̄_p (H is the slope against the equivalent plastic strain)."""

    youngs_modulus: float
    poisson_ratio: float
    density: float
    yield_stress: float
    hardening_modulus: float = 0.0

    def __post_init__(self):
        for name in ("youngs_modulus", "density", "yield_stress"):
            if not getattr(self, name) > 0:
                raise ValueError(f"{name} must be > 0, got {getattr(self, name)!r}")
        if not -1.0 < self.poisson_ratio < 0.5:
            raise ValueError(f"poisson_ratio must lie in (-1, 0.5), got {self.poisson_ratio!r}")
        if not self.hardening_modulus >= 0:
            raise ValueError(f"hardening_modulus must be >= 0, got {self.hardening_modulus!r}")

    @property
    def bending_stiffness_factor(self) -> float:
        """E/(12(1 − ν²)) [Pa]: D = this × h³."""
        return self.youngs_modulus / (12 * (1 - self.poisson_ratio**2))


#: Illustrative aluminium (Al 2024-T3-like: E 73 GPa, ν 0.33, ρ 2780 kg/m³, σ_y0 345 MPa, H 700 MPa): the
#: numbers of the brief, chosen for the benchmark, not a sourced catalogue entry.
ILLUSTRATIVE_AL_2024 = Metal(73e9, 0.33, 2780.0, 345e6, 700e6)


# ---------------------------------------------------------------------------------------------------------------
# material point: plane-stress J2 in the principal axes (σ₁, σ₂), σ₃ = 0


def return_map(strain, plastic_strain, eqps, metal: Metal):
    """Backward-Euler J2 return map for two in-plane normal stresses (principal axes, no shear), σ₃ = 0.

    ``strain``, ``plastic_strain`` shape (..., 2) [-]; ``eqps`` (...,) the equivalent plastic strain ε̄_p.
    Returns (stress (..., 2) [Pa], plastic_strain (..., 2), eqps (...,), tangent dσ/dε (..., 2, 2) [Pa]).

    Derivation (written for this module). With C = E/(1−ν²)[[1, ν], [ν, 1]] and P = [[1, −½], [−½, 1]] the
    von Mises stress is σ_eq = √(σᵀPσ) (σ₁² − σ₁σ₂ + σ₂²); the flow is Δε_p = Δε̄_p Pσ/σ_eq (work-conjugate:
    σ·Δε_p = σ_eq Δε̄_p). At the end of the step σ_eq = σ_y = σ_yn + H Δε̄_p, so with x = Δε̄_p/σ_y

        (I + x CP) σ = σ_tr = C(ε − ε_pn).

    C and P share the eigenvectors (1, ±1)/√2: in the sum/difference components s = (σ₁+σ₂)/√2,
    d = (σ₁−σ₂)/√2, C = diag(E/(1−ν), E/(1+ν)), P = diag(½, 3/2), so σ_s = s_tr/(1 + c_s x),
    σ_d = d_tr/(1 + c_d x) with c_s = E/(2(1−ν)), c_d = 3E/(2(1+ν)), and σ_eq(x)² = ½σ_s² + 3/2σ_d².
    From σ_y = σ_yn + H x σ_y, σ_y = σ_yn/(1 − Hx), the one scalar equation is

        φ(x) = σ_eq(x)(1 − Hx) − σ_yn = 0,   0 ≤ x < 1/H.

    φ is convex and decreasing (σ_eq(x) is a weighted 2-norm of positive convex decreasing functions, and a
    product of positive decreasing convex functions is convex), φ(0) > 0 on plastic steps: Newton from x = 0
    rises monotonically to the root. The consistent tangent follows by differentiating σ = A(x)σ_tr with
    A = diag(1/(1+c_s x), 1/(1+c_d x)) and dx = −(∂φ/∂σ_tr · dσ_tr)/(∂φ/∂x):
    dσ = [A − (A'σ_tr) ⊗ (∂φ/∂σ_tr)/(∂φ/∂x)] C dε (in the s, d components; symmetric).
    The plane-strain strip passes ε₂ = 0: the constraint ε_yy = 0 is then exact, σ₂ whatever it must be.
    """
    E, nu, H = metal.youngs_modulus, metal.poisson_ratio, metal.hardening_modulus
    lam_s, lam_d = E / (1 - nu), E / (1 + nu)
    c_s, c_d = lam_s / 2, 1.5 * lam_d
    r2 = math.sqrt(2.0)
    strain, plastic_strain = np.asarray(strain, float), np.asarray(plastic_strain, float)
    eqps = np.asarray(eqps, float)
    ee = strain - plastic_strain
    s_tr, d_tr = lam_s * (ee[..., 0] + ee[..., 1]) / r2, lam_d * (ee[..., 0] - ee[..., 1]) / r2
    sy_n = metal.yield_stress + H * eqps
    q_tr = np.sqrt(0.5 * s_tr**2 + 1.5 * d_tr**2)
    plastic = q_tr > sy_n * (1 + YIELD_TOL)
    x = np.zeros(s_tr.shape)
    sp, dp, syp = s_tr[plastic], d_tr[plastic], sy_n[plastic]
    xp, tol = np.zeros(sp.shape), 1e-13 * syp + 1e-15 * q_tr[plastic]  # the second: round-off of a far trial state
    for _ in range(100):
        a_s, a_d = 1 / (1 + c_s * xp), 1 / (1 + c_d * xp)
        q = np.sqrt(0.5 * (a_s * sp) ** 2 + 1.5 * (a_d * dp) ** 2)
        phi = q * (1 - H * xp) - syp
        if np.all(np.abs(phi) <= tol):
            break
        if not np.all(np.isfinite(phi)):
            raise FloatingPointError("return map: a non-finite trial stress")
        dq = -(0.5 * c_s * a_s**3 * sp**2 + 1.5 * c_d * a_d**3 * dp**2) / q
        xp = xp - phi / (dq * (1 - H * xp) - H * q)
    else:
        raise FloatingPointError("return map: the scalar Newton on x did not converge")
    x[plastic] = xp
    a_s, a_d = 1 / (1 + c_s * x), 1 / (1 + c_d * x)
    sig_s, sig_d = a_s * s_tr, a_d * d_tr
    stress = np.stack([(sig_s + sig_d) / r2, (sig_s - sig_d) / r2], axis=-1)
    p_sigma = np.stack([stress[..., 0] - stress[..., 1] / 2, stress[..., 1] - stress[..., 0] / 2], axis=-1)
    new_plastic = plastic_strain + x[..., None] * p_sigma
    sy = sy_n / (1 - H * x)
    new_eqps = eqps + x * sy
    # tangent in the (s, d) components, then back to (1, 2) with Q = [[1, 1], [1, −1]]/√2 (Q = Q⁻¹), entry by entry
    u_s, u_d = -c_s * a_s * sig_s, -c_d * a_d * sig_d  # ∂σ/∂x at fixed σ_tr
    g_s, g_d = (1 - H * x) * 0.5 * a_s * sig_s / sy * lam_s, (1 - H * x) * 1.5 * a_d * sig_d / sy * lam_d  # ∂φ/∂ε (s, d)
    dphi = -(0.5 * c_s * a_s * sig_s**2 + 1.5 * c_d * a_d * sig_d**2) / sy * (1 - H * x) - H * sy
    k = np.divide(-1.0, dphi, out=np.zeros(np.shape(dphi)), where=plastic)
    dss, dsd, dds, ddd = a_s * lam_s + k * u_s * g_s, k * u_s * g_d, k * u_d * g_s, a_d * lam_d + k * u_d * g_d
    tangent = 0.5 * np.stack([np.stack([dss + dsd + dds + ddd, dss - dsd + dds - ddd], -1), np.stack([dss + dsd - dds - ddd, dss - dsd - dds + ddd], -1)], -2)
    return stress, new_plastic, new_eqps, tangent


@functools.lru_cache(maxsize=16)
def _through_thickness(thickness: float, layers: int):
    return through_thickness(thickness, layers)


def through_thickness(thickness: float, layers: int):
    """Points z (2·layers,) [m] and weights (2·layers,) [m] of the composite two-point Gauss rule over ``layers``
    equal layers of [−h/2, h/2]: ∫ f dz ≈ Σ wₖ f(zₖ). Exact for the elastic section (polynomials to degree 3 in each
    layer); with an even ``layers`` the fully plastic section's sign change at z = 0 falls on a layer boundary, so
    M_p is integrated exactly too; the error left is where an elastic–plastic front cuts a layer."""
    if layers < 1:
        raise ValueError(f"layers must be >= 1, got {layers!r}")
    edges = np.linspace(-thickness / 2, thickness / 2, layers + 1)
    mid, half = (edges[:-1] + edges[1:]) / 2, thickness / (2 * layers)
    g = half / math.sqrt(3.0)
    z = np.stack([mid - g, mid + g], axis=1).ravel()
    return z, np.full(z.size, half)


def section_response(membrane, curvature, plastic_strain, eqps, metal: Metal, thickness: float, layers: int):
    """Through-thickness integration of the return map for the generalised strains of a section.

    ``membrane`` (..., 2) = (ε̄₁, ε̄₂), ``curvature`` (..., 2) = (κ₁, κ₂) [1/m], the layer strain ε(z) = ε̄ + zκ;
    ``plastic_strain`` (..., nz, 2), ``eqps`` (..., nz) the committed state at the nz = 2·layers points.
    Returns (resultants (..., 4) = (N₁, N₂ [N/m], M₁, M₂ [N·m/m]), tangent ∂(N, M)/∂(ε̄, κ) (..., 4, 4),
    stress (..., nz, 2), plastic_strain, eqps) — the last three the trial state at these strains."""
    z, wz = _through_thickness(thickness, layers)
    strain = np.asarray(membrane)[..., None, :] + z[:, None] * np.asarray(curvature)[..., None, :]
    stress, plastic, eqps_new, D = return_map(strain, plastic_strain, eqps, metal)
    res = np.concatenate([np.einsum("...zi,z->...i", stress, wz), np.einsum("...zi,z->...i", stress, z * wz)], axis=-1)
    A, B, Dm = (np.einsum("...zij,z->...ij", D, wz * z**k) for k in (0, 1, 2))
    tangent = np.concatenate([np.concatenate([A, B], axis=-1), np.concatenate([B, Dm], axis=-1)], axis=-2)
    return res, tangent, stress, plastic, eqps_new


# ---------------------------------------------------------------------------------------------------------------
# loads (what an analysis does) and results


@dataclass(frozen=True)
class Pressure:
    """Static uniform pressure [Pa] raised to ``peak`` in ``steps`` equal increments, then (``unload``) removed in as
    many; the permanent deflection is the one left at zero pressure."""

    peak: float
    steps: int = 40
    unload: bool = True


@dataclass(frozen=True)
class CentreDeflection:
    """Static, displacement controlled: the centre deflection [m] raised to ``peak`` in ``steps`` equal increments,
    the uniform pressure that holds it found at each; then (``unload``) the pressure removed in ``steps``. Follows a
    load–deflection curve through a collapse plateau, where pressure control cannot."""

    peak: float
    steps: int = 40
    unload: bool = True


@dataclass(frozen=True)
class Impulse:
    """Impulsive load: a uniform initial transverse velocity [m/s] (nodal: w' = 0, ẇ = V₀ at every free node; the
    supported edge stays at rest, so the initial kinetic energy converges to ½ρhV₀²·area from below with the mesh)."""

    velocity: float


@dataclass(frozen=True)
class MassImpact:
    """A rigid mass striking the centre at ``velocity`` [m/s]: ``mass`` [kg] (the plate) or [kg/m] (the strip: a line
    of mass per unit width). It acts on the structure through a uniform pressure on the central disc (plate) or band
    (strip, half-width) of ``contact_radius`` [m] (0: a point or line load at the centre), coupled to the disc's mean
    deflection w̄ = gᵀd by a stiff penalty spring, F = k_c⟨W − w̄⟩₊ (no tension: the mass separates when F would
    turn tensile). ``contact_stiffness`` [N/m, or N/m per m for the strip]; default CONTACT_STIFFNESS_FACTOR times the
    static stiffness of the elastic structure under that load: stiff enough that the dent is the rigid contact's (a 0.1-kg
    mass at 30 m/s on the benchmark plate, Δt = 1 µs: 100× and 400× the static stiffness leave the dent 2 % and 0.3 %
    short of the 6400× value, 1600× within 0.1 %); the default Δt resolves the contact period 2π√(m/k_c)."""

    mass: float
    velocity: float
    contact_radius: float = 0.0
    contact_stiffness: float | None = None


@dataclass(frozen=True)
class StaticResult:
    """Static load–unload path. Histories along the path, shape (n,): ``pressure`` [Pa], ``centre_deflection`` [m],
    ``work_in`` (trapezoidal ∫p dV), ``elastic_energy`` and ``plastic_work`` [J, or J/m for the strip]. Profiles at the
    nodes (nodes,): ``position`` [m] from the centre, ``deflection_loaded`` (at the peak) and ``deflection_permanent``.
    ``first_yield_pressure`` brackets the onset of plastic flow on the path (last elastic, first plastic) [Pa];
    ``energy_error`` = max |work_in − Ψ − W_p| / max work_in; ``plastic_zone_area`` [m², or m for the strip] and
    ``max_plastic_strain`` (ε̄_p) of the final state (see ``_Model.plastic_zone``)."""

    pressure: np.ndarray
    centre_deflection: np.ndarray
    work_in: np.ndarray
    elastic_energy: np.ndarray
    plastic_work: np.ndarray
    position: np.ndarray
    deflection_loaded: np.ndarray
    deflection_permanent: np.ndarray
    peak_pressure: float
    peak_centre_deflection: float
    permanent_centre_deflection: float
    first_yield_pressure: tuple[float, float]
    energy_error: float
    plastic_zone_area: float
    max_plastic_strain: float


@dataclass(frozen=True)
class DynamicResult:
    """Transient from the impulse or impact, then the static springback. Histories (n,): ``time`` [s],
    ``centre_deflection`` [m], ``centre_velocity`` [m/s], ``kinetic_energy``, ``elastic_energy``, ``plastic_work``,
    ``contact_energy`` (the penalty spring) [J, or J/m], ``contact_force`` [N, or N/m] and ``impactor_velocity`` [m/s]
    (zero without a mass). ``work_in`` the initial kinetic energy of the discrete model; ``energy_error`` =
    max |KE + Ψ + W_p + E_c − work_in| / work_in over the run. ``peak_centre_deflection`` (the largest over the run) at
    ``time_of_peak``. Two permanent deflections, each after a static springback (loads and inertia removed in
    ``springback`` steps, plasticity active): ``permanent_centre_deflection`` from the end of the run (at rest if
    ``settled``: no plastic work over the run's last ``time_of_peak``), and ``peak_springback_centre_deflection`` from
    the state at that peak (the dent if the structure were stopped there: what rigid-plastic theory predicts,
    and robust where the first is not). ``snapped_through``: the centre crossed to the other side after the peak, the
    anomalous response in which "the permanent deflection is predicted ... to be in the direction opposite that of
    the load" and codes "exhibit a wide spread in the predicted final deflections" (Symonds & Yu 1985, J. Appl. Mech.
    52:517, abstract): then only the peak and the peak's springback are references. ``late_mean_centre_deflection``
    the mean over the run's last ``time_of_peak``; ``springback_plastic_work`` the end springback's plastic work;
    ``plastic_zone_area`` [m², or m for the strip] and ``max_plastic_strain`` (ε̄_p) after it."""

    time: np.ndarray
    centre_deflection: np.ndarray
    centre_velocity: np.ndarray
    kinetic_energy: np.ndarray
    elastic_energy: np.ndarray
    plastic_work: np.ndarray
    contact_energy: np.ndarray
    contact_force: np.ndarray
    impactor_velocity: np.ndarray
    work_in: float
    energy_error: float
    peak_centre_deflection: float
    time_of_peak: float
    permanent_centre_deflection: float
    peak_springback_centre_deflection: float
    springback_plastic_work: float
    late_mean_centre_deflection: float
    settled: bool
    snapped_through: bool
    position: np.ndarray
    deflection_permanent: np.ndarray
    time_step: float
    contact_stiffness: float
    plastic_zone_area: float
    max_plastic_strain: float


# ---------------------------------------------------------------------------------------------------------------
# the one-dimensional model


def _shapes(xi, le):
    """Shape functions on ξ ∈ [0, 1] of an element of length le, each (len(ξ), 7) over the element's DOFs
    (u_i, w_i, w'_i, u_j, w_j, w'_j, u_mid): u and u' (quadratic), w, w', w'' (cubic Hermite), derivatives in s."""
    xi = np.atleast_1d(np.asarray(xi, float))
    o, n = np.ones_like(xi), len(xi)
    U, dU, W, dW, ddW = (np.zeros((n, 7)) for _ in range(5))
    U[:, [0, 3, 6]] = np.stack([1 - 3 * xi + 2 * xi**2, -xi + 2 * xi**2, 4 * xi - 4 * xi**2], axis=1)
    dU[:, [0, 3, 6]] = np.stack([-3 + 4 * xi, -1 + 4 * xi, 4 - 8 * xi], axis=1) / le
    W[:, [1, 2, 4, 5]] = np.stack([1 - 3 * xi**2 + 2 * xi**3, le * (xi - 2 * xi**2 + xi**3), 3 * xi**2 - 2 * xi**3, le * (-(xi**2) + xi**3)], axis=1)
    dW[:, [1, 2, 4, 5]] = np.stack([(-6 * xi + 6 * xi**2) / le, 1 - 4 * xi + 3 * xi**2, (6 * xi - 6 * xi**2) / le, -2 * xi + 3 * xi**2], axis=1)
    ddW[:, [1, 2, 4, 5]] = np.stack([(-6 + 12 * xi) / le**2, (-4 + 6 * xi) / le, (6 - 12 * xi) / le**2, (-2 + 6 * xi) * o / le], axis=1)
    return U, dU, W, dW, ddW


class _Model:
    """Discretised strip (``axisymmetric=False``) or circular plate on s ∈ [0, a], ``elements`` equal elements.

    Global DOFs: node k carries (u, w, w') at 3k, 3k+1, 3k+2; element e's mid-node u at 3(n+1)+e. The centre's
    u and w' are zero (symmetry); the support has w = 0, and w' = 0 if clamped, u = 0 if immovable. The material
    state (stress, plastic strain, ε̄_p) lives at (elements, GAUSS_POINTS, 2·layers) points."""

    def __init__(self, *, axisymmetric, span, thickness, metal, support, edge, kinematics, elements, layers):
        if support not in ("clamped", "simply-supported"):
            raise ValueError(f"support must be 'clamped' or 'simply-supported', got {support!r}")
        if edge not in ("immovable", "movable"):
            raise ValueError(f"edge must be 'immovable' or 'movable', got {edge!r}")
        if kinematics not in ("von-karman", "linear"):
            raise ValueError(f"kinematics must be 'von-karman' or 'linear', got {kinematics!r}")
        if elements < 1 or not span > 0 or not thickness > 0:
            raise ValueError("span, thickness and elements must be positive")
        self.axisymmetric, self.span, self.h, self.metal, self.layers = axisymmetric, span, thickness, metal, layers
        self.vk = kinematics == "von-karman"
        ne = elements
        self.nodes = np.linspace(0.0, span, ne + 1)
        le = span / ne
        g, wg = np.polynomial.legendre.leggauss(GAUSS_POINTS)
        self.xi, wxi = (g + 1) / 2, wg / 2
        self.U, self.dU, self.W, self.dW, self.ddW = _shapes(self.xi, le)
        self.r = self.nodes[:-1, None] + le * self.xi[None, :]  # (ne, ng)
        self.weight = le * wxi[None, :] * (2 * math.pi * self.r if axisymmetric else 2.0 * np.ones_like(self.r))
        self.ndof = 3 * (ne + 1) + ne
        e = np.arange(ne)[:, None]
        self.dofs = np.concatenate([3 * e + np.arange(6)[None, :], 3 * (ne + 1) + e], axis=1)
        fixed = [0, 2, 3 * ne + 1] + ([3 * ne + 2] if support == "clamped" else []) + ([3 * ne] if edge == "immovable" else [])
        self.free = np.setdiff1d(np.arange(self.ndof), fixed)
        self.centre = 1  # the centre's w
        rho_h = metal.density * thickness
        Me = rho_h * np.einsum("eg,gi,gj->eij", self.weight, self.U, self.U) + rho_h * np.einsum("eg,gi,gj->eij", self.weight, self.W, self.W)
        self.mass = self._scatter_matrix(Me)
        self.pressure_vector = self._scatter_vector(np.einsum("eg,gi->ei", self.weight, self.W))
        self.z, self.wz = through_thickness(thickness, layers)
        nz = self.z.size
        self.state0 = (np.zeros((ne, GAUSS_POINTS, nz, 2)), np.zeros((ne, GAUSS_POINTS, nz, 2)), np.zeros((ne, GAUSS_POINTS, nz)))
        # the force scale below which a residual is round-off: the pressure vector at the smaller of a first-yield
        # pressure σ_y(h/a)² and a pressure E(h/a)⁴ that bends the plate by about its thickness (times 1e-3)
        scale = min(metal.yield_stress * (thickness / span) ** 2, 1e-3 * metal.youngs_modulus * (thickness / span) ** 4)
        self.force_scale = np.linalg.norm(self.pressure_vector[self.free]) * scale

    def _scatter_vector(self, fe):
        f = np.zeros(self.ndof)
        np.add.at(f, self.dofs, fe)
        return f

    def _scatter_matrix(self, Ke):
        K = np.zeros((self.ndof, self.ndof))
        np.add.at(K, (self.dofs[:, :, None], self.dofs[:, None, :]), Ke)
        return K

    def load_vector(self, radius):
        """g (ndof,): the work-conjugate of a unit force spread uniformly over the central disc (plate, area πρ²) or
        band (strip, width 2ρ) of radius ρ: gᵀd is that region's mean deflection; ρ = 0, the centre's w."""
        if radius <= 0:
            g = np.zeros(self.ndof)
            g[self.centre] = 1.0
            return g
        if radius > self.span:
            raise ValueError(f"contact_radius {radius!r} m exceeds the span {self.span!r} m")
        gx, gw = np.polynomial.legendre.leggauss(GAUSS_POINTS)
        le, g = self.nodes[1] - self.nodes[0], np.zeros(self.ndof)
        for e in range(self.nodes.size - 1):
            lo, hi = self.nodes[e], min(self.nodes[e + 1], radius)
            if hi <= lo:
                break
            s = lo + (hi - lo) * (gx + 1) / 2
            W = _shapes((s - self.nodes[e]) / le, le)[2]
            dA = (hi - lo) * gw / 2 * (2 * math.pi * s if self.axisymmetric else 2.0)
            np.add.at(g, self.dofs[e], dA @ W)
        return g / (math.pi * radius**2 if self.axisymmetric else 2 * radius)

    def assemble(self, d, state):
        """Internal force (ndof,), tangent (ndof, ndof), the trial state from the committed ``state`` at d, the elastic
        energy Ψ = ∫∫ ½ σ·C⁻¹σ dz dA of that trial state, and the gross size of the force (for convergence tests)."""
        de = d[self.dofs]
        u, du, th, k = de @ self.U.T, de @ self.dU.T, de @ self.dW.T, de @ self.ddW.T
        zero = np.zeros_like(u)
        ax = self.axisymmetric
        membrane = np.stack([du + (0.5 * th**2 if self.vk else 0.0), u / self.r if ax else zero], axis=-1)
        curvature = np.stack([-k, -th / self.r if ax else zero], axis=-1)
        res, C, stress, plastic, eqps = section_response(membrane, curvature, state[1], state[2], self.metal, self.h, self.layers)
        B = np.zeros(u.shape + (4, 7))  # ∂(ε̄₁, ε̄₂, κ₁, κ₂)/∂d_e at each point
        B[..., 0, :] = self.dU + (th[..., None] * self.dW if self.vk else 0.0)
        B[..., 2, :] = -self.ddW
        if ax:
            B[..., 1, :] = self.U / self.r[..., None]
            B[..., 3, :] = -self.dW / self.r[..., None]
        fe = np.einsum("eg,egai,ega->ei", self.weight, B, res)
        Ke = np.einsum("egib,egbj->eij", np.einsum("eg,egai,egab->egib", self.weight, B, C), B)
        if self.vk:
            Ke += np.einsum("eg,gi,gj->eij", self.weight * res[..., 0], self.dW, self.dW)
        E, nu = self.metal.youngs_modulus, self.metal.poisson_ratio
        density = (stress[..., 0] ** 2 - 2 * nu * stress[..., 0] * stress[..., 1] + stress[..., 1] ** 2) / (2 * E)
        psi = float(np.einsum("eg,egz,z->", self.weight, density, self.wz))
        # the gross size of the internal forces (their terms without cancellation): where they cancel to zero, as under
        # residual stresses at rest, a residual is round-off below a small fraction of it
        gross = float(np.linalg.norm(self._scatter_vector(np.einsum("eg,egai,ega->ei", self.weight, np.abs(B), np.abs(res)))[self.free]))
        return self._scatter_vector(fe), self._scatter_matrix(Ke), (stress, plastic, eqps), psi, gross

    def plastic_zone(self, state):
        """(area [m², or m per metre of width for the strip], largest ε̄_p) of a state: the area of the mid-surface whose
        section has yielded anywhere through the thickness, each Gauss point standing for its weight (first order in
        the element size)."""
        return float(self.weight[state[2].max(axis=-1) > 0].sum()), float(state[2].max())

    def plastic_increment(self, old, new):
        """Trapezoidal plastic work of a step, Σ ½(σₙ + σₙ₊₁)·(ε_p,ₙ₊₁ − ε_p,ₙ) over the points [J, or J/m]."""
        inc = np.einsum("egzi,egzi->egz", 0.5 * (old[0] + new[0]), new[1] - old[1])
        return float(np.einsum("eg,egz,z->", self.weight, inc, self.wz))


class _NoConvergence(RuntimeError):
    """An equilibrium iteration that did not reach NEWTON_TOL in NEWTON_MAX iterations."""


def _newton(evaluate, x, floor):
    """Newton with a backtracking line search on the residual norm: ``evaluate(x)`` returns (r, J, scale, extra),
    the residual, its Jacobian, the size of the forces it balances and what to hand back. Stops when
    |r| ≤ NEWTON_TOL·max(scale, floor) and returns (x, extra). Full steps overshoot on the first steps of a
    strongly plastic transient (the yield kinks of many points at once); halving the step restores descent."""
    r, J, scale, extra = evaluate(x)
    for _ in range(NEWTON_MAX):
        norm = np.linalg.norm(r)
        if not np.isfinite(norm):
            raise _NoConvergence("Newton: a non-finite residual")
        if norm <= NEWTON_TOL * max(scale, floor):
            return x, extra
        dx, alpha = np.linalg.solve(J, -r), 1.0
        while True:
            try:
                trial = evaluate(x + alpha * dx)
                if np.linalg.norm(trial[0]) < (1 - 1e-4 * alpha) * norm or alpha < 1e-3:
                    break
            except FloatingPointError:  # a return map past any sense: a shorter step
                if alpha < 1e-3:
                    raise _NoConvergence("Newton: no admissible step") from None
            alpha /= 2
        x = x + alpha * dx
        r, J, scale, extra = trial
    raise _NoConvergence("Newton did not converge")


def _static_solve(model, d, state, load, *, factor=0.0, centre=None, guess=None):
    """Newton on f_int(d) = λ·``load`` with the factor λ given, or (``centre`` given) with the centre deflection
    prescribed and λ the unknown (a bordered system: λ takes the place of the centre's w; ``factor`` its start).
    The iteration starts from ``guess`` (default d); the return map from the committed ``state`` (at d).
    Returns (d, λ, trial state, Ψ) at equilibrium."""
    free, d = model.free, (d if guess is None else guess).copy()
    if centre is not None:
        d[model.centre] = centre
    unknown = free if centre is None else free[free != model.centre]

    def evaluate(x):
        y, lam = d.copy(), (factor if centre is None else x[-1])
        y[unknown] = x[: unknown.size]
        f, K, trial, psi, gross = model.assemble(y, state)
        J = K[np.ix_(free, unknown)]
        if centre is not None:
            J = np.concatenate([J, -load[free][:, None]], axis=1)
        return (f - lam * load)[free], J, max(np.linalg.norm(f[free]), GROSS_FRACTION * gross), (y, lam, trial, psi)

    x0 = d[unknown] if centre is None else np.append(d[unknown], factor)
    return _newton(evaluate, x0, model.force_scale)[1]


def _tangent_predictor(model, d, state, load, lam, step, control):
    """d + Δd from the tangent at the committed state (elastic where a point is not flowing): K Δd = Δλ·load, or with
    the centre's Δw = ``step`` prescribed and Δλ unknown. Starts a path, or a reversal, where no secant is known."""
    f, K = model.assemble(d, state)[:2]
    free = model.free
    if not control:
        rhs = (lam + step) * load - f
        out = d.copy()
        out[free] += np.linalg.solve(K[np.ix_(free, free)], rhs[free])
        return out
    unknown = free[free != model.centre]
    J = np.concatenate([K[np.ix_(free, unknown)], -load[free][:, None]], axis=1)
    rhs = (lam * load - f)[free] - K[free, model.centre] * step
    out = d.copy()
    out[unknown] += np.linalg.solve(J, rhs)[:-1]
    out[model.centre] += step
    return out


def _static_path(model, targets, by_centre, *, load=None, start=None):
    """Follow ``targets`` (a factor λ of ``load``, default the unit pressure's vector, or a centre deflection where
    ``by_centre``) from ``start`` = (d, state, λ) (default: the unloaded structure), cutting a step in halves (down to
    1/64) where Newton fails. Each step starts from the previous step's increment scaled to this one (a secant
    predictor) while the path goes on the same way. Returns, after each target, (d, λ, state, Ψ, W_p, work in) with the
    plastic work and the trapezoidal work of the load, Σ ½(λₙ + λₙ₊₁) loadᵀΔd, accumulated along the path."""
    load = model.pressure_vector if load is None else load
    d, state, lam = (np.zeros(model.ndof), model.state0, 0.0) if start is None else start
    wp, win, out, last = 0.0, 0.0, [], None  # last: (Δd, Δ target, control) of the previous step
    for target, control in zip(targets, by_centre):
        todo = [(target, 0)]
        while todo:
            value, depth = todo.pop()
            begin = d[model.centre] if control else lam
            if last is not None and last[2] == control and (value - begin) * last[1] > 0:
                guess = d + last[0] * (value - begin) / last[1]
            else:
                guess = _tangent_predictor(model, d, state, load, lam, value - begin, control)
            try:
                d_new, lam_new, s_new, psi = _static_solve(
                    model, d, state, load, factor=lam if control else value, centre=value if control else None, guess=guess
                )
            except _NoConvergence:
                if depth >= 6:
                    raise
                todo += [(value, depth + 1), (0.5 * (begin + value), depth + 1)]
                continue
            wp += model.plastic_increment(state, s_new)
            win += 0.5 * (lam + lam_new) * load @ (d_new - d)
            last = (d_new - d, value - begin, control)
            d, lam, state = d_new, lam_new, s_new
        out.append((d.copy(), lam, state, psi, wp, win))
    return out


def _static(model, load):
    """Pressure or centre-deflection controlled loading, then (``load.unload``) the pressure removed."""
    if load.steps < 1:
        raise ValueError(f"steps must be >= 1, got {load.steps!r}")
    by_centre = isinstance(load, CentreDeflection)
    targets = [load.peak * k / load.steps for k in range(1, load.steps + 1)]
    path = _static_path(model, targets, [by_centre] * load.steps)
    d_peak, p_peak = path[-1][0], path[-1][1]
    if load.unload:
        d, lam, state, _, wp, win = path[-1]
        back = _static_path(model, [p_peak * (1 - k / load.steps) for k in range(1, load.steps + 1)], [False] * load.steps, start=(d, state, lam))
        path += [(b[0], b[1], b[2], b[3], b[4] + wp, b[5] + win) for b in back]
    d_end, zone = path[-1][0], model.plastic_zone(path[-1][2])
    p = np.array([0.0] + [q[1] for q in path])
    wc = np.array([0.0] + [q[0][model.centre] for q in path])
    psi, wp, win = (np.array([0.0] + [q[k] for q in path]) for k in (3, 4, 5))
    plastic = np.flatnonzero(wp > 1e-12 * max(win.max(), 1e-300))
    if plastic.size:
        k = plastic[0]
        first = (float(p[k - 1]), float(p[k]))
    else:
        first = (math.inf, math.inf)
    w_nodes = slice(1, 3 * model.nodes.size, 3)
    return StaticResult(
        pressure=p,
        centre_deflection=wc,
        work_in=win,
        elastic_energy=psi,
        plastic_work=wp,
        position=model.nodes.copy(),
        deflection_loaded=d_peak[w_nodes].copy(),
        deflection_permanent=d_end[w_nodes].copy(),
        peak_pressure=float(p_peak),
        peak_centre_deflection=float(np.max(wc)),
        permanent_centre_deflection=float(wc[-1]) if load.unload else math.nan,
        first_yield_pressure=first,
        energy_error=float(np.max(np.abs(win - psi - wp)) / max(np.max(np.abs(win)), 1e-300)),
        plastic_zone_area=zone[0],
        max_plastic_strain=zone[1],
    )


def _fundamental_period(model):
    """Lowest period [s] of the linear elastic structure (small-deflection stiffness and consistent mass)."""
    import scipy.linalg

    K = model.assemble(np.zeros(model.ndof), model.state0)[1]
    f = model.free
    lam = scipy.linalg.eigh(K[np.ix_(f, f)], model.mass[np.ix_(f, f)], eigvals_only=True, subset_by_index=[0, 0])[0]
    return 2 * math.pi / math.sqrt(lam)


def _springback(model, d, state, steps):
    """Static springback from (d, state): f_int(d) = (1 − λ) f_int(d*) with λ from 0 to 1 in ``steps`` (the inertia and
    contact forces that held d* removed), plasticity active. Returns (d at rest, its plastic work, the state at rest), or
    (None, nan, the state at d*) where the unloading meets a limit point (the dent would snap through: no reference)."""
    f_star = model.assemble(d, state)[0]
    try:
        back = _static_path(model, [1 - k / steps for k in range(1, steps + 1)], [False] * steps, load=f_star, start=(d, state, 1.0))
    except _NoConvergence:  # a limit point on the way down: the dent snaps (oil-cans); no quasi-static rest state
        return None, math.nan, state
    return back[-1][0], back[-1][4], back[-1][2]


def _transient(model, load, dt, duration):
    """Newmark average acceleration with Newton from the impulse or the impact.

    The unknowns are the structure's DOFs and, for a mass impact, the mass's displacement W (one more DOF, mass m,
    coupled through F = k_c⟨W − gᵀd⟩₊ only). Each step solves M aₙ₊₁ + f_int(dₙ₊₁) + f_c(dₙ₊₁) = 0 with
    aₙ₊₁ = 4(dₙ₊₁ − dₙ − Δt vₙ)/Δt² − aₙ, vₙ₊₁ = vₙ + Δt(aₙ + aₙ₊₁)/2. Without ``duration`` the run stops at rest:
    past three times the peak's time, out of contact, with no plastic work over the last such interval
    (capped at 20 times the peak's time), the peak being the largest centre deflection so far. Returns the histories,
    the (d, state) at the peak and at the end, the peak's time, whether the run ended at rest, Δt and k_c."""
    n, free, impact = model.ndof, model.free, isinstance(load, MassImpact)
    g, kc = (model.load_vector(load.contact_radius) if impact else np.zeros(n)), 0.0
    if impact:
        if not load.mass > 0:
            raise ValueError(f"mass must be > 0, got {load.mass!r}")
        K0 = model.assemble(np.zeros(n), model.state0)[1][np.ix_(free, free)]
        kc = load.contact_stiffness or CONTACT_STIFFNESS_FACTOR / (g[free] @ np.linalg.solve(K0, g[free]))
    M = np.zeros((n + 1, n + 1))  # the mass's DOF last (inert without an impact)
    M[:n, :n], M[n, n] = model.mass, (load.mass if impact else 0.0)
    act = np.append(free, n) if impact else free
    d, v, a = np.zeros(n + 1), np.zeros(n + 1), np.zeros(n + 1)
    if impact:
        v[n] = load.velocity
    else:
        v[np.intersect1d(np.arange(1, 3 * model.nodes.size, 3), free)] = load.velocity
    dt = dt or min(_fundamental_period(model) / 400, (2 * math.pi * math.sqrt(load.mass / kc) / 50 if impact else math.inf))
    gg, Mf, state = np.append(g, -1.0), M[np.ix_(act, act)], model.state0
    hist = {k: [0.0] for k in ("t", "w", "psi", "wp", "ec", "fc")}
    hist.update(v=[v[model.centre]], ke=[0.5 * v @ M @ v], vm=[v[n]])
    t, wp, settled, w_peak, t_peak, at_peak = 0.0, 0.0, False, 0.0, dt, (d[:n].copy(), state)
    while duration is None or t < duration - 0.5 * dt:
        pred = d + dt * v + dt**2 / 4 * a

        def evaluate(y):
            x = pred.copy()
            x[act] = y
            f, K, trial, psi, gross = model.assemble(x[:n], state)
            F, Kf = np.zeros(n + 1), np.zeros((n + 1, n + 1))
            F[:n], Kf[:n, :n] = f, K
            fc = kc * max(x[n] - g @ x[:n], 0.0) if impact else 0.0
            if fc > 0:  # the mass pushes the structure along +g, the structure pushes the mass back
                F, Kf = F - fc * gg, Kf + kc * np.outer(gg, gg)
            inertia = (M @ (4 / dt**2 * (x - pred)))[act]
            scale = max(np.linalg.norm(F[act]), np.linalg.norm(inertia), GROSS_FRACTION * gross)
            return inertia + F[act], 4 / dt**2 * Mf + Kf[np.ix_(act, act)], scale, (x, trial, psi, fc)

        try:
            x, trial, psi, fc = _newton(evaluate, (pred + dt**2 / 4 * a)[act], model.force_scale)[1]  # start: aₙ₊₁ = aₙ
        except _NoConvergence:
            raise RuntimeError(f"Newmark–Newton did not converge at t = {t + dt!r} s") from None
        a_new = 4 / dt**2 * (x - pred)
        v, wp = v + dt / 2 * (a + a_new), wp + model.plastic_increment(state, trial)
        d, a, state, t = x, a_new, trial, t + dt
        for key, val in zip(hist, (t, d[model.centre], psi, wp, 0.5 * fc**2 / kc if kc else 0.0, fc, v[model.centre], 0.5 * v @ M @ v, v[n])):
            hist[key].append(val)
        if d[model.centre] > w_peak:
            w_peak, t_peak, at_peak = d[model.centre], t, (d[:n].copy(), state)
        if duration is None and fc == 0.0 and t >= 3 * t_peak:
            settled = wp - hist["wp"][int(np.searchsorted(hist["t"], t - t_peak))] <= 1e-6 * max(wp, 1e-300)
            if settled or t >= 20 * t_peak:
                break
    H = {k: np.array(val) for k, val in hist.items()}
    if duration is not None:
        back = int(np.searchsorted(H["t"], t - t_peak))
        settled = bool(H["wp"][-1] - H["wp"][back] <= 1e-6 * max(H["wp"][-1], 1e-300))
    return H, at_peak, (d[:n], state), t_peak, settled, dt, kc


def _dynamic(model, load, dt, duration, springback_steps):
    """The transient (:func:`_transient`), then the static springbacks from the end and from the peak."""
    H, (d_peak, s_peak), (d_end, s_end), t_peak, settled, dt, kc = _transient(model, load, dt, duration)
    rest, sb_work, s_rest = _springback(model, d_end, s_end, springback_steps)
    rest_peak = _springback(model, d_peak, s_peak, springback_steps)[0]
    zone = model.plastic_zone(s_rest)
    nan = np.full(model.ndof, math.nan)
    rest, rest_peak = (nan if x is None else x for x in (rest, rest_peak))
    work_in = H["ke"][0]
    total = H["ke"] + H["psi"] + H["wp"] + H["ec"]
    after = H["t"] >= t_peak
    return DynamicResult(
        time=H["t"],
        centre_deflection=H["w"],
        centre_velocity=H["v"],
        kinetic_energy=H["ke"],
        elastic_energy=H["psi"],
        plastic_work=H["wp"],
        contact_energy=H["ec"],
        contact_force=H["fc"],
        impactor_velocity=H["vm"],
        work_in=float(work_in),
        energy_error=float(np.max(np.abs(total - work_in)) / work_in),
        peak_centre_deflection=float(np.max(H["w"])),
        time_of_peak=float(t_peak),
        permanent_centre_deflection=float(rest[model.centre]),
        peak_springback_centre_deflection=float(rest_peak[model.centre]),
        springback_plastic_work=float(sb_work),
        late_mean_centre_deflection=float(np.mean(H["w"][H["t"] >= H["t"][-1] - t_peak])),
        settled=bool(settled),
        snapped_through=bool(np.min(H["w"][after]) < 0.0),
        position=model.nodes.copy(),
        deflection_permanent=rest[1 : 3 * model.nodes.size : 3].copy(),
        time_step=float(dt),
        contact_stiffness=float(kc),
        plastic_zone_area=zone[0],
        max_plastic_strain=zone[1],
    )


def _run(model, load, dt, duration, springback_steps):
    if isinstance(load, (Pressure, CentreDeflection)):
        return _static(model, load)
    if isinstance(load, (Impulse, MassImpact)):
        return _dynamic(model, load, dt, duration, springback_steps)
    raise TypeError(f"load must be a Pressure, CentreDeflection, Impulse or MassImpact, got {load!r}")


def strip(
    load,
    *,
    length,
    thickness,
    metal=ILLUSTRATIVE_AL_2024,
    support="clamped",
    ends="immovable",
    kinematics="von-karman",
    elements=32,
    layers=16,
    dt=None,
    duration=None,
    springback_steps=10,
):
    """A strip of span ``length`` [m] and ``thickness`` [m] in cylindrical bending (plane strain, per metre of width),
    ``support`` "clamped" or "simply-supported" at both ends, the ends ``"immovable"`` (u = 0) or ``"movable"``,
    modelled on its half (``elements`` cubic-Hermite/quadratic elements from mid-span to a support; ``layers`` through
    the thickness). ``load``: :class:`Pressure` or :class:`CentreDeflection` (static, returns :class:`StaticResult`),
    :class:`Impulse` or :class:`MassImpact` (transient, :class:`DynamicResult`; ``dt`` [s] default T₁/400 with T₁ the
    linear fundamental period, or a fiftieth of the contact period 2π√(m/k_c) if shorter; ``duration`` [s] default: until at rest, i.e. past three times the peak's time
    with no plastic work over the last such interval, at most 20 times the peak's time). Elastic small-deflection limit: the clamped
    strip's centre deflection p L⁴/(384 D), D = E h³/(12(1 − ν²))."""
    model = _Model(
        axisymmetric=False,
        span=length / 2,
        thickness=thickness,
        metal=metal,
        support=support,
        edge=ends,
        kinematics=kinematics,
        elements=elements,
        layers=layers,
    )
    return _run(model, load, dt, duration, springback_steps)


def circular_plate(
    load,
    *,
    radius,
    thickness,
    metal=ILLUSTRATIVE_AL_2024,
    support="clamped",
    edge="immovable",
    kinematics="von-karman",
    elements=32,
    layers=16,
    dt=None,
    duration=None,
    springback_steps=10,
):
    """A circular plate of ``radius`` [m] and ``thickness`` [m], axisymmetric, ``support`` "clamped" or
    "simply-supported", the edge ``"immovable"`` (u = 0) or ``"movable"`` in its plane, ``elements`` from the centre
    to the edge. Loads and the other arguments as for :func:`strip` (a :class:`MassImpact` mass in kg on a central
    disc of ``contact_radius``). Elastic small-deflection limits: p R⁴/(64 D) clamped,
    ((5 + ν)/(1 + ν)) p R⁴/(64 D) simply supported."""
    model = _Model(
        axisymmetric=True,
        span=radius,
        thickness=thickness,
        metal=metal,
        support=support,
        edge=edge,
        kinematics=kinematics,
        elements=elements,
        layers=layers,
    )
    return _run(model, load, dt, duration, springback_steps)


def first_yield_pressure_clamped_circular(radius, thickness, metal=ILLUSTRATIVE_AL_2024):
    """The classical small-deflection first-yield pressure [Pa] of a clamped circular plate: the largest moment is the
    edge's M_r = pR²/8 (M_θ = νM_r), so σ_r = 6M_r/h², σ_θ = νσ_r and von Mises σ_eq = σ_r√(1 − ν + ν²) = σ_y0:

        p_y = 4 σ_y0 h² / (3 R² √(1 − ν + ν²)).

    (Linear theory: at this pressure the thin plate's deflection is already a few thicknesses, where the membrane
    forces of the von Kármán plate carry part of the load; it is the benchmark's unit of pressure, nothing more.)"""
    nu = metal.poisson_ratio
    return 4 * metal.yield_stress * thickness**2 / (3 * radius**2 * math.sqrt(1 - nu + nu**2))
