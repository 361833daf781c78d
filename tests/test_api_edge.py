"""The Python edge (issue 32): results frozen down to their arrays, options read from the command line's table, errors in Python's words."""

import inspect
from pathlib import Path

import pytest

import softimpact as si
from softimpact.app.options import CALIBRATE, CONVERGE, IDENTIFY, PREDICT, SERIES, SWEEP
from softimpact.cli import main
from softimpact.errors import InputError

from _support.small_cases import BEAM

RUBBER_RECORD = Path(si.__file__).parent / "data" / "series" / "paper-rubber-series" / "1_2in-1000.csv"


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """A beam case run, a coupled beam impact, a bar impact and a lab record: one of each result with arrays."""
    path = tmp_path_factory.mktemp("beam") / "beam.toml"
    path.write_text(BEAM)
    beam = si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(40, 4))
    ball = si.Sphere("steel", "0.5 in", velocity="100 in/s")
    bar = si.Bar("Al 6061-T6", length="36 in", diameter="0.5 in")
    return {
        "beam": si.run(si.load(path), figures=False),
        "impact": si.impact(beam, at="3 in", impactor=ball, time_step="1 us", duration="150 us", gauges={"g1": "2 in"}),
        "bar": si.impact(bar, impactor=si.Sphere("steel", "0.625 in", velocity="62.1 in/s"), time_step="0.5 us", duration="200 us", gauges={"g1": "12 in"}),
    }


@pytest.mark.parametrize("kind", ["beam", "impact", "bar"])
def test_a_results_arrays_are_read_only_and_its_files_unchanged(runs, kind):
    """`f = res.force; f *= 2` raises, as does writing into a strain history or the inner result's time, and history.csv is what it was."""
    res = runs[kind]
    before = res.files(figures=False)["history.csv"]
    f = res.force
    with pytest.raises(ValueError, match="read-only"):
        f *= 2
    with pytest.raises(ValueError, match="read-only"):
        next(iter(res.strain.values()))[0] = 1.0
    with pytest.raises(ValueError, match="read-only"):
        res.result.time[:] = 0.0
    assert res.files(figures=False)["history.csv"] == before


def test_a_records_arrays_are_read_only():
    """si.read_record's time and signal cannot be written into (the Record is frozen, its arrays too)."""
    rec = si.read_record(RUBBER_RECORD)
    with pytest.raises(ValueError, match="read-only"):
        rec.signal *= 2
    with pytest.raises(ValueError, match="read-only"):
        rec.time[0] = 0.0


@pytest.mark.parametrize(
    ("command", "function", "table"),
    [
        ("predict", si.predict, PREDICT),
        ("calibrate", si.calibrate, CALIBRATE),
        ("converge", si.converge, CONVERGE),
        ("reduce", si.reduce, SERIES),
        ("fit", si.fit, SERIES),
        ("identify", si.identify, IDENTIFY),
        ("sweep", si.sweep, SWEEP),
    ],
)
def test_the_api_and_the_command_line_show_the_same_options_and_defaults(command, function, table):
    """`softimpact COMMAND --help` and si.COMMAND list the same options with the same defaults, the table's (out and the figure format are the command line's own)."""
    cli = {p.name: p.default for p in main.commands[command].params if p.name not in ("out", "accept_poor") and not p.opts[0].startswith("--figure-format")}
    cli = {k: v for k, v in cli.items() if k not in ("case", "series", "spec")}
    api = {
        p.name: (None if p.default is inspect.Parameter.empty else p.default)
        for p in inspect.signature(function).parameters.values()
        if p.name not in ("case", "series", "spec", "out")  # sweep's out: the API's checkpoints folder, the command line's --out
    }
    assert api == cli
    assert api == {o.name: o.default for o in table}
    assert all(o.help.split()[0] in function.__doc__ for o in table)  # each option's help is in the Parameters


def test_the_app_predict_takes_every_option_of_the_table_and_no_default_of_its_own():
    """app.predict's keywords are the table's names (plus progress), none with a default: the defaults live in the table alone."""
    from softimpact.app.predict import predict

    params = inspect.signature(predict).parameters
    assert [n for n in params if n != "progress"] == [o.name for o in PREDICT]
    assert all(p.default is inspect.Parameter.empty for n, p in params.items() if n != "progress")


def _never_called(*args, **kwargs):
    raise AssertionError("the command ran: the refusal came after the compute")


@pytest.mark.parametrize(
    ("keywords", "named"),
    [
        ({"projectile": "rubber-1/2in", "velocity": "1166 in/s", "units": "imperial"}, "units"),
        ({"projectile": "rubber-1/2in", "velocity": 1166}, "velocity"),
        ({"projectile": "rubber-1/2in", "velocity": "1166 in/s", "model": "Hertz"}, "model"),
        ({"projectile": "rubber-1/2in", "velocity": "1166 in/s", "tail": "yes"}, "tail"),
        ({"mass": "1.1 kg/m", "diameter": "0.5 in", "velocity": "1166 in/s"}, "mass"),
    ],
)
def test_predict_refuses_a_bad_keyword_value_before_running_naming_it(monkeypatch, keywords, named):
    """A bad units=, a velocity without its unit, an unknown model, a non-bool tail or a mass in the wrong unit: InputError naming the keyword, the command never called."""
    monkeypatch.setattr("softimpact.app.predict.predict", _never_called)
    with pytest.raises(InputError) as info:
        si.predict(**keywords)
    assert str(info.value).startswith(f"{named}:"), str(info.value)
    assert "--" not in str(info.value)


def test_an_unknown_keyword_is_pythons_type_error(monkeypatch):
    """si.predict(unit=...) (a misspelt keyword) is a TypeError, as Python gives any function, and an InputError that
    names the keyword and suggests the one meant (issue 43), before anything runs."""
    monkeypatch.setattr("softimpact.app.predict.predict", _never_called)
    with pytest.raises(TypeError, match="unit: not a keyword of si.predict \\(did you mean 'units'\\?\\)") as caught:
        si.predict(projectile="rubber-1/2in", velocity="1166 in/s", unit="SI")
    assert isinstance(caught.value, InputError)
    with pytest.raises(TypeError, match="missing required keyword-only argument: 'velocity'"):
        si.predict(projectile="rubber-1/2in")


@pytest.mark.parametrize(
    ("call", "words", "flags"),
    [
        (lambda: si.predict(velocity="1166 in/s"), "projectile or both mass and diameter", "--mass"),
        (lambda: si.calibrate("paper-long-beam", velocity="1166 in/s", figures=False), "measured and velocity are required", "--measured"),
        (lambda: si.converge("plate-ss-8in", figures=False), "levels", "--levels"),
    ],
)
def test_errors_from_below_name_the_keywords_not_the_flags(call, words, flags):
    """An app error written for the command line (--mass, --measured, --levels, --ignore-limits) reaches the API in its keywords' words."""
    with pytest.raises(InputError) as info:
        call()
    text = str(info.value)
    assert words in text, text
    assert flags not in text and "--ignore-limits" not in text, text


def test_the_resource_guards_advice_is_the_environment_variable(monkeypatch):
    """A problem refused by the resource guard says to set SOFTIMPACT_IGNORE_LIMITS=1 (the API has no --ignore-limits), and keeps its class."""
    from softimpact.errors import TooLarge

    monkeypatch.delenv("SOFTIMPACT_IGNORE_LIMITS", raising=False)
    beam = si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(4000, 200))
    with pytest.raises(TooLarge) as info:
        si.impact(beam, at="3 in", impactor=si.Sphere("steel", "0.5 in", velocity="100 in/s"), time_step="0.01 us", duration="4000 us")
    assert "SOFTIMPACT_IGNORE_LIMITS=1" in str(info.value) and "--ignore-limits" not in str(info.value), str(info.value)


def test_load_and_run_take_the_display_system_over_the_cases_own():
    """si.load and si.run show the case's units by default and units= when given (the numbers the same); a bad one is an InputError naming units."""
    own = si.load("paper-calibration")
    assert own.units == "in-lbf-s" and si.load("paper-calibration", units="SI").units == "SI"
    res, shown = si.run(own), si.run(own, units="SI")
    assert (res.units, shown.units) == ("in-lbf-s", "SI") and shown.peak_force == res.peak_force
    for call in (lambda: si.load("paper-calibration", units="imperial"), lambda: si.run(own, units="imperial")):
        with pytest.raises(InputError, match="^units: 'imperial'"):
            call()


def test_sweep_and_the_command_line_default_to_the_machines_cores():
    """si.sweep's workers default is None (the machine's cores, as `softimpact sweep`'s), not a plain loop; 0 must be asked for."""
    assert inspect.signature(si.sweep).parameters["workers"].default is None
    (workers,) = [p for p in main.commands["sweep"].params if p.name == "workers"]
    assert workers.default is None and "machine's cores" in workers.help and "machine's cores" in si.sweep.__doc__
