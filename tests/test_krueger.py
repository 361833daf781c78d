"""Krueger's NASA delamination benchmarks through the stacked plate's own interface code (fem.cohesive_plate: FSDT
sublaminates tied by the bilinear mixed-mode law, nodal integration): the DCB of NASA/TM-2008-215123 and the MMB of
NASA/CR-2012-217562, both by crack closure on the plate's interface (LEFM, the benchmarks' own definition) and by the
cohesive law's growth (the peak of the load), with the quasi-static solver (fem.quasistatic) checked against a
closed-form softening spring and an energy balance.

The benchmark numbers are as quoted and digitised by saullocastro/panels' notebooks (krueger2008_dcb.ipynb,
krueger2012_mmb_benchmark.ipynb; the DCB's ±1 N by eye, the MMB's "given in the text"): see the research notes of
issue 39 and docs/delamination.md."""

from __future__ import annotations

import math

import numpy as np
import pytest

from softimpact.fem.plate_specimens import critical_load, dcb, mmb, release_rates
from softimpact.fem.quasistatic import QuasiStatic, linear_response, quasistatic_path
from softimpact.models.cohesive import BilinearCohesive
from softimpact.models.krueger import DCB_SPECIMEN, MMB_HALF_SPAN, MMB_SPECIMEN

# Krueger 2008, NASA/TM-2008-215123, Figs. 11 and 13 (mid-width VCCT onset, digitised ±1 N): a [mm] -> P_crit [N]
DCB_BENCHMARK = {30: 60.7, 31: 58.8, 32: 57.3, 33: 55.6, 34: 54.2, 35: 52.5, 40: 46.7}
# Krueger 2012, NASA/CR-2012-217562 (text): G_II/G_T -> (lever c [m], P_crit [N])
MMB_BENCHMARK = {0.2: (92.9e-3, 128.5), 0.5: (41.3e-3, 385.0), 0.8: (27.3e-3, 751.0)}
TOLERANCE = 0.03  # issue 39's "within 3 %"

D, M = DCB_SPECIMEN, MMB_SPECIMEN
DCB_STRENGTH = 30e6  # Pa: a process zone of ~1.2 mm, 5 elements of 0.25 mm (docs/delamination.md)
MMB_STRENGTH = 60e6  # Pa (normal; shear N·sqrt(G_IIc/G_Ic))


def penalty(specimen) -> float:
    """Turon et al. 2007's Eq. 7 (as quoted by NASA's CompDam): K = 50·E33/t, t the arm's thickness [N/m³]."""
    return 50 * specimen.ply.E3 / specimen.arm


def dcb_law(N: float = DCB_STRENGTH) -> BilinearCohesive:
    """The DCB's mode-I law (G_IIc = G_Ic: no sliding at its front by symmetry)."""
    return BilinearCohesive(K=penalty(D), N=N, S=N, GIc=D.GIc, GIIc=D.GIc, eta=D.eta)


def mmb_law(N: float = MMB_STRENGTH) -> BilinearCohesive:
    """The MMB's law, the shear strength N·sqrt(G_IIc/G_Ic) (Turon et al. 2010's consistency, not retrieved: a choice, as in
    the beam MMB test of tests/test_delamination.py)."""
    return BilinearCohesive(K=penalty(M), N=N, S=N * math.sqrt(M.GIIc / M.GIc), GIc=M.GIc, GIIc=M.GIIc, eta=M.eta)


def dcb_specimen(a0: float, element: float, *, law=None, fine=3e-3, coarse=None, **kw):
    return dcb(
        D.ply,
        plies_per_arm=D.plies_per_arm,
        width=D.width,
        length=D.length,
        a0=a0,
        law=law or dcb_law(),
        element=element,
        fine=(a0, a0 + fine),
        coarse=coarse,
        **kw,
    )


def mmb_specimen(ratio: float, a0: float, element: float, *, law=None, fine=(-1e-3, 1e-3), **kw):
    lever = MMB_BENCHMARK[ratio][0]
    return mmb(
        M.ply,
        plies_per_arm=M.plies_per_arm,
        width=M.width,
        half_span=MMB_HALF_SPAN,
        a0=a0,
        lever=lever,
        law=law or mmb_law(),
        element=element,
        fine=(M.a0 + fine[0], M.a0 + fine[1]),
        **kw,
    )


# -- the quasi-static solver against a closed form -----------------------------------------------------------------


class SofteningSpring:
    """A cohesive point of area ``area`` (the law's traction t(x1)) in series with a linear spring ``k`` to the load point
    x2: f_int = (a·t(x1) − k(x2 − x1), k(x2 − x1)); the committed-damage model the solver expects."""

    def __init__(self, law: BilinearCohesive, area: float, k: float):
        self.law, self.area, self.k, self.n = law, area, k, 2
        self.damage = np.zeros(1)

    def _t(self, u):
        return self.law.K * (1 - self.damage[0]) * u[0]

    def internal_force(self, u):
        s = self.k * (u[1] - u[0])
        return np.array([self.area * self._t(u) - s, s])

    def tangent(self, u):
        import scipy.sparse

        a = self.area * self.law.K * (1 - self.damage[0])
        return scipy.sparse.csr_matrix([[a + self.k, -self.k], [-self.k, self.k]])

    def commit(self, u):
        self.damage = self.law.traction(np.array([[u[0], 0.0]]), self.damage).damage


def exact_spring(law, area, k, opening):
    """(load-point displacement, force) of the spring in series along a monotone opening: P = a·t(δ), u = δ + P/k, t the
    bilinear law's triangle (0 → N at δ0, N → 0 at δf)."""
    d0, df = law.N / law.K, 2 * law.GIc / law.N
    t = np.where(opening <= d0, law.K * opening, law.N * (df - opening) / (df - d0))
    P = area * t
    return opening + P / k, P


@pytest.mark.parametrize("damage", ["newton", "iterate"])
def test_solver_follows_a_softening_spring_through_its_snap_back(damage):
    """A softening point in series with a soft spring snaps back (its load-point displacement falls after the peak): under the
    opening's control the path follows the closed form u = δ + a·t(δ)/k to 1e-9 through the peak and the snap-back."""
    law = BilinearCohesive(K=1e14, N=20e6, S=20e6, GIc=100.0, GIIc=100.0, eta=2.0)
    area, k = 1e-4, 1e5  # softer than the point's softening, a·N/(δf − δ0) = 2.04e5 N/m: du/dδ = 1 − 2.04 < 0, a snap-back
    model = SofteningSpring(law, area, k)
    openings = np.linspace(0.05e-6, 9.5e-6, 40)
    path = quasistatic_path(model, openings, load=np.array([0.0, 1.0]), control=np.array([1.0, 0.0]), damage=damage)
    u_exact, P_exact = exact_spring(law, area, k, openings)
    assert np.allclose(path.force, P_exact, rtol=1e-9, atol=1e-9 * P_exact.max())
    assert np.allclose(path.displacement, u_exact, rtol=1e-9)
    assert np.any(np.diff(path.displacement) < 0)  # the snap-back was passed


def test_lagged_damage_converges_to_the_iterated_one_as_the_increments_shrink():
    """With the damage lagged one increment the spring's force at a softening state is off by O(increment): halving the
    increments halves the error (0.45–0.55 of it), while the iterated damage meets the closed form."""
    law = BilinearCohesive(K=1e14, N=20e6, S=20e6, GIc=100.0, GIIc=100.0, eta=2.0)
    errors = []
    for n in (20, 40):
        model = SofteningSpring(law, 1e-4, 1e7)
        openings = np.linspace(0.0, 6e-6, n + 1)[1:]
        path = quasistatic_path(model, openings, load=np.array([0.0, 1.0]), control=np.array([1.0, 0.0]), damage="lagged")
        errors.append(abs(path.force[-1] - exact_spring(law, 1e-4, 1e7, openings[-1:])[1][0]))
    assert 0.45 < errors[1] / errors[0] < 0.55


# -- the specimens: supports and symmetry ------------------------------------------------------------------------------


def test_half_width_dcb_is_the_full_width_dcb_and_its_supports_carry_nothing():
    """The half-width DCB (symmetry edge v = φy = 0) has the full-width model's compliance to 1e-9, and the point constraints
    that remove the rigid motions carry no reaction (a self-equilibrated load): the internal force at the held DOFs is
    round-off against the load."""
    half = dcb_specimen(30e-3, 2e-3, coarse=10e-3, ny=1)
    full = dcb_specimen(30e-3, 2e-3, coarse=10e-3, ny=2, half=False)
    u_half, u_full = (linear_response(s.model, s.load, s.fixed) for s in (half, full))
    assert half.displacement(u_half) == pytest.approx(full.displacement(u_full), rel=1e-9)
    for spec, u in ((half, u_half), (full, u_full)):
        reaction = spec.model.internal_force(u)[spec.fixed]
        assert np.max(np.abs(reaction)) < 1e-9 * np.max(np.abs(spec.load / spec.share))


# -- crack closure through the plate's interface: the benchmarks' own definition (LEFM) -----------------------------------


def _dcb_closure(a_mm: int, element: float = 0.125e-3, extension: float = 1e-3, ny: int = 2):
    a = a_mm * 1e-3
    spec = dcb(
        D.ply,
        plies_per_arm=12,
        width=D.width,
        length=D.length,
        a0=a - extension / 2,
        law=dcb_law(),
        element=element,
        ny=ny,
        fine=(a - extension, a + extension),
    )
    return release_rates(spec, extension)


@pytest.mark.parametrize("a_mm", [pytest.param(a, marks=() if a == 30 else pytest.mark.slow) for a in DCB_BENCHMARK])
def test_dcb_crack_closure_at_mid_width_meets_krueger(a_mm):
    """Krueger 2008 (NASA/TM-2008-215123, Figs. 11, 13): the critical load is where G at mid-width reaches G_Ic; the plate's
    crack closure over a 1-mm extension (0.125-mm elements) gives it within 3 % at every crack length (measured +0.3 to
    +1.4 %), and G at mid-width exceeds the width's mean by 3.5–5 % (the benchmark's caveat: a width-averaged model sits
    above it)."""
    r = _dcb_closure(a_mm)
    P = r.critical_load(D.GIc, D.GIc, D.eta, "middle")
    assert abs(P / DCB_BENCHMARK[a_mm] - 1) < TOLERANCE
    assert 1.03 < r.total[-1] / (r.mean_I + r.mean_II + r.mean_III) < 1.06
    assert r.mean_II + r.mean_III < 1e-9 * r.mean_I  # mode I by symmetry


@pytest.mark.parametrize("ratio", [pytest.param(r, marks=() if r == 0.5 else pytest.mark.slow) for r in MMB_BENCHMARK])
def test_mmb_crack_closure_meets_krueger(ratio):
    """Krueger 2012 (NASA/CR-2012-217562): with the lever lengths c of the report, the plate's crack closure gives the
    report's mode ratio G_II/G_T within 0.03 (measured 0.185, 0.472, 0.778) and, by the B-K criterion (η = 2.1), its
    critical loads 128.5, 385 and 751 N within 3 % (measured within 0.1 %)."""
    spec = mmb_specimen(ratio, M.a0 - 0.5e-3, 0.125e-3)
    r = release_rates(spec, 1e-3)
    mixity = (r.mean_II + r.mean_III) / (r.mean_I + r.mean_II + r.mean_III)
    assert abs(mixity - ratio) < 0.03
    assert abs(r.critical_load(M.GIc, M.GIIc, M.eta) / MMB_BENCHMARK[ratio][1] - 1) < TOLERANCE


@pytest.mark.slow
def test_crack_closure_converges_with_the_element_and_the_extension():
    """The DCB's crack-closure load at a = 30 mm moves by under 0.1 % from 0.125- to 0.0625-mm elements and from a 1-mm to a
    0.5-mm extension (second order in Δa, a central difference); a single node line released instead depends on the
    element (first order: 58.9, 61.2, 62.2 N at 0.25, 0.125, 0.0625 mm, the penalty's boundary layer in it)."""
    base = _dcb_closure(30).critical_load(D.GIc, D.GIc, D.eta)
    finer = _dcb_closure(30, element=0.0625e-3).critical_load(D.GIc, D.GIc, D.eta)
    shorter = _dcb_closure(30, extension=0.5e-3).critical_load(D.GIc, D.GIc, D.eta)
    assert abs(finer / base - 1) < 1e-3 and abs(shorter / base - 1) < 1e-3


# -- the cohesive law's growth: the peak of the load --------------------------------------------------------------------


def _dcb_peak(a_mm: float, element: float = 0.25e-3, **kw):
    a = a_mm * 1e-3
    spec = dcb_specimen(a, element, **kw)
    EI = D.ply.E1 * D.width * D.arm**3 / 12
    estimate = math.sqrt(D.width * EI * D.GIc) / (a + 3e-3)  # beam theory, the crack ~3 mm longer (root rotation)
    return spec, critical_load(spec, near=0.85 * estimate, step=0.02)


@pytest.fixture(scope="module")
def dcb_at_a0():
    """The cohesive DCB at a0 = 30 mm, 0.25-mm elements over 30–33 mm, 12-mm elements far from it, through its peak."""
    return _dcb_peak(30, coarse=12e-3)


def test_dcb_cohesive_critical_load_at_a0_meets_krueger(dcb_at_a0):
    """Krueger 2008: P_crit = 60.7 N at a0 = 30 mm; the cohesive plate's peak (N = 30 MPa, K = 50·E33/t) is within 3 %
    (measured −0.2 %) with its process zone resolved by at least 4 elements of 0.25 mm at mid-width (measured 4.5)."""
    spec, crit = dcb_at_a0
    assert abs(crit.load / DCB_BENCHMARK[30] - 1) < TOLERANCE
    assert crit.zone / 0.25e-3 >= 4


def test_dcb_work_is_the_stored_energy_plus_the_fracture_energy(dcb_at_a0):
    """Energy along the cohesive DCB's path to its peak and past it: the work P·dδ (trapezoid) equals the arms' elastic
    energy, the interface's stored energy and the dissipated energy, the last from the law's own triangle: G_Ic per
    unit area of every newly cracked point, ½·K·δ0·δ_max(d)·d of one in the process zone (mode I), within 2 % of the
    dissipated energy (0.2 % of the work)."""
    spec, crit = dcb_at_a0
    path, law, model = crit.path, spec.model.law, spec.model
    d = model.damage[0]
    new = np.ones(d.size, bool)
    x = np.repeat(model.layers[0].fe.node_xs, model.layers[0].fe.node_ys.size)
    new[x < spec.a0 - 1e-10] = False  # the pre-crack dissipated nothing in this run
    d0, df = law.N / law.K, 2 * law.GIc / law.N
    d_max = df * d0 / (df - d * (df - d0))  # the largest opening a point reached, from its damage
    expected = float(np.sum(model.area[new] * 0.5 * law.K * d0 * d_max[new] * d[new]))
    assert expected > 0.3 * law.GIc * model.area[new & (d > 0)].sum()  # a real process zone, not a sliver
    assert path.dissipated[-1] == pytest.approx(expected, rel=0.02)
    assert abs(path.dissipated[-1] - expected) < 2e-3 * path.external_work[-1]


@pytest.mark.slow
@pytest.mark.parametrize("a_mm", [31, 32, 33, 34, 35, 40])
def test_dcb_cohesive_critical_loads_meet_krueger(a_mm):
    """Krueger 2008: the cohesive plate's peak load of a DCB pre-cracked to a is within 3 % of the benchmark at every
    crack length (0.25-mm elements, N = 30 MPa; measured −0.3 to +0.3 %)."""
    _, crit = _dcb_peak(a_mm)
    assert abs(crit.load / DCB_BENCHMARK[a_mm] - 1) < TOLERANCE


@pytest.mark.slow
def test_dcb_cohesive_critical_load_converges_with_the_mesh():
    """At a fixed strength (30 MPa) the cohesive DCB's peak at a0 = 30 mm converges as the elements over the front halve
    from 0.5 to 0.25 to 0.125 mm: the second difference is under half the first (measured 60.75, 60.58, 60.56 N)."""
    peaks = [_dcb_peak(30, element=h)[1].load for h in (0.5e-3, 0.25e-3, 0.125e-3)]
    assert abs(peaks[2] - peaks[1]) < 0.5 * abs(peaks[1] - peaks[0])
    assert abs(peaks[2] / DCB_BENCHMARK[30] - 1) < TOLERANCE


@pytest.mark.slow
@pytest.mark.parametrize(
    "ratio",
    [
        0.2,
        pytest.param(
            0.5,
            marks=pytest.mark.xfail(
                strict=True,
                reason="the law's mode mixity is the current displacement ratio: in the MMB's process zone it turns from ~1 at onset "
                "to ~0.2 at separation, so the dissipated toughness is below G_c at the front's LEFM mixity (peak −5.9 %, "
                "−6.05 % at twice the strength on 0.0625-mm elements)",
            ),
        ),
        pytest.param(0.8, marks=pytest.mark.xfail(strict=True, reason="as 0.5: the cohesive peak is 5.5 % low (models.cohesive's mixity)")),
    ],
)
def test_mmb_cohesive_critical_load_meets_krueger(ratio):
    """Krueger 2012: the cohesive plate's MMB peak (N = 60 MPa, S = N·sqrt(G_IIc/G_Ic), 0.25-mm elements, the crack tip's
    opening plus sliding controlled through the snap-back) within 3 % of the benchmark: met at G_II/G_T = 0.2 (−1.4 %),
    not at 0.5 and 0.8 (−5.9 %, −5.5 %; the reason in the xfail marks, docs/delamination.md)."""
    spec = mmb_specimen(ratio, M.a0, 0.25e-3, fine=(0.0, 3e-3), control="tip")
    crit = critical_load(spec, near=0.8 * MMB_BENCHMARK[ratio][1], increment=0.2e-6)
    assert abs(crit.load / MMB_BENCHMARK[ratio][1] - 1) < TOLERANCE


def test_quasistatic_refuses_unknown_damage_modes():
    """A damage mode not in DAMAGE_MODES is refused, naming the argument."""
    model = SofteningSpring(dcb_law(), 1e-4, 1e7)
    with pytest.raises(ValueError, match="damage must be one of"):
        QuasiStatic(model, load=np.array([0.0, 1.0]), damage="implicit")
