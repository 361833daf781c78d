"""`softimpact calibrate-bar` on the built-in synthetic records: the hidden bar recovered, its bar file read by series
and bar cases, and a reduce with the calibrated bar equal to one with the true bar."""

import json
import math
import tomllib

import numpy as np
import pytest
from click.testing import CliRunner

from softimpact.app.calibrate_bar import calibrate_bar
from softimpact.cli import main
from softimpact.input.series import load_series

# The truth of the built-in `lab-bar-calibration` (tools/make_lab_bar_records.py): E = 204 GPa, density 7850 kg/m^3
# (c0 = sqrt(E/rho)), nu = 0.29, the gauge at 0.5 m, its true gauge factor 2.11 (the file's nominal: 2.00).
TRUE_E, RHO, TRUE_NU, TRUE_GF, GAUGE = 204.0e9, 7850.0, 0.29, 2.11, 0.5


@pytest.fixture(scope="module")
def outcome():
    """The calibration of the built-in records, once for the module."""
    return calibrate_bar(calibration="lab-bar-calibration", figures=False)


@pytest.fixture(scope="module")
def constants(outcome):
    return json.loads(outcome.files["calibration.json"])["constants"]


@pytest.mark.parametrize(
    ("key", "truth"),
    [
        ("wave_speed_m_s", math.sqrt(TRUE_E / RHO)),
        ("poisson_ratio", TRUE_NU),
        ("gauge_position_m", GAUGE),
        ("gauge_factor", TRUE_GF),
        ("youngs_modulus_Pa", TRUE_E),
    ],
)
def test_builtin_calibration_recovers_the_hidden_bar(constants, key, truth):
    """Each constant of calibration.json holds the generator's hidden value within its 95 % interval."""
    c = constants[key]
    assert abs(c["value"] - truth) <= c["ci95_half_width"]


def test_bar_file_carries_the_calibrated_constants(outcome, constants):
    """bar.toml's material has E = ρc0² of the calibrated c0 and the calibrated ν; its gauge the calibrated factor and position."""
    bar = tomllib.loads(outcome.files["bar.toml"])
    assert all(g.passed for g in outcome.gates)
    from softimpact import units

    E = units.parse(bar["bar"]["material"]["youngs_modulus"], "stress", "E")
    assert E == pytest.approx(RHO * constants["wave_speed_m_s"]["value"] ** 2, rel=1e-12)
    assert bar["bar"]["material"]["poisson_ratio"] == pytest.approx(constants["poisson_ratio"]["value"], rel=1e-12)
    assert bar["gauge"]["gauge_factor"] == pytest.approx(constants["gauge_factor"]["value"], rel=1e-12)


def _series(tmp_path, bar_lines, gauge_lines, record="r.csv"):
    (tmp_path / "s.toml").write_text(
        "\n".join(
            [
                'units = "SI"',
                "[bar]",
                *bar_lines,
                "[gauge]",
                *gauge_lines,
                "[[test]]",
                f'record = "{record}"',
                'velocity = "10 m/s"',
                'diameter = "12.7 mm"',
                'mass = "1.1 g"',
            ]
        )
        + "\n"
    )
    return tmp_path / "s.toml"


def test_series_reads_the_bar_file_and_its_own_keys_win(tmp_path, outcome):
    """A series naming the bar file gets its material, length and gauge factor; a key written beside `file` (elements) replaces the file's."""
    (tmp_path / "bar.toml").write_text(outcome.files["bar.toml"])
    (tmp_path / "r.csv").write_text("time_s,voltage_V\n" + "".join(f"{k * 1e-6},{0.0}\n" for k in range(80)))
    series = load_series(str(_series(tmp_path, ['file = "bar.toml"', "elements = 60"], [])))
    bar = tomllib.loads(outcome.files["bar.toml"])
    assert series.bar.elements == 60 and series.bar.length == pytest.approx(1.0)
    assert series.bridge.gauge_factor == pytest.approx(bar["gauge"]["gauge_factor"], rel=1e-12)
    assert series.gauge_position == pytest.approx(bar["gauge"]["position"] and float(bar["gauge"]["position"].split()[0]), rel=1e-12)
    assert series.bar_file == tmp_path / "bar.toml"


def test_bar_case_reads_the_bar_file(tmp_path, outcome):
    """A bar case's [bar] file = "bar.toml": the FE bar's wave speed is the calibrated c0."""
    from softimpact.fem.bar import Rod
    from softimpact.input.bar_case import load_bar_case

    (tmp_path / "bar.toml").write_text(outcome.files["bar.toml"])
    (tmp_path / "case.toml").write_text(
        '[bar]\nfile = "bar.toml"\nelements = 60\n[projectile]\nmaterial = "steel"\ndiameter = "8 mm"\nvelocity = "3 m/s"\n'
        '[solver]\ntime_step = "0.2 us"\nduration = "100 us"\n[[gauges]]\nname = "g"\nposition = "0.5 m"\n'
    )
    problem, _ = load_bar_case(str(tmp_path / "case.toml"))
    c = json.loads(outcome.files["calibration.json"])["constants"]["wave_speed_m_s"]["value"]
    assert Rod.of(problem.bar).wave_speed == pytest.approx(c, rel=1e-12)


def test_missing_record_is_bad_input(tmp_path):
    """A calibration file whose record is missing: exit 2, one line naming the file, nothing written."""
    (tmp_path / "c.toml").write_text(
        '[bar]\nmaterial = "steel"\nlength = "1 m"\ndiameter = "20 mm"\n[gauge]\nposition = "0.5 m"\n[[shot]]\nrecord = "nope.csv"\n'
    )
    run = CliRunner().invoke(main, ["calibrate-bar", str(tmp_path / "c.toml"), "--out", str(tmp_path / "out")])
    assert run.exit_code == 2 and "nope.csv" in run.output
    assert not (tmp_path / "out" / "bar.toml").exists()


@pytest.mark.slow  # the hidden bar's FE response and two reductions: a few seconds
def test_reduce_with_the_calibrated_bar_equals_reduce_with_the_true_bar(tmp_path, outcome):
    """A projectile's record on the hidden bar (its FE, the true bridge): reduce with the calibrated bar file gives F0 within
    0.5 % of F0 reduced with the true bar (E, ν, gauge factor known), and within the calibration's own interval on ρc0²/GF."""
    from softimpact.input.series_records import read_series_records
    from softimpact.models.bridge import Bridge
    from softimpact.models.materials import Material
    from softimpact.models.pulses import SkewedPulse
    from softimpact.models.specimens import BarSpec
    from softimpact.studies.series import reduce_series
    from softimpact.workflows.synthetic import gauge_model, synthetic_record
    from softimpact.workflows.synthetic_bars import strain_to_volts

    hidden = Material("hidden steel", TRUE_E, TRUE_NU, RHO)
    gm = gauge_model(BarSpec(hidden, 1.0, 0.020, 200), GAUGE, 0.2e-6, 900e-6)
    t, eps = synthetic_record(
        gm,
        SkewedPulse(800.0, 25e-6, 80e-6),
        pre_trigger=100e-6,
        length=800e-6,
        sample_interval=0.4e-6,
        noise=0.005,
        offset=0.0,
        clock_start=0.0,
        rng=np.random.default_rng(5),
    )
    volts = strain_to_volts(eps, Bridge("quarter", TRUE_GF, 5.0, 500.0, polarity=-1))
    (tmp_path / "r.csv").write_text("time_s,voltage_V\n" + "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(t, volts)))
    (tmp_path / "bar.toml").write_text(outcome.files["bar.toml"])
    gauge = ['bridge = "quarter"', 'excitation = "5 V"', "gain = 500"]
    true_bar = [
        'material = { youngs_modulus = "204 GPa", poisson_ratio = 0.29, density = "7850 kg/m^3" }',
        'length = "1 m"',
        'diameter = "20 mm"',
        "elements = 200",
    ]
    peaks = {}
    for label, bar_lines, gauge_lines in (
        ("true", true_bar, ['position = "0.5 m"', f"gauge_factor = {TRUE_GF}", *gauge]),
        ("calibrated", ['file = "bar.toml"', "elements = 200"], []),
    ):
        folder = tmp_path / label
        folder.mkdir()
        (folder / "r.csv").write_text((tmp_path / "r.csv").read_text())
        (folder / "bar.toml").write_text((tmp_path / "bar.toml").read_text())
        series = load_series(str(_series(folder, bar_lines, gauge_lines)))
        (reduced,) = reduce_series(series, *read_series_records(series))
        peaks[label] = reduced.reduction.peak_force
    c = json.loads(outcome.files["calibration.json"])["constants"]
    scale_half = math.hypot(
        2 * c["wave_speed_m_s"]["ci95_half_width"] / c["wave_speed_m_s"]["value"], c["gauge_factor"]["ci95_half_width"] / c["gauge_factor"]["value"]
    )
    diff = abs(peaks["calibrated"] / peaks["true"] - 1)
    print(f"F0 calibrated/true - 1 = {diff:.2e}; the calibration's 95 % half-width on rho c0^2/GF {scale_half:.2e}")
    assert diff < 0.005 and diff <= scale_half
