"""The object-first API (`import softimpact as si`): the same numbers as the command line, units at the edge, the result contract."""

import inspect
import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

import softimpact as si
from softimpact.cli import main
from softimpact.errors import InputError

BEAM_CASE = """title = "API twin"
units = "in-lbf-s"
[beam]
length = "6 in"
width = "1 in"
elements = [200, 6]
support = "clamped-free"
[beam.laminate]
ply = "T300/934"
layup = "[90/0]5s"
model = "smeared"
[load]
position = "3 in"
contact_radius = "0.25 in"
history = { shape = "skewed", peak_force = "44 lbf", time_of_peak = "30 us", duration = "355 us" }
[solver]
time_step = "1 us"
duration = "400 us"
[[gauges]]
name = "g1"
position = "2 in"
[[gauges]]
name = "g2"
position = "0.5 in"
"""

IMPACT_CASE = """title = "API twin"
units = "in-lbf-s"
[target]
case = "beam.toml"
[impactor]
material = "steel"
diameter = "0.5 in"
velocity = "100 in/s"
[contact]
law = "hertz"
[solver]
time_step = "0.5 us"
duration = "400 us"
"""


def _cli(tmp_path, *args):
    out = tmp_path / "cli-out"
    result = CliRunner().invoke(main, [*args, "--out", str(out), "--no-figures"], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    return json.loads((out / "summary.json").read_text())


def _five_lines():
    beam = si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(200, 6))
    return si.impact(
        beam,
        at="3 in",
        impactor=si.Sphere("steel", "0.5 in", velocity="100 in/s"),
        law="hertz",
        time_step="0.5 us",
        duration="400 us",
        gauges={"g1": "2 in", "g2": "0.5 in"},
    )


@pytest.fixture(scope="module")
def five_lines():
    return _five_lines()


def test_issue_example_matches_the_command_on_the_equivalent_case(tmp_path, five_lines):
    """The issue's five-line example gives the peak force, its time and the gauge peaks of `softimpact impact` on the same case written as files."""
    (tmp_path / "beam.toml").write_text(BEAM_CASE)
    (tmp_path / "impact.toml").write_text(IMPACT_CASE)
    cli = _cli(tmp_path, "impact", str(tmp_path / "impact.toml"))
    res = five_lines
    assert res.peak_force == pytest.approx(cli["peak_force_N"], rel=1e-12)
    assert res.time_of_peak == pytest.approx(cli["time_of_peak_s"], rel=1e-12)
    assert res.impulse == pytest.approx(cli["impulse_N_s"], rel=1e-12)
    for g in ("g1", "g2"):
        eps = res.strain[g]
        assert np.max(eps) == pytest.approx(cli["gauges"][g]["peak_tensile_strain"], rel=1e-12)


def test_load_and_run_equal_the_commands_summary(tmp_path):
    """si.load + si.run of the built-in impact case reproduce every number of the command's summary.json."""
    cli = _cli(tmp_path, "impact", "paper-long-beam-impact")
    ours = si.run(si.load("paper-long-beam-impact"), figures=False).summary()

    def numbers(tree, prefix=""):
        out = {}
        for k, v in tree.items():
            if isinstance(v, dict):
                out.update(numbers(v, f"{prefix}{k}."))
            elif isinstance(v, (int, float)) and not isinstance(v, bool):
                out[prefix + k] = v
        return out

    a, b = numbers(ours), numbers(cli)
    assert set(a) == set(b)
    timing = {k for k in a if "seconds" in k or k.endswith("wall_s")}
    for k in sorted(set(a) - timing):
        assert a[k] == pytest.approx(b[k], rel=1e-12, nan_ok=True), k


def test_hertz_peak_force_against_the_rigid_target_closed_form(five_lines):
    """The peak force lies below the closed-form Hertz peak on a rigid half-space with the same law (the beam's compliance lowers it) and above a tenth of it."""
    law = five_lines.problem.law
    ball = five_lines.problem.impactor
    # Hertz on a rigid target: α_max = (5 m V² / (4 K))^(2/5), F_max = K α_max^(3/2)
    alpha = (5 * ball.mass * ball.velocity**2 / (4 * law.K)) ** 0.4
    rigid = law.K * alpha**1.5
    assert 0.1 * rigid < five_lines.peak_force < rigid


def test_pint_quantities_equal_unit_strings():
    """A pint quantity and the same quantity as text give the same SI number (to round-off of the two conversions)."""
    from softimpact.units import registry

    q = registry().Quantity
    a = si.Sphere("steel", q(0.5, "inch"), velocity=q(100, "inch/second"))
    b = si.Sphere("steel", "0.5 in", velocity="100 in/s")
    assert a.diameter == pytest.approx(0.0127, rel=1e-15) and b.diameter == pytest.approx(0.0127, rel=1e-15)
    assert a.velocity == pytest.approx(b.velocity, rel=1e-15)
    assert a.mass == pytest.approx(b.mass, rel=1e-14)


@pytest.mark.parametrize(
    "make, argument",
    [
        (lambda: si.Sphere("steel", 0.5, velocity="100 in/s"), "diameter"),
        (lambda: si.Sphere("steel", "0.5 in", velocity="100 in"), "velocity"),
        (lambda: si.Beam(length="6 in", width="1 kg", laminate=si.Laminate("T300/934", "[0]4")), "width"),
        (lambda: si.Laminate("no-such-ply", "[0]4"), "ply"),
        (lambda: si.Beam(length="6 in", width="1 in"), "Beam"),
    ],
)
def test_bad_input_names_the_argument(make, argument):
    """A missing unit, a wrong dimension or an unknown name is an InputError whose message starts with the argument's name."""
    with pytest.raises(InputError, match=f"^{argument}"):
        make()


def test_impact_point_off_the_beam_names_at():
    """An impact point beyond the beam's length is refused naming `at`."""
    beam = si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(40, 4))
    with pytest.raises(InputError, match="^at"):
        si.impact(beam, at="7 in", impactor=si.Sphere("steel", "0.5 in", velocity="1 m/s"), time_step="1 us", duration="10 us")


def test_result_is_frozen_and_carries_si_inputs(five_lines):
    """The result refuses assignment and holds its inputs in SI (6 in = 0.1524 m, 0.5 us = 5e-7 s)."""
    with pytest.raises(AttributeError):
        five_lines.result = None
    p = five_lines.problem
    assert p.target.beam.length == pytest.approx(6 * 0.0254, rel=1e-15)
    assert p.solver.time_step == pytest.approx(0.5e-6, rel=1e-15)
    assert p.position == pytest.approx(3 * 0.0254, rel=1e-15)


def test_write_follows_the_file_contract(tmp_path, five_lines):
    """`.write(dir)` writes history.csv, summary.json and a manifest listing them with their SHA-256."""
    five_lines.write(tmp_path / "out", figures=False)
    manifest = json.loads((tmp_path / "out" / "manifest.json").read_text())
    names = {f["name"] if isinstance(f, dict) else f for f in manifest["files"]}
    assert {"history.csv", "summary.json"} <= names
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["peak_force_N"] == five_lines.peak_force


def test_to_frame_has_time_index_and_units(five_lines):
    """`.to_frame()` is indexed by time [s] and names each column's SI unit in df.attrs; its force column is the force history."""
    df = five_lines.to_frame()
    assert df.index.name == "time_s"
    assert df.attrs["units"]["contact_force_N"] == "N"
    np.testing.assert_array_equal(df["contact_force_N"].to_numpy(), five_lines.force)
    np.testing.assert_array_equal(df.index.to_numpy(), five_lines.time)


def test_plot_draws_the_force_history(five_lines):
    """`.plot()` draws one line whose peak is the peak force in lbf (the case's display units)."""
    import matplotlib

    matplotlib.use("Agg")
    ax = five_lines.plot()
    y = ax.lines[0].get_ydata()
    assert np.max(y) == pytest.approx(np.max(five_lines.force) / 4.4482216152605, rel=1e-9)


def test_bar_from_objects_equals_the_bar_case():
    """A si.Bar struck by a si.Sphere gives the contact force of the paper's calibration case read from its file."""
    case = si.load("paper-calibration")
    p = case.problem
    bar = si.Bar(
        "Al 6061-T6",
        length="36 in",
        diameter="0.5 in",
        elements=39,
        end_cap={"material": "Al 6061-T6", "diameter": "1.0 in", "length": "0.25 in"},
    )
    res = si.impact(bar, impactor=si.Sphere("steel", "0.625 in", velocity="62.1 in/s"), time_step="0.5 us", duration="400 us", gauges={"midpoint": "18 in"})
    ref = si.run(case)
    assert res.problem.bar == p.bar
    assert res.peak_force == pytest.approx(ref.peak_force, rel=1e-12)
    # paper Fig 5: about 250 lbf (1100 N) for the 5/8-in ball at 62.1 in/s
    assert 900 < res.peak_force < 1300


def _callables():
    for name in si.__all__:
        obj = getattr(si, name)
        if callable(obj):
            yield name, obj


@pytest.mark.parametrize("name, obj", list(_callables()))
def test_every_public_name_documents_parameters_with_units(name, obj):
    """Every public callable has a numpydoc docstring; one that takes parameters has a Parameters section naming units, and Returns/Examples where it runs something."""
    doc = inspect.getdoc(obj)
    assert doc, name
    params = [p for p in inspect.signature(obj).parameters.values() if p.name != "self"]
    if params:
        assert "Parameters\n----------" in doc, name
        unit_words = ("[length]", "[time]", "[velocity]", "[mass]", "[stress]", "[m]", "[s]", "[N", "SI", "unit", "µs", "degrees", "Seconds")
        assert any(w in doc for w in unit_words), name
        if inspect.isfunction(obj):
            for section in ("Returns\n-------", "Raises\n------", "Examples\n--------"):
                assert section in doc, (name, section)


API_MODULES = [
    "softimpact.api",
    "softimpact.api.structures",
    "softimpact.api.results",
    "softimpact.api.results.runs",
    "softimpact.api.results.prescribed",
    "softimpact.api.results.command",
    "softimpact.api.commands",
    "softimpact.api.chain",
]
SLOW_EXAMPLES = {
    "softimpact.api.chain.identify",  # identifies a law on the 13 tests of the built-in series (minutes)
    "softimpact.api.chain.fit",  # fits the built-in series (seconds)
    "softimpact.api.chain.calibrate",  # calibrates a Table II history (seconds)
    "softimpact.api.chain.calibrate_bar",  # five records' echoes fitted (the same run as tests/test_cli_calibrate_bar.py)
    "softimpact.api.chain.shpb",  # five two-bar tests (the same run as tests/test_cli_shpb.py)
}


def _examples():
    """Every docstring of the API's modules that holds an example, as a doctest (slow ones marked)."""
    import doctest
    import importlib

    finder = doctest.DocTestFinder()
    for module in API_MODULES:
        for test in finder.find(importlib.import_module(module)):
            if test.examples:
                marks = [pytest.mark.slow] if test.name in SLOW_EXAMPLES else []
                yield pytest.param(test, id=test.name, marks=marks)


@pytest.mark.parametrize("example", list(_examples()))
def test_docstring_examples_run(example):
    """An Example of the API's docstrings runs as a doctest and gives what it shows (the paper's numbers where it states one)."""
    import doctest

    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    runner.run(example)
    assert runner.failures == 0, example.name


def test_no_docstring_example_is_skipped():
    """No Example of the API is skipped (each runs above), and every public function of the API has one."""
    import importlib

    for module in API_MODULES:
        assert "doctest: +SKIP" not in inspect.getsource(importlib.import_module(module)), module
    names = {p.id.rsplit(".", 1)[-1] for p in _examples()}
    assert {n for n in si.__all__ if n[0].islower() and n != "__version__"} <= names


def test_all_is_sorted_out_of_the_heavy_layers():
    """`si.__all__` names only the curated API and the version, each resolvable."""
    assert "__version__" in si.__all__
    for name in si.__all__:
        assert getattr(si, name) is not None
    assert not math.isnan(len(si.__all__))


def test_law_object_equals_the_law_name(five_lines):
    """law= a HertzLaw object built as the reader builds "hertz" (Sun's form with the ply's E3) gives the same run as the name."""
    from softimpact.models.contact_laws import HertzLaw

    p = five_lines.problem
    law = HertzLaw.sphere_on_laminate(p.impactor.diameter / 2, p.impactor_material, p.target.beam.stack.ply.E3)
    beam = si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(200, 6))
    res = si.impact(
        beam,
        at="3 in",
        impactor=si.Sphere("steel", "0.5 in", velocity="100 in/s"),
        law=law,
        time_step="0.5 us",
        duration="400 us",
        gauges={"g1": "2 in", "g2": "0.5 in"},
    )
    assert res.peak_force == five_lines.peak_force
    np.testing.assert_array_equal(res.force, five_lines.force)
