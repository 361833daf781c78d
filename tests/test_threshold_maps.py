"""Threshold maps from coupled impact (issue 21 item 5): the damage-onset velocity found over kernel runs,
checked on direct coupled stepping, its band, and its trend with the impactor's diameter."""

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
    problem, result = T._run(s, law, 0.5 * INCH, v_strong)
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
