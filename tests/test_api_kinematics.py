"""Large deflection reaches the Python API: ``si.Plate(kinematics=, in_plane=)`` and ``si.Beam(kinematics=)`` run the
same von Kármán models as a case file's ``[plate]``/``[beam] kinematics`` keys."""

import warnings

import pytest

import softimpact as si
from softimpact.errors import InputError

from _support import small_cases

PLATE = """title = "API twin, large deflection"
units = "SI"
[plate]
length = "8 in"
width = "8 in"
elements = [6, 6]
support = {{ x0 = "simply-supported", x1 = "simply-supported", y0 = "simply-supported", y1 = "simply-supported" }}
kinematics = "von-karman"
in_plane = "{in_plane}"
[plate.laminate]
ply = "T300/934"
layup = "[90/0]5s"
[load]
position = ["4 in", "4 in"]
contact_radius = "0.5 in"
history = {{ shape = "skewed", peak_force = "100 lbf", time_of_peak = "20 us", duration = "250 us" }}
[solver]
time_step = "2 us"
duration = "300 us"
"""

IMPACT = """title = "API twin, large deflection"
units = "SI"
[target]
case = "{target}"
[impactor]
material = "steel"
diameter = "{diameter}"
velocity = "{velocity}"
[contact]
law = "hertz"
[solver]
time_step = "{time_step}"
duration = "{duration}"
"""


def _api(kinematics, in_plane="immovable"):
    plate = si.Plate(length="8 in", width="8 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(6, 6), kinematics=kinematics, in_plane=in_plane)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # w/h and the plies' allowables are past their limits at 20 m/s: the point here
        return si.impact(plate, at=("4 in", "4 in"), impactor=si.Sphere("steel", "1 in", velocity="20 m/s"), time_step="2 us", duration="300 us", units="SI")


@pytest.mark.slow
def test_api_plate_kinematics_equal_the_case_file(tmp_path):
    """A von Kármán plate with movable edges built in Python gives the peak force, time of peak and impulse of the same plate read from case files."""
    in_plane = "movable"  # not the default, so both keys must reach the model
    (tmp_path / "plate.toml").write_text(PLATE.format(in_plane=in_plane))
    (tmp_path / "impact.toml").write_text(IMPACT.format(target="plate.toml", diameter="1 in", velocity="20 m/s", time_step="2 us", duration="300 us"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        file = si.run(si.load(tmp_path / "impact.toml"), figures=False)
    ours = _api("von-karman", in_plane)
    assert ours.summary()["target"]["kinematics"] == "von-karman"
    for name in ("peak_force", "time_of_peak", "impulse"):
        assert getattr(ours, name) == pytest.approx(getattr(file, name), rel=1e-12)


def test_membrane_stiffening_raises_the_api_plates_peak_force():
    """At 20 m/s the 1-in ball drives the 5-mm plate past w/h = 1: membrane stretching stiffens it, so the von Kármán peak force exceeds the linear one."""
    linear, vk = _api("linear"), _api("von-karman")
    assert linear.summary()["target"]["kinematics"] == "linear"
    assert vk.peak_force > 1.05 * linear.peak_force


@pytest.mark.parametrize("kwargs", [{"kinematics": "nonlinear"}, {"in_plane": "free"}, {"support": "free"}])
def test_bad_plate_options_name_the_argument(kwargs):
    """An unknown kinematics or in-plane restraint, or edges that leave the plate a mechanism, are InputErrors naming the argument."""
    with pytest.raises(InputError, match=next(iter(kwargs))):
        si.Plate(length="8 in", width="8 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(6, 6), **kwargs)


def test_unknown_beam_kinematics_names_the_argument():
    """An unknown beam kinematics is an InputError naming the argument."""
    with pytest.raises(InputError, match="kinematics"):
        si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), kinematics="nonlinear")


BEAM = small_cases.BEAM.replace("[beam]\n", '[beam]\nkinematics = "von-karman"\n')  # 40 × 4, clamped-free, smeared


def test_api_beam_kinematics_equal_the_case_file(tmp_path):
    """``si.Beam(kinematics="von-karman")`` gives the peak force and impulse of the same beam read from case files, and its run says its kinematics."""
    beam = si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(40, 4), kinematics="von-karman")
    assert beam.kinematics == "von-karman"
    sphere = si.Sphere("steel", "0.5 in", velocity="100 in/s")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ours = si.impact(beam, at="3 in", impactor=sphere, time_step="1 us", duration="100 us", units="SI")
        (tmp_path / "beam.toml").write_text(BEAM)
        (tmp_path / "impact.toml").write_text(IMPACT.format(target="beam.toml", diameter="0.5 in", velocity="100 in/s", time_step="1 us", duration="100 us"))
        file = si.run(si.load(tmp_path / "impact.toml"), figures=False)
    assert ours.summary()["target"]["kinematics"] == "von-karman"
    for name in ("peak_force", "time_of_peak", "impulse"):
        assert getattr(ours, name) == pytest.approx(getattr(file, name), rel=1e-12)


@pytest.mark.slow
def test_press_equals_the_static_case_and_levys_point():
    """``si.press`` on the built-in static case's plate gives its summary's deflection (to 1e-12), and at Levy's load P = 278.5 the simply supported immovable plate's w_c/h = 1.83 (NACA TN 846, ν = 0.316; tests/test_plate_levy.py) within 2 % plus its ±0.01 reading."""
    from softimpact.models.laminate import Ply

    case = si.run(si.load("plate-ss-pressure-vk"), figures=False)
    ply = case.problem.plate.stack.ply
    plate = si.Plate(length="10 in", width="10 in", laminate=si.Laminate(ply, "[0]"), elements=(6, 6), kinematics="von-karman")
    ours = si.press(plate, pressure="20 psi", load_steps=10)
    assert ours.max_deflection == pytest.approx(case.summary()["max_deflection_m"], rel=1e-12)
    E, G, nu, h = 10e6 * 6894.757, 10e6 * 6894.757 / (2 * 1.316), 0.316, 0.00254  # Pa, m: the case's plate with Levy's nu
    levy = Ply("isotropic, Levy's nu", E, E, E, G, G, G, nu, nu, nu, 2700.0, h)
    plate = si.Plate(length="10 in", width="10 in", laminate=si.Laminate(levy, "[0]"), elements=(6, 6), kinematics="von-karman")
    res = si.press(plate, pressure=f"{278.5 * E * (h / 0.254) ** 4} Pa", load_steps=10)  # P = q a⁴/(E h⁴) = 278.5
    assert res.converged
    assert abs(res.max_deflection / h - 1.83) <= 0.02 * 1.83 + 0.01


@pytest.mark.parametrize(
    "kwargs,name",
    [
        ({"pressure": "2"}, "pressure"),
        ({"pressure": "2 in"}, "pressure"),
        ({"pressure": "-2 psi"}, "pressure"),
        ({"pressure": "2 psi", "load_steps": 0}, "load_steps"),
        ({"pressure": "2 psi", "load_steps": True}, "load_steps"),
        ({"pressure": "2 psi", "load_steps": 2.5}, "load_steps"),
    ],
)
def test_press_refuses_bad_input(kwargs, name):
    """A pressure without its unit, of another dimension or not positive, or a bad load step count, is an InputError naming the argument."""
    plate = si.Plate(length="8 in", width="8 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(4, 4), kinematics="von-karman")
    with pytest.raises(InputError, match=name):
        si.press(plate, **kwargs)


def test_press_refuses_a_beam():
    """``si.press`` takes a plate only: a beam is an InputError naming the argument."""
    beam = si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(20, 2))
    with pytest.raises(InputError, match="plate"):
        si.press(beam, pressure="2 psi")


def test_static_result_frame_plot_and_files(tmp_path):
    """The static result's frame has one row per load step ending at the full pressure and the largest deflection; write() puts its summary.json in the folder."""
    import numpy as np

    plate = si.Plate(length="8 in", width="8 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(4, 4), kinematics="von-karman")
    res = si.press(plate, pressure="20 psi", load_steps=4, units="SI")
    df = res.to_frame()
    assert list(df.index) == [1, 2, 3, 4] and df.attrs["units"]["pressure_Pa"] == "Pa"
    assert df["pressure_Pa"].iloc[-1] == pytest.approx(20 * 6894.757293168, rel=1e-9)
    assert df["max_deflection_m"].iloc[-1] == res.max_deflection
    assert np.all(np.diff(df["max_deflection_m"]) > 0)
    assert res.plot() is not None
    written = res.write(tmp_path / "out", figures=False)
    assert {p.name for p in written} == {"summary.json"}


def test_a_metal_skin_from_python_is_the_case_file_s():
    """si.Plate(material=..., thickness=...) builds the plate a case file's [plate] material/thickness builds (the
    built-in al-skin-2mm: Al 2024-T3, 2 mm), and its refusals name the user's keyword."""
    import softimpact as si
    from softimpact.errors import InputError
    from softimpact.input.plate_case import load_plate_case

    case = load_plate_case("al-skin-2mm")[0]
    skin = si.Plate(
        length="125 mm",
        width="125 mm",
        material="Al 2024-T3",
        thickness="2 mm",
        elements=case.plate.elements,
        support=dict(zip(("x0", "x1", "y0", "y1"), case.plate.supports)),
        kinematics=case.kinematics,
    )
    assert skin.spec == case.plate and skin.plasticity is None
    for bad, named in (
        (dict(material="Al 2024-T3"), "thickness"),
        (dict(material="Al 9999", thickness="2 mm"), "material"),
        (dict(material="Al 2024-T3", thickness="2 mm", plasticity="yes"), "plasticity"),
        (dict(laminate=si.Laminate("T300/934", "[0/90]s"), thickness="2 mm"), "thickness"),
        (dict(laminate=si.Laminate("T300/934", "[0/90]s"), material="Al 2024-T3", thickness="2 mm"), "material"),
    ):
        with pytest.raises(InputError, match=f"^{named}"):
            si.Plate(length="125 mm", width="125 mm", **bad)
