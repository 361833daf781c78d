"""softimpact sweep: spec checks, sampling, grouping against direct beam runs, failures, resume, Dask."""

import json
import math
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact.cli import main

from _support.problems import COARSE_LONG_BEAM, LONG_BEAM_IMPACT

INCH = 0.0254

CASE = COARSE_LONG_BEAM

GRID = """
[sweep]
case = "beam.toml"
method = "grid"
outputs = ["peak_force_N", "strain_g1.peak", "gauges.g2.peak_compressive_strain", "damage.max_strain"]
[[sweep.parameter]]
key = "load.history.velocity"
values = ["1000 in/s", "3000 in/s", "5000 in/s"]
"""


def _write(tmp_path, spec, case=CASE):
    (tmp_path / "beam.toml").write_text(case)
    (tmp_path / "spec.toml").write_text(spec)
    return tmp_path / "spec.toml"


def _sweep(tmp_path, spec, *extra):
    path = _write(tmp_path, spec)
    out = tmp_path / "out"
    return CliRunner().invoke(main, ["sweep", str(path), "--out", str(out), "--no-figures", *extra]), out


def _table(out):
    import pyarrow.parquet as pq

    return pq.read_table(out / "runs.parquet").to_pydict()


def test_grid_matches_direct_beam_runs(tmp_path):
    """A velocity grid on one beam (one structure group, response engine) gives the peak strains of
    direct Newmark stepping of the beam workflow at each velocity, and F0 of eq (4)."""
    from softimpact.input.beam_case import beam_problem
    from softimpact.input.toml import load_toml
    from softimpact.workflows.beam_impact import BeamModel

    result, out = _sweep(tmp_path, GRID, "--workers", "0")
    assert result.exit_code == 0, result.output
    t = _table(out)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["groups"] == 1 and summary["failed"] == 0
    assert t["load.history.velocity"] == pytest.approx([1000 * INCH, 3000 * INCH, 5000 * INCH])
    data = load_toml(tmp_path / "beam.toml")
    for k, v in enumerate((1000, 3000, 5000)):
        data["load"]["history"]["velocity"] = f"{v} in/s"
        r = BeamModel(beam_problem(data, tmp_path)).direct(energy=False)
        eps = r.strain[0]
        assert t["strain_g1.peak"][k] == pytest.approx(eps[np.argmax(np.abs(eps))], rel=1e-6)
        assert t["gauges.g2.peak_compressive_strain"][k] == pytest.approx(r.strain[1].min(), rel=1e-6)
        # [90/0]5s has 90° plies on both faces: under plane strain their worst strain is transverse
        # tension ε_x at a face, allowable Y_t/E2 = 40 MPa / 7.9 GPa (Tsai & Hahn's T300/5208; E2 of the ply).
        faces = np.concatenate((r.strain, r.strain - 2 * r.bending))
        assert t["damage.max_strain"][k] == pytest.approx(faces.max() / (40e6 / 7.9e9), rel=1e-6)
        # eq (4) with Table I's α1 = 4.25 for the 1.1-g, 1/2-in ball; the pulse's sampled peak within 1 %
        V = v * INCH
        assert t["peak_force_N"][k] == pytest.approx(4.25 * 1.1e-3 * V**2 / (2 * 0.5 * INCH), rel=1e-2)


@pytest.mark.parametrize(
    "spec, message",
    [
        (GRID.replace('method = "grid"', 'method = "bayes"'), "sweep.method"),
        (GRID.replace('values = ["1000 in/s", "3000 in/s", "5000 in/s"]', 'distribution = { normal = ["3000 in/s", "100 in/s"] }'), "monte-carlo"),
        (GRID.replace('"peak_force_N"', '"peak_farce_N"'), "sweep.outputs"),
        (GRID.replace('values = ["1000 in/s", "3000 in/s", "5000 in/s"]', 'values = ["1000 in/s", "3 lbf"]'), "load.history.velocity"),
        (GRID.replace('values = ["1000 in/s", "3000 in/s", "5000 in/s"]', 'value = "1000 in/s"'), "nothing varies"),
        (GRID.replace('case = "beam.toml"', 'case = "nowhere"'), "CASE"),
        (GRID.replace('values = ["1000 in/s", "3000 in/s", "5000 in/s"]', 'range = ["1000 in/s", "5000 in/s"]'), "sweep.parameter[0].range"),
        (GRID.replace('key = "load.history.velocity"', 'key = "load.histroy.velocity"'), "load.histroy"),
        (GRID + '[[sweep.parameter]]\nkey = "load.history"\nfrom = "missing.json"\n', "from"),
    ],
)
def test_bad_spec_fails_at_once(tmp_path, spec, message):
    """A bad spec exits with code 2 and one line naming the key, and writes nothing."""
    result, out = _sweep(tmp_path, spec, "--workers", "0")
    assert result.exit_code == 2, result.output
    assert message in result.output and len(result.output.strip().splitlines()) == 1
    assert not out.exists()


def test_failing_runs_are_recorded(tmp_path):
    """Draws of a negative velocity fail with their one-line reason; the other runs are done."""
    spec = GRID.replace('method = "grid"', 'method = "monte-carlo"\nruns = 40\nseed = 3').replace(
        'values = ["1000 in/s", "3000 in/s", "5000 in/s"]', 'distribution = { normal = ["300 in/s", "300 in/s"] }'
    )
    result, out = _sweep(tmp_path, spec, "--workers", "0")
    assert result.exit_code == 0, result.output
    t = _table(out)
    summary = json.loads((out / "summary.json").read_text())
    bad = [i for i, v in enumerate(t["load.history.velocity"]) if v <= 0]
    assert bad and summary["failed"] == len(bad) and summary["succeeded"] == 40 - len(bad)
    assert all("velocity" in t["error"][i] and "\n" not in t["error"][i] for i in bad)
    assert all(math.isnan(t["peak_force_N"][i]) for i in bad)
    assert f"warning: {len(bad)} of 40 runs failed" in result.output  # the statistics are over the rest
    assert json.loads((out / "manifest.json").read_text())["warnings"]


def _spec_object(tmp_path, spec):
    from softimpact.input.sweep_spec import load_sweep_spec

    return load_sweep_spec(str(_write(tmp_path, spec)))


def test_latin_hypercube_stratifies_each_parameter(tmp_path):
    """Latin hypercube: each of the n equal-probability strata of a uniform parameter holds one draw."""
    spec = GRID.replace('method = "grid"', 'method = "latin-hypercube"\nruns = 20').replace(
        'values = ["1000 in/s", "3000 in/s", "5000 in/s"]', 'distribution = { uniform = ["1000 in/s", "5000 in/s"] }'
    )
    runs = _spec_object(tmp_path, spec).runs()
    v = np.array([r.row["load.history.velocity"] for r in runs]) / INCH
    strata = np.floor((v - 1000) / 4000 * 20).astype(int)
    assert sorted(strata) == list(range(20))


def test_scaling_draws_follow_the_fit_covariance(tmp_path):
    """The α's drawn `from` a scaling.json have the mean and the covariance built from its intervals
    (se = half-width / t(0.975, n-1)) and residual correlations, computed here independently."""
    from scipy.stats import t as student

    rng = np.random.default_rng(0)
    res = rng.normal(size=(4, 6))
    res[1] += 0.8 * res[0]  # α1 and α2 errors correlated
    halves = [0.2, 0.05, 0.01, 0.03]
    means = [4.2, 0.93, 0.25, 0.66]
    group = {f"alpha{i + 1}": {"value": means[i], "ci95": [means[i] - halves[i], means[i] + halves[i]], "residuals": list(res[i])} for i in range(4)}
    (tmp_path / "scaling.json").write_text(json.dumps({"groups": {"0.5 in": group}, "pooled": group}))
    spec = (
        GRID.replace('method = "grid"', 'method = "monte-carlo"\nruns = 4000\nseed = 2') + '[[sweep.parameter]]\nkey = "load.history"\nfrom = "scaling.json"\n'
    )
    spec = spec.replace('values = ["1000 in/s", "3000 in/s", "5000 in/s"]', 'values = ["1000 in/s"]')
    runs = _spec_object(tmp_path, spec).runs()
    a = np.array([[r.row[f"load.history.alpha{i}"] for i in range(1, 5)] for r in runs])
    se = np.array(halves) / student.ppf(0.975, 5)
    expected = np.corrcoef(res) * np.outer(se, se)
    assert a.mean(axis=0) == pytest.approx(means, abs=4 * se.max() / math.sqrt(4000) * 3)
    assert np.cov(a.T) == pytest.approx(expected, rel=0.1, abs=0.05 * se.max() ** 2)
    # the α's reach the case: eq (4) with the drawn α1
    assert runs[0].sets[-4] == ("load.history.alpha1", a[0, 0])


def test_grid_with_levels_crossed_and_common_draws(tmp_path):
    """Levels are crossed; every level combination gets the same draws (common random numbers)."""
    spec = GRID.replace('method = "grid"', 'method = "monte-carlo"\nruns = 5') + (
        '[[sweep.parameter]]\nkey = "load.history.projectile"\nvalues = ["rubber-3/8in", "rubber-1/2in"]\n'
        '[[sweep.parameter]]\nkey = "beam.laminate.ply.E1"\ndistribution = { normal = ["120 GPa", "5 GPa"] }\n'
    )
    s = _spec_object(tmp_path, spec)
    runs = s.runs()
    assert len(runs) == 3 * 2 * 5
    e1 = np.array([r.row["beam.laminate.ply.E1"] for r in runs]).reshape(6, 5)
    assert np.all(e1 == e1[0])
    from softimpact.cases import BeamKind

    case = s.case_for(runs[0], BeamKind().expand)
    assert case["beam"]["laminate"]["ply"]["E1"] == f"{float(e1[0, 0])!r} Pa"
    assert case["beam"]["laminate"]["ply"]["E2"] == f"{7.9e9!r} Pa"  # the catalogue ply, expanded


def _resume_spec():
    return (
        GRID.replace('method = "grid"', 'method = "monte-carlo"\nruns = 200\nseed = 5\nchunk = 2').replace(
            'values = ["1000 in/s", "3000 in/s", "5000 in/s"]', 'distribution = { uniform = ["1000 in/s", "5000 in/s"] }\n'
        )
        + '[[sweep.parameter]]\nkey = "beam.laminate.ply.E2"\ndistribution = { normal = ["7.9 GPa", "0.3 GPa"] }\n'
    )


@pytest.mark.slow
def test_killed_sweep_resumes_and_computes_every_run_once(tmp_path):
    """A sweep killed half-way (SIGKILL) and started again keeps its checkpointed chunks untouched,
    computes only the rest, and ends with the table of an uninterrupted sweep."""
    path = _write(tmp_path, _resume_spec().replace("runs = 200", "runs = 30"))
    out = tmp_path / "out"
    cmd = [os.path.join(os.path.dirname(sys.executable), "softimpact"), "sweep", str(path), "--out", str(out), "--workers", "0", "--no-figures"]
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    deadline = time.time() + 120
    folder = None
    while time.time() < deadline:
        found = list((out / "checkpoints").glob("*/chunk-*.json")) if (out / "checkpoints").exists() else []
        if len(found) >= 5:
            folder = found[0].parent
            break
        time.sleep(0.05)
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    assert folder is not None, "no checkpoint appeared"
    before = {p.name: p.stat().st_mtime_ns for p in folder.glob("chunk-*.json")}
    saved = sum(len(json.loads(p.read_text())) for p in folder.glob("chunk-*.json"))
    assert 0 < saved < 30
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    summary = json.loads((out / "summary.json").read_text())
    assert summary["from_checkpoints"] == saved and summary["computed_now"] == 30 - saved
    after = {p.name: p.stat().st_mtime_ns for p in folder.glob("chunk-*.json")}
    assert sum(len(json.loads(p.read_text())) for p in folder.glob("chunk-*.json")) == 30
    assert all(after[k] == v for k, v in before.items())
    ref = tmp_path / "ref"
    r = CliRunner().invoke(main, ["sweep", str(path), "--out", str(ref), "--workers", "0", "--no-figures"])
    assert r.exit_code == 0, r.output
    assert _table(out) == _table(ref)


@pytest.mark.slow
def test_same_results_in_a_loop_on_a_local_cluster_and_on_a_separate_scheduler(tmp_path):
    """Same seed → identical run tables from the plain loop, a LocalCluster and a `dask scheduler`
    + `dask worker` started separately on localhost."""
    spec = _resume_spec().replace("runs = 200", "runs = 12").replace("chunk = 2", "chunk = 4")
    path = _write(tmp_path, spec)
    tables = []
    r = CliRunner().invoke(main, ["sweep", str(path), "--out", str(tmp_path / "loop"), "--workers", "0", "--no-figures"])
    assert r.exit_code == 0, r.output
    tables.append(_table(tmp_path / "loop"))
    r = CliRunner().invoke(main, ["sweep", str(path), "--out", str(tmp_path / "local"), "--workers", "2", "--no-figures"])
    assert r.exit_code == 0, r.output
    tables.append(_table(tmp_path / "local"))
    dask = os.path.join(os.path.dirname(sys.executable), "dask")
    port = 8786 + os.getpid() % 1000
    sched = subprocess.Popen([dask, "scheduler", "--port", str(port), "--no-dashboard"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    worker = subprocess.Popen(
        [dask, "worker", f"tcp://127.0.0.1:{port}", "--nworkers", "1", "--nthreads", "1", "--no-dashboard"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    try:
        from distributed import Client

        with Client(f"tcp://127.0.0.1:{port}", timeout="60s") as c:
            c.wait_for_workers(1, timeout=60)
        r = CliRunner().invoke(main, ["sweep", str(path), "--out", str(tmp_path / "remote"), "--scheduler", f"tcp://127.0.0.1:{port}", "--no-figures"])
        assert r.exit_code == 0, r.output
        tables.append(_table(tmp_path / "remote"))
    finally:
        for p in (worker, sched):
            p.terminate()
            p.wait(timeout=30)
    assert tables[0] == tables[1] == tables[2]
    assert len(set(tables[0]["beam.laminate.ply.E2"])) == 12  # each run its own structure


def test_statistics_and_rank_correlation():
    """Percentiles of 0..100 are the values themselves; a monotone output ranks its driver first (ρ = 1)."""
    from softimpact.workflows.sweep_stats import sensitivity, statistics

    s = statistics(np.arange(101.0))
    assert (s["median"], s["p05"], s["p95"], s["interval95"]) == (50.0, 5.0, 95.0, [2.5, 97.5])
    rng = np.random.default_rng(1)
    x, noise = rng.uniform(1, 2, 200), rng.uniform(0, 1, 200)
    ranked = sensitivity({"noise": noise, "x": x}, np.exp(3 * x) + 0.01 * noise)
    assert ranked[0]["parameter"] == "x" and ranked[0]["spearman"] == pytest.approx(1.0)


@pytest.mark.slow
def test_monte_carlo_of_the_long_beam_medians_of_the_deterministic_runs(tmp_path):
    """Issue 13: 1000 runs of paper-long-beam under the rubber-ball law (α's drawn from the fitted
    covariance of the built-in series, V uniform in 1000–5000 in/s): the median peak strains equal
    those of direct stepping at the median velocity with the fitted mean α's (peak strain is monotone
    in V and the α's scatter by < 1 %). Its time (under a minute) is benchmarks/bench_sweep_mc.py's."""
    from softimpact.input.beam_case import beam_problem
    from softimpact.input.toml import load_toml, locate
    from softimpact.workflows.beam_impact import BeamModel

    r = CliRunner().invoke(main, ["fit", "paper-rubber-series", "--out", str(tmp_path / "fit"), "--no-figures"])
    assert r.exit_code == 0, r.output
    spec = """
[sweep]
case = "paper-long-beam"
method = "monte-carlo"
runs = 1000
seed = 7
chunk = 100
outputs = ["peak_force_N", "strain_g1.peak", "strain_g2.peak"]
[[sweep.parameter]]
key = "load.history"
value = { shape = "empirical", projectile = "rubber-1/2in", velocity = "1166 in/s" }
[[sweep.parameter]]
key = "load.history.velocity"
distribution = { uniform = ["1000 in/s", "5000 in/s"] }
[[sweep.parameter]]
key = "load.history"
from = "fit/scaling.json"
group = "0.5 in"
"""
    (tmp_path / "mc.toml").write_text(spec)
    r = CliRunner().invoke(main, ["sweep", str(tmp_path / "mc.toml"), "--out", str(tmp_path / "out"), "--no-figures"])
    assert r.exit_code == 0, r.output
    t = _table(tmp_path / "out")
    fit = json.loads((tmp_path / "fit" / "scaling.json").read_text())["groups"]["0.5 in"]
    data = load_toml(locate("paper-long-beam"))
    V = float(np.median(t["load.history.velocity"]))
    data["load"]["history"] = {"shape": "empirical", "projectile": "rubber-1/2in", "velocity": f"{V!r} m/s"}
    data["load"]["history"].update({f"alpha{i}": fit[f"alpha{i}"]["value"] for i in range(1, 5)})
    ref = BeamModel(beam_problem(data)).direct(energy=False)
    for g, eps in zip(("g1", "g2"), ref.strain):
        assert float(np.median(t[f"strain_{g}.peak"])) == pytest.approx(eps[np.argmax(np.abs(eps))], rel=5e-3)


def test_convolve_with_cached_spectrum_equals_respond():
    """The engine's cached-spectrum convolution equals its FFT convolution (and so direct stepping)."""
    import tomllib

    from softimpact.input.beam_case import beam_problem
    from softimpact.workflows.beam_impact import BeamModel

    model = BeamModel(beam_problem(tomllib.loads(CASE)))
    F = model.force_samples()
    loads = model.nodal_loads(F)
    e = model.engine()
    assert e.convolve(loads) == pytest.approx(e.respond(loads), rel=1e-9, abs=1e-12 * np.abs(e.respond(loads)).max())
    assert e.convolve(0.5 * loads) == pytest.approx(0.5 * e.respond(loads), rel=1e-9, abs=1e-12 * np.abs(e.respond(loads)).max())


BAR_SPEC = """
[sweep]
case = "paper-calibration"
method = "grid"
outputs = ["peak_force_N", "contact_duration_s"]
[[sweep.parameter]]
key = "projectile.velocity"
values = ["40 in/s", "80 in/s"]
[[sweep.parameter]]
key = "solver.duration"
value = "120 us"
[[sweep.parameter]]
key = "output.snapshots"
value = ["60 us"]
"""


def test_bar_cases_sweep_through_their_adapter(tmp_path):
    """A bar case sweeps too (each run its own nonlinear contact run): the rows equal the bar
    workflow run on the case at each velocity."""
    from softimpact.input.bar_case import bar_problem
    from softimpact.input.toml import load_toml, locate
    from softimpact.workflows.bar_impact import simulate_impact

    (tmp_path / "spec.toml").write_text(BAR_SPEC)
    out = tmp_path / "out"
    r = CliRunner().invoke(main, ["sweep", str(tmp_path / "spec.toml"), "--out", str(out), "--workers", "0", "--no-figures"])
    assert r.exit_code == 0, r.output
    t = _table(out)
    data = load_toml(locate("paper-calibration"))
    data["solver"]["duration"] = "120 us"
    data["output"]["snapshots"] = ["60 us"]
    for k, v in enumerate((40, 80)):
        data["projectile"]["velocity"] = f"{v} in/s"
        ref = simulate_impact(bar_problem(data))
        assert t["peak_force_N"][k] == pytest.approx(ref.peak_force, rel=1e-12)
        assert t["contact_duration_s"][k] == pytest.approx(ref.contact_duration, rel=1e-12)


@pytest.mark.parametrize(
    "law, check",
    [
        ('normal = ["3000 in/s", "200 in/s"]', lambda v: (np.mean(v), np.std(v)) == pytest.approx((3000, 200), rel=0.05)),
        ('uniform = ["1000 in/s", "2000 in/s"]', lambda v: v.min() >= 1000 and v.max() <= 2000 and np.mean(v) == pytest.approx(1500, rel=0.02)),
        ('lognormal = ["2000 in/s", 0.2]', lambda v: (np.median(v), np.std(np.log(v))) == pytest.approx((2000, 0.2), rel=0.05)),
    ],
)
def test_distributions(tmp_path, law, check):
    """Draws follow the named law: normal [mean, sd], uniform [low, high], lognormal [median, sigma of ln]."""
    spec = GRID.replace('method = "grid"', 'method = "monte-carlo"\nruns = 2000\nseed = 11').replace(
        'values = ["1000 in/s", "3000 in/s", "5000 in/s"]', f"distribution = {{ {law} }}"
    )
    v = np.array([r.row["load.history.velocity"] for r in _spec_object(tmp_path, spec).runs()]) / INCH
    assert check(v)


# A key inside load.history varied, then the whole table (the README's parameters swapped): the
# table, applied second, would replace every velocity level with its own 1166 in/s.
SWAPPED = GRID + '[[sweep.parameter]]\nkey = "load.history"\nvalue = { shape = "empirical", projectile = "rubber-1/2in", velocity = "1166 in/s" }\n'
TWICE = GRID + '[[sweep.parameter]]\nkey = "load.history.velocity"\nvalues = ["2000 in/s", "4000 in/s"]\n'
LEVELS_AND_DRAWS = GRID.replace('method = "grid"', 'method = "monte-carlo"\nruns = 4') + (
    '[[sweep.parameter]]\nkey = "load.history.velocity"\ndistribution = { uniform = ["1000 in/s", "5000 in/s"] }\n'
)


@pytest.mark.parametrize(
    "spec, first, second",
    [
        (SWAPPED, "load.history.velocity", "load.history"),
        (TWICE, "load.history.velocity", "load.history.velocity"),
        (LEVELS_AND_DRAWS, "load.history.velocity", "load.history.velocity"),
    ],
)
def test_parameters_touching_one_key_are_refused_naming_both(tmp_path, spec, first, second):
    """Issue 23: a key set by two parameters, or a table listed after a key inside it, is exit 2 with one
    line naming both parameters and keys, before anything is written."""
    result, out = _sweep(tmp_path, spec, "--workers", "0")
    assert result.exit_code == 2, result.output
    line = result.output.strip()
    assert len(line.splitlines()) == 1 and "sweep.parameter[0]" in line and "sweep.parameter[1]" in line
    assert repr(first) in line and repr(second) in line
    assert not out.exists()


@pytest.mark.parametrize("address", ["tcp://127.0.0.1", "127.0.0.1", "tcp://127.0.0.1:", "tcp://127.0.0.1:99999", "tcp://:8786"])
def test_a_scheduler_address_without_a_valid_port_is_refused_up_front(tmp_path, address):
    """Issue 23: --scheduler without a port (or with a bad one) is one line naming --scheduler, exit 2, nothing
    written; it was an internal error once the runs were planned."""
    result, out = _sweep(tmp_path, GRID, "--scheduler", address)
    assert result.exit_code == 2, result.output
    assert result.output.startswith("softimpact: error: --scheduler:") and len(result.output.strip().splitlines()) == 1
    assert not out.exists()


def test_a_full_disk_while_checkpointing_is_exit_2_and_leaves_nothing_a_resume_would_trust(tmp_path, monkeypatch):
    """Issue 23: ENOSPC while a chunk's checkpoint is written is exit 2 with the folder and the reason, no chunk
    file (whole or partial) and no staging file is left, and the sweep run again once the disk has room
    gives the table of an uninterrupted sweep."""
    import errno
    import pathlib

    spec = GRID.replace('method = "grid"', 'method = "grid"\nchunk = 1')
    real = {"write_text": pathlib.Path.write_text, "write_bytes": pathlib.Path.write_bytes}

    def full(name):
        def write(self, data, *args, **kwargs):
            if "checkpoints" in str(self):
                real[name](self, data[: len(data) // 2], *args, **kwargs)  # part of it reaches the disk, then the disk is full
                raise OSError(errno.ENOSPC, "No space left on device", str(self))
            return real[name](self, data, *args, **kwargs)

        return write

    monkeypatch.setattr(pathlib.Path, "write_text", full("write_text"))
    monkeypatch.setattr(pathlib.Path, "write_bytes", full("write_bytes"))
    result, out = _sweep(tmp_path, spec, "--workers", "0")
    monkeypatch.undo()
    assert result.exit_code in (2, 3), result.output
    errors = [line for line in result.output.splitlines() if "error" in line]  # after the progress display
    assert len(errors) == 1 and errors[0].startswith("softimpact: error:"), result.output
    assert "No space left on device" in errors[0] and str(out / "checkpoints") in errors[0]
    left = [p for p in (out / "checkpoints").rglob("*") if p.is_file()]
    assert left == [], left
    again, _ = _sweep(tmp_path, spec, "--workers", "0")
    assert again.exit_code == 0, again.output
    ref, ref_out = (
        CliRunner().invoke(main, ["sweep", str(tmp_path / "spec.toml"), "--out", str(tmp_path / "ref"), "--workers", "0", "--no-figures"]),
        tmp_path / "ref",
    )
    assert ref.exit_code == 0, ref.output
    assert _table(out) == _table(ref_out)


IMPACT_CASE = LONG_BEAM_IMPACT

IMPACT_SPEC = """
[sweep]
case = "impact.toml"
method = "grid"
outputs = ["peak_force_N", "contact_duration_s", "gauges.g1.peak_tensile_strain"]
[[sweep.parameter]]
key = "impactor.velocity"
values = ["50 in/s", "100 in/s", "150 in/s"]
"""


@pytest.mark.slow
def test_an_impact_sweep_equals_single_impact_runs_and_its_peak_force_grows_with_velocity(tmp_path):
    """A velocity sweep of the long-beam impact case (one target model shared by the runs) gives, at
    each velocity, the peak force and contact duration of `softimpact impact` run alone at that
    velocity (to 1e-9), and peak forces increasing with the velocity."""
    (tmp_path / "impact.toml").write_text(IMPACT_CASE.format(velocity="100 in/s"))
    (tmp_path / "spec.toml").write_text(IMPACT_SPEC)
    r = CliRunner().invoke(main, ["sweep", str(tmp_path / "spec.toml"), "--out", str(tmp_path / "out"), "--workers", "0", "--no-figures"])
    assert r.exit_code == 0, r.output
    t = _table(tmp_path / "out")
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["case_type"] == "impact" and summary["groups"] == 1 and t["error"] == ["", "", ""]
    assert np.all(np.diff(t["peak_force_N"]) > 0)
    for k, v in enumerate((50, 100, 150)):
        case = tmp_path / f"impact-{v}.toml"
        case.write_text(IMPACT_CASE.format(velocity=f"{v} in/s"))
        one = CliRunner().invoke(main, ["impact", str(case), "--out", str(tmp_path / f"one-{v}"), "--no-figures"])
        assert one.exit_code == 0, one.output
        s = json.loads((tmp_path / f"one-{v}" / "summary.json").read_text())
        assert t["impactor.velocity"][k] == pytest.approx(v * INCH, rel=1e-12)
        assert t["peak_force_N"][k] == pytest.approx(s["peak_force_N"], rel=1e-9)
        assert t["contact_duration_s"][k] == pytest.approx(s["contact_duration_s"], rel=1e-9)
        assert t["gauges.g1.peak_tensile_strain"][k] == pytest.approx(s["gauges"]["g1"]["peak_tensile_strain"], rel=1e-9)


def test_a_bar_as_impact_target_sweeps_as_the_bar_case_with_the_impactor(tmp_path):
    """An impact case whose target is a bar case sweeps as that bar case with the impact case's impactor:
    each run's peak force is that of `softimpact bar` on the bar case at that velocity."""
    from softimpact.input.bar_case import bar_problem
    from softimpact.input.toml import load_toml, locate
    from softimpact.workflows.bar_impact import simulate_impact

    (tmp_path / "impact.toml").write_text(
        '[target]\ncase = "paper-calibration"\n[impactor]\nmaterial = "steel"\ndiameter = "0.625 in"\nvelocity = "62.1 in/s"\n'
        '[contact]\nlaw = "hertz"\n[solver]\ntime_step = "0.5 us"\nduration = "120 us"\n'
    )
    (tmp_path / "spec.toml").write_text(
        '[sweep]\ncase = "impact.toml"\nmethod = "grid"\noutputs = ["peak_force_N"]\n'
        '[[sweep.parameter]]\nkey = "impactor.velocity"\nvalues = ["40 in/s", "80 in/s"]\n'
    )
    r = CliRunner().invoke(main, ["sweep", str(tmp_path / "spec.toml"), "--out", str(tmp_path / "out"), "--workers", "0", "--no-figures"])
    assert r.exit_code == 0, r.output
    t = _table(tmp_path / "out")
    data = load_toml(locate("paper-calibration"))
    data["solver"]["duration"] = "120 us"
    data.pop("output")
    for k, v in enumerate((40, 80)):
        data["projectile"]["velocity"] = f"{v} in/s"
        assert t["peak_force_N"][k] == pytest.approx(simulate_impact(bar_problem(data)).peak_force, rel=1e-12)


def test_softimpact_impact_on_a_bar_target_names_the_cause(tmp_path):
    """`softimpact impact` on a bar target: exit 2 and one line saying it is a bar case (it said 'beam: missing')."""
    (tmp_path / "impact.toml").write_text(
        '[target]\ncase = "paper-calibration"\n[impactor]\nmaterial = "steel"\ndiameter = "0.625 in"\nvelocity = "62.1 in/s"\n'
        '[contact]\nlaw = "hertz"\n[solver]\ntime_step = "0.5 us"\nduration = "120 us"\n'
    )
    r = CliRunner().invoke(main, ["impact", str(tmp_path / "impact.toml"), "--out", str(tmp_path / "out")])
    assert r.exit_code == 2 and "a bar case" in r.output and "beam: missing" not in r.output
    assert len(r.output.strip().splitlines()) == 1
