"""The one run path (:func:`softimpact.cases.run.execute`), the Target protocol and the named output groups."""

from __future__ import annotations

import dataclasses
import tomllib
import warnings

import numpy as np
import pytest

from softimpact.cases.run import execute
from softimpact.fem.newmark import SolverSpec
from softimpact.input.impact_case import impact_problem
from softimpact.input.plate_case import load_plate_case
from softimpact.models.protocols import Target
from softimpact.models.validity import ValidityWarning

from _support.problems import LONG_BEAM_IMPACT


@pytest.fixture(scope="module")
def beam_impact():
    """The 1/2-in steel ball on the long beam, coarsened (60 × 4 Q4, 1 µs over 200 µs)."""
    problem, _ = impact_problem(tomllib.loads(LONG_BEAM_IMPACT.format(velocity="200 in/s")))
    t = problem.target
    t = dataclasses.replace(t, beam=dataclasses.replace(t.beam, nx=60, nz=4), solver=SolverSpec(1e-6, 200e-6, t.solver.newmark))
    return dataclasses.replace(problem, target=t)


def test_beam_and_plate_problems_are_targets(beam_impact):
    """A beam and a plate problem each have every member of the Target protocol (checked at run time)."""
    plate, _ = load_plate_case("plate-ss-8in")
    assert isinstance(beam_impact.target, Target)
    assert isinstance(plate, Target)


def test_damage_group_reads_what_gauges_at_its_points_read(beam_impact):
    """The "damage" output group of a coupled run equals the strains of user gauges placed where its outputs are (a
    second, independent run), and adding the group leaves the user's gauges unchanged."""
    with_damage = execute(beam_impact, damage=True).result
    names, rows = with_damage.groups["damage"]
    assert len(names) == 2 + len(beam_impact.target.gauges)  # the load point's two faces, the face opposite each gauge
    assert with_damage.strain_names == tuple(g.name for g in beam_impact.target.gauges)
    assert not any(n in with_damage.strain_names for n in names)
    as_gauges = dataclasses.replace(beam_impact, target=dataclasses.replace(beam_impact.target, gauges=beam_impact.target.damage_gauges()))
    plain = execute(as_gauges, damage=False).result
    assert plain.strain_names == names
    scale = np.abs(rows).max()
    np.testing.assert_allclose(rows, plain.strain, rtol=0, atol=1e-10 * scale)
    without = execute(beam_impact, damage=False).result
    np.testing.assert_allclose(with_damage.strain, without.strain, rtol=0, atol=1e-10 * np.abs(without.strain).max())


def test_execute_returns_warnings_as_objects_and_warns_nothing(beam_impact):
    """execute raises no ValidityWarning itself; its Validity carries the deflection over the beam's thickness,
    recomputed here from the run's deflection history."""
    with warnings.catch_warnings(record=True) as heard:
        warnings.simplefilter("always")
        run = execute(beam_impact)
    assert not [w for w in heard if issubclass(w.category, ValidityWarning)]
    expected = np.max(np.abs(run.result.target_displacement)) / beam_impact.target.beam.thickness
    assert run.warnings.values["deflection_over_thickness"] == pytest.approx(expected, rel=1e-12)
    assert run.summary["validity"]["deflection_over_thickness"] == pytest.approx(expected, rel=1e-12)
