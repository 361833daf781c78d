"""Von Kármán plate (fem.plate_vk): consistency of force and tangent, the linear limit, large static
deflection against an independent Ritz series, Newmark–Newton energy balance, hardening of the
fundamental frequency with amplitude.

Levy's tabulated series solution (Timoshenko & Woinowsky-Krieger, *Theory of Plates and Shells*,
ch. 13) and Chu & Herrmann's (1956) frequency–amplitude relation could not be retrieved here;
the references are the Ritz series of ``_support.plate_vk_ritz`` (written from the energy, not
from the elements) and the exact period of its one-mode (Duffing) reduction.
"""

import math

import numpy as np
import pytest
import scipy.sparse

from softimpact.errors import InputError
from softimpact.fem.newmark import NewmarkParameters
from softimpact.fem.plate import Plate, PlateFE
from softimpact.fem.plate_vk import PlateVK, VonKarmanNewmark, solve_static
from softimpact.models.laminate import PLIES, Stack, parse_layup
from softimpact.models.plate_laminate import PlateSection, plate_section

from _support import plate_vk_ritz as ritz

SIDE, H, E, NU, RHO = 1.0, 0.01, 70e9, 0.3, 2700.0  # a thin (a/h = 100) aluminium-like square plate
LOAD_UNIT = E * H**4 / SIDE**4  # Levy's load parameter q a⁴/(E h⁴) = 1


def isotropic(h=H):
    """Homogeneous isotropic FSDT section (k = 5/6)."""
    Q = E * h / (1 - NU**2) * np.array([[1, NU, 0], [NU, 1, 0], [0, 0, (1 - NU) / 2]])
    return PlateSection(Q, np.zeros((3, 3)), Q * h * h / 12, 5 / 6 * E / (2 * (1 + NU)) * h * np.eye(2), RHO * h, 0.0, RHO * h**3 / 12, h)


def quarter(kind, n=2, element="mitc9", in_plane="immovable", section=None):
    """A quarter of the square plate, the centre at the origin (symmetry edges x0, y0)."""
    plate = Plate(SIDE / 2, SIDE / 2, n, n, section or isotropic(), supports=("symmetry", kind, "symmetry", kind), element=element)
    return PlateVK(plate, in_plane=in_plane)


@pytest.mark.parametrize("coupled", [False, True])
@pytest.mark.parametrize("in_plane", ["immovable", "movable"])
def test_force_and_tangent_are_the_energy_gradient_and_hessian(coupled, in_plane):
    """Central differences of the strain energy give the internal force, and of the force the tangent (also with B ≠ 0)."""
    sec = plate_section(Stack(PLIES["T300/934"], parse_layup("[0/90]"))) if coupled else isotropic()
    model = PlateVK(Plate(0.2, 0.15, 3, 2, sec, supports=("clamped", "simply-supported", "free", "symmetry"), element="mitc9"), in_plane=in_plane)
    assert model.coupled is coupled
    rng = np.random.default_rng(1)
    d, dd = rng.standard_normal((2, model.n)) * sec.thickness
    eps = 1e-6
    dU = (model.strain_energy(d + eps * dd) - model.strain_energy(d - eps * dd)) / (2 * eps)
    assert dU == pytest.approx(model.internal_force(d) @ dd, rel=1e-7)
    df = (model.internal_force(d + eps * dd) - model.internal_force(d - eps * dd)) / (2 * eps)
    Kdd = model.tangent(d) @ dd
    assert np.linalg.norm(df - Kdd) <= 1e-7 * np.linalg.norm(Kdd)


@pytest.mark.parametrize("kind", ["simply-supported", "clamped"])
@pytest.mark.parametrize("element", ["mitc4", "mitc9"])
def test_small_load_recovers_the_linear_plate(kind, element):
    """At w/h ~ 1e-6 the von Kármán deflection field equals the linear PlateFE solution to 1e-6 (the extra terms are O(w³))."""
    plate = Plate(SIDE / 2, SIDE / 2, 3, 3, isotropic(), supports=("symmetry", kind, "symmetry", kind), element=element)
    linear = PlateFE(plate)
    model = PlateVK(plate, "immovable")
    q = 1e-6 / 0.00406 * H / SIDE**4 * (E * H**3 / (12 * (1 - NU**2)))  # w0 ≈ 1e-6 h (Navier: w0 = 0.00406 q a⁴/D)
    u_lin = np.linalg.solve(linear.K.toarray(), linear.load_vector(q))
    res = solve_static(model, model.load_vector(q), load_steps=1)
    assert res.converged
    w_lin = linear.expand(u_lin)[linear.basis.nodal_dofs[2]]
    w_vk = model.expand(res.u[-1])[model.fe.basis.nodal_dofs[2]]
    assert np.abs(w_vk - w_lin).max() <= 1e-6 * np.abs(w_lin).max()


LEVY_LIKE = {  # load parameters q a⁴/(E h⁴), w0/h reaching past 2.5 (as Levy's tables)
    "simply-supported": (50, 100, 200, 400, 700),
    "clamped": (100, 200, 400, 700, 900),
}


@pytest.fixture(scope="module")
def ritz_reference():
    """Centre deflections w0/h of the Ritz series at two truncations, per support kind."""
    out = {}
    for kind, P in LEVY_LIKE.items():
        q = np.array(P) * LOAD_UNIT
        coarse = ritz.centre_deflections(q, a=SIDE, h=H, E=E, nu=NU, clamped=kind == "clamped", n_w=3, n_u=6, n_quad=32) / H
        fine = ritz.centre_deflections(q, a=SIDE, h=H, E=E, nu=NU, clamped=kind == "clamped", n_w=5, n_u=8, n_quad=32) / H
        out[kind] = (coarse, fine)
    return out


@pytest.mark.parametrize("kind", ["simply-supported", "clamped"])
def test_ritz_reference_has_converged(ritz_reference, kind):
    """The oracle's two truncations (3² and 5² deflection terms) agree to 0.5 %: the reference is converged well inside the 2 % test."""
    coarse, fine = ritz_reference[kind]
    assert np.abs(coarse / fine - 1).max() < 0.005
    assert fine[-1] > 2.5


@pytest.mark.parametrize("kind", ["simply-supported", "clamped"])
@pytest.mark.parametrize("element,n", [("mitc9", 2), ("mitc4", 8)])
def test_large_deflection_of_square_plate_with_immovable_edges(ritz_reference, kind, element, n):
    """w0/h of the uniformly loaded square plate with immovable edges, up to w0/h > 2.5, within 2 % of the Ritz series."""
    P = np.array(LEVY_LIKE[kind], float)
    model = quarter(kind, n=n, element=element)
    res = solve_static(model, P[-1] * LOAD_UNIT * model.load_vector(1.0), load_factors=np.concatenate((np.linspace(0.02, 0.9, 8) * P[0], P)) / P[-1])
    assert res.converged, res.message
    assert res.iterations.max() <= 8  # quadratic convergence of full Newton from the previous step
    w0 = (res.u @ model.deflection(0.0, 0.0))[-P.size :] / H
    np.testing.assert_allclose(w0, ritz_reference[kind][1], rtol=0.02)


def test_membrane_stiffening_depends_on_the_edges_restraint():
    """Immovable edges stiffen more than movable ones; both deflect less than the linear plate, which is recovered by kinematics='linear'."""
    q = 100 * LOAD_UNIT
    out = {}
    for in_plane in ("immovable", "movable"):
        model = quarter("simply-supported", in_plane=in_plane)
        res = solve_static(model, q * model.load_vector(1.0), load_steps=10)
        out[in_plane] = res.u[-1] @ model.deflection(0, 0) / H
    lin = solve_static(model, q * model.load_vector(1.0), kinematics="linear")
    w_lin = lin.u[-1] @ model.deflection(0, 0) / H
    D = E * H**3 / (12 * (1 - NU**2))
    assert w_lin == pytest.approx(0.00406 * q * SIDE**4 / D / H, rel=0.01)  # Navier (Timoshenko & Woinowsky-Krieger §30)
    assert out["immovable"] < out["movable"] < w_lin


def test_static_input_errors():
    """Bad in-plane restraint, kinematics or load factors are refused with the name of the argument."""
    with pytest.raises(InputError, match="in_plane"):
        quarter("clamped", in_plane="sliding")
    model = quarter("clamped")
    with pytest.raises(InputError, match="kinematics"):
        solve_static(model, model.load_vector(1.0), kinematics="large")
    with pytest.raises(InputError, match="load_factors"):
        solve_static(model, model.load_vector(1.0), load_factors=[0.5, 0.2])


def _pulse_run(steps, n=2, tangent="newton", rtol=1e-9, extra=None, model=None):
    """A half-sine uniform pressure of 2 ms peaking at q a⁴/(E h⁴) = 300 on the SS quarter plate, then 2 ms free: Newmark–Newton."""
    model = model or quarter("simply-supported", n=n)
    f1 = 300 * LOAD_UNIT * model.load_vector(1.0)
    T = 2e-3

    def load(t):
        return f1 * (math.sin(math.pi * t / T) if t < T else 0.0)

    stepper = VonKarmanNewmark(model, 4e-3 / steps, params=NewmarkParameters(), tangent=tangent, rtol=rtol)
    return model, stepper.run(load, steps, rows=model.deflection(0, 0), extra=extra)


def test_newmark_newton_energy_balance_converges_at_second_order():
    """Kinetic + strain energy = initial + external work, the balance error falling as dt² (trapezoidal work of a quartic energy)."""
    errs = []
    for steps in (100, 200):
        _, res = _pulse_run(steps)
        scale = res.work.max()
        errs.append(np.abs(res.balance_error()).max() / scale)
        assert res.outputs[0].max() / H > 1.0  # well past the linear range
    assert errs[1] < 2e-3
    rate = math.log2(errs[0] / errs[1])
    assert 1.7 < rate < 2.5


def test_modified_newton_reaches_the_same_answer():
    """Keeping the factor while it converges fast ('modified') gives the full-Newton history to the iteration tolerance, with fewer factorisations."""
    _, full = _pulse_run(100, rtol=1e-10)
    _, mod = _pulse_run(100, tangent="modified", rtol=1e-10)
    np.testing.assert_allclose(mod.outputs, full.outputs, atol=1e-7 * np.abs(full.outputs).max())
    assert mod.factorisations < full.factorisations


def test_extra_load_joins_the_newton_iterations():
    """A centre spring given as ``extra`` (force and stiffness, as contact would be) gives the history of the model whose K holds the spring."""
    import copy

    model = quarter("simply-supported")
    e = model.deflection(0, 0)
    k = 20 * E * H**3 / SIDE**2  # a stiff spring: the centre's motion changes markedly
    with_spring = copy.copy(model)
    with_spring.K = (model.K + scipy.sparse.csr_matrix(k * np.outer(e, e))).tocsr()
    spring = scipy.sparse.csr_matrix(k * np.outer(e, e))
    _, hooked = _pulse_run(60, tangent="modified", rtol=1e-10, extra=lambda u: (-k * (e @ u) * e, spring), model=model)
    _, built_in = _pulse_run(60, tangent="modified", rtol=1e-10, model=with_spring)
    _, free = _pulse_run(60, tangent="modified", rtol=1e-10, model=model)
    np.testing.assert_allclose(hooked.outputs, built_in.outputs, atol=1e-6 * np.abs(built_in.outputs).max())
    assert np.abs(free.outputs).max() > 1.3 * np.abs(hooked.outputs).max()


def test_fundamental_frequency_hardens_with_amplitude():
    """Free vibration released from a static deflection of the fundamental mode's shape to w0 ≈ h: the period ratio to the
    small-amplitude one is within 3 % of the exact Duffing period of the one-mode Ritz reduction at the same w0."""
    model = quarter("simply-supported", n=2)
    k = math.pi / SIDE
    shape = model.load_vector(lambda x, y: np.cos(k * x) * np.cos(k * y))  # the fundamental mode's load shape
    row = model.deflection(0, 0)
    omega_lin = 2 * k * k * math.sqrt(E * H**3 / (12 * (1 - NU**2)) / (RHO * H))  # Navier, thin plate
    dt = 2 * math.pi / omega_lin / 100
    periods, amplitudes = [], []
    for load in (1e-4, 80.0):  # q a⁴/(E h⁴) of the shape's peak: w0 ≈ 3e-6 h and ≈ h
        u0 = solve_static(model, load * LOAD_UNIT * shape, load_steps=5).u[-1]
        run = VonKarmanNewmark(model, dt, tangent="modified").run(None, 240, rows=row, u0=u0)
        w = run.outputs[0]
        up = np.nonzero((w[:-1] < 0) & (w[1:] >= 0))[0]  # upward zero crossings, linearly interpolated
        tc = run.t[up] - w[up] * dt / (w[up + 1] - w[up])
        periods.append(float(np.mean(np.diff(tc))))
        amplitudes.append(float(u0 @ row))
    # One-mode Ritz (w = A sin sin, in-plane relaxed): its energy is exactly ½ k1 A² + ¼ k3 A⁴; k1, k3 from two static loads.
    q = np.array([1e-3, 200.0]) * LOAD_UNIT
    A = ritz.centre_deflections(q, a=SIDE, h=H, E=E, nu=NU, clamped=False, n_w=1, n_u=8, n_quad=32)
    area = 4 * SIDE**2 / math.pi**2  # ∫ sin sin over the plate
    k1 = q[0] * area / A[0]
    k3 = (q[1] * area - k1 * A[1]) / A[1] ** 3
    m1 = RHO * H * SIDE**2 / 4  # ρh ∫ sin² sin²
    omega0 = math.sqrt(k1 / m1)
    ratio_ritz = ritz.duffing_period(omega0, k3 / m1, amplitudes[1]) / ritz.duffing_period(omega0, k3 / m1, amplitudes[0])
    ratio_fe = periods[1] / periods[0]
    assert 0.8 < amplitudes[1] / H < 1.2
    assert ratio_fe < 0.8  # hardening: a markedly shorter period at w0 ≈ h
    assert ratio_fe == pytest.approx(ratio_ritz, rel=0.03), (ratio_fe, ratio_ritz, amplitudes[1] / H)
