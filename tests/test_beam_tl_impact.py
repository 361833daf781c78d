"""The large-deflection beam through the cases (``[beam] kinematics = "von-karman"``): the key and its refusals,
the summaries that state it, the gauges read as their chord's stretch, and the coupled impact on the built-in
long beam made nonlinear: its energy balance, and peak force and contact time against an independent time loop
written here (the impactor, Hertz's law and the beam's own Newmark–Newton with the contact as its extra load)."""

import json
import tomllib

import numpy as np
import pytest
import scipy.optimize
import scipy.sparse
from click.testing import CliRunner

from softimpact.cases.impact import ImpactKind
from softimpact.cases.run import execute
from softimpact.cli import main
from softimpact.errors import InputError
from softimpact.fem.impact import ContactPatch
from softimpact.fem.plate_vk import VonKarmanNewmark
from softimpact.input.beam_case import beam_problem
from softimpact.input.toml import locate
from softimpact.workflows.beam.nonlinear import BeamTLModel

BEAM = locate("paper-long-beam").read_text()
# The built-in long-beam impact on its beam made nonlinear, over its first contact (about 106 us at 100 in/s) only.
IMPACT = (
    locate("paper-long-beam-impact")
    .read_text()
    .replace('case = "paper-long-beam"', 'case = "target.toml"')
    .replace('duration = "1000 us"', 'duration = "200 us"')
)


def _beam_text(kinematics="von-karman", elements="[200, 6]"):
    return BEAM.replace('support = "clamped-free"', f'support = "clamped-free"\nkinematics = "{kinematics}"').replace(
        "elements = [200, 6]", f"elements = {elements}"
    )


def _write(tmp_path, velocity="100 in/s", kinematics="von-karman"):
    tmp_path.mkdir(parents=True, exist_ok=True)
    (tmp_path / "target.toml").write_text(_beam_text(kinematics))
    case = tmp_path / "impact.toml"
    case.write_text(IMPACT.replace('velocity = "100 in/s"', f'velocity = "{velocity}"'))
    return case


def _command(tmp_path, **kw):
    case = _write(tmp_path, **kw)
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["impact", str(case), "--out", str(out), "--no-figures"])
    assert result.exit_code == 0, result.output
    return json.loads((out / "summary.json").read_text())


def test_key_selects_the_total_lagrangian_model_and_refuses_unknown_kinematics():
    """beam.kinematics = "von-karman" builds the total Lagrangian model; an unknown value is refused naming the key."""
    problem = beam_problem(tomllib.loads(_beam_text(elements="[20, 2]")), locate("paper-long-beam").parent)
    assert problem.kinematics == "von-karman"
    assert isinstance(problem.model(), BeamTLModel)
    with pytest.raises(InputError, match="beam.kinematics"):
        beam_problem(tomllib.loads(_beam_text("vonkarman")), locate("paper-long-beam").parent)


def test_gauges_read_the_chord_stretch_zero_under_a_rigid_rotation():
    """A rigid rotation of 0.2 rad (on the free DOFs) leaves the gauges' chord-stretch strain at round-off, where the linear rows read about −θ²/2 = −0.02."""
    problem = beam_problem(tomllib.loads(_beam_text(elements="[40, 2]")), locate("paper-long-beam").parent)
    model = problem.model()
    pm, theta = model.plane, 0.2
    x, z = pm.node_x, pm.node_z
    ux, uz = x * (np.cos(theta) - 1) - z * np.sin(theta), x * np.sin(theta) + z * (np.cos(theta) - 1)
    full = np.zeros(pm.basis.N)
    full[pm.basis.nodal_dofs[0]], full[pm.basis.nodal_dofs[1]] = ux, uz
    u = full[pm.free]
    y = model.outputs_at(u)
    gauges = model.O.shape[0] - 1
    assert np.abs(y[:gauges]).max() < 1e-12
    assert (model.O[:gauges] @ u) == pytest.approx(np.full(gauges, np.cos(theta) - 1), rel=1e-9)


def test_beam_command_summary_states_the_kinematics(tmp_path):
    """softimpact beam on the nonlinear long beam (coarse, 100 us) writes kinematics and closes its energy balance within 1e-4."""
    case = tmp_path / "beam.toml"
    case.write_text(_beam_text(elements="[40, 2]").replace('duration = "1000 us"', 'duration = "100 us"'))
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["beam", str(case), "--out", str(out), "--no-figures"])
    assert result.exit_code == 0, result.output
    summary = json.loads((out / "summary.json").read_text())
    assert summary["kinematics"] == "von-karman"
    assert abs(summary["energy_balance_relative"]) < 1e-4


def test_kernels_are_refused_on_a_nonlinear_beam_target(tmp_path):
    """Contact kernels need a linear target: execute refuses them on a nonlinear beam, naming beam.kinematics."""
    problem, _ = ImpactKind().load(str(_write(tmp_path)))
    with pytest.raises(InputError, match="beam.kinematics"):
        execute(problem, method="kernels", energy=False)


def _independent(problem):
    """Peak force [N] and end of the first contact [s] by a time loop of its own: Newmark (β, γ of the problem) on
    the impactor, Hertz's law solved for the impactor against the beam held at u (brentq), and the force on the
    cosine line patch of the top face's nodes as the extra load of the beam's Newmark–Newton steps."""
    model = problem.model()
    point, imp = problem.position, problem.impactor
    st = model.contact_structure(point, model.contact_reach(point, imp.diameter))
    patch = ContactPatch(st.surface_x, st.center)
    law, dt, steps, par = problem.law, problem.solver.time_step, problem.solver.steps, problem.solver.newmark
    nm = VonKarmanNewmark(model.tl, dt, None, par, rtol=1e-8, tangent="modified")
    c, dofs, m = st.approach_row, st.surface_dofs, imp.mass
    hm = par.beta * dt * dt / m
    n = model.tl.n
    u, v, a = np.zeros(n), np.zeros(n), np.zeros(n)
    x, xv, xa = 0.0, imp.velocity, 0.0
    forces = [0.0]

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
            b = -patch.shares(law.radius(alpha))[0]
            f[dofs] = F * b
            k = 1.5 * F / alpha / (1 + hm * 1.5 * F / alpha)  # Hertz: dF/dα = 1.5 F/α; through the impactor's step
            return f, scipy.sparse.csr_matrix((k * np.outer(b, b).ravel(), (np.repeat(dofs, dofs.size), np.tile(dofs, dofs.size))), shape=(n, n))

        u, v, a, _ = nm.step(u, v, a, np.zeros(n), extra)
        F, _ = contact(u, x_pred)
        xa1 = -F / m
        x, xv, xa = x_pred - hm * F, xv + dt * ((1 - par.gamma) * xa + par.gamma * xa1), xa1
        forces.append(F)
    F = np.array(forces)
    end = int(np.argmax(F[1:] == 0.0)) + 1  # the first sample after first contact with no force
    return F.max(), end * dt


FAST = "1000 in/s"  # w/h ≈ 0.9 under the impactor within the run (2 later; the built-in 100 in/s reaches 0.2)


@pytest.mark.slow
def test_coupled_impact_on_the_nonlinear_long_beam(tmp_path):
    """The built-in long-beam impact made nonlinear, at its velocity and at ten times it: energy balance within 1e-4 of the
    impact energy, the fast one's deflection past linear theory's envelope unflagged, and its peak force and contact time
    within 1 % of the independent loop."""
    for velocity in ("100 in/s", FAST):
        summary = _command(tmp_path / velocity.split()[0], velocity=velocity)
        assert summary["target"]["kinematics"] == "von-karman"
        assert abs(summary["energy_balance_relative"]) < 1e-4
    assert summary["validity"]["deflection_over_thickness"] > 0.5
    assert not any("linear beam theory" in f for f in summary["validity"]["flags"])
    problem, _ = ImpactKind().load(str(_write(tmp_path / "independent", velocity=FAST)))
    peak, end = _independent(problem)
    assert summary["peak_force_N"] == pytest.approx(peak, rel=0.01)
    assert summary["contact_duration_s"] == pytest.approx(end, rel=0.01)


SWEEP = """
[sweep]
case = "beam.toml"
method = "grid"
outputs = ["peak_force_N", "strain_g1.peak"]
[[sweep.parameter]]
key = "load.history.velocity"
values = ["1000 in/s", "3000 in/s"]
"""


@pytest.mark.slow
def test_sweep_of_a_nonlinear_beam_steps_each_run(tmp_path):
    """A velocity grid on the coarse nonlinear long beam (one structure group, no response engine) gives each run's
    peak gauge strain of the nonlinear model stepped directly on that run's case."""
    import pyarrow.parquet as pq

    from _support.problems import COARSE_LONG_BEAM

    case = COARSE_LONG_BEAM.replace('support = "clamped-free"', 'support = "clamped-free"\nkinematics = "von-karman"').replace(
        'duration = "500 us"', 'duration = "100 us"'
    )
    (tmp_path / "beam.toml").write_text(case)
    (tmp_path / "spec.toml").write_text(SWEEP)
    result = CliRunner().invoke(main, ["sweep", str(tmp_path / "spec.toml"), "--out", str(tmp_path / "out"), "--no-figures", "--workers", "0"])
    assert result.exit_code == 0, result.output
    t = pq.read_table(tmp_path / "out" / "runs.parquet").to_pydict()
    data = tomllib.loads(case)
    for k, v in enumerate((1000, 3000)):
        data["load"]["history"]["velocity"] = f"{v} in/s"
        r = beam_problem(data, tmp_path).model().direct(energy=False, displacement=False)
        eps = r.strain[0]
        assert t["strain_g1.peak"][k] == pytest.approx(eps[np.argmax(np.abs(eps))], rel=1e-9)


def test_field_files_of_the_nonlinear_beam_carry_green_lagrange_strain():
    """The nonlinear beam's field frames read zero strain under a rigid rotation of 0.2 rad (Green–Lagrange), where the linear beam's read cos θ − 1 along x."""
    base = locate("paper-long-beam").parent
    problem = beam_problem(tomllib.loads(_beam_text(elements="[40, 2]")), base)
    linear = beam_problem(tomllib.loads(_beam_text("linear", elements="[40, 2]")), base)
    theta = 0.2
    for prob, expected in ((problem, 0.0), (linear, np.cos(theta) - 1)):
        model = prob.model()
        pm = model.plane
        x, z = pm.node_x, pm.node_z
        full = np.zeros(pm.basis.N)
        full[pm.basis.nodal_dofs[0]] = x * (np.cos(theta) - 1) - z * np.sin(theta)
        full[pm.basis.nodal_dofs[1]] = x * np.sin(theta) + z * (np.cos(theta) - 1)
        _, _, _, cells = model.mesh.field_frames(full[:, None])
        assert cells["strain_xx"] == pytest.approx(np.full_like(cells["strain_xx"], expected), abs=1e-12)
        assert np.abs(cells["shear_strain_xz"]).max() < 1e-12  # γ = −sin θ + sin θ in both measures


def test_green_lagrange_field_strain_of_a_simple_shear():
    """Under the simple shear u_x = γ·z the nonlinear beam's field frames read E_xx = 0, E_zz = γ²/2 and 2E_xz = γ (FᵀF − I: not FFᵀ − I, which gives E_xx = γ²/2)."""
    model = beam_problem(tomllib.loads(_beam_text(elements="[40, 2]")), locate("paper-long-beam").parent).model()
    pm, gamma = model.plane, 0.3
    full = np.zeros(pm.basis.N)
    full[pm.basis.nodal_dofs[0]] = gamma * pm.node_z
    _, _, _, cells = model.mesh.field_frames(full[:, None])
    assert np.abs(cells["strain_xx"]).max() < 1e-12
    assert cells["strain_zz"] == pytest.approx(np.full_like(cells["strain_zz"], gamma**2 / 2), rel=1e-12)
    assert cells["shear_strain_xz"] == pytest.approx(np.full_like(cells["shear_strain_xz"], gamma), rel=1e-12)
