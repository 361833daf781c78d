"""Discretisation error of a run by systematic refinement (verification as a feature).

A run is any callable ``run(level) -> {name: value}`` whose outputs are scalars
(peak force, gauge peaks, a zero crossing) or histories sampled on a grid that
is the same at every level (time on the last axis). Levels are refined by a
constant ratio r > 1 (h, h/r, h/r², … with the time step scaled with h), listed
coarse → fine. Nothing here knows what the structure is.

For the three finest levels f1 (coarse), f2, f3 (fine), ε21 = f2 − f1 and
ε32 = f3 − f2 (Roache 1998, *Verification and Validation in Computational
Science and Engineering*, ch. 5; Celik et al. 2008, *J. Fluids Eng.* 130,
078001, whose subscripts run the other way):

- observed order p = ln(ε21/ε32) / ln r when 0 < ε32/ε21 < 1
  (monotone convergence);
- Richardson extrapolation f* = f3 + ε32/(r^p − 1);
- relative error of each level e_i = |f_i − f*|/|f*|;
- grid convergence index of the fine level GCI_fine = Fs·|ε32/f3|/(r^p − 1) and
  of the medium one GCI_coarse = Fs·|ε21/f2|/(r^p − 1), Fs = 1.25 with three
  levels; GCI_coarse/(r^p·GCI_fine) ≈ 1 in the asymptotic range;
- with only two levels p cannot be observed: the formal order is assumed and
  Fs = 3.

Fs = 1.25 is Roache's factor for a sequence shown to be in the asymptotic range;
a monotone sequence is not shown so by its diagonal alone. When mesh and time
step are refined together their errors may have opposite signs and cancel along
the diagonal, and the "observed order" is then a coincidence (a t_F0 ladder with
p = 1.89 whose error was 1.3 × its GCI). So a monotone sequence is called
``asymptotic`` only when

1. the observed order is near the formal one, |p − p_formal| ≤ NEAR_FORMAL·p_formal
   (when a formal order is given);
2. the two one-factor refinements of the coarsest of the three finest levels —
   mesh only (``space``) and time step only (``time``), each by r — move the output
   the same way: ⟨f_space − f1, f_time − f1⟩ ≥ 0, or the smaller of the two moves is
   under CANCELLATION of the larger (it cannot cancel the other); skipped when not
   given (a ladder in one factor only has nothing to cancel);
3. the coarsest of the three levels resolves the pulse rise with at least
   MIN_RISE_STEPS time steps (``rise_steps``, when given).

Otherwise the status is ``monotone``: Fs = 3, and the order used in the
extrapolation and the GCI is min(p, p_formal) (a larger observed order would
shrink the estimate below what the scheme promises).

The ratio R = ε32/ε21 classifies the sequence (the ``status``):

- ``asymptotic``: 0 < R < 1, monotone convergence;
- ``oscillatory``: R < 0; p is computed from |R| but the extrapolation is not
  trusted: f* is the finest value and the uncertainty half the range of the
  three (Stern et al. 2001, *J. Fluids Eng.* 123, 793);
- ``diverging``: |R| ≥ 1 (the differences do not shrink);
- ``converged to round-off``: both differences within ``ROUNDOFF`` of the
  value; nothing left to extrapolate.

A history y(t) is treated as a whole rather than point by point (pointwise
orders blow up where a difference changes sign): ε are the RMS norms of the
differences, p = ln(‖ε21‖/‖ε32‖)/ln r, the sign of R is that of the inner
product ⟨ε32, ε21⟩, the extrapolated history is f3 + ε32/(r^p − 1) pointwise
with that one p, and the error of each level is the normalised RMS error
‖f_i − f*‖/‖f*‖ (‖·‖ the RMS over the samples).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..errors import InputError

__all__ = [
    "STATUSES",
    "OutputConvergence",
    "ConvergenceStudy",
    "richardson",
    "one_factor_agreement",
    "convergence_study",
    "observed_order",
    "study_case",
]

SAFETY_THREE_LEVELS = 1.25  # Roache's factor of safety when p is observed from three levels
SAFETY_TWO_LEVELS = 3.0  # ... and when p is only assumed (two levels)
ROUNDOFF = 1e-12  # differences below this fraction of the value are round-off, not discretisation error
NEAR_FORMAL = 0.25  # |p − p_formal| ≤ 0.25·p_formal: observed order "near" the formal one (1.5–2.5 for a second-order scheme)
CANCELLATION = 0.1  # a one-factor move under 10 % of the other cannot cancel it along the diagonal
MIN_RISE_STEPS = 10  # fewer time steps in the pulse rise on the coarsest level: not in the asymptotic range

STATUSES = {
    "asymptotic": "monotone convergence, p near the formal order, mesh-only and step-only refinements agree in sign; safety factor 1.25",
    "monotone": "monotone convergence not shown to be asymptotic (order far from formal, errors of mesh and step of opposite signs, "
    "or too few steps in the pulse rise); safety factor 3",
    "oscillatory": "differences change sign: extrapolation not trusted, uncertainty = half the range",
    "diverging": "differences do not shrink with refinement",
    "converged to round-off": "differences are at round-off level",
    "two levels": "order assumed (formal), not observed; safety factor 3",
    "undefined": "the output is not finite at some level (e.g. no zero crossing within the run)",
}


@dataclass(frozen=True)
class OutputConvergence:
    """Convergence of one output over the levels (module docstring for the formulas).

    ``values``: shape (n_levels,) for a scalar, (n_levels, n_t) for a history,
    coarse → fine. ``extrapolated`` is a float or an (n_t,) array. ``errors``
    (n_levels,): relative error of each level against ``extrapolated`` (the
    normalised RMS error for a history). ``gci_fine`` / ``gci_coarse``:
    relative GCI of the finest and the second finest level. ``asymptotic_ratio``:
    GCI_coarse/(r^p·GCI_fine), ≈ 1 in the asymptotic range (nan unless three
    levels converge monotonically).
    """

    name: str
    kind: str  # "scalar" | "history"
    values: np.ndarray
    ratio: float
    order: float
    extrapolated: float | np.ndarray
    errors: np.ndarray
    gci_fine: float
    gci_coarse: float
    asymptotic_ratio: float
    safety_factor: float
    status: str
    message: str

    @property
    def meaning(self) -> str:
        """What the status says, in a sentence (:data:`STATUSES`)."""
        return STATUSES[self.status]

    @property
    def finest(self) -> float | np.ndarray:
        return self.values[-1]

    @property
    def reliable(self) -> bool:
        """Whether the extrapolation can be trusted (monotone convergence, its GCI with the safety
        factor its evidence allows, or round-off)."""
        return self.status in ("asymptotic", "monotone", "converged to round-off")


@dataclass(frozen=True)
class ConvergenceStudy:
    """All outputs of a run over the refinement levels."""

    levels: tuple
    ratio: float
    outputs: tuple[OutputConvergence, ...]

    def __getitem__(self, name: str) -> OutputConvergence:
        for o in self.outputs:
            if o.name == name:
                return o
        raise KeyError(f"no output named {name!r} (have {', '.join(o.name for o in self.outputs)})")

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(o.name for o in self.outputs)


def _rms(x: np.ndarray) -> float:
    return float(np.sqrt(np.mean(np.square(x))))


def observed_order(coarse, medium, fine, ratio: float) -> float:
    """p = ln(|f2 − f1| / |f3 − f2|)/ln r for scalars; RMS norms of the differences for histories."""
    a = np.asarray(medium, float) - np.asarray(coarse, float)
    b = np.asarray(fine, float) - np.asarray(medium, float)
    na, nb = (_rms(a), _rms(b)) if a.ndim else (abs(float(a)), abs(float(b)))
    if na == 0 or nb == 0:
        return math.nan
    return math.log(na / nb) / math.log(ratio)


def one_factor_agreement(base, space, time) -> tuple[bool, str]:
    """Whether refining the mesh only (``space``) and the time step only (``time``) from
    ``base`` move the output the same way (module docstring, rule 2); and a sentence.
    Scalars or histories on a common grid (sign of the inner product)."""
    b = np.asarray(base, float)
    ds, dt = np.asarray(space, float) - b, np.asarray(time, float) - b
    if not (np.all(np.isfinite(ds)) and np.all(np.isfinite(dt))):
        return False, "a one-factor refinement is not finite"
    history = b.ndim > 0
    norm = _rms if history else (lambda x: abs(float(x)))
    ns, nt = norm(ds), norm(dt)
    dot = float(np.mean(ds * dt)) if history else float(ds * dt)
    if dot >= 0 or min(ns, nt) < CANCELLATION * max(ns, nt):
        return True, f"mesh-only and step-only refinements move it by {ns:.3g} and {nt:.3g}, not against each other"
    return False, f"mesh-only and step-only refinements move it in opposite directions ({ns:.3g} vs {nt:.3g}): they cancel along the diagonal"


@dataclass(frozen=True)
class _Levels:
    """The levels of one output, coarse → fine, checked, with their norm: |x| for a scalar, the RMS for a history."""

    name: str
    v: np.ndarray
    ratio: float

    @property
    def history(self) -> bool:
        return self.v.ndim == 2

    def norm(self, x) -> float:
        return _rms(x) if self.history else abs(float(x))

    def inner(self, x, y) -> float:
        return float(np.mean(x * y)) if self.history else float(x * y)

    @cached_property
    def scale(self) -> float:
        """The norm of the finest level (of the largest level if it is zero; 1 if all are)."""
        return self.norm(self.v[-1]) or max(self.norm(row) for row in self.v) or 1.0

    def rel(self, x) -> float:
        return self.norm(x) / self.scale

    def result(self, order, ext, gci_f, gci_c, asym, fs, status, message) -> OutputConvergence:
        """The OutputConvergence of these levels, their errors taken against ``ext``."""
        errors = np.array([self.rel(row - ext) for row in self.v])
        ext = ext if self.history else float(ext)
        kind = "history" if self.history else "scalar"
        return OutputConvergence(
            self.name, kind, self.v, float(self.ratio), float(order), ext, errors, float(gci_f), float(gci_c), float(asym), float(fs), status, message
        )


def _levels(values, ratio: float, name: str) -> np.ndarray:
    """``values`` as an array of 2 levels or more, scalars or histories; the ratio checked."""
    v = np.asarray(values, dtype=float)
    if v.ndim not in (1, 2):
        raise InputError(f"{name or 'values'}: expected shape (n_levels,) or (n_levels, n_t), got {v.shape}")
    if v.shape[0] < 2:
        raise InputError(f"{name or 'values'}: need at least 2 levels, got {v.shape[0]}")
    if not (math.isfinite(ratio) and ratio > 1):
        raise InputError(f"ratio: the refinement ratio must exceed 1, got {ratio!r}")
    return v


def _undefined(name: str, v: np.ndarray, ratio: float) -> OutputConvergence:
    """The result for levels of which some are not finite: every number nan."""
    history = v.ndim == 2
    bad = [i for i in range(v.shape[0]) if not np.all(np.isfinite(v[i]))]
    nan = np.full(v.shape[1:], math.nan) if history else math.nan
    kind = "history" if history else "scalar"
    nans = (math.nan,) * 4
    return OutputConvergence(name, kind, v, float(ratio), math.nan, nan, np.full(v.shape[0], math.nan), *nans, "undefined", f"not finite at level(s) {bad}")


def _two_levels(lv: _Levels, ratio, formal_order) -> OutputConvergence:
    """Two levels: the formal order assumed, Roache's safety factor for an assumed order."""
    v = lv.v
    if formal_order is None:
        raise InputError(f"{lv.name or 'values'}: with two levels the formal order must be given")
    e = v[1] - v[0]
    rp = ratio**formal_order
    ext = v[1] + e / (rp - 1)
    gci = SAFETY_TWO_LEVELS * lv.rel(e) / (rp - 1)
    message = f"order {formal_order:g} assumed; GCI {gci:.3g} with safety factor {SAFETY_TWO_LEVELS:g}"
    return lv.result(formal_order, ext, gci, math.nan, math.nan, SAFETY_TWO_LEVELS, "two levels", message)


def _not_monotone(lv: _Levels, ratio) -> OutputConvergence | None:
    """The three finest levels when they do not converge monotonically (round-off, diverging,
    oscillatory); None when they do."""
    v, norm, rel, scale = lv.v, lv.norm, lv.rel, lv.scale
    f1, f2, f3 = v[-3], v[-2], v[-1]
    e21, e32 = f2 - f1, f3 - f2
    n21, n32 = norm(e21), norm(e32)
    fs = SAFETY_THREE_LEVELS
    if n21 <= ROUNDOFF * scale and n32 <= ROUNDOFF * scale:
        return lv.result(math.nan, f3, rel(e32), rel(e21), math.nan, fs, "converged to round-off", f"differences {rel(e21):.1e}, {rel(e32):.1e} of the value")
    if n21 == 0:
        message = "the two coarser levels agree but the finest departs: no order can be observed"
        return lv.result(math.nan, f3, math.nan, math.nan, math.nan, fs, "diverging", message)
    # Signed ratio of the differences; for a history its sign is that of ⟨ε32, ε21⟩.
    R = math.copysign(n32 / n21, lv.inner(e32, e21)) if n32 else 0.0
    if R == 0.0:
        return lv.result(math.nan, f3, 0.0, rel(e21), math.nan, fs, "converged to round-off", "the two finest levels agree exactly")
    p = math.log(n21 / n32) / math.log(ratio)
    if abs(R) >= 1:
        message = f"|ε32/ε21| = {abs(R):.3g} ≥ 1: the difference does not shrink (observed p = {p:.3g})"
        return lv.result(p, f3, math.nan, math.nan, math.nan, fs, "diverging", message)
    if R < 0:
        half_range = 0.5 * norm(np.max(v[-3:], axis=0) - np.min(v[-3:], axis=0)) / scale
        message = (
            f"ε32/ε21 = {R:.3g} < 0: oscillatory convergence; finest level kept, uncertainty ±{half_range:.3g} (half the range); |R| would give p = {p:.3g}"
        )
        return lv.result(p, f3, half_range, math.nan, math.nan, fs, "oscillatory", message)
    return None


def _doubts(p, formal_order, f1, space, time, rise_steps) -> list[str]:
    """Why a monotone sequence is not shown asymptotic (module docstring's rules); empty when it is."""
    doubts = []
    if formal_order is not None and abs(p - formal_order) > NEAR_FORMAL * formal_order:
        doubts.append(f"observed order {p:.3g} far from the formal {formal_order:g}")
    if space is not None and time is not None:
        agree, why = one_factor_agreement(f1, space, time)
        if not agree:
            doubts.append(why)
    if rise_steps is not None and rise_steps < MIN_RISE_STEPS:
        doubts.append(f"the coarsest level has {rise_steps:.3g} time steps in the pulse rise (< {MIN_RISE_STEPS})")
    return doubts


def richardson(
    values,
    ratio: float,
    formal_order: float | None = None,
    name: str = "",
    *,
    space=None,
    time=None,
    rise_steps: float | None = None,
) -> OutputConvergence:
    """Observed order, Richardson extrapolation, errors and GCI of a sequence coarse → fine.

    ``values``: (n_levels,) scalars or (n_levels, n_t) histories on a common
    grid, n_levels ≥ 2; the three finest levels are used (with two, the
    ``formal_order`` must be given). ``ratio``: the constant refinement ratio r > 1.
    ``space`` / ``time``: the output of the coarsest of the three finest levels with
    only its mesh / only its time step refined by r (same shape as a level);
    ``rise_steps``: time steps in the pulse rise on that level. With them the
    sequence is called asymptotic only by the rules of the module docstring.
    """
    v = _levels(values, ratio, name)
    if not np.all(np.isfinite(v)):
        return _undefined(name, v, ratio)
    lv = _Levels(name, v, ratio)
    if v.shape[0] == 2:
        return _two_levels(lv, ratio, formal_order)
    if (other := _not_monotone(lv, ratio)) is not None:
        return other
    norm, rel, scale = lv.norm, lv.rel, lv.scale
    f1, f2, f3 = v[-3], v[-2], v[-1]
    e21, e32 = f2 - f1, f3 - f2
    p = math.log(norm(e21) / norm(e32)) / math.log(ratio)
    rp = ratio**p
    fs = SAFETY_THREE_LEVELS
    doubts = _doubts(p, formal_order, f1, space, time, rise_steps)
    status = "monotone" if doubts else "asymptotic"
    if doubts:
        fs = SAFETY_TWO_LEVELS
        if formal_order is not None:
            p_use = min(p, formal_order)
            rp = ratio**p_use
    ext = f3 + e32 / (rp - 1)
    gci_f = fs * rel(e32) / (rp - 1)
    gci_c = fs * (norm(e21) / (norm(f2) or scale)) / (rp - 1)
    asym = gci_c / (rp * gci_f) if gci_f > 0 else math.nan
    msg = f"observed order {p:.3g}; GCI of the finest level {gci_f:.3g}"
    if doubts:
        msg += f" with safety factor {fs:g}: not shown asymptotic ({'; '.join(doubts)})"
    return lv.result(p, ext, gci_f, gci_c, asym, fs, status, msg)


def convergence_study(
    run: Callable[[object], dict],
    levels: Sequence,
    ratio: float,
    formal_order: float | None = None,
    progress: Callable[[int, object], None] | None = None,
    *,
    one_factor: Callable[[], tuple[dict, dict] | None] | None = None,
    rise_steps: Callable[[dict], float | None] | None = None,
) -> ConvergenceStudy:
    """Run each level (coarse → fine) and analyse every output it returns.

    ``run(level)`` returns {name: float | (n_t,) array}; every level must return
    the same names and, for a history, the same number of samples (a common
    grid). ``ratio`` is the constant refinement ratio between consecutive levels.
    ``one_factor()``: the outputs of the coarsest of the three finest levels with its
    mesh only and its time step only refined by ``ratio`` (two dicts like ``run``'s;
    None when the run cannot separate them); ``rise_steps(outputs)``: the time steps in
    the pulse rise on that level, from its outputs. Both feed :func:`richardson`'s
    test of the asymptotic range.
    """
    levels = tuple(levels)
    if len(levels) < 2:
        raise InputError(f"levels: need at least 2 refinement levels, got {len(levels)}")
    outs = []
    for i, level in enumerate(levels):
        if progress is not None:
            progress(i, level)
        outs.append(run(level))
    names = tuple(outs[0])
    for i, o in enumerate(outs[1:], 1):
        if tuple(o) != names:
            raise InputError(f"run: level {levels[i]!r} returned outputs {tuple(o)}, level {levels[0]!r} returned {names}")
    sides = one_factor() if (one_factor is not None and len(levels) >= 3) else None
    base = outs[-3] if len(levels) >= 3 else outs[0]
    steps = rise_steps(base) if (rise_steps is not None and len(levels) >= 3) else None
    results = []
    for name in names:
        rows = [np.asarray(o[name], float) for o in outs]
        if len({r.shape for r in rows}) != 1:
            raise InputError(f"run: output {name!r} has shapes {[r.shape for r in rows]} over the levels (need a common grid)")
        space, time = (sides[0].get(name), sides[1].get(name)) if sides else (None, None)
        if space is not None and np.shape(space) != rows[0].shape:
            space = time = None
        results.append(richardson(np.stack(rows), ratio, formal_order, name, space=space, time=time, rise_steps=steps))
    return ConvergenceStudy(levels, float(ratio), tuple(results))


def study_case(kind, problem, levels: int, ratio: int, progress=None, case_level: int = 0) -> tuple[ConvergenceStudy, list[dict]]:
    """Run ``levels`` refinements of ``problem`` (factors 1, r, r², …) and analyse them.

    ``kind``: how to refine, check and run the problem (a case kind, :class:`softimpact.cases.CaseKind`:
    ``refine(problem, factor)``, ``check(problem)``, ``study(problem, stride, progress) -> (outputs, size)``).
    Every level is checked (resolution and resources) before the first is run: the finest
    decides whether the study fits the machine. ``case_level``: the index of the user's own
    discretisation among the levels; the levels below it are coarsenings the study chose (the
    paper report's ½), so the warnings of their checks (a mesh below the advised resolution) are
    not the user's and are not shown. ``progress(done, total, label)`` in time steps.
    Returns the study and, per level, its size (``factor``, ``elements``, ``time_step_s``,
    ``dofs`` as the model that ran counts them, ``run_time_s``).
    """
    import time
    import warnings

    from ..errors import SoftimpactWarning, TooLarge

    progress = progress or (lambda done, total, label: None)
    factors = [ratio**k for k in range(levels)]
    problems = [kind.refine(problem, f) for f in factors]
    for k, p in enumerate(problems):
        with warnings.catch_warnings():
            if k < case_level:
                warnings.simplefilter("ignore", SoftimpactWarning)
            try:
                kind.check(p)
            except TooLarge as exc:
                if k == 0:
                    raise
                fits = (
                    f"--levels {k} (×1 … ×{factors[k - 1]}) is the most that fits this machine at --ratio {ratio}"
                    if k >= 2
                    else f"not even two levels fit this machine at --ratio {ratio}: coarsen the case"
                )
                raise TooLarge(f"{fits}; level {k + 1} of {levels} (×{factors[k]}): {exc}") from None
    work = [p.solver.steps for p in problems]
    total = sum(work)
    sizes = []

    def run(k):
        done = sum(work[:k])
        label = f"level {k + 1}/{levels} (×{factors[k]})"
        progress(done, total, label)
        t0 = time.perf_counter()
        values, size = kind.study(problems[k], factors[k], lambda i: progress(done + i, total, label))
        sizes.append({"factor": factors[k], **size, "run_time_s": time.perf_counter() - t0})
        return values

    def one_factor():
        # From the coarsest of the three finest levels: its mesh refined with its step kept, and
        # its step refined with its mesh kept (the kind refines both; the solver is swapped back).
        k = levels - 3
        base, both = problems[k], problems[k + 1]
        space, time = _with_solver_of(both, base), _with_solver_of(base, both)
        progress(total, total, "one-factor refinements (mesh only, time step only)")
        return kind.study(space, factors[k])[0], kind.study(time, factors[k + 1])[0]

    def rise(outputs):
        t_peak = outputs.get("time_of_peak_s")
        dt = problems[levels - 3].solver.time_step
        return None if t_peak is None or not math.isfinite(float(t_peak)) else float(t_peak) / dt

    result = convergence_study(run, range(levels), float(ratio), formal_order=2.0, one_factor=one_factor, rise_steps=rise)
    progress(total, total, "done")
    return result, sizes


def _with_solver_of(problem, other):
    """``problem`` with the time step of ``other`` (every problem kind's ``with_solver``): a one-factor refinement."""
    return problem.with_solver(other.solver)
