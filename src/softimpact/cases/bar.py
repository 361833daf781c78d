"""Bar cases (``softimpact bar``): a projectile on the instrumented bar, a nonlinear contact run each."""

from __future__ import annotations

import json
from pathlib import Path

from ..errors import InputError
from ._common import GAUGE_FIELDS, magnitude_and_history

__all__ = ["BarKind"]


def _run_bar(problem, plain: bool = True):
    """The run, the same run without the end cap (None without one, or without ``plain``), and the force
    read from the first gauge as (time, force, gauge name) (None without a gauge)."""
    from ..workflows.bar_impact import force_from_gauge, simulate_impact, without_end_cap

    result = simulate_impact(problem)
    plain = simulate_impact(without_end_cap(problem)) if plain and problem.bar.end_cap is not None else None
    inferred = None
    if problem.gauges:
        t, f = force_from_gauge(result, 0)
        inferred = (t, f, problem.gauges[0].name)
    return result, plain, inferred


class BarKind:
    """Bar cases: nothing is shared between sweep runs (each run steps the contact anew)."""

    name = "bar"
    table = "projectile"  # a bar series has a [bar] too, but no [projectile]

    def detect(self, data):
        return "projectile" in data

    def load(self, case, history=None):
        from ..input.bar_case import load_bar_case

        if history is not None:
            raise InputError("--history: a bar case has no table of histories", "history")
        from ..input.sweep_spec import case_files

        problem, path = load_bar_case(case)
        return problem, case_files(path)  # the case and every file it names

    def problem(self, data, base):
        from ..input.bar_case import bar_problem

        return bar_problem(data)

    def problem_class(self):
        from ..workflows.bar_impact import BarImpactProblem

        return BarImpactProblem

    def execute(
        self,
        problem,
        *,
        figures=False,
        fields=False,
        frames=None,
        damage=True,
        method="direct",
        kernels=None,
        model=None,
        energy=True,
        stop_after=None,
        progress=None,
        force=None,
        summary=True,
    ):
        """The bar run (:func:`softimpact.cases.run.execute`; :func:`_run_bar`: also the run without the end cap,
        unless not ``summary`` (the Run's summary then empty), and the force read from the first gauge); the stepping options of an impact do not
        apply. ``force``: the bar driven by this prescribed end force F(t) instead (its
        :class:`~softimpact.workflows.bar_impact.BarForceResult`; no summary, no envelope: no contact)."""
        from ..models.validity import Validity
        from ..output.bar import bar_summary, bar_validity
        from .run import Run

        if force is not None:
            from ..workflows.bar_impact import simulate_force

            return Run(simulate_force(problem.bar, problem.solver, problem.gauges, force), None, {}, Validity({}), problem)
        result, plain, inferred = _run_bar(problem, summary)
        return Run(result, None, bar_summary(result, plain) if summary else {}, bar_validity(result), problem, plain=plain, inferred=inferred)

    def refusal(self, problem, study):
        """Every bar case sweeps and converges."""
        return None

    def damage_refusal(self, problem):
        return None  # a bar has no damage outputs: the sweep's check of the outputs names it

    def check(self, problem):
        from ..workflows.bar_impact import check_problem

        check_problem(problem)

    def refine(self, problem, factor):
        from ..workflows.refinement import refine_bar

        return refine_bar(problem, factor)

    def study(self, problem, stride, progress=None):
        """Pulse scalars, the force history and gauge peaks and histories of a run; its size (the
        Hermite rod's DOFs: an axial displacement and a strain per node)."""
        from ..fem.bar import Rod, assemble_rod
        from .run import execute

        r = execute(problem, summary=False).result
        out = {
            "peak_force_N": r.peak_force,
            "time_of_peak_s": r.time_of_peak,
            "contact_duration_s": r.contact_duration,
            "impulse_N_s": r.total_impulse,  # ∫F dt over the run, as the bar's summary.json
            "contact_force_history_N": r.force[::stride],
        }
        magnitude_and_history(out, [g.name for g in problem.gauges], r.strain, stride)
        dofs = int(assemble_rod(Rod.of(problem.bar)).n)
        return out, {"elements": [problem.bar.elements], "time_step_s": problem.solver.time_step, "dofs": dofs}

    def structure_key(self, data):
        return json.dumps(data, sort_keys=True, default=str)

    def prepare(self, data, base, runs, outputs=(), cases=()):
        return None

    def run(self, prepared, data, base, outputs=(), problem=None):
        """One run of the case ``data`` (or of ``problem``, already read)."""
        from .run import execute

        return self.summary(None, execute(problem or self.problem(data, Path(base)), summary=False).result)

    def summary(self, problem, result, model=None):
        """The scalars of ``softimpact bar``'s summary.json (:func:`softimpact.output.bar.bar_summary`); ``validity_flags``:
        the names of the run's validity flags (:func:`softimpact.output.bar.bar_validity`, as the command's)."""
        from ..output.bar import bar_summary, bar_validity

        s = bar_summary(result)
        scalars = {k: v for k, v in s.items() if isinstance(v, (int, float, dict)) and k != "case_SI"}
        return {**scalars, "validity_flags": bar_validity(result).names}

    def output_keys(self, problem):
        keys = ["peak_force_N", "time_of_peak_s", "contact_duration_s", "impulse_N_s", "rebound_velocity_m_s", "energy_balance_relative", "newton_iterations"]
        for g in problem.gauges:
            keys += [f"gauges.{g.name}.{f}" for f in GAUGE_FIELDS]
        # the contact envelope's ratios (summary.json's validity, output.bar.bar_validity): a sweep may keep them per run
        keys += ["validity.approach_over_diameter", "validity.contact_radius_over_projectile_radius", "validity.contact_radius_over_bar_radius"]
        return tuple(keys)

    def expand(self, data, key):
        pass
