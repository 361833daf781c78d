"""Every kind of run passes through every command that takes a case, or is refused by it up front (issue 42): cohesive
interfaces, large-deflection beams, static plates and bar targets through sweep and converge; a static plate as an
impact's target; options a static plate cannot honour."""

import json

import pyarrow.parquet as pq
import pytest
from click.testing import CliRunner

from softimpact.cli import main
from softimpact.input.toml import locate

COHESIVE_TARGET = locate("plate-ss-8in-quarter").read_text().replace("elements = [24, 24]", "elements = [4, 4]")
COHESIVE = (
    locate("plate-ss-8in-impact-cohesive")
    .read_text()
    .replace('case = "plate-ss-8in-quarter"', 'case = "quarter.toml"')
    .replace('time_step = "1 us"', 'time_step = "2 us"')
    .replace('duration = "600 us"', 'duration = "20 us"')
)
VK_BEAM = """units = "in-lbf-s"
[beam]
length = "6 in"
width = "1 in"
elements = [30, 4]
kinematics = "von-karman"
[beam.laminate]
ply = "T300/934"
layup = "[90/0]5s"
[load]
position = "3 in"
contact_radius = "0.25 in"
history = { shape = "skewed", peak_force = "44 lbf", time_of_peak = "30 us", duration = "355 us" }
[solver]
time_step = "2 us"
duration = "60 us"
[[gauges]]
name = "g1"
position = "2 in"
"""
BAR_TARGET = """units = "in-lbf-s"
[target]
case = "paper-calibration"
[impactor]
material = "steel"
diameter = "0.625 in"
velocity = "62.1 in/s"
[contact]
law = "hertz"
[solver]
time_step = "1 us"
duration = "150 us"
"""
# (case file, the key a sweep varies and its two values, the output asked)
KINDS = {
    "cohesive impact": ("case.toml", "impactor.velocity", ["3 m/s", "5 m/s"], "peak_force_N"),
    "von Karman beam": ("case.toml", "load.history.peak_force", ["30 lbf", "44 lbf"], "peak_force_N"),
    "impact on a bar": ("case.toml", "impactor.velocity", ["50 in/s", "62.1 in/s"], "peak_force_N"),
}


def _case(folder, kind):
    if kind == "cohesive impact":
        (folder / "quarter.toml").write_text(COHESIVE_TARGET)
        (folder / "case.toml").write_text(COHESIVE)
    else:
        (folder / "case.toml").write_text(VK_BEAM if kind == "von Karman beam" else BAR_TARGET)
    case, key, values, output = KINDS[kind]
    spec = f'[sweep]\ncase = "{case}"\nmethod = "grid"\noutputs = ["{output}"]\n[[sweep.parameter]]\nkey = "{key}"\nvalues = {json.dumps(values)}\n'
    (folder / "spec.toml").write_text(spec)
    return folder / "case.toml", folder / "spec.toml", output


def invoke(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def _single(kind: str, value: str):
    """(command, case text): the first run of the sweep as a case of its own command, its key set to ``value`` by hand."""
    if kind == "cohesive impact":
        return "impact", COHESIVE.replace('velocity = "5 m/s"', f'velocity = "{value}"')
    if kind == "von Karman beam":
        return "beam", VK_BEAM.replace('peak_force = "44 lbf"', f'peak_force = "{value}"')
    # an impact case on a bar target runs as the bar case with the impact's impactor, contact law and solver
    bar = locate("paper-calibration").read_text().split("[output]")[0]
    bar = bar.replace('velocity = "62.1 in/s"', f'velocity = "{value}"').replace('time_step = "0.5 us"', 'time_step = "1 us"')
    return "bar", bar.replace('duration = "400 us"', 'duration = "150 us"')


# the cohesive sweep builds its stacked model three times (4.5 s): the slow tier; its converge (one path, 1.3 s) stays quick
SWEPT = [pytest.param(k, marks=pytest.mark.slow) if k == "cohesive impact" else k for k in sorted(KINDS)]


@pytest.mark.parametrize("kind", SWEPT)
def test_a_run_kind_sweeps_to_the_numbers_of_its_single_runs(tmp_path, kind):
    """A sweep of each run kind exits 0 with every run done, and its first row's output equals that of the same case run
    alone by its own command at that value (an independent run, through the command line)."""
    _, spec, output = _case(tmp_path, kind)
    r = invoke("sweep", spec, "--out", tmp_path / "s", "--no-figures", "--workers", "0")
    assert r.exit_code == 0, r.output
    summary = json.loads((tmp_path / "s" / "summary.json").read_text())
    assert summary["failed"] == 0 and summary["succeeded"] == 2, summary.get("failures")
    table = pq.read_table(tmp_path / "s" / "runs.parquet").to_pydict()
    command, text = _single(kind, KINDS[kind][2][0])
    (tmp_path / "single.toml").write_text(text)
    one = invoke(command, tmp_path / "single.toml", "--out", tmp_path / "one", "--no-figures")
    assert one.exit_code == 0, one.output
    alone = json.loads((tmp_path / "one" / "summary.json").read_text())["peak_force_N"]
    assert table[output][0] == pytest.approx(alone, rel=1e-9)


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_a_run_kind_converges_on_two_levels(tmp_path, kind):
    """`softimpact converge --levels 2` of each run kind exits 0 (a cohesive impact used to end in a KeyError, exit 70) and
    writes its convergence table."""
    case, _, _ = _case(tmp_path, kind)
    r = invoke("converge", case, "--levels", "2", "--out", tmp_path / "c", "--no-figures")
    assert r.exit_code == 0, r.output
    assert (tmp_path / "c" / "convergence.csv").is_file()


STATIC = "plate-ss-pressure-vk"
STATIC_IMPACT = BAR_TARGET.replace('case = "paper-calibration"', f'case = "{STATIC}"').replace('diameter = "0.625 in"', 'diameter = "0.5 in"')


@pytest.mark.parametrize(
    "args, words",
    [
        (("sweep", "spec.toml", "--workers", "0"), "static"),
        (("converge", STATIC, "--levels", "2"), "static"),
        (("impact", "impact.toml"), "a static plate case"),
        (("plate", STATIC, "--fields"), "--fields"),
        (("plate", STATIC, "--history", "1"), "--history"),
    ],
    ids=["sweep", "converge", "impact target", "--fields", "--history"],
)
def test_a_static_plate_is_refused_at_once_where_it_cannot_run(tmp_path, monkeypatch, args, words):
    """A static plate swept, converged, struck by an impactor, or given options it cannot honour: exit 2 in one line
    naming why, before any run (a sweep used to run every point to fail each), nothing written."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "spec.toml").write_text(
        f'[sweep]\ncase = "{STATIC}"\nmethod = "grid"\noutputs = ["peak_force_N"]\n[[sweep.parameter]]\nkey = "load.pressure"\nvalues = ["10 psi", "20 psi"]\n'
    )
    (tmp_path / "impact.toml").write_text(STATIC_IMPACT)
    r = invoke(*args, "--out", tmp_path / "o")
    assert r.exit_code == 2, r.output
    lines = [line for line in r.stderr.splitlines() if line.startswith("softimpact: error:")]
    assert len(lines) == 1 and words in lines[0], r.output
    assert not (tmp_path / "o").exists()
