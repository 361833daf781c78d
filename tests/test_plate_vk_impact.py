"""Coupled impact on the von Kármán plate (``[plate] kinematics = "von-karman"`` on an impact's target): the energy
balance through the command, and peak force, contact time and deflection against an independent time loop
written here (the impactor, Hertz's law and the plate's own Newmark–Newton with the contact as its extra load)."""

import json

import numpy as np
import pytest
import scipy.optimize
import scipy.sparse
from click.testing import CliRunner

from softimpact.cases.impact import ImpactKind
from softimpact.cases.run import execute
from softimpact.cli import main
from softimpact.errors import InputError
from softimpact.fem.plate_vk import VonKarmanNewmark
from softimpact.input.toml import locate

H = 0.110 * 0.0254  # the built-in plate's thickness [m] (plate-ss-8in: [90/0]5s T300/934, 0.110 in)
# The built-in plate-ss-8in-impact made von Kármán, on a 6 × 6 MITC9 mesh and over its first contact only (speed).
TARGET = locate("plate-ss-8in").read_text().replace("elements = [48, 48]", 'elements = [6, 6]\nkinematics = "von-karman"')
IMPACT = (
    locate("plate-ss-8in-impact").read_text().replace('case = "plate-ss-8in"', 'case = "target.toml"').replace('duration = "1000 us"', 'duration = "240 us"')
)
FAST = "1500 in/s"  # w/h ~ 0.8: the membrane stiffening is visible (the built-in 100 in/s reaches w/h ~ 0.06)


def _write(tmp_path, velocity="100 in/s", kinematics="von-karman"):
    tmp_path.mkdir(parents=True, exist_ok=True)
    (tmp_path / "target.toml").write_text(TARGET.replace('"von-karman"', f'"{kinematics}"'))
    case = tmp_path / "impact.toml"
    case.write_text(IMPACT.replace('velocity = "100 in/s"', f'velocity = "{velocity}"'))
    return case


def _command(tmp_path, **kw):
    case = _write(tmp_path, **kw)
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["impact", str(case), "--out", str(out), "--no-figures"])
    assert result.exit_code == 0, result.output
    return json.loads((out / "summary.json").read_text())


@pytest.fixture(scope="module")
def fast_run(tmp_path_factory):
    """summary.json of the fast impact on the von Kármán plate, through the command."""
    return _command(tmp_path_factory.mktemp("vk"), velocity=FAST)


def _independent(problem):
    """Peak force [N], end of the first contact [s] and peak deflection under the impactor [m] by a time loop of
    its own: Newmark (β, γ of the problem) on the impactor, Hertz's law solved for the impactor against the plate
    held at u (brentq), and the force on the contact disc as the extra load of the plate's Newmark–Newton steps."""
    model = problem.model()
    point, imp = problem.position, problem.impactor
    st = model.contact_structure(point, model.contact_reach(point, imp.diameter))
    law, dt, steps, par = problem.law, problem.solver.time_step, problem.solver.steps, problem.solver.newmark
    nm = VonKarmanNewmark(model.vk, dt, None, par, rtol=1e-8, tangent="modified")
    c, dofs, m = st.approach_row, st.surface_dofs, imp.mass
    hm = par.beta * dt * dt / m
    n = model.vk.n
    u, v, a = np.zeros(n), np.zeros(n), np.zeros(n)
    x, xv, xa = 0.0, imp.velocity, 0.0
    forces, deflections = [0.0], [0.0]

    def contact(u, x_pred):
        top = x_pred - c @ u
        if top <= 0:
            return 0.0, 0.0
        alpha = scipy.optimize.brentq(lambda al: al + hm * law.force(al) - top, 0.0, top, xtol=1e-16, rtol=1e-14)
        return law.force(alpha), alpha

    for _ in range(steps):
        x_pred = x + dt * xv + dt * dt * (0.5 - par.beta) * xa

        def extra(u, x_pred=x_pred):
            F, alpha = contact(u, x_pred)
            f = np.zeros(n)
            if F == 0.0:
                return f, None
            b = -st.patch.shares(law.radius(alpha))[0]
            f[dofs] = F * b
            k = 1.5 * F / alpha / (1 + hm * 1.5 * F / alpha)  # Hertz: dF/dα = 1.5 F/α; through the impactor's step
            return f, scipy.sparse.csr_matrix((k * np.outer(b, b).ravel(), (np.repeat(dofs, dofs.size), np.tile(dofs, dofs.size))), shape=(n, n))

        u, v, a, _ = nm.step(u, v, a, np.zeros(n), extra)
        F, _ = contact(u, x_pred)
        xa1 = -F / m
        x, xv, xa = x_pred - hm * F, xv + dt * ((1 - par.gamma) * xa + par.gamma * xa1), xa1
        forces.append(F)
        deflections.append(c @ u)
    F = np.array(forces)
    end = int(np.argmax(F[1:] == 0.0)) + 1  # the first sample after first contact with no force
    return F.max(), end * dt, max(deflections)


def test_energy_balance_on_the_von_karman_plate(tmp_path, fast_run):
    """The built-in plate impact made von Kármán closes its energy balance within 1e-4 of the impact energy, at 100 in/s and at w/h ~ 0.8."""
    slow = _command(tmp_path)
    for s in (slow, fast_run):
        assert s["target"]["kinematics"] == "von-karman"
        assert abs(s["energy_balance_relative"]) < 1e-4
    assert fast_run["validity"]["deflection_over_thickness"] > 0.5  # past linear theory's envelope, unflagged: the model is nonlinear
    assert not any("linear plate theory" in f for f in fast_run["validity"]["flags"])


def test_peak_force_contact_time_and_deflection_match_an_independent_loop(tmp_path, fast_run):
    """Peak force, contact time and peak deflection within 1 % of the independent loop; the linear plate's deflection is > 5 % off (the test sees the kinematics)."""
    problem, _ = ImpactKind().load(str(_write(tmp_path, velocity=FAST)))
    peak, end, w = _independent(problem)
    assert fast_run["peak_force_N"] == pytest.approx(peak, rel=0.01)
    assert fast_run["contact_duration_s"] == pytest.approx(end, rel=0.01)
    assert fast_run["target"]["peak_deflection_at_impact_m"] == pytest.approx(w, rel=0.01)
    linear = _command(tmp_path / "lin", velocity=FAST, kinematics="linear")
    assert linear["target"]["kinematics"] == "linear"
    assert abs(linear["target"]["peak_deflection_at_impact_m"] / w - 1) > 0.05


def test_kernels_are_refused_on_a_von_karman_target(tmp_path):
    """Contact kernels need a linear target: execute refuses them on a von Kármán plate, naming the key."""
    problem, _ = ImpactKind().load(str(_write(tmp_path)))
    with pytest.raises(InputError, match="plate.kinematics"):
        execute(problem, method="kernels", energy=False)
