"""`softimpact impact` on plate targets: rigid-wall limit, momentum, energy, a half/quarter model,
an independent Navier-mode oracle integrated by solve_ivp, the file contract and bad input."""

import csv
import json
import math
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from scipy.integrate import solve_ivp

from softimpact.cli import main
from softimpact.fem.newmark import SolverSpec
from softimpact.input.impact_case import load_impact_case
from softimpact.models.contact_laws import HertzLaw
from softimpact.models.materials import lookup
from softimpact.workflows.coupled import Impactor, run_impact
from softimpact.workflows.plate_impact import PlateGauge

from _support.constants import INCH
from _support.plate_navier import cosine_patch_coefficients, modes

CASES = Path(__file__).parents[1] / "src/softimpact/data/cases"


def _problem(elements=24, duration=300e-6, velocity=100 * INCH, scale=1.0, law=None):
    """The built-in plate impact (1/2-in steel ball on the SS 8 × 8 in plate) on a coarser mesh;
    ``scale`` multiplies the ply's moduli and density (a stiff, heavy plate)."""
    p, _ = load_impact_case("plate-ss-8in-impact")
    t = p.target
    ply = t.plate.stack.ply
    if scale != 1.0:
        ply = replace(ply, **{k: getattr(ply, k) * scale for k in ("E1", "E2", "E3", "G12", "G13", "G23", "density")})
    spec = replace(t.plate, elements=(elements, elements), stack=replace(t.plate.stack, ply=ply))
    target = replace(t, plate=spec, solver=SolverSpec(0.5e-6, duration, t.solver.newmark))
    return replace(p, target=target, impactor=Impactor(p.impactor.mass, p.impactor.diameter, velocity), law=law or p.law)


@pytest.fixture(scope="module")
def coarse():
    return run_impact(_problem())


def test_stiff_heavy_plate_tends_to_the_rigid_wall():
    """A plate 10⁴ times stiffer and heavier (same frequencies, 10⁻⁴ the compliance) gives Hertz's
    rigid-wall closed form (HertzLaw.rigid_impact): peak force, duration and approach within 0.2 %."""
    p = _problem(elements=16, duration=130e-6, scale=1e4)
    _, r = run_impact(p)
    a_max, F_max, T = p.law.rigid_impact(p.impactor.mass, p.impactor.velocity)
    assert r.peak_force == pytest.approx(F_max, rel=2e-3)
    assert r.contact_duration == pytest.approx(T, rel=2e-3)
    assert r.approach.max() == pytest.approx(a_max, rel=2e-3)
    assert r.rebound_velocity == pytest.approx(-p.impactor.velocity, rel=5e-3)


def test_impulse_is_the_impactor_momentum_change(coarse):
    """∫F dt (the integration's trapezoid rule) equals m·(V − v_end) to round-off, over the run and over
    the first contact (velocity just after separation)."""
    _, r = coarse
    m, V = r.impactor.mass, r.impactor.velocity
    assert r.total_impulse == pytest.approx(m * (V - r.final_velocity), rel=1e-10)
    assert r.impulse == pytest.approx(m * (V - r.rebound_velocity), rel=1e-9)


def test_energy_balance(coarse):
    """Impactor KE = impactor KE now + plate KE + strain energy + contact work + mismatch, to round-off;
    without the mismatch (the force on the disc's nodes, the approach at the centre), within 0.5 % of the
    impactor's KE over the whole run, and within 0.3 % after the first contact (24 × 24 mesh)."""
    _, r = coarse
    E, KE0 = r.energies, r.impactor.kinetic_energy
    total = E.impactor_kinetic + E.kinetic + E.strain + E.contact_work
    assert np.max(np.abs(total - E.surface_mismatch - KE0)) < 1e-9 * KE0
    assert np.max(np.abs(total - KE0)) < 5e-3 * KE0
    k = int(np.searchsorted(r.time, r.contacts[0].end))
    assert abs(total[k] - KE0) < 3e-3 * KE0
    assert E.impactor_kinetic[k] < 0.05 * KE0  # a compliant plate keeps most of the energy


def test_quarter_plate_is_the_whole_plate():
    """A quarter model (symmetry edges through the impact point at its corner) gives the whole plate's
    contact force, gauge strains and (scaled back to the whole plate) energies."""
    whole = _problem(elements=16, duration=200e-6)
    t = whole.target
    g = (PlateGauge("gx", (3 * INCH, 4 * INCH), "bottom", "x"), PlateGauge("gy", (4 * INCH, 2 * INCH), "bottom", "y"))
    whole = replace(whole, target=replace(t, gauges=g))
    spec = replace(t.plate, length_x=4 * INCH, length_y=4 * INCH, elements=(8, 8), supports=("simply-supported", "symmetry", "simply-supported", "symmetry"))
    quarter = replace(whole, target=replace(whole.target, plate=spec))
    _, rw = run_impact(whole)
    _, rq = run_impact(quarter)
    F = rw.force.max()
    assert np.max(np.abs(rq.force - rw.force)) < 1e-7 * F
    assert np.max(np.abs(rq.strain - rw.strain)) < 1e-7 * np.max(np.abs(rw.strain))
    for name in ("kinetic", "strain", "surface_mismatch"):
        a, b = getattr(rq.energies, name), getattr(rw.energies, name)
        assert np.max(np.abs(a - b)) < 1e-7 * rw.impactor.kinetic_energy


# --- an independent oracle: Navier modes of the SS plate coupled to Hertz, by solve_ivp -------------


@dataclass(frozen=True)
class FixedDisc:
    """Hertz's force on a contact disc of fixed radius r0 (a well-posed FSDT load: under a point-like
    load the FSDT deflection is log-singular, and the centre's deflection would depend on the mesh)."""

    hertz: HertzLaw
    r0: float

    def force(self, a, rate=0.0):
        return self.hertz.force(a)

    def stiffness(self, a, rate=0.0):
        return self.hertz.stiffness(a)

    def damping(self, a, rate=0.0):
        return 0.0

    def energy(self, a):
        return self.hertz.energy(a)

    def radius(self, a):
        return self.r0 if a > 0 else 0.0


def navier_hertz_impact(section, a, b, center, r0, K, mass, V, t_end, terms=99, f_dynamic=1e5):
    """First contact of a rigid ball (Hertz F = K·α^{3/2}) on a simply supported FSDT plate loaded by
    the unit cosine disc of radius r0, the approach taken at the centre's mid-surface.

    The plate is its Navier modes (tests/_support/plate_navier.py): η̈ + ω²η = b·F for modes below
    ``f_dynamic`` [Hz], the others quasi-static (w_static = c·F, c = Σ b·g/ω²); with the ball
    (ẍ = −F/m) that is an ODE integrated by DOP853, α solving α − c·K·α^{3/2} = x + w_dyn.
    Converged here: 99 → 199 terms and 100 kHz → 300 kHz change F0 and T by < 1e-4.
    Returns (peak force, time of peak, contact duration, impulse).
    """
    m = np.arange(1, terms + 1, 2)  # a centred load excites odd (m, n) only
    al, be = np.meshgrid(m * math.pi / a, m * math.pi / b, indexing="ij")
    q = cosine_patch_coefficients(a, b, *center, r0, m, m)
    om, vec = modes(section.D, section.S, section.I0, section.I2, al, be)
    sxy = np.outer(np.sin(m * math.pi * center[0] / a), np.sin(m * math.pi * center[1] / b))
    bk = (-vec[..., 0, :] * q[..., None]).ravel()  # modal force per unit contact force (down)
    gk = (vec[..., 0, :] * sxy[..., None]).ravel()  # centre deflection (up +) per unit modal amplitude
    om = om.ravel()
    dyn = om < 2 * math.pi * f_dynamic
    c = float(np.sum(bk[~dyn] * gk[~dyn] / om[~dyn] ** 2))
    bd, gd, od = bk[dyn], gk[dyn], om[dyn]
    nd = od.size

    def alpha(beta):
        if beta <= 0:
            return beta
        x = beta
        for _ in range(60):
            x_new = max(x - (x - c * K * x**1.5 - beta) / (1 - 1.5 * c * K * x**0.5), 0.5 * x)
            if abs(x_new - x) < 1e-15 * beta:
                return x_new
            x = x_new
        return x

    def rhs(t, y):
        eta = y[2 : 2 + nd]
        al_ = alpha(y[0] + gd @ eta)
        F = K * al_**1.5 if al_ > 0 else 0.0
        return np.concatenate(([y[1], -F / mass], y[2 + nd :], -(od**2) * eta + bd * F))

    def gap(t, y):
        return y[0] + gd @ y[2 : 2 + nd]

    gap.terminal, gap.direction = True, -1
    y0 = np.zeros(2 + 2 * nd)
    y0[1] = V
    sol = solve_ivp(rhs, (0, t_end), y0, method="DOP853", rtol=1e-10, atol=1e-16, dense_output=True, events=gap, first_step=1e-9)
    T = float(sol.t_events[0][0])
    t = np.linspace(0, T, 20001)
    Y = sol.sol(t)
    F = K * np.maximum([alpha(v) for v in Y[0] + gd @ Y[2 : 2 + nd]], 0.0) ** 1.5
    k = int(np.argmax(F))
    return float(F[k]), float(t[k]), T, float(np.trapezoid(F, t))


@pytest.fixture(scope="module")
def oracle():
    p = _problem()
    law = FixedDisc(p.law, 0.25 * INCH)
    t = p.target
    ref = navier_hertz_impact(
        t.plate.section(), t.plate.length_x, t.plate.length_y, t.load.position, law.r0, p.law.K, p.impactor.mass, p.impactor.velocity, 400e-6
    )
    fe = {}
    for element, meshes in (("mitc9", (12, 24)), ("mitc4", (24, 48))):
        for n in meshes:
            q = _problem(elements=n, duration=260e-6, law=law)
            q = replace(q, target=replace(q.target, plate=replace(q.target.plate, element=element)))
            _, r = run_impact(q, energy=False)
            fe[element, n] = (r.peak_force, r.time_of_peak, r.contact_duration, r.impulse)
    return ref, fe


def test_flexible_plate_agrees_with_the_navier_modal_oracle(oracle):
    """Steel ball 1/2 in at 100 in/s on the SS 8 × 8 in [90/0]5s plate (contact force on a fixed 0.25-in
    cosine disc): on the default element (MITC9) at 24 × 24, the peak force, time of peak, contact
    duration and impulse are within 0.6 % of the Navier-mode solution by solve_ivp (peak 263 N, 2.8
    times below the rigid wall's 728 N; measured 0.17, 0.47, 0.01 and 0.01 %); MITC4 needs 48 × 48
    for 2 %."""
    ref, fe = oracle
    for got, want in zip(fe["mitc9", 24], ref):
        assert got == pytest.approx(want, rel=0.006)
    for got, want in zip(fe["mitc4", 48], ref):
        assert got == pytest.approx(want, rel=0.02)


def test_plate_impact_converges_at_the_elements_orders(oracle):
    """Halving the elements divides the errors in peak force and contact duration by about 4 with MITC4
    (order 2; its two-mesh Richardson extrapolation is within 0.3 % of the oracle) and by at least
    8 with MITC9 (measured orders 3.6 and 6.0 from 12 to 24 elements)."""
    ref, fe = oracle
    for i in (0, 2):
        e24, e48 = fe["mitc4", 24][i] - ref[i], fe["mitc4", 48][i] - ref[i]
        assert math.log2(e24 / e48) == pytest.approx(2.0, abs=0.5)
        assert fe["mitc4", 48][i] + (fe["mitc4", 48][i] - fe["mitc4", 24][i]) / 3 == pytest.approx(ref[i], rel=3e-3)
        e12, e24 = fe["mitc9", 12][i] - ref[i], fe["mitc9", 24][i] - ref[i]
        assert math.log2(abs(e12 / e24)) > 3.0


# --- the command: files, gauges, figures; bad input ---------------------------------------------------


def _cases(tmp_path, position='["4 in", "4 in"]', support=None, extra=""):
    """A 16 × 16 copy of plate-ss-8in (load position and supports changeable) and an impact case on it."""
    plate = (CASES / "plate-ss-8in.toml").read_text().replace("elements = [48, 48]", "elements = [16, 16]")
    plate = plate.replace('position = ["4 in", "4 in"]', f"position = {position}")
    if support:
        plate = plate.replace('x1 = "simply-supported"', f'x1 = "{support}"')
    (tmp_path / "plate.toml").write_text(plate)
    case = (CASES / "plate-ss-8in-impact.toml").read_text().replace('case = "plate-ss-8in"', 'case = "plate.toml"')
    case = case.replace('duration = "1000 us"', 'duration = "250 us"') + extra
    (tmp_path / "case.toml").write_text(case)
    return tmp_path / "case.toml"


def _run(*args):
    return CliRunner().invoke(main, list(map(str, args)))


def test_command_writes_the_impact_contract_for_a_plate(tmp_path):
    """`softimpact impact` on a plate case: history.csv with the contract's columns and the plate's
    gauges, summary.json with the first contact's scalars, the contacts, the gauges and the plate,
    the beam's figures and the plate's mesh and deflected shapes; the Hertz constant from the ply's
    transverse modulus."""
    out = tmp_path / "out"
    r = _run("impact", _cases(tmp_path), "--out", out)
    assert r.exit_code == 0, r.output
    with open(out / "history.csv") as fh:
        names = next(csv.reader(fh))
    for col in ("time_s", "contact_force_N", "impactor_velocity_m_s", "impactor_displacement_m", "approach_m", "contact_radius_m", "strain_g1", "strain_g2"):
        assert col in names
    s = json.loads((out / "summary.json").read_text())
    for key in ("peak_force_N", "time_of_peak_s", "contact_duration_s", "impulse_N_s", "rebound_velocity_m_s", "contacts", "energy_balance_relative"):
        assert key in s
    assert s["energy_balance_relative"] < 1e-9 and abs(s["energy_error_after_first_contact_relative"]) < 5e-3
    assert set(s["gauges"]) == {"g1", "g2"} and s["gauges"]["g2"]["direction"] == "y"
    assert s["target"]["elements"] == [16, 16] and s["target"]["peak_deflection_at_impact_m"] > 0
    assert s["target"]["model"] == "fsdt (MITC9)"  # the default element, named
    steel = lookup("steel")
    E_star = 1 / ((1 - steel.poisson_ratio**2) / steel.youngs_modulus + 1 / 7.9e9)  # Sun's form, E3 of T300/934
    assert s["case_SI"]["law"]["K"] == pytest.approx(4 / 3 * math.sqrt(0.25 * INCH) * E_star, rel=1e-12)
    for name in ("force-history.png", "approach.png", "gauge-strains.png", "energy.png", "plate-mesh.png", "deflection.png"):
        assert (out / name).read_bytes()[:4] == b"\x89PNG"


def test_impact_case_gauges_replace_the_plate_cases(tmp_path):
    """[[gauges]] in the impact case are plate gauges (position [x, y], direction) and replace the target's."""
    extra = '\n[[gauges]]\nname = "top45"\nposition = ["5 in", "5 in"]\nsurface = "top"\ndirection = 45\n'
    out = tmp_path / "out"
    r = _run("impact", _cases(tmp_path, extra=extra), "--out", out, "--no-figures")
    assert r.exit_code == 0, r.output
    s = json.loads((out / "summary.json").read_text())
    assert set(s["gauges"]) == {"top45"} and s["gauges"]["top45"]["surface"] == "top"


def _bad(tmp_path, case, needle):
    out = tmp_path / "out"
    r = _run("impact", case, "--out", out)
    assert r.exit_code == 2, r.output
    lines = r.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("softimpact: error:") and needle in lines[0], r.output
    assert not out.exists()


def test_impact_point_off_the_plate(tmp_path):
    """An impact point beyond the plate is refused naming the target case's load position."""
    _bad(tmp_path, _cases(tmp_path, position='["9 in", "4 in"]'), "target.case")


def test_impact_point_at_a_supported_edge(tmp_path):
    """An impact point within one element of a supported edge leaves no room for the contact disc."""
    _bad(tmp_path, _cases(tmp_path, position='["0.3 in", "4 in"]'), "load.position")


def test_symmetry_edge_away_from_the_impact(tmp_path):
    """A symmetry edge that does not pass through the impact point (a mirrored second impactor) is refused."""
    _bad(tmp_path, _cases(tmp_path, support="symmetry"), "symmetry")
