"""`import softimpact` stays cheap: the top-level namespace is lazy (PEP 562)."""

import subprocess
import sys

import pytest

HEAVY = ("numpy", "scipy", "skfem", "pint", "matplotlib", "pandas", "meshio", "click")


def _run(code: str, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, *args, "-c", code], capture_output=True, text=True, check=True)


def test_importtime_lists_no_heavy_module():
    """`python -X importtime -c "import softimpact"` imports none of numpy, scipy, skfem, pint, matplotlib (nor pandas, meshio, click)."""
    report = _run("import softimpact", "-X", "importtime").stderr
    imported = {line.split("|")[-1].strip().split(".")[0] for line in report.splitlines() if line.startswith("import time:") and "|" in line}
    assert "softimpact" in imported
    assert not imported & set(HEAVY), sorted(imported & set(HEAVY))


def test_sys_modules_after_import_has_no_heavy_module():
    """After `import softimpact`, sys.modules holds no heavy module, and dir() still lists the lazy names."""
    code = "import sys, softimpact as si; print(sorted({m.split('.')[0] for m in sys.modules})); print('Beam' in dir(si), 'impact' in si.__all__)"
    out = _run(code).stdout.splitlines()
    loaded = set(eval(out[0]))  # a list literal printed by the child
    assert not loaded & set(HEAVY), sorted(loaded & set(HEAVY))
    assert out[1] == "True True"


def test_importing_the_api_package_itself_stays_light():
    """`import softimpact.api` (the package, its submodules and the options table) imports none of the heavy modules either: they load inside the calls."""
    out = _run("import sys, softimpact.api; print(sorted({m.split('.')[0] for m in sys.modules}))").stdout
    loaded = set(eval(out))  # a list literal printed by the child
    assert not loaded & set(HEAVY), sorted(loaded & set(HEAVY))


@pytest.mark.parametrize("name", ["Beam", "impact", "load", "run"])
def test_lazy_name_resolves_to_the_api_object(name):
    """A lazy name is the api module's object itself, cached in the package after first use."""
    import softimpact
    from softimpact import api

    assert getattr(softimpact, name) is getattr(api, name)
    assert name in vars(softimpact)


def test_unknown_name_is_an_attribute_error():
    """A name that is not public raises AttributeError naming it (what hasattr and tab completion rely on)."""
    import softimpact

    with pytest.raises(AttributeError, match="no_such_thing"):
        softimpact.no_such_thing  # noqa: B018
