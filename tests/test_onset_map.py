"""The onset map (issue 30): the velocity at which the coupled peak force reaches Olsson's quasi-static threshold
F_d, found over kernel runs and checked on direct stepping, with each row's response regime."""

import math
from pathlib import Path

import pytest

from softimpact.formats.law_json import read_law
from softimpact.input.beam_case import beam_problem
from softimpact.input.toml import load_toml, locate
from softimpact.models.laminate import PLIES
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


def test_the_onset_threshold_gives_peak_over_olsson_one_on_a_direct_run(beam):
    """At the onset velocity found over kernel runs, a direct coupled run's largest contact peak is Olsson's F_d within 0.5 %,
    and 5 % slower it is below; F_d is below Davies–Zhang's P_c here, so onset comes before the Davies–Zhang threshold."""
    s, law = beam
    v = T.threshold_velocity(s, law, 0.5 * INCH, T.ONSET, 500 * INCH, 30000 * INCH)
    assert math.isfinite(v)
    assert T.index_at(s, law, 0.5 * INCH, v, T.ONSET, method="direct") == pytest.approx(1.0, rel=5e-3)
    assert T.index_at(s, law, 0.5 * INCH, 0.95 * v, T.ONSET, method="direct") < 1.0
    assert v < T.threshold_velocity(s, law, 0.5 * INCH, "delamination", 500 * INCH, 30000 * INCH)


def test_onset_map_rows_state_their_regime_from_the_mass_ratio(beam):
    """Each onset-map row carries the ball's mass over the beam's (ρ·h·b·L by hand for the 6 × 1 in [90/0]5s beam) and the
    regime of that ratio against the stand-in bounds; its band contains its median."""
    from softimpact.models.delamination import REGIME_BOUNDS

    s, law = beam
    rows = T.threshold_map(s, law, [0.375 * INCH, 0.75 * INCH], 500 * INCH, 30000 * INCH, draws=2, strength_quantiles=3, indices=(T.ONSET,))
    ply = PLIES["T300/934"]
    beam_mass = ply.density * 20 * ply.thickness * 1 * INCH * 6 * INCH
    for r in rows:
        assert r.index == T.ONSET and r.p05 <= r.median <= r.p95
        ratio = lookup("silicone rubber").density * math.pi / 6 * r.diameter**3 / beam_mass
        assert r.mass_ratio == pytest.approx(ratio, rel=1e-9)
        lo, hi = REGIME_BOUNDS
        assert r.regime == ("wave-controlled" if ratio < lo else "quasi-static" if ratio > hi else "intermediate")
        assert r.as_dict()["regime"] == r.regime


def test_the_report_lays_out_the_onset_map_with_each_rows_regime(beam):
    """The paper's onset-map CSV keeps each row's regime and mass ratio, and the report's table names them in every cell."""
    import csv

    from softimpact.app.paper.thresholds import _onset_files, _onset_table
    from softimpact.units import display

    s, law = beam
    rows = [r.as_dict() for r in T.threshold_map(s, law, [0.5 * INCH], 500 * INCH, 30000 * INCH, draws=2, strength_quantiles=3, indices=(T.ONSET,))]
    files = {}
    assert _onset_files(rows, False, files, "thresholds/", "in-lbf-s") == []
    written = list(csv.DictReader(files["thresholds/onset-map.csv"].splitlines()))
    assert [w["regime"] for w in written] == [r["regime"] for r in rows]
    assert float(written[0]["impactor_over_target_mass"]) == pytest.approx(rows[0]["impactor_over_target_mass"], rel=1e-9)
    (_, header, table), text = _onset_table(rows, display("in-lbf-s", "velocity"))
    assert header == ["structure", "d = 0.5 in"] and table[0][0] == "long beam"
    assert rows[0]["regime"] in table[0][1] and "not retrieved" in text[0]


def test_onset_rows_outside_the_quasi_static_regime_carry_the_criterion_flag(beam):
    """An onset-map row (Olsson's quasi-static F_d) whose ball is light against the beam (wave-controlled or intermediate)
    carries criterion_outside_regime and so is not inside validity (issue 42); a Tsai–Wu row of the same ball does not
    carry it (that index assumes no regime)."""
    s, law = beam
    rows = T.threshold_map(s, law, [0.5 * INCH], 500 * INCH, 30000 * INCH, draws=0, strength_quantiles=3, indices=(T.ONSET, "tsai_wu"))
    onset, tsai_wu = rows
    assert onset.regime != "quasi-static" and math.isfinite(onset.nominal)
    assert "criterion_outside_regime" in onset.flags and onset.as_dict()["inside_validity"] is False
    assert "criterion_outside_regime" not in tsai_wu.flags
