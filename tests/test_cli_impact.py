"""`softimpact impact`: the file contract, bad input, and agreement with an independent implementation."""

import csv
import json
import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact.cli import main
from softimpact.models.contact_laws import HertzLaw
from softimpact.models.materials import lookup

from _support.constants import INCH
from _support.coupled import independent_explicit, long_beam_model

STEEL = lookup("steel")
E2 = 7.9e9  # T300/934 transverse modulus (NOTES.md)


def _case(tmp_path, name="case.toml", *, diameter="0.5 in", velocity="100 in/s", law='law = "hertz"\ntarget_modulus = "7.9 GPa"', duration="300 us", extra=""):
    text = f"""title = "test"
units = "in-lbf-s"
[target]
case = "paper-long-beam"
[impactor]
material = "steel"
diameter = "{diameter}"
velocity = "{velocity}"
[contact]
{law}
[solver]
time_step = "0.5 us"
duration = "{duration}"
{extra}"""
    path = tmp_path / name
    path.write_text(text)
    return path


def _run(*args):
    return CliRunner().invoke(main, list(map(str, args)))


def _history(path):
    with open(path) as fh:
        rows = list(csv.reader(fh))
    return rows[0], np.array(rows[1:], float)


@pytest.fixture(scope="module")
def builtin_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("impact") / "out"
    r = _run("impact", "paper-long-beam-impact", "--out", out, "--no-figures")
    assert r.exit_code == 0, r.output
    names, data = _history(out / "history.csv")
    return out, names, data, json.loads((out / "summary.json").read_text())


def test_history_columns_follow_the_contract(builtin_run):
    """history.csv has the contract's columns in SI, from t = 0 at the case's time step."""
    _, names, data, _ = builtin_run
    for col in ("time_s", "contact_force_N", "impactor_velocity_m_s", "impactor_displacement_m", "approach_m", "contact_radius_m", "strain_g1", "strain_g2"):
        assert col in names
    assert any(n.endswith("_J") for n in names)
    t = data[:, names.index("time_s")]
    assert t[0] == 0.0 and np.allclose(np.diff(t), 0.5e-6)
    assert t[-1] == pytest.approx(1000e-6)
    assert data[0, names.index("impactor_velocity_m_s")] == pytest.approx(100 * INCH)


def test_summary_impulse_is_momentum_change(builtin_run):
    """The total impulse of the force column equals m·(V − v_end) (momentum, exactly); the first
    contact's impulse is the integral of the force up to the first separation."""
    _, names, data, s = builtin_run
    t, F, v = (data[:, names.index(k)] for k in ("time_s", "contact_force_N", "impactor_velocity_m_s"))
    m = s["impactor_mass_kg"]
    assert m == pytest.approx(STEEL.density * math.pi / 6 * (0.5 * INCH) ** 3, rel=1e-12)
    total = float(np.sum(0.5 * (F[1:] + F[:-1])) * (t[1] - t[0]))
    assert total == pytest.approx(m * (v[0] - v[-1]), rel=1e-10)
    assert s["total_impulse_N_s"] == pytest.approx(total, rel=1e-12)
    k_end = int(np.flatnonzero((F[1:] == 0) & (t[1:] > 0))[0]) + 1
    first = float(np.sum(0.5 * (F[1 : k_end + 1] + F[:k_end])) * (t[1] - t[0]))
    assert s["impulse_N_s"] == pytest.approx(first, rel=1e-9)
    assert s["contacts"][0]["impulse_N_s"] == pytest.approx(s["impulse_N_s"])
    assert s["number_of_contacts"] == len(s["contacts"]) >= 2


def test_summary_first_contact_and_energy(builtin_run):
    """First-contact figures are those of the force column; the energy columns balance the impactor's
    initial kinetic energy to round-off once the top/mid-surface work difference is counted."""
    _, names, data, s = builtin_run
    F = data[:, names.index("contact_force_N")]
    assert s["peak_force_N"] == pytest.approx(F[: int(s["contact_duration_s"] / 0.5e-6)].max(), rel=2e-3)
    KE0 = 0.5 * s["impactor_mass_kg"] * (100 * INCH) ** 2
    e = sum(data[:, names.index(k)] for k in ("impactor_kinetic_energy_J", "structure_kinetic_energy_J", "structure_strain_energy_J", "contact_work_J"))
    assert np.max(np.abs(e - data[:, names.index("surface_mismatch_J")] - KE0)) < 1e-8 * KE0
    assert s["case_SI"]["impactor"]["velocity"] == pytest.approx(100 * INCH)
    assert s["case_SI"]["law"]["K"] == pytest.approx(HertzLaw.sphere_on_laminate(0.25 * INCH, STEEL, E2).K)
    assert set(s["gauges"]) == {"g1", "g2"}


def test_figures_are_drawn(tmp_path):
    """With figures: force history, approach, gauge strains and energies as PNG."""
    out = tmp_path / "out"
    r = _run("impact", _case(tmp_path, duration="60 us"), "--out", out)
    assert r.exit_code == 0, r.output
    for name in ("force-history.png", "approach.png", "gauge-strains.png", "energy.png"):
        assert (out / name).read_bytes()[:4] == b"\x89PNG"


@pytest.mark.parametrize(
    "law",
    ['law = "hertz-unloading"\ncritical_indentation = "0.01 mm"', 'law = "hunt-crossley"\nrestitution = 0.8'],
)
def test_dissipative_laws_lose_energy_and_keep_momentum(tmp_path, law):
    """Yang–Sun unloading and Hunt–Crossley damping lose contact energy; momentum still balances."""
    out = tmp_path / "out"
    r = _run("impact", _case(tmp_path, law=law, duration="150 us"), "--out", out, "--no-figures")
    assert r.exit_code == 0, r.output
    names, data = _history(out / "history.csv")
    t, F, v = (data[:, names.index(k)] for k in ("time_s", "contact_force_N", "impactor_velocity_m_s"))
    m = json.loads((out / "summary.json").read_text())["impactor_mass_kg"]
    assert float(np.sum(0.5 * (F[1:] + F[:-1])) * (t[1] - t[0])) == pytest.approx(m * (v[0] - v[-1]), rel=1e-10)
    loss = data[-1, names.index("contact_work_J")] - data[-1, names.index("contact_stored_energy_J")]
    assert loss > 1e-3 * 0.5 * m * v[0] ** 2


def test_identified_law_from_law_file(tmp_path):
    """An identified law read from law.json drives the run: the force column is the law's formula of the
    approach and approach-rate columns."""
    from softimpact.formats.law_json import law_json
    from softimpact.workflows.identification import IdentifiedLaw

    law = IdentifiedLaw(("k_ref", "p", "c_ref", "q_k", "q_c"), np.array([2.0, 1.2, 0.5, 0.0, 0.0]), np.zeros(5), 0.5 * INCH, np.zeros(1), 0.0)
    (tmp_path / "law.json").write_text(law_json(law, ["t1"]))
    out = tmp_path / "out"
    case = _case(tmp_path, velocity="1166 in/s", law='law = "identified"\nlaw_file = "law.json"', duration="100 us", diameter="0.5 in", extra="")
    r = _run("impact", case, "--out", out, "--no-figures")
    assert r.exit_code == 0, r.output
    names, data = _history(out / "history.csv")
    s = json.loads((out / "summary.json").read_text())
    m, d, V = s["impactor_mass_kg"], 0.5 * INCH, 1166 * INCH
    a, ad, F = (data[1:40, names.index(k)] for k in ("approach_m", "approach_rate_m_s", "contact_force_N"))
    # the law written out here: F = (m V²/d)·k·(α/d)^p·(1 + c·α̇/V)
    assert np.allclose(F, m * V**2 / d * 2.0 * (a / d) ** 1.2 * (1 + 0.5 * ad / V), rtol=1e-9, atol=0)
    assert s["case_SI"]["law"]["k"] == pytest.approx(2.0) and s["peak_force_N"] > 0


def test_warnings_for_an_unfinished_contact_and_an_extrapolated_law(tmp_path):
    """law.json records the velocities and diameters it was identified on; an impactor well outside
    them runs with a warning that the force is an extrapolation (inside: none); a run that ends before
    the first contact does gets a warning that its duration and rebound are unknown (they are null)."""
    from softimpact.formats.law_json import law_json
    from softimpact.workflows.identification import IdentifiedLaw

    ranges = {"velocity_m_s": [1000 * INCH, 5000 * INCH], "diameter_m": [0.375 * INCH, 0.5 * INCH]}
    law = IdentifiedLaw(("k_ref", "p", "c_ref", "q_k", "q_c"), np.array([2.0, 1.2, 0.5, 0.0, 0.0]), np.zeros(5), 0.5 * INCH, np.zeros(2), 0.0, ranges)
    (tmp_path / "law.json").write_text(law_json(law, ["t1", "t2"]))
    assert json.loads((tmp_path / "law.json").read_text())["identified_on"]["velocity_m_s"] == pytest.approx([1000 * INCH, 5000 * INCH])
    identified = 'law = "identified"\nlaw_file = "law.json"'
    inside = _run("impact", _case(tmp_path, "a.toml", velocity="1166 in/s", law=identified, duration="20 us"), "--out", tmp_path / "a", "--no-figures")
    assert inside.exit_code == 0 and "extrapolation" not in inside.output
    assert "has not ended" in inside.output and json.loads((tmp_path / "a" / "summary.json").read_text())["contact_duration_s"] is None
    slow = _run("impact", _case(tmp_path, "b.toml", velocity="100 in/s", law=identified, duration="20 us"), "--out", tmp_path / "b", "--no-figures")
    assert slow.exit_code == 0 and "velocity" in slow.output and "extrapolation" in slow.output


# --- bad input: one line, exit 2, nothing written ---------------------------------------------------


def _bad(tmp_path, case, needle):
    out = tmp_path / "out"
    r = _run("impact", case, "--out", out)
    assert r.exit_code == 2, r.output
    lines = r.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("softimpact: error:") and needle in lines[0]
    assert not out.exists()


def test_law_file_that_is_not_a_law(tmp_path):
    """A law_file holding some other JSON is refused, naming the key."""
    (tmp_path / "law.json").write_text('{"groups": {}, "pooled": {}}')
    _bad(tmp_path, _case(tmp_path, law='law = "identified"\nlaw_file = "law.json"'), "contact.law_file")


def test_impact_point_off_the_structure(tmp_path):
    """A target whose impact point lies beyond the beam is refused, naming the target's key."""
    text = (Path(__file__).parents[1] / "src/softimpact/data/cases/paper-long-beam.toml").read_text().replace('position = "3.0 in"', 'position = "7.0 in"')
    (tmp_path / "beam.toml").write_text(text)
    case = _case(tmp_path).read_text().replace('case = "paper-long-beam"', 'case = "beam.toml"')
    (tmp_path / "case.toml").write_text(case)
    _bad(tmp_path, tmp_path / "case.toml", "load.position")


def test_negative_velocity(tmp_path):
    """A velocity away from the target is refused."""
    _bad(tmp_path, _case(tmp_path, velocity="-100 in/s"), "impactor.velocity")


def test_unknown_law(tmp_path):
    """An unknown contact law is refused with the list of known ones."""
    _bad(tmp_path, _case(tmp_path, law='law = "plastic"'), "hunt-crossley")


# --- the Done-when: the command against an independent implementation ----------------------------


CASES = [(0.5, 100.0), (0.5, 400.0), (0.625, 62.1)]


@pytest.fixture(scope="module")
def long_beam():
    return long_beam_model(duration=400e-6)


@pytest.mark.slow
@pytest.mark.parametrize("case", CASES)
def test_command_agrees_with_independent_explicit_solution(tmp_path, long_beam, case):
    """`softimpact impact` on the long beam (Hertz, 7.9 GPa, 200 × 6, 0.5 µs): peak force, time of peak,
    contact duration, impulse and gauge-strain peaks within 1 % of an independent explicit
    central-difference integration of the same formulation (tests/_support/coupled.py)."""
    d_in, v_in = case
    out = tmp_path / "out"
    r = _run("impact", _case(tmp_path, diameter=f"{d_in} in", velocity=f"{v_in} in/s", duration="400 us"), "--out", out, "--no-figures")
    assert r.exit_code == 0, r.output
    s = json.loads((out / "summary.json").read_text())
    d = d_in * INCH
    m = STEEL.density * math.pi / 6 * d**3
    law = HertzLaw.sphere_on_laminate(d / 2, STEEL, E2)
    t, F, eps, k_end, dt = independent_explicit(long_beam, d, m, v_in * INCH, law.K, 400e-6)
    first = slice(0, k_end)
    imp = np.sum(0.5 * (F[1 : k_end + 1] + F[:k_end])) * dt
    assert s["peak_force_N"] == pytest.approx(F[first].max(), rel=0.01)
    assert s["time_of_peak_s"] == pytest.approx(t[first][np.argmax(F[first])], rel=0.01)
    assert s["contact_duration_s"] == pytest.approx(t[k_end - 1] + 0.5 * dt, rel=0.01)  # dt ≈ 25 ns
    assert s["impulse_N_s"] == pytest.approx(imp, rel=0.01)
    for j, g in enumerate(("g1", "g2")):
        assert s["gauges"][g]["peak_abs_strain"] == pytest.approx(np.max(np.abs(eps[j])), rel=0.01)
