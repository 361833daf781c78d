"""Impact sweeps on contact kernels: a group of runs sharing a target builds its kernels once, each run
is a kernel run, and every run equals `softimpact impact` run alone (direct stepping) to 1e-9; law
parameters drawn from a law.json's spread give finite coupled peak forces on a plate."""

import json
import re
import shutil
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact.cli import main
from softimpact.input.toml import locate

from _support.problems import LONG_BEAM_IMPACT

INCH = 0.0254
LAW = Path(__file__).parent / "data" / "law-v-main.json"

BEAM_CASE = LONG_BEAM_IMPACT

PLATE_CASE = """
title = "1/2-in {material} ball on a coarse SS plate (coupled, {law})"
units = "in-lbf-s"
[target]
case = "plate.toml"
[impactor]
material = "{material}"
diameter = "0.5 in"
velocity = "{velocity}"
[contact]
{contact}
[solver]
time_step = "1 us"
duration = "400 us"
"""

SPEC = """
[sweep]
case = "impact.toml"
method = "{method}"
{runs}
outputs = ["peak_force_N", "contact_duration_s", "gauges.g1.peak_tensile_strain"]
[[sweep.parameter]]
key = "impactor.velocity"
values = {values}
"""


def _table(out: Path) -> dict:
    import pyarrow.parquet as pq

    cols = pq.read_table(out / "runs.parquet").to_pydict()
    return {k: v if k in ("error", "validity_flags", "warnings") else np.array(v, float) for k, v in cols.items()}


def _coarse_plate(tmp_path: Path, elements: int = 12) -> None:
    """The built-in SS 8-in plate case with a coarse mesh (the physics kept), as plate.toml."""
    text = locate("plate-ss-8in").read_text()
    (tmp_path / "plate.toml").write_text(re.sub(r"elements = \[48, 48\]", f"elements = [{elements}, {elements}]", text))


@pytest.fixture
def kernel_builds(monkeypatch):
    """Counts the contact-kernel builds of the sweep (workflows.coupled.impact_kernels)."""
    import softimpact.workflows.coupled as coupled

    calls = []
    real = coupled.impact_kernels

    def counting(problem, model=None):
        calls.append(problem.impactor.velocity)
        return real(problem, model)

    monkeypatch.setattr(coupled, "impact_kernels", counting)
    return calls


def _single(tmp_path: Path, case_text: str, name: str) -> dict:
    """`softimpact impact` alone on a case (direct coupled stepping): its summary."""
    case = tmp_path / f"{name}.toml"
    case.write_text(case_text)
    r = CliRunner().invoke(main, ["impact", str(case), "--out", str(tmp_path / f"one-{name}"), "--no-figures"])
    assert r.exit_code == 0, r.output
    return json.loads((tmp_path / f"one-{name}" / "summary.json").read_text())


@pytest.mark.parametrize("target", ["beam", "plate"])
def test_a_kernel_impact_sweep_equals_single_impact_runs(tmp_path, kernel_builds, target):
    """A velocity grid of four runs on one target builds the contact kernels once, and each run's peak
    force, contact duration and peak gauge strain equal those of `softimpact impact` (direct stepping) to 1e-9."""
    velocities = (50, 90, 130, 170)
    if target == "beam":
        case = lambda v: BEAM_CASE.format(velocity=f"{v} in/s")  # noqa: E731
    else:
        _coarse_plate(tmp_path)
        case = lambda v: PLATE_CASE.format(material="steel", law="Hertz", velocity=f"{v} in/s", contact='law = "hertz"')  # noqa: E731
    (tmp_path / "impact.toml").write_text(case(100))
    values = "[" + ", ".join(f'"{v} in/s"' for v in velocities) + "]"
    (tmp_path / "spec.toml").write_text(SPEC.format(method="grid", runs="", values=values))
    r = CliRunner().invoke(main, ["sweep", str(tmp_path / "spec.toml"), "--out", str(tmp_path / "out"), "--workers", "0", "--no-figures"])
    assert r.exit_code == 0, r.output
    assert len(kernel_builds) == 1
    t = _table(tmp_path / "out")
    assert t["error"] == [""] * len(velocities)
    for k, v in enumerate(velocities):
        s = _single(tmp_path, case(v), f"{target}-{v}")
        assert t["peak_force_N"][k] == pytest.approx(s["peak_force_N"], rel=1e-9)
        assert t["contact_duration_s"][k] == pytest.approx(s["contact_duration_s"], rel=1e-9)
        assert t["gauges.g1.peak_tensile_strain"][k] == pytest.approx(s["gauges"]["g1"]["peak_tensile_strain"], rel=1e-9)


def test_a_plate_sweep_with_law_parameters_drawn_from_a_law_json(tmp_path, kernel_builds):
    """`softimpact sweep` on a plate impact with the identified law, its parameters drawn from law.json's
    spread (Monte Carlo) at two velocities: every run finishes with a finite positive peak force, the
    drawn parameters spread about the file's values, and the kernels are built once."""
    _coarse_plate(tmp_path)
    shutil.copy(LAW, tmp_path / "law.json")
    contact = 'law = "identified"\nlaw_file = "law.json"'
    (tmp_path / "impact.toml").write_text(PLATE_CASE.format(material="silicone rubber", law="identified", velocity="2000 in/s", contact=contact))
    spec = SPEC.format(method="monte-carlo", runs="runs = 12\nseed = 3", values='["1500 in/s", "2500 in/s"]')
    spec += '[[sweep.parameter]]\nkey = "contact"\nfrom = "law.json"\n'
    (tmp_path / "spec.toml").write_text(spec)
    r = CliRunner().invoke(main, ["sweep", str(tmp_path / "spec.toml"), "--out", str(tmp_path / "out"), "--workers", "0", "--no-figures"])
    assert r.exit_code == 0, r.output
    t = _table(tmp_path / "out")
    assert len(kernel_builds) == 1
    assert t["error"] == [""] * 24
    assert np.all(np.isfinite(t["peak_force_N"])) and np.all(t["peak_force_N"] > 0)
    law = json.loads(LAW.read_text())["parameters"]
    k = t["contact.parameters.k_ref"]
    assert np.std(k) > 0 and abs(np.mean(k) - law["k_ref"]["value"]) < 3 * law["k_ref"]["ci95_half_width"] / 1.96 / np.sqrt(12)
    # the common random numbers: both velocities see the same draws, and the faster impact hits harder
    assert np.array_equal(k[:12], k[12:])
    assert np.all(t["peak_force_N"][12:] > t["peak_force_N"][:12])


def test_drawn_law_parameters_reach_the_contact_law(tmp_path):
    """A `contact.parameters` table (a sweep's draw) replaces the law.json's values in the law the impact runs."""
    from softimpact.input.impact_case import impact_problem
    from softimpact.input.toml import load_toml

    _coarse_plate(tmp_path)
    shutil.copy(LAW, tmp_path / "law.json")
    contact = 'law = "identified"\nlaw_file = "law.json"\nparameters = { k_ref = 3.5, p = 1.2 }'
    (tmp_path / "impact.toml").write_text(PLATE_CASE.format(material="silicone rubber", law="identified", velocity="2000 in/s", contact=contact))
    problem, _ = impact_problem(load_toml(tmp_path / "impact.toml"), tmp_path)
    base = problem.law.base
    assert base.p == pytest.approx(1.2, rel=1e-12)
    d_ref = json.loads(LAW.read_text())["d_ref_m"]
    q_k = json.loads(LAW.read_text())["parameters"]["q_k"]["value"]
    assert base.k == pytest.approx(3.5 * (0.5 * INCH / d_ref) ** q_k, rel=1e-12)


def test_law_parameters_out_of_range_are_one_line(tmp_path):
    """A drawn k_ref ≤ 0 is refused naming contact.parameters (a sweep records it as that run's failure)."""
    from softimpact.errors import InputError
    from softimpact.input.impact_case import impact_problem
    from softimpact.input.toml import load_toml

    _coarse_plate(tmp_path)
    shutil.copy(LAW, tmp_path / "law.json")
    contact = 'law = "identified"\nlaw_file = "law.json"\nparameters = { k_ref = -1.0 }'
    (tmp_path / "impact.toml").write_text(PLATE_CASE.format(material="silicone rubber", law="identified", velocity="2000 in/s", contact=contact))
    with pytest.raises(InputError, match="contact.parameters"):
        impact_problem(load_toml(tmp_path / "impact.toml"), tmp_path)


@pytest.mark.parametrize("target", ["beam", "plate"])
def test_impactors_of_several_diameters_share_one_kernel_build(tmp_path, kernel_builds, target):
    """Diameters 3/8 and 1/2 in crossed with two velocities form one group: the kernels are built once
    (for the widest contact), and each run equals `softimpact impact` alone (direct stepping) to 1e-9."""
    if target == "beam":
        text = BEAM_CASE
    else:
        _coarse_plate(tmp_path)
        text = PLATE_CASE.replace("{material}", "steel").replace("{law}", "Hertz").replace("{contact}", 'law = "hertz"')
    case = lambda v, d: text.format(velocity=f"{v} in/s").replace('diameter = "0.5 in"', f'diameter = "{d} in"')  # noqa: E731
    (tmp_path / "impact.toml").write_text(case(100, 0.5))
    spec = SPEC.format(method="grid", runs="", values='["60 in/s", "140 in/s"]')
    spec += '[[sweep.parameter]]\nkey = "impactor.diameter"\nvalues = ["0.375 in", "0.5 in"]\n'
    (tmp_path / "spec.toml").write_text(spec)
    r = CliRunner().invoke(main, ["sweep", str(tmp_path / "spec.toml"), "--out", str(tmp_path / "out"), "--workers", "0", "--no-figures"])
    assert r.exit_code == 0, r.output
    assert len(kernel_builds) == 1
    t = _table(tmp_path / "out")
    assert t["error"] == [""] * 4
    for k in range(4):
        v, d = round(t["impactor.velocity"][k] / INCH), t["impactor.diameter"][k] / INCH
        s = _single(tmp_path, case(v, f"{d:g}"), f"{target}-{k}")
        assert t["peak_force_N"][k] == pytest.approx(s["peak_force_N"], rel=1e-9)
        assert t["gauges.g1.peak_tensile_strain"][k] == pytest.approx(s["gauges"]["g1"]["peak_tensile_strain"], rel=1e-9)


def test_hailstones_of_several_sizes_share_one_kernel_build(tmp_path, kernel_builds):
    """Hail threats of 3/8 and 1/2 in (``impactor.threat.hail``, the crushing law) crossed with two velocities on the
    long beam form one group: the kernels are built once, for the widest stone, and each run equals `softimpact impact`
    alone (direct stepping) to 1e-9."""
    text = BEAM_CASE.replace('law = "hertz"\ntarget_modulus = "7.9 GPa"', 'law = "crushing"').replace('"300 us"', '"100 us"')
    case = lambda v, d: text.format(velocity=f"{v} in/s").replace('material = "steel"\ndiameter = "0.5 in"', f'threat = {{ hail = "{d} in" }}')  # noqa: E731
    (tmp_path / "impact.toml").write_text(case(1000, 0.5))
    spec = SPEC.format(method="grid", runs="", values='["600 in/s", "1400 in/s"]')
    spec += '[[sweep.parameter]]\nkey = "impactor.threat.hail"\nvalues = ["0.375 in", "0.5 in"]\n'
    (tmp_path / "spec.toml").write_text(spec)
    r = CliRunner().invoke(main, ["sweep", str(tmp_path / "spec.toml"), "--out", str(tmp_path / "out"), "--workers", "0", "--no-figures"])
    assert r.exit_code == 0, r.output
    assert len(kernel_builds) == 1
    t = _table(tmp_path / "out")
    assert t["error"] == [""] * 4
    for k in range(4):
        v, d = round(t["impactor.velocity"][k] / INCH), t["impactor.threat.hail"][k] / INCH
        s = _single(tmp_path, case(v, f"{d:g}"), f"hail-{k}")
        assert t["peak_force_N"][k] == pytest.approx(s["peak_force_N"], rel=1e-9)


@pytest.mark.parametrize("with_covariance", [False, True])
def test_law_parameter_draws_follow_the_law_json(tmp_path, with_covariance):
    """Draws of a law.json's parameters have its values as mean and, per parameter, σ = half-width/1.96 (no
    covariance given) or the file's covariance (correlation included), within sampling error of 4000 draws."""
    from softimpact.input.sweep_spec import LawDraw, read_sweep_spec

    law = json.loads(LAW.read_text())
    pars = law["parameters"]
    names = [n for n, v in pars.items() if v["ci95_half_width"] > 0]
    sd = np.array([pars[n]["ci95_half_width"] / 1.96 for n in names])
    corr = np.eye(len(names))
    if with_covariance:
        corr[0, 1] = corr[1, 0] = 0.6  # k_ref and p correlated
        law["covariance"] = {"names": names, "matrix": (corr * np.outer(sd, sd)).tolist()}
    (tmp_path / "law.json").write_text(json.dumps(law))
    (tmp_path / "impact.toml").write_text(BEAM_CASE.format(velocity="100 in/s"))
    spec = {
        "sweep": {
            "case": "impact.toml",
            "method": "monte-carlo",
            "runs": 4000,
            "outputs": ["peak_force_N"],
            "parameter": [{"key": "contact", "from": "law.json"}],
        }
    }
    s = read_sweep_spec(spec, tmp_path)
    (p,) = s.parameters
    assert isinstance(p, LawDraw) and p.names == tuple(names)
    x = np.array([[r.row[c] for c in p.columns] for r in s.runs()])
    mean = np.array([pars[n]["value"] for n in names])
    assert np.all(np.abs(x.mean(axis=0) - mean) < 4 * sd / np.sqrt(4000))
    assert np.allclose(x.std(axis=0), sd, rtol=4 / np.sqrt(2 * 4000))
    rho = np.corrcoef(x[:, 0], x[:, 1])[0, 1]
    assert abs(rho - corr[0, 1]) < 4 * (1 - corr[0, 1] ** 2) / np.sqrt(4000)
