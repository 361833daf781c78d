"""Unusual inputs on the newer surfaces end in the right answer or one clear line (issue 42): a law.json that refuses
another projectile family and edited ranges, a singular covariance, an impactor the time step cannot follow, a solver
that gives up, maps given lists that do not match, edges that leave a plate a mechanism (or do not), a large-deflection
beam given to calibrate, the cohesive stack's resource estimate."""

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact.cli import main
from softimpact.errors import InputError
from softimpact.input.toml import locate

from _support.problems import COARSE_LONG_BEAM, IDENTIFIED_LAW, IDENTIFIED_ON_LONG_BEAM


def invoke(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def error_line(result) -> str:
    assert result.exit_code == 2, result.output
    lines = [line for line in result.stderr.splitlines() if line.startswith("softimpact: error:")]
    assert len(lines) == 1 and "Traceback" not in result.output, result.output
    return lines[0]


# --- law.json: the family and the projectile it was identified on ----------------------------------------------------


def _ice_law() -> dict:
    """A crushing law.json (family "crushing": an ice sphere's), identified on 31.8-50.8 mm ice spheres at 13-105 m/s."""
    return {
        "family": "crushing",
        "units": "SI",
        "parameters": {"strength_ref": {"value": 8.9e6, "ci95_half_width": 1e5}, "rate_exponent": {"value": 0.15, "ci95_half_width": 0.01}},
        "reference_rate_1_s": 1.0,
        "identified_on": {"velocity_m_s": [13.0, 105.0], "diameter_m": [0.0318, 0.0508], "strain_rate_1_s": [256.0, 3302.0]},
    }


@pytest.mark.parametrize(
    "law, material, refused",
    [
        ("ice", "silicone rubber", "holds a crushing law"),
        ("rubber", "ice", "holds a soft projectile's law"),
        ("ice", "ice", ""),
        ("rubber", "silicone rubber", ""),
    ],
)
def test_a_law_json_refuses_another_projectile_family(tmp_path, law, material, refused):
    """An ice crushing law on a rubber ball, or a rubber ball's law on ice: exit 2 naming the law file and the impactor's
    material, nothing written; each law on its own family's ball runs."""
    data = _ice_law() if law == "ice" else json.loads(IDENTIFIED_LAW.read_text())
    (tmp_path / "law.json").write_text(json.dumps(data))
    (tmp_path / "beam.toml").write_text(COARSE_LONG_BEAM)
    case = IDENTIFIED_ON_LONG_BEAM.format(material=material, velocity="2000 in/s", duration="20 us").replace('"paper-long-beam"', '"beam.toml"')
    (tmp_path / "case.toml").write_text(case.replace('time_step = "0.5 us"', 'time_step = "1 us"'))
    r = invoke("impact", tmp_path / "case.toml", "--out", tmp_path / "o", "--no-figures")
    if refused:
        line = error_line(r)
        assert refused in line and "contact.law_file" in line and material in line
        assert not (tmp_path / "o").exists()
    else:
        assert r.exit_code == 0, r.output


@pytest.mark.parametrize("key, pair", [("velocity_m_s", [105.0, 13.0]), ("diameter_m", [0.0508, -1.0]), ("strain_rate_1_s", [float("inf"), 1.0])])
def test_an_edited_identified_range_is_refused_not_reported_reversed(tmp_path, key, pair):
    """identified_on ranges must read [min, max] with 0 < min <= max: a reversed one (105-13 m/s) is refused naming the
    key, not reported as "outside 105-13 m/s"."""
    from softimpact.formats.law_json import read_law

    data = _ice_law()
    data["identified_on"][key] = pair
    (tmp_path / "law.json").write_text(json.dumps(data).replace("Infinity", "1e999"))
    with pytest.raises(InputError, match=f"identified_on.{key}"):
        read_law(tmp_path / "law.json")


# --- a law.json's covariance ------------------------------------------------------------------------------------------


def test_a_singular_covariance_draws_on_its_span_and_an_indefinite_one_is_refused(tmp_path):
    """A law.json whose k_ref and p are perfectly correlated (a rank-one covariance) runs a Monte Carlo sweep (it used
    to end in LinAlgError) whose draws lie on the line p − p̄ = (σ_p/σ_k)(k − k̄) the covariance spans (checked on
    the run table); a covariance with a negative eigenvalue is refused naming the file."""
    import pyarrow.parquet as pq

    law = json.loads(IDENTIFIED_LAW.read_text())
    pars = law["parameters"]
    names = [n for n, v in pars.items() if v["ci95_half_width"] > 0]
    sk, sp = 0.4, 0.05
    cov = np.zeros((len(names), len(names)))
    i, j = names.index("k_ref"), names.index("p")
    cov[i, i], cov[j, j], cov[i, j], cov[j, i] = sk * sk, sp * sp, sk * sp, sk * sp
    law["covariance"] = {"names": names, "matrix": cov.tolist()}
    (tmp_path / "law.json").write_text(json.dumps(law))
    (tmp_path / "beam.toml").write_text(COARSE_LONG_BEAM)
    case = IDENTIFIED_ON_LONG_BEAM.format(material="silicone rubber", velocity="2000 in/s", duration="20 us").replace('"paper-long-beam"', '"beam.toml"')
    (tmp_path / "case.toml").write_text(case.replace('time_step = "0.5 us"', 'time_step = "1 us"'))
    spec = (
        '[sweep]\ncase = "case.toml"\nmethod = "monte-carlo"\nruns = 3\noutputs = ["peak_force_N"]\n[[sweep.parameter]]\nkey = "contact"\nfrom = "law.json"\n'
    )
    (tmp_path / "spec.toml").write_text(spec)
    r = invoke("sweep", tmp_path / "spec.toml", "--out", tmp_path / "s", "--no-figures", "--workers", "0")
    assert r.exit_code == 0, r.output
    t = pq.read_table(tmp_path / "s" / "runs.parquet").to_pydict()
    k, p = np.array(t["contact.parameters.k_ref"]), np.array(t["contact.parameters.p"])
    k0, p0 = pars["k_ref"]["value"], pars["p"]["value"]
    assert np.ptp(k) > 0 and np.allclose(p - p0, sp / sk * (k - k0), rtol=1e-9, atol=1e-12)
    cov[i, j] = cov[j, i] = 2 * sk * sp  # correlation 2: not a covariance
    law["covariance"]["matrix"] = cov.tolist()
    (tmp_path / "law.json").write_text(json.dumps(law))
    assert "positive semi-definite" in error_line(invoke("sweep", tmp_path / "spec.toml", "--out", tmp_path / "s2", "--no-figures", "--workers", "0"))


# --- an impactor the time step cannot follow ----------------------------------------------------------------------------


def _hail(velocity: str, step: str):
    text = locate("hail-plate-38mm").read_text().replace('threat = { hail = "38.1 mm" }', f'threat = {{ hail = "38.1 mm" }}\nvelocity = "{velocity}"')
    return text.replace('time_step = "1 us"', f'time_step = "{step}"').replace('duration = "1500 us"', 'duration = "100 us"')


def test_an_impactor_crossing_its_diameter_between_steps_is_refused_with_a_step_that_passes(tmp_path):
    """A 38.1-mm ice sphere at 2000 m/s stepped at 20 us (it crossed its diameter, d/V = 19.05 us, in one step: peak force
    0, as if through the plate) exits 2 naming a step below d/(4V) = 4.76 us, and that advised step passes the check."""
    import re

    from softimpact.cases import KINDS
    from softimpact.input.impact_case import load_impact_case

    (tmp_path / "fast.toml").write_text(_hail("2000 m/s", "20 us"))
    line = error_line(invoke("impact", tmp_path / "fast.toml", "--out", tmp_path / "o", "--no-figures"))
    advised = float(re.search(r"solver.time_step = ([0-9.]+) us or less", line).group(1))
    assert advised <= 0.0381 / 2000 / 4 * 1e6 < 20
    (tmp_path / "ok.toml").write_text(_hail("2000 m/s", f"{advised} us"))
    KINDS["impact"].check(load_impact_case(str(tmp_path / "ok.toml"))[0])


# --- a solver that gives up ---------------------------------------------------------------------------------------------


def test_a_solver_that_gives_up_writes_why_and_blames_an_over_stiff_penalty(tmp_path, monkeypatch):
    """A cohesive run whose stepper fails (made to, here) with a penalty 1e21 N/m^3 exits 3, writes summary.json with the
    reason and a failed manifest, and the reason names the penalty against E3/t of the thinnest sublaminate (2 plies
    of T300/934 here, E3 and t from the catalogue, the ratio computed here)."""
    from softimpact.errors import SolverFailed
    from softimpact.models.laminate import PLIES

    def fails(*args, **kwargs):
        raise SolverFailed("the step did not converge: a finer mesh or a smaller time step")

    monkeypatch.setattr("softimpact.workflows.coupled.run_impact", fails)
    (tmp_path / "quarter.toml").write_text(locate("plate-ss-8in-quarter").read_text().replace("elements = [24, 24]", "elements = [4, 4]"))
    case = locate("plate-ss-8in-impact-cohesive").read_text().replace('case = "plate-ss-8in-quarter"', 'case = "quarter.toml"')
    (tmp_path / "c.toml").write_text(case.replace('penalty = "1e15 N/m^3"', 'penalty = "1e21 N/m^3"').replace('duration = "600 us"', 'duration = "20 us"'))
    r = invoke("impact", tmp_path / "c.toml", "--out", tmp_path / "o", "--no-figures")
    assert r.exit_code == 3, r.output
    summary = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert summary["status"] == "failed" and json.loads((tmp_path / "o" / "manifest.json").read_text())["status"] == "failed"
    ply = PLIES["T300/934"]
    ratio = 1e21 / (ply.E3 / (2 * ply.thickness))
    assert "damage.penalty" in summary["reason"] and f"{ratio:.3g} times" in summary["reason"]


# --- maps given what they cannot use ------------------------------------------------------------------------------------


def _never(*args, **kwargs):
    raise AssertionError("built a structure: the arguments should have been refused first")


@pytest.mark.parametrize(
    "kwargs, words",
    [
        ({"thicknesses": (1.59e-3, 3.11e-3, 4.66e-3), "layups": ("[45/0/-45/90]s", "[45/0/-45/90]2s")}, "3 thicknesses and 2 layups"),
        ({"indices": ("olson",)}, "did you mean 'olsson'"),
        ({"diameters": (38.1e-3, float("nan"))}, "diameters"),
        ({"kinematics": "nonlinear"}, "kinematics"),
    ],
)
def test_a_hail_map_refuses_what_it_would_drop_or_misread(kwargs, words):
    """hail_map given thicknesses and layups of different lengths (a panel would be dropped by zip), a misspelt index, a
    NaN diameter or an unknown kinematics: an InputError naming it, before any structure is built."""
    from softimpact.studies.hail import CatalogueIce, hail_map

    with pytest.raises(InputError, match=words.replace("(", r"\(")):
        hail_map(CatalogueIce(), _never, **kwargs)


@pytest.mark.parametrize("kwargs, words", [({"indices": ("tsaiwu",)}, "did you mean 'tsai_wu'"), ({"strength_cov": float("nan")}, "strength_cov")])
def test_a_threshold_map_refuses_a_misspelt_index_and_a_nan_scatter(kwargs, words):
    """threshold_map with a misspelt index or a NaN strength scatter (which gave a NaN band): an InputError naming it, before any run."""
    from softimpact.studies.thresholds import threshold_map

    with pytest.raises(InputError, match=words):
        threshold_map(None, None, [0.0127], 1.0, 100.0, **kwargs)


# --- the plate's edges: a mechanism by its rigid motions ----------------------------------------------------------------

SUPPORTS = [
    ("symmetry", "free", "symmetry", "simply-supported"),  # a quarter of a plate simply supported on two opposite edges
    ("symmetry", "free", "free", "simply-supported"),
    ("free", "free", "simply-supported", "free"),
    ("simply-supported", "simply-supported", "free", "free"),
    ("free", "free", "free", "clamped"),
    ("symmetry", "symmetry", "symmetry", "symmetry"),
]


@pytest.mark.parametrize("supports", SUPPORTS)
def test_the_mechanism_rule_agrees_with_the_plates_stiffness(supports):
    """Edges are refused as a mechanism exactly when the assembled plate's stiffness (4 × 4 MITC4, [90/0]5s) has a zero
    eigenvalue (below 1e-12 of its largest; a held plate's smallest is about 1e-7 of it): a symmetry half or quarter
    model that is held is accepted."""
    from softimpact.fem.newmark import SolverSpec
    from softimpact.input.plate_case import check_supports
    from softimpact.models.laminate import PLIES, Stack, parse_layup
    from softimpact.models.pulses import SkewedPulse
    from softimpact.workflows.plate_impact import PlateLoad, PlateModel, PlateProblem, PlateSpec

    spec = PlateSpec(0.1, 0.1, (4, 4), Stack(PLIES["T300/934"], parse_layup("[90/0]5s")), supports, element="mitc4")
    model = PlateModel(PlateProblem(spec, PlateLoad((0.05, 0.05), 0.005, SkewedPulse(1.0, 1e-5, 1e-4), False), SolverSpec(1e-6, 1e-5), ()))
    K = model.K.toarray() if hasattr(model.K, "toarray") else np.asarray(model.K)
    eig = np.linalg.eigvalsh(K)
    singular = eig[0] < 1e-12 * eig[-1]
    if singular:
        with pytest.raises(InputError, match="mechanism"):
            check_supports(supports)
    else:
        check_supports(supports)


def test_one_support_for_all_edges_reads_as_the_table_of_four(tmp_path):
    """A plate case's support = "simply-supported" gives the same run (summary.json's numbers) as the table of the four
    edges each simply supported (as si.Plate takes one kind for all four)."""
    text = locate("plate-ss-8in").read_text().replace("elements = [48, 48]", "elements = [6, 6]").replace('duration = "1000 us"', 'duration = "100 us"')
    table = 'support = { x0 = "simply-supported", x1 = "simply-supported", y0 = "simply-supported", y1 = "simply-supported" }'
    assert table in text
    (tmp_path / "a.toml").write_text(text)
    (tmp_path / "b.toml").write_text(text.replace(table, 'support = "simply-supported"'))
    out = {}
    for name in ("a", "b"):
        r = invoke("plate", tmp_path / f"{name}.toml", "--out", tmp_path / name, "--no-figures")
        assert r.exit_code == 0, r.output
        out[name] = json.loads((tmp_path / name / "summary.json").read_text())
    assert out["a"]["supports"] == out["b"]["supports"] and out["a"]["peak_deflection_at_load_m"] == out["b"]["peak_deflection_at_load_m"]


# --- calibrate, the beam's mesh advice, the cohesive guard ---------------------------------------------------------------


def test_calibrate_refuses_a_large_deflection_beam(tmp_path):
    """calibrate on a von Kármán beam (it fits on the linear response) exits 2 naming beam.kinematics, nothing written."""
    (tmp_path / "beam.toml").write_text(COARSE_LONG_BEAM.replace("[beam]\n", '[beam]\nkinematics = "von-karman"\n'))
    (tmp_path / "m.csv").write_text("time_s,strain_g1\n0,0\n1e-6,1e-6\n2e-6,2e-6\n")
    line = error_line(invoke("calibrate", tmp_path / "beam.toml", "--measured", tmp_path / "m.csv", "--velocity", "1166 in/s", "--out", tmp_path / "o"))
    assert "beam.kinematics" in line and "linear" in line
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("elements, exit_code", [(10, 2), (16, 0)])
def test_the_beams_mesh_advice_asks_for_more_elements_than_it_has(tmp_path, elements, exit_code):
    """A 6-in beam under a 0.25-in contact radius needs L/(2r) = 12 elements to put one across the patch and 24 for the
    comfortable two (by hand): with 10 it exits 2 asking for at least 12; with 16 it runs, warning to use at least 24
    (above the 16 it has: the advice never asks for fewer than the mesh holds)."""
    import re

    (tmp_path / "b.toml").write_text(
        COARSE_LONG_BEAM.replace("elements = [60, 4]", f"elements = [{elements}, 4]").replace('duration = "500 us"', 'duration = "50 us"')
    )
    r = invoke("beam", tmp_path / "b.toml", "--out", tmp_path / "o", "--no-figures")
    assert r.exit_code == exit_code, r.output
    need = int(re.search(r"use at least (\d+) elements along the length", r.output).group(1))
    assert need == (12 if exit_code == 2 else 24) and need > elements


def test_the_cohesive_guard_counts_the_stacked_dofs_it_factors():
    """The cohesive plate's resource estimate counts 5 DOFs a node in each of the S sublaminates: on a 4 × 4 MITC9 quarter
    plate with 3 interfaces, the stacked model actually built has as many free DOFs as that count less its supported
    ones (at most the edges' nodes), and 19 interfaces on the 24 × 24 quarter are refused at once (its factor's memory or
    its hour past the limit)."""
    import dataclasses

    import softimpact as si
    from softimpact.workflows._cohesive_plate_model import CohesivePlateModel

    problem = si.load("plate-ss-8in-impact-cohesive").problem
    target = problem.target
    # the whole plate stacked on its own mesh (no near field): the count of the guard's whole-plate branch
    small = dataclasses.replace(target, plate=dataclasses.replace(target.plate, elements=(4, 4)), splits=(5, 9, 11), near_field=None, element_size=None)
    nodes = 9 * 9
    estimate = 5 * 4 * nodes
    built = CohesivePlateModel(small).size
    assert estimate - 5 * 4 * 2 * 9 <= built <= estimate
    big = dataclasses.replace(target, splits=tuple(range(1, 20)))
    with pytest.raises(InputError, match=r"20 sublaminates.*(GB of memory|h \(limit)"):
        big.check()
    assert math.isfinite(built)
