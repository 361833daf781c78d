"""Threshold maps from coupled impact (issue 21 item 5): the damage-onset velocity found over kernel runs,
checked on direct coupled stepping, its band, and its trend with the impactor's diameter."""

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

from softimpact.formats.law_json import read_law
from softimpact.input.beam_case import beam_problem
from softimpact.input.toml import load_toml, locate
from softimpact.models.materials import lookup
from softimpact.studies import thresholds as T

INCH = 0.0254
LAW = Path(__file__).parent / "data" / "law-v-main.json"


@pytest.fixture(scope="module")
def beam():
    """The long beam, layered laminate, on a coarse 60 × 4 mesh (2 µs, 400 µs), struck by rubber balls under the identified law."""
    data = load_toml(locate("paper-long-beam"))
    data["beam"]["elements"] = [60, 4]
    data["beam"]["laminate"]["model"] = "layered"
    law = read_law(LAW)
    s = T.structure("long beam", beam_problem(data, locate("paper-long-beam").parent), 0.75 * INCH, lookup("silicone rubber").density, 2e-6, 400e-6, law)
    return s, law


@pytest.mark.parametrize("index", T.INDICES)
def test_the_threshold_found_on_kernels_gives_index_one_on_a_direct_run(beam, index):
    """At the velocity found by root-finding over kernel runs, a direct coupled run gives the index within 0.5 % of 1."""
    s, law = beam
    v = T.threshold_velocity(s, law, 0.5 * INCH, index, 500 * INCH, 30000 * INCH)
    assert math.isfinite(v)
    assert T.index_at(s, law, 0.5 * INCH, v, index, method="direct") == pytest.approx(1.0, rel=5e-3)
    assert T.index_at(s, law, 0.5 * INCH, 0.95 * v, index, method="direct") < 1.0  # the first crossing: below it at 5 % less


def test_the_delamination_threshold_scales_with_the_strength_as_its_power_law_says(beam):
    """With the threshold force P_c scaled by s the delamination index (F_peak/P_c) is divided by s, so the threshold moves by s^(1/β)."""
    s, law = beam
    v = T.threshold_velocity(s, law, 0.5 * INCH, "delamination", 500 * INCH, 30000 * INCH)
    i1, i2 = (T.index_at(s, law, 0.5 * INCH, v * f, "delamination") for f in (0.98, 1.02))
    beta = math.log(i2 / i1) / math.log(1.02 / 0.98)
    v_strong = v * 1.1 ** (1 / beta)
    problem, result = T.structure_run(s, law, 0.5 * INCH, v_strong)
    assert T.damage_index(problem, result, "delamination", scale=1.1) == pytest.approx(1.0, rel=5e-3)


def test_the_band_contains_the_median_and_the_threshold_falls_with_the_diameter(beam):
    """Each row's 5-95 % band contains its median; a heavier ball (mass ∝ d³, more momentum at a given velocity) damages at a lower velocity."""
    s, law = beam
    rows = T.threshold_map(s, law, [0.375 * INCH, 0.5 * INCH, 0.75 * INCH], 500 * INCH, 30000 * INCH, draws=4, strength_quantiles=5)
    for r in rows:
        assert r.reached == r.draws == 4
        assert r.p05 <= r.law_p05 <= r.median <= r.law_p95 <= r.p95
        assert r.mass == pytest.approx(lookup("silicone rubber").density * math.pi / 6 * r.diameter**3)
    for index in T.INDICES:
        med = [r.median for r in rows if r.index == index]
        assert np.all(np.diff(med) < 0), (index, med)


def test_both_indices_are_homogeneous_of_degree_minus_one_in_a_common_strength_factor(beam):
    """The scatter's scaling rule checked on the criteria themselves: every strength × 1.1 and G_IIc × 1.21 (P_c ∝ √G_IIc) divides Tsai–Wu's 1/R and F/P_c by 1.1."""
    s, law = beam
    problem, result = T.structure_run(s, law, 0.5 * INCH, 3000 * INCH)
    target = problem.target
    stack = target.beam.stack
    st = stack.ply.strength
    strong = dataclasses.replace(st, **{k: getattr(st, k) * 1.1 for k in ("Xt", "Xc", "Yt", "Yc", "S12", "S23")}, GIIc=st.GIIc * 1.21)
    stack2 = dataclasses.replace(stack, ply=dataclasses.replace(stack.ply, strength=strong))
    problem2 = dataclasses.replace(problem, target=dataclasses.replace(target, beam=dataclasses.replace(target.beam, stack=stack2)))
    for index in T.INDICES:
        assert T.damage_index(problem2, result, index) == pytest.approx(T.damage_index(problem, result, index) / 1.1, rel=1e-9)


def test_the_threshold_on_kernels_equals_the_threshold_on_direct_stepping(beam):
    """The Tsai–Wu threshold of the 1/2-in ball found over kernel runs equals the one found over direct coupled stepping within 0.5 %."""
    s, law = beam
    v_k = T.threshold_velocity(s, law, 0.5 * INCH, "tsai_wu", 500 * INCH, 30000 * INCH)
    v_d = T.threshold_velocity(s, law, 0.5 * INCH, "tsai_wu", 500 * INCH, 30000 * INCH, method="direct")
    assert v_d == pytest.approx(v_k, rel=5e-3)
