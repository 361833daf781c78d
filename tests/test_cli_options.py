"""The command line's shared options come from one factory, and the app commands take keyword-only options."""

import inspect

import pytest

from softimpact.cli import main

DRAWING = ["bar", "beam", "converge", "sweep", "plate", "reduce", "fit", "predict", "calibrate", "impact", "identify", "paper"]
GATED = {"reduce", "fit", "calibrate", "identify"}  # the fits whose quality gates can fail (exit 3)
HISTORY = {"beam", "converge", "plate"}  # the cases with a [[load.table]]


def _options(name):
    return {p.name: p for p in main.commands[name].params}


@pytest.mark.parametrize("name", DRAWING)
def test_shared_options(name):
    """Every drawing command has --out (default softimpact-NAME) and --figures/--no-figures (default on); --accept-poor only on the fits; --history only on the tabulated cases."""
    opts = _options(name)
    assert opts["out"].default == f"softimpact-{name}" and opts["out"].opts == ["--out"]
    assert opts["figures"].default is True and opts["figures"].opts == ["--figures"] and opts["figures"].secondary_opts == ["--no-figures"]
    assert ("accept_poor" in opts) == (name in GATED)
    assert ("history" in opts) == (name in HISTORY)
    if name in HISTORY:
        assert opts["history"].default is None and "[[load.table]]" in opts["history"].help


@pytest.mark.parametrize(
    ("module", "function"),
    [
        ("bar", "bar"),
        ("beam", "beam"),
        ("plate", "plate"),
        ("series", "reduce"),
        ("series", "fit"),
        ("predict", "predict"),
        ("calibrate", "calibrate_command"),
        ("identify", "identify"),
        ("paper", "paper"),
    ],
)
def test_app_commands_take_keyword_only_options(module, function):
    """An app command cannot be called with positional options (a reordered signature cannot silently swap two of them), and takes progress."""
    import importlib

    fn = getattr(importlib.import_module(f"softimpact.app.{module}"), function)
    params = inspect.signature(fn).parameters.values()
    assert all(p.kind is inspect.Parameter.KEYWORD_ONLY for p in params)
    assert "progress" in inspect.signature(fn).parameters
