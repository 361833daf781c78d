"""Threshold maps stepped on the reduced von Kármán plate (studies.thresholds, ``nonlinear_stepping="von-karman-rom"``):
the threshold of the full plate's map within the reduced model's force error, the rows' validity from a single reduced
run, the reduced model built once a map, and a clear refusal where the reduced model does not apply."""

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

from softimpact.app.paper.thresholds import PAPER_PLATE, paper_plate_case
from softimpact.cases.run import impact_validity
from softimpact.errors import InputError
from softimpact.fem import vk_rom
from softimpact.fem.contact import group_outputs
from softimpact.formats.law_json import read_law
from softimpact.input.beam_case import beam_problem
from softimpact.input.plate_case import plate_problem
from softimpact.input.toml import load_toml, locate
from softimpact.models.materials import lookup
from softimpact.output.sweep import threshold_csv
from softimpact.studies import thresholds as T
from softimpact.workflows.coupled import run_impact
from softimpact.workflows.damage import coupled_damage

INCH = 0.0254
LAW = Path(__file__).parent / "data" / "law-v-main.json"
RHO = lookup("silicone rubber").density
# The reduced model's peak-force error against the full run on the 48 × 48 plate at w/h 0.7 (+1.78 %, its default
# basis): BENCHMARKS.md, "Large deflection at design-study speed", the reduced-order model's table.
ROM_FORCE_ERROR = 0.0178
RTOL = 2e-4  # threshold_velocity's default relative tolerance on V*


def _memoryless(law):
    """The identified law without its Maxwell arm (kappa_ref = 0: the memoryless soft law, which the reduced model takes)."""
    v = np.array(law.values, float)
    v[list(law.names).index("kappa_ref")] = 0.0
    return dataclasses.replace(law, values=v)


LAW0 = _memoryless(read_law(LAW))


def _plate(elements: int, layup: str = "[90/0]5s"):
    """The report's quarter of the 8-in plate (MITC4, symmetry edges, struck at the centre) with von Kármán kinematics."""
    data = paper_plate_case(elements, "240 us")
    data["plate"]["kinematics"] = "von-karman"
    data["plate"]["laminate"]["layup"] = layup
    return plate_problem(data, locate(PAPER_PLATE).parent)


def _structure(target, time_step: float, stepping: str, law=LAW0, widest: float = 0.5 * INCH):
    """The map's structure of ``target`` for silicone-rubber balls up to ``widest`` [m], 240 µs of ``time_step``."""
    return T.structure("plate", target, widest, RHO, time_step, 240e-6, law, nonlinear_stepping=stepping)


def _row(s, law=LAW0, lo: float = 1000 * INCH, hi: float = 20000 * INCH):
    """The delamination row of the 1/2-in ball over [lo, hi] m/s, the law's mean alone (no draws)."""
    return T.threshold_map(s, law, [0.5 * INCH], lo, hi, draws=0, strength_quantiles=3, indices=("delamination",))


@pytest.mark.slow
def test_the_reduced_maps_threshold_is_the_full_maps_shifted_by_its_force_error():
    """On the 10 × 10 quarter plate (4 µs) the reduced map's delamination threshold of the 1/2-in ball is the full map's within
    the reduced model's benchmarked force error over β, and the shift is the one its peak-force error ε at V* predicts:
    V*_full/V*_rom = (1 + ε)^(1/β) (the index is the peak force over P_c and grows as V^β), to the root-finding's tolerance."""
    target = _plate(10)
    rom, full = _structure(target, 4e-6, "von-karman-rom"), _structure(target, 4e-6, "von-karman")
    assert rom.rom.r < rom.rom.bset.size  # a true reduction: fewer coordinates than the plate's bending DOFs
    (r,), (f,) = _row(rom), _row(full)
    assert (r.stepping, f.stepping) == ("von-karman-rom", "von-karman")
    assert r.kinematics == f.kinematics == "von-karman"
    assert math.isfinite(r.nominal) and f.beta > 0
    assert abs(r.nominal / f.nominal - 1) <= ROM_FORCE_ERROR / f.beta
    _, a = T.structure_run(rom, LAW0, 0.5 * INCH, r.nominal)
    _, b = T.structure_run(full, LAW0, 0.5 * INCH, r.nominal)
    eps = a.peak_force / b.peak_force - 1
    assert f.nominal / r.nominal == pytest.approx((1 + eps) ** (1 / f.beta), rel=RTOL)


@pytest.fixture(scope="module")
def rom_map():
    """(structure, rows, reduced-model builds (the structure's, the map's)) of the 4 × 4 quarter plate (4 µs) stepped on its
    reduced model, the 1/2-in ball."""
    builds = []
    init = vk_rom.PlateVKROM.__init__

    def counted(self, *args, **kwargs):
        builds.append(1)
        init(self, *args, **kwargs)

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(vk_rom.PlateVKROM, "__init__", counted)
        s = _structure(_plate(4), 4e-6, "von-karman-rom")
        built = len(builds)
        rows = _row(s, lo=3000 * INCH, hi=8000 * INCH)  # (the threshold is near 4800 in/s: a short scan)
    return s, rows, (built, len(builds) - built)


def test_the_reduced_model_is_built_once_for_the_whole_map(rom_map):
    """The structure builds the reduced plate once and a map (its root-finding's runs, β's and the validity run) builds none: every run reuses it."""
    s, rows, builds = rom_map
    assert s.rom is not None and s.stepping == "von-karman-rom"
    assert builds == (1, 0) and sum(r.runs for r in rows) > 3


def test_a_reduced_maps_row_carries_the_validity_of_a_single_reduced_run(rom_map):
    """Every validity ratio of a reduced map's row equals that of a single reduced run at its V* (run_impact's own reduced
    model, built for that run; the impact command's composition of the checks) to 1e-9, its flags are that run's plus the
    identified law's range, and the CSV says how the row was stepped."""
    s, rows, _ = rom_map
    for row in rows:
        problem = s.problem_at(LAW0, row.diameter, row.nominal)
        model = problem.model(damage=True)
        _, result = run_impact(problem, model, energy=False, method="von-karman-rom")
        result = group_outputs(result, model.contact_groups())
        dmg = coupled_damage(problem.target, result, impactor_mass=problem.impactor.mass).summary()
        single = impact_validity(problem, result, dmg)
        assert set(row.ratios) == set(single.values)
        for name, value in single.values.items():
            assert row.as_dict()[name] == pytest.approx(value, rel=1e-9, abs=1e-12), name
        assert set(single.names) <= set(row.flags)
        # the row's own: the identified law's envelope (its ranges; with no approach recorded in this law.json, its contact
        # radius held to the ball's) and the criterion's regime (an onset row)
        extra = set(row.flags) - set(single.names)
        assert all(f.startswith("extrapolated_") or f in ("contact_past_projectile_radius", "criterion_outside_regime") for f in extra)
    text = threshold_csv([r.as_dict() for r in rows]).splitlines()
    column = text[0].split(",").index("stepping")
    assert [line.split(",")[column] for line in text[1:]] == ["von-karman-rom"] * len(rows)


def _beam():
    data = load_toml(locate("paper-long-beam"))
    data["beam"].update(elements=[60, 4], kinematics="von-karman")
    data["beam"]["laminate"]["model"] = "layered"
    return beam_problem(data, locate("paper-long-beam").parent)


@pytest.mark.parametrize(
    "target, law, message",
    [
        (lambda: _plate(4), read_law(LAW), "memoryless contact law"),
        (lambda: _plate(4, "[0/90]5"), LAW0, "bending-extension coupling"),
        (_beam, LAW0, "plate with von Karman kinematics"),
    ],
    ids=["law-with-memory", "unsymmetric-laminate", "large-deflection-beam"],
)
def test_reduced_stepping_is_refused_where_the_reduced_model_does_not_apply(target, law, message):
    """A law with memory, a laminate with B coupling or a beam: an InputError naming the option and the reason."""
    with pytest.raises(InputError, match=f"nonlinear_stepping = 'von-karman-rom'.*{message}"):
        _structure(target(), 4e-6, "von-karman-rom", law=law)


def test_an_unknown_nonlinear_stepping_is_refused():
    """A stepping that is neither the full nor the reduced plate's is an InputError listing the two."""
    with pytest.raises(InputError, match="nonlinear_stepping must be one of von-karman, von-karman-rom"):
        _structure(_plate(4), 4e-6, "von-karman-reduced")


@pytest.mark.slow
@pytest.mark.parametrize("velocity", [16.0, 22.0])
def test_the_reduced_plate_follows_an_ice_crush_to_its_end(velocity):
    """A 38.1-mm ice sphere crushing on the report's thinnest hail panel (1.59 mm, von Kármán, 8 × 8 at 2 µs, w/h 2-3) runs
    to its end on the reduced plate (its Newton once stalled where the crush stops), with the full plate's peak force within 2 %."""
    from softimpact.app.paper import hail as H
    from softimpact.studies.hail import RHYMER_DIAMETERS, RHYMER_LAYUPS, RHYMER_THICKNESSES, CatalogueIce, hail_structures

    law = CatalogueIce()
    peaks = []
    for stepping in ("von-karman-rom", "von-karman"):
        fine, _ = hail_structures(
            H.panel_target, RHYMER_THICKNESSES[0], RHYMER_LAYUPS[0], law, H.HAIL_MESHES, H.HAIL_DURATION, max(RHYMER_DIAMETERS), "von-karman", stepping
        )
        _, result = T.structure_run(fine, law, RHYMER_DIAMETERS[0], velocity)
        peaks.append(max(c.peak_force for c in result.contacts))
    assert peaks[0] == pytest.approx(peaks[1], rel=0.02)


@pytest.mark.slow
def test_the_reduced_plate_steps_across_the_crushing_strengths_kink():
    """A 50.8-mm ice sphere at 9 m/s on a 150-mm clamped 3.11-mm panel (von Kármán, 8 × 8 at 2 µs): where the crush slows onto its
    strength's ramp the reduced plate's full Newton steps cycled between two iterates (SolverFailed at 0.788 ms); it now backtracks
    and runs to the end, with the full plate's peak force within 2 %."""
    import functools

    from softimpact.app.paper import hail as H
    from softimpact.studies.hail import RHYMER_DIAMETERS, RHYMER_LAYUPS, CatalogueIce, hail_structures

    panel = functools.partial(H.panel_target, side=0.150, support="clamped")
    law = CatalogueIce()
    peaks = []
    for stepping in ("von-karman-rom", "von-karman"):
        fine, _ = hail_structures(panel, 3.11e-3, RHYMER_LAYUPS[1], law, H.HAIL_MESHES, H.HAIL_DURATION, max(RHYMER_DIAMETERS), "von-karman", stepping)
        _, result = T.structure_run(fine, law, RHYMER_DIAMETERS[1], 9.0)
        assert result.time[-1] == pytest.approx(H.HAIL_DURATION, rel=1e-6)
        peaks.append(max(c.peak_force for c in result.contacts))
    assert peaks[0] == pytest.approx(peaks[1], rel=0.02)
