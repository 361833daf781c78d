"""The shape of the delaminations of a struck quasi-isotropic plate (issue 39), against the classic C-scan observation:
each interface's delamination is elongated along the fibres of the ply below it (Aymerich, Dore & Priolo 2009, Compos.
Sci. Technol. 69:1383, abstract: "the major axis along the fibre direction of the lower ply"; the source cited by
workflows/plate/cscan.py). Read on the cheapest quasi-isotropic run found in which a delamination grows (the case of
examples/11_delamination_cscan.py): a 1/4-in steel ball at 50 m/s on a simply supported 60 × 60 mm IM7/8552
[45/0/-45/90]s plate, the three interfaces of its lower half cohesive (below plies 5, 6, 7: 90/-45, -45/0, 0/45) in a
25 × 25 mm near field of 2.5-mm MITC9 with Turon's strengths, 100 steps of 1 µs. About 3 min of one core: the slow tier,
the run once for the module.

What it showed (docs/delamination.md): one interface of three delaminated, 90/-45, 154 mm², its equal-moment ellipse
16.9 × 12.0 mm (aspect 1.41) with the major axis at 19° from x, 64° from the -45° fibres below; the two deeper
interfaces softened (process zones) but no point reached d = 1. The observation is not reproduced: the two tests
that state it are strict xfails carrying those numbers. The run is not converged in its time step: at 0.5 µs the
delamination is 293 mm², its axis at 53° (82° from the fibres below), aspect 1.25 - still one interface, still not
along the lower ply; the xfails hold the 1-µs numbers the test computes."""

from __future__ import annotations

import numpy as np
import pytest

MIN_NODES = 9  # a region of fewer nodes than a 3 × 3 block has the moments of its grid cells (0°, 45° or 90°), not a shape
MAX_MISALIGNMENT_DEG = 15.0  # the major axis within this of the lower ply's fibres (the observation's "along")
MIN_ASPECT = 1.3  # major / minor axis: elongated, not round (a disc's 1 up to the grid's staircase)
L, NEAR = 60e-3, 12.5e-3


def qi_problem(velocity: float = 50.0, element_size: float = 2.5e-3, time_step: float = 1e-6):
    """The QI case (module docstring), from the package's Python objects."""
    import softimpact as si
    from softimpact.fem.newmark import SolverSpec
    from softimpact.models.cohesive import BilinearCohesive
    from softimpact.models.contact_laws import HertzLaw
    from softimpact.workflows.coupled import ImpactProblem
    from softimpact.workflows.plate import PlateLoad, PlateProblem
    from softimpact.workflows.plate.cohesive import CohesivePlateProblem

    laminate = si.Laminate("IM7/8552", "[45/0/-45/90]s")
    plate = si.Plate(length=f"{L} m", width=f"{L} m", laminate=laminate, elements=(6, 6))
    ball = si.Sphere("steel", "0.25 in", velocity=f"{velocity} m/s")
    ply = laminate.stack.ply
    law = BilinearCohesive(K=1.5e15, N=ply.strength.Yt, S=ply.strength.S12, GIc=277.0, GIIc=ply.strength.GIIc, eta=1.634)
    target = PlateProblem(plate.spec, PlateLoad((L / 2, L / 2), ball.diameter / 2, None), SolverSpec(time_step, 100e-6), title="QI")
    target = CohesivePlateProblem.of(target, (5, 6, 7), law, near_field=NEAR, element_size=element_size, turon=True)
    hertz = HertzLaw.sphere_on_laminate(ball.diameter / 2, ball.material, ply.E3)
    return ImpactProblem(target, "(test)", ball.impactor, ball.material, "hertz", hertz, "QI")


@pytest.fixture(scope="module")
def struck():
    """The run (result) and its C-scan."""
    import softimpact as si

    res = si.run(qi_problem(), figures=False, units="SI")
    return res, res.model.cscan()


def _shaped(res, scan):
    """The interfaces whose delaminated region has at least MIN_NODES nodes of the model."""
    counts = (np.asarray(res.model.stack.damage) >= 1.0).sum(axis=1)
    return [i for i, n in zip(scan.interfaces, counts, strict=True) if n >= MIN_NODES]


@pytest.mark.slow
def test_the_run_delaminates_inside_its_near_field(struck):
    """The peak force passes Olsson's quasi-static onset force F_d (measured 1.70 F_d), a delamination of MIN_NODES or more
    grows, and every delaminated node lies at least a node spacing inside the near field's rim: the shapes are the
    model's, not the rim's."""
    res, scan = struck
    assert res.run_summary["damage"]["peak_over_olsson"] > 1.0
    assert _shaped(res, scan)
    X, Y = np.meshgrid(scan.xs, scan.ys, indexing="ij")
    cracked = (scan.damage >= 1.0).any(axis=0)
    reach = max(np.abs(X[cracked] - L / 2).max(), np.abs(Y[cracked] - L / 2).max())
    assert reach <= NEAR - res.model.problem.node_spacing()


@pytest.mark.slow
@pytest.mark.xfail(
    strict=True,
    reason="measured: only the 90/-45 interface (plies 5/6) delaminated; the -45/0 and 0/45 interfaces softened (process zones of "
    "52 and 14 nodes) without a point at d = 1 (docs/delamination.md)",
)
def test_delaminations_grow_at_several_interfaces(struck):
    """A quasi-isotropic plate struck past onset delaminates at several interfaces (the C-scans of the observation): at
    least two of the three with a region of MIN_NODES nodes or more."""
    assert len(_shaped(*struck)) >= 2


@pytest.mark.slow
@pytest.mark.xfail(
    strict=True,
    reason="measured: plies 5/6 (lower ply -45°) 154 mm², 16.9 × 12.0 mm (aspect 1.41), major axis at 18.6° from x, 63.6° from "
    "the lower ply's fibres: elongated, but not along them (docs/delamination.md)",
)
def test_each_delamination_is_elongated_along_the_lower_ply(struck):
    """Every delamination large enough to have a shape (MIN_NODES nodes) is elongated (major/minor > MIN_ASPECT) with its
    major axis within MAX_MISALIGNMENT_DEG of the fibres of the ply below its interface."""
    shaped = _shaped(*struck)
    assert shaped
    for i in shaped:
        assert i.major_axis / i.minor_axis > MIN_ASPECT, (i.label, i.major_axis / i.minor_axis)
        assert i.misalignment_deg <= MAX_MISALIGNMENT_DEG, (i.label, i.orientation_deg, i.lower_ply_deg)


def test_the_run_says_it_is_not_resolved_in_its_step(struck):
    """The run is not converged in its step (the area nearly doubles at half the step: module docstring), and says so
    where it reports: its contact force zigzags from step to step (force_unresolved_in_time: 8 steps, up to 0.12 of the
    peak). Its delamination fronts' largest advance a step is reported beside (validity.front_spacings_per_step, 0.46:
    below the one spacing that would raise cohesive_front_unresolved_in_time)."""
    res, _ = struck
    validity = res.summary()["validity"]
    assert "front_spacings_per_step" in validity
    assert any("zigzags from step to step" in f or "delamination front" in f for f in validity["flags"]), validity["flags"]
