"""`softimpact bar` with the coupled-impact contact laws (hertz-unloading, hunt-crossley, identified)."""

import json
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact.cli import main

CASE = (Path(__file__).parents[1] / "src/softimpact/data/cases/paper-calibration.toml").read_text()


def _bar(tmp_path, contact: str, name: str):
    case = tmp_path / f"{name}.toml"
    case.write_text(CASE.replace('[contact]\nlaw = "hertz"', "[contact]\n" + contact))
    out = tmp_path / name
    r = CliRunner().invoke(main, ["bar", str(case), "--out", str(out), "--no-figures"])
    return r, out


def _history(out):
    lines = (out / "history.csv").read_text().splitlines()
    return lines[0].split(","), np.array([[float(v) for v in ln.split(",")] for ln in lines[1:]])


@pytest.fixture(scope="module")
def hertz_run(tmp_path_factory):
    r, out = _bar(tmp_path_factory.mktemp("bar"), 'law = "hertz"', "hertz")
    assert r.exit_code == 0, r.output
    return json.loads((out / "summary.json").read_text()), _history(out)


def test_hunt_crossley_without_loss_is_the_hertz_bar_run(tmp_path, hertz_run):
    """Hunt–Crossley with e = 1 (no damping) through the general coupled stepping reproduces the bar's own
    Hertz integration (impulse-response convolution): force, gauge strain and pulse figures to 1e-6."""
    r, out = _bar(tmp_path, 'law = "hunt-crossley"\nrestitution = 1.0', "hc1")
    assert r.exit_code == 0, r.output
    s, (names, data) = json.loads((out / "summary.json").read_text()), _history(out)
    ref, (rnames, rdata) = hertz_run
    assert names == rnames
    for k in ("peak_force_N", "time_of_peak_s", "contact_duration_s", "impulse_N_s", "rebound_velocity_m_s"):
        assert s[k] == pytest.approx(ref[k], rel=1e-6)
    for col in ("contact_force_N", "strain_midpoint", "impactor_velocity_m_s"):
        a, b = data[:, names.index(col)], rdata[:, rnames.index(col)]
        assert np.max(np.abs(a - b)) <= 1e-6 * np.max(np.abs(b))


@pytest.mark.parametrize("contact", ['law = "hunt-crossley"\nrestitution = 0.5', 'law = "hertz-unloading"\ncritical_indentation = "0.002 mm"'])
def test_lossy_laws_on_the_bar(tmp_path, hertz_run, contact):
    """A lossy law gives a smaller rebound than Hertz, and the impulse is still the impactor's momentum change."""
    r, out = _bar(tmp_path, contact, "lossy")
    assert r.exit_code == 0, r.output
    s = json.loads((out / "summary.json").read_text())
    names, data = _history(out)
    v = data[:, names.index("impactor_velocity_m_s")]
    F, t = data[:, names.index("contact_force_N")], data[:, names.index("time_s")]
    m = s["projectile_mass_kg"]
    assert np.sum(0.5 * (F[1:] + F[:-1])) * (t[1] - t[0]) == pytest.approx(m * (v[0] - v[-1]), rel=1e-10)
    assert abs(s["rebound_velocity_m_s"]) < 0.95 * abs(hertz_run[0]["rebound_velocity_m_s"])


def test_identified_law_on_the_bar(tmp_path):
    """A bar case with law = "identified" reads its law.json (relative to the case) and runs."""
    from softimpact.formats.law_json import law_json
    from softimpact.workflows.identification import IdentifiedLaw

    law = IdentifiedLaw(("k_ref", "p", "c_ref", "q_k", "q_c"), np.array([2.0, 1.0, 1.0, 0.0, 0.0]), np.zeros(5), 0.0159, np.zeros(1), 0.0)
    (tmp_path / "law.json").write_text(law_json(law, ["t"]))
    r, out = _bar(tmp_path, 'law = "identified"\nlaw_file = "law.json"', "ident")
    assert r.exit_code == 0, r.output
    assert json.loads((out / "summary.json").read_text())["case_SI"]["law"]["k"] == pytest.approx(2.0)


def test_bar_law_file_that_is_not_a_law(tmp_path):
    """A law_file that is not a law.json: one line, exit 2, nothing written."""
    (tmp_path / "law.json").write_text("[1, 2]")
    r, out = _bar(tmp_path, 'law = "identified"\nlaw_file = "law.json"', "bad")
    assert r.exit_code == 2 and "contact.law_file" in r.output and not out.exists()
