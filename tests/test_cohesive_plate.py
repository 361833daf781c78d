"""Sublaminates tied by cohesive interfaces in a coupled plate impact (fem.cohesive_plate): intact stack against
the single plate, energy balance with the fracture energy, irreversible growth, the case key and the outputs."""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest

from softimpact.errors import InputError
from softimpact.fem.cohesive_plate import CohesivePlate, nodal_areas
from softimpact.fem.plate import Plate, PlateFE
from softimpact.fem.plate_vk import PlateVK, _factor
from softimpact.models.cohesive import BilinearCohesive
from softimpact.models.laminate import PLIES, Stack, parse_layup
from softimpact.models.plate_laminate import plate_section

PLY = PLIES["T300/934"]
STACK = Stack(PLY, parse_layup("[90/0]5s"))
L = 0.2032  # the 8-in plate of plate-ss-8in
SPLITS = (9, 11)  # the two 0/90 interfaces nearest the mid-plane
STRONG = BilinearCohesive(K=1e15, N=PLY.strength.Yt, S=PLY.strength.S12, GIc=280.0, GIIc=PLY.strength.GIIc, eta=2.1)
WEAK = BilinearCohesive(K=1e14, N=1.5e6, S=2.2e6, GIc=10.0, GIIc=20.0, eta=2.1)  # damage grows under a small impact: a test law


def _plate(n: int, element: str = "mitc9") -> Plate:
    return Plate(L, L, n, n, plate_section(STACK), element=element)


@pytest.mark.parametrize("element", ["mitc4", "mitc9"])
def test_nodal_areas_integrate_a_quadratic_exactly(element):
    """The tributary areas sum to the plate's area and (Simpson on MITC9) integrate x²·y exactly: ∫ = Lx³/3·Ly²/2."""
    fe = PlateFE(Plate(0.3, 0.2, 3, 5, plate_section(STACK), element=element))
    a = nodal_areas(fe)
    x, y = fe.node_xy()
    assert a.sum() == pytest.approx(0.3 * 0.2, rel=1e-13)
    if element == "mitc9":
        assert a @ (x**2 * y) == pytest.approx(0.3**3 / 3 * 0.2**2 / 2, rel=1e-13)


def _static_centre(K: float) -> tuple[float, float]:
    """(stack, single plate) centre deflection under a uniform 10 kPa on the 8 × 8 MITC9 mesh, intact interfaces of penalty K."""
    plate = _plate(8)
    single = PlateVK(replace(plate, membrane=True), "movable")
    pressure = lambda x, y: -1e4 + 0 * x  # noqa: E731 - pushing down
    w1 = single.deflection(L / 2, L / 2) @ _factor(single.K).solve(single.load_vector(pressure))
    cp = CohesivePlate(plate, STACK, SPLITS, replace(STRONG, K=K))
    f = cp.layer_row(0, cp.layers[0].load_vector(pressure))
    w2 = cp.deflection(L / 2, L / 2) @ _factor(cp.tangent(np.zeros(cp.n))).solve(f)
    return w2, w1


def test_intact_stack_reproduces_the_single_plate_static():
    """Intact interfaces (penalty 1e15 N/m³): the three sublaminates deflect as the one FSDT plate of the whole laminate to 3e-4,
    the penalty's compliance plus the layerwise model's own transverse shear (the part that remains as K → ∞)."""
    w2, w1 = _static_centre(1e15)
    assert w2 / w1 - 1 == pytest.approx(0.0, abs=3e-4)


def test_penalty_error_falls_as_one_over_the_penalty():
    """The penalty's share of the difference falls as 1/K: (w(1e14) − w(1e16)) / (w(1e15) − w(1e16)) ≈ (1/1e14 − 1/1e16)/(1/1e15 − 1/1e16) = 11."""
    w = {K: _static_centre(K)[0] for K in (1e14, 1e15, 1e16)}
    ratio = (w[1e14] - w[1e16]) / (w[1e15] - w[1e16])
    assert ratio == pytest.approx(11.0, rel=0.05)


def _problem(law, n=4, velocity=None, duration=None, splits=SPLITS):
    """The built-in cohesive impact case's impactor and solver on the whole plate of plate-ss-8in-impact, n × n MITC9 (law replaced; a shorter run)."""
    from softimpact.input.impact_case import load_impact_case
    from softimpact.workflows._cohesive_plate_model import CohesivePlateProblem

    problem, _ = load_impact_case("plate-ss-8in-impact-cohesive")
    whole = load_impact_case("plate-ss-8in-impact")[0].target
    solver = replace(problem.target.solver, duration=duration or problem.target.solver.duration)
    plain = replace(whole, plate=replace(whole.plate, elements=(n, n)), solver=solver)
    target = CohesivePlateProblem.of(plain, splits, law)
    imp = problem.impactor if velocity is None else replace(problem.impactor, velocity=velocity)
    return replace(problem, target=target, impactor=imp)


@pytest.fixture(scope="module")
def grown():
    """A coupled impact whose weak interfaces soften (4 × 4 MITC9, 150 µs: a process zone, no point fully delaminated yet)."""
    from softimpact.cases import KINDS

    return KINDS["impact"].execute(_problem(WEAK, duration=150e-6))


def _intact_runs(n: int, duration: float, penalties=(1e15,)):
    """Force histories of coupled impacts on intact interfaces (strong law) of each penalty, then the single plate's (linear direct run)."""
    from softimpact.workflows.coupled import run_impact
    from softimpact.workflows.plate_impact import PlateProblem

    out = []
    for K in penalties:
        problem = _problem(replace(STRONG, K=K), n=n, duration=duration)
        out.append(run_impact(problem, method="cohesive")[1])
    fields = {f: getattr(problem.target, f) for f in PlateProblem.__dataclass_fields__}
    out.append(run_impact(replace(problem, target=PlateProblem(**fields)), method="direct")[1])
    return out


def test_intact_impact_reproduces_the_single_plate_run():
    """Intact interfaces: the penalty's error (1e15 against 1e17 N/m³) on the force history is below 1e-3 of the peak, and the stack
    gives the single plate's force to 2.5 % on the 4 × 4 mesh over the first 80 µs (measured 1.6 %): the rest is the layerwise model's own difference
    from one FSDT plate (it does not move with the penalty, and falls with the mesh: test_intact_impact_converges_to_the_single_plate)."""
    soft, stiff, single = _intact_runs(4, 80e-6, (1e15, 1e17))
    peak = np.max(single.force)
    assert np.max(np.abs(soft.force - stiff.force)) <= 1e-3 * peak
    assert np.max(np.abs(soft.force - single.force)) <= 2.5e-2 * peak
    assert soft.strain_names[-8] == "delaminated_area_m2" and np.all(soft.strain[-8:-6] == 0.0)


@pytest.mark.slow
def test_intact_impact_converges_to_the_single_plate():
    """The stack's difference from the single plate over 120 µs falls with the mesh (measured 2.7 % of the peak force on 4 × 4, 0.86 %
    on 8 × 8): below 1 % on 8 × 8 and a third of the 4 × 4 difference."""
    coarse, single_coarse = _intact_runs(4, 120e-6)
    fine, single_fine = _intact_runs(8, 120e-6)
    d4 = np.max(np.abs(coarse.force - single_coarse.force)) / np.max(single_coarse.force)
    d8 = np.max(np.abs(fine.force - single_fine.force)) / np.max(single_fine.force)
    assert d8 <= 1e-2 and d8 <= d4 / 3


def test_energy_balances_with_the_fracture_energy(grown):
    """With cohesive damage growing, impactor KE + structure KE + strain + interfaces' stored + dissipated + contact work = KE0
    to 1e-3 of KE0 (summary.json's energy_balance_relative), the dissipated energy positive."""
    s, d = grown.summary, grown.summary["damage"]
    assert d["process_zone_area_max_m2"] > 0 and d["fracture_energy_dissipated_J"] > 0
    assert s["energy_balance_relative"] <= 1e-3


def test_dissipated_energy_is_bounded_by_the_toughness(grown):
    """No point dissipates more than the larger toughness G_IIc per unit area: the fracture energy is at most G_IIc × the
    damaged (delaminated and process-zone) area."""
    d = grown.summary["damage"]
    assert 0 < d["fracture_energy_dissipated_J"] <= WEAK.GIIc * (d["delaminated_area_m2"] + d["process_zone_area_final_m2"])


def test_damaged_area_never_shrinks(grown):
    """Damage is irreversible: the damaged area (delaminated + process zone) never decreases, and the verdict names the process zone."""
    names, rows = grown.result.groups["columns"]
    area = rows[names.index("delaminated_area_m2")] + rows[names.index("process_zone_area_m2")]
    assert np.all(np.diff(area) >= 0.0) and area[-1] > 0
    d = grown.summary["damage"]
    assert f"process zone up to {d['process_zone_area_max_m2'] * 1e6:.4g} mm²" in d["verdict"]


def test_case_key_reads_the_interfaces_and_the_ply():
    """``[damage] cohesive`` of the built-in case: interfaces below plies 9 and 11, strengths and G_IIc from the ply."""
    from softimpact.input.impact_case import load_impact_case

    problem, _ = load_impact_case("plate-ss-8in-impact-cohesive")
    t = problem.target
    assert t.splits == SPLITS and t.coupled_stepper == "cohesive"
    assert (t.law.N, t.law.S, t.law.GIIc) == (PLY.strength.Yt, PLY.strength.S12, PLY.strength.GIIc)


@pytest.mark.parametrize(
    "between, message",
    [([9, 11], "two consecutive ply numbers"), ([20, 21], "not both in the laminate"), ("9", "two consecutive ply numbers")],
)
def test_case_key_refuses_a_bad_interface(between, message):
    """A pair that is not two consecutive plies of the laminate is refused naming the key."""
    from softimpact.input.impact_case import impact_problem
    from softimpact.input.toml import builtin_cases, load_toml

    data = load_toml(builtin_cases()["plate-ss-8in-impact-cohesive"])
    data["damage"]["cohesive"] = [{"between": between}]
    with pytest.raises(InputError, match=message) as err:
        impact_problem(data, builtin_cases()["plate-ss-8in-impact-cohesive"].parent)
    assert "damage.cohesive[0].between" in str(err.value)


@pytest.mark.slow  # seconds: the slow tier (make test-slow)
def test_command_writes_the_area_history_and_the_verdict(tmp_path):
    """``softimpact impact`` on a small cohesive case writes history.csv's area columns, summary.json's delaminated area and the
    area and damage-map figures, and the struck sublaminate's fields."""
    from click.testing import CliRunner

    from softimpact.cli import main
    from softimpact.input.toml import builtin_cases

    plate = builtin_cases()["plate-ss-8in-quarter"].read_text().replace("elements = [24, 24]", "elements = [3, 3]")
    (tmp_path / "plate.toml").write_text(plate)
    case = builtin_cases()["plate-ss-8in-impact-cohesive"].read_text()
    case = case.replace('case = "plate-ss-8in-quarter"', 'case = "plate.toml"').replace('duration = "600 us"', 'duration = "60 us"')
    (tmp_path / "case.toml").write_text(case)
    run = CliRunner().invoke(main, ["impact", str(tmp_path / "case.toml"), "--out", str(tmp_path / "out"), "--fields"])
    assert run.exit_code == 0, run.output
    assert all((tmp_path / "out" / f).stat().st_size > 0 for f in ("delamination-area.png", "delamination-map.png", "delamination-cscan.png", "fields.xdmf"))
    header = (tmp_path / "out" / "history.csv").read_text().splitlines()[0].split(",")
    assert {"delaminated_area_m2", "process_zone_area_m2", "fracture_energy_dissipated_J", "delaminated_area_m2_plies_9_10"} <= set(header)
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["damage"]["delaminated_area_m2"] == 0.0 and "cohesive" in summary["damage"]["verdict"]
    assert summary["damage"]["projected_delamination_area_m2"] == 0.0
    assert set(summary["damage"]["delamination_shapes"]) == {k.removeprefix("delaminated_area_m2_") for k in header if k.startswith("delaminated_area_m2_")}
