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

import numpy as np

from ..errors import InputError

__all__ = [
    "STATUSES",
    "OutputConvergence",
    "ConvergenceStudy",
    "richardson",
    "convergence_study",
    "observed_order",
    "study_case",
]

SAFETY_THREE_LEVELS = 1.25  # Roache's factor of safety when p is observed from three levels
SAFETY_TWO_LEVELS = 3.0  # ... and when p is only assumed (two levels)
ROUNDOFF = 1e-12  # differences below this fraction of the value are round-off, not discretisation error

STATUSES = {
    "asymptotic": "monotone convergence; p observed from the three finest levels",
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
    def finest(self) -> float | np.ndarray:
        return self.values[-1]

    @property
    def reliable(self) -> bool:
        """Whether the extrapolation can be trusted (monotone convergence or round-off)."""
        return self.status in ("asymptotic", "converged to round-off")


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


def richardson(values, ratio: float, formal_order: float | None = None, name: str = "") -> OutputConvergence:
    """Observed order, Richardson extrapolation, errors and GCI of a sequence coarse → fine.

    ``values``: (n_levels,) scalars or (n_levels, n_t) histories on a common
    grid, n_levels ≥ 2; the three finest levels are used (with two, the
    ``formal_order`` must be given). ``ratio``: the constant refinement ratio r > 1.
    """
    v = np.asarray(values, dtype=float)
    if v.ndim not in (1, 2):
        raise InputError(f"{name or 'values'}: expected shape (n_levels,) or (n_levels, n_t), got {v.shape}")
    if v.shape[0] < 2:
        raise InputError(f"{name or 'values'}: need at least 2 levels, got {v.shape[0]}")
    if not (math.isfinite(ratio) and ratio > 1):
        raise InputError(f"ratio: the refinement ratio must exceed 1, got {ratio!r}")
    history = v.ndim == 2
    kind = "history" if history else "scalar"
    if not np.all(np.isfinite(v)):
        bad = [i for i in range(v.shape[0]) if not np.all(np.isfinite(v[i]))]
        nan = np.full(v.shape[1:], math.nan) if history else math.nan
        return OutputConvergence(
            name,
            kind,
            v,
            float(ratio),
            math.nan,
            nan,
            np.full(v.shape[0], math.nan),
            math.nan,
            math.nan,
            math.nan,
            math.nan,
            "undefined",
            f"not finite at level(s) {bad}",
        )
    norm = _rms if history else (lambda x: abs(float(x)))
    inner = (lambda x, y: float(np.mean(x * y))) if history else (lambda x, y: float(x * y))
    scale = norm(v[-1]) or max(norm(row) for row in v) or 1.0

    def rel(x):
        return norm(x) / scale

    def result(order, ext, gci_f, gci_c, asym, fs, status, message):
        errors = np.array([rel(row - ext) for row in v])
        return OutputConvergence(
            name,
            kind,
            v,
            float(ratio),
            float(order),
            ext if history else float(ext),
            errors,
            float(gci_f),
            float(gci_c),
            float(asym),
            float(fs),
            status,
            message,
        )

    if v.shape[0] == 2:
        if formal_order is None:
            raise InputError(f"{name or 'values'}: with two levels the formal order must be given")
        e = v[1] - v[0]
        rp = ratio**formal_order
        ext = v[1] + e / (rp - 1)
        gci = SAFETY_TWO_LEVELS * rel(e) / (rp - 1)
        return result(
            formal_order,
            ext,
            gci,
            math.nan,
            math.nan,
            SAFETY_TWO_LEVELS,
            "two levels",
            f"order {formal_order:g} assumed; GCI {gci:.3g} with safety factor {SAFETY_TWO_LEVELS:g}",
        )

    f1, f2, f3 = v[-3], v[-2], v[-1]
    e21, e32 = f2 - f1, f3 - f2
    n21, n32 = norm(e21), norm(e32)
    fs = SAFETY_THREE_LEVELS
    if n21 <= ROUNDOFF * scale and n32 <= ROUNDOFF * scale:
        return result(math.nan, f3, rel(e32), rel(e21), math.nan, fs, "converged to round-off", f"differences {rel(e21):.1e}, {rel(e32):.1e} of the value")
    if n21 == 0:
        return result(
            math.nan, f3, math.nan, math.nan, math.nan, fs, "diverging", "the two coarser levels agree but the finest departs: no order can be observed"
        )
    # Signed ratio of the differences; for a history its sign is that of ⟨ε32, ε21⟩.
    R = math.copysign(n32 / n21, inner(e32, e21)) if n32 else 0.0
    if R == 0.0:
        return result(math.nan, f3, 0.0, rel(e21), math.nan, fs, "converged to round-off", "the two finest levels agree exactly")
    p = math.log(n21 / n32) / math.log(ratio)
    if abs(R) >= 1:
        return result(
            p, f3, math.nan, math.nan, math.nan, fs, "diverging", f"|ε32/ε21| = {abs(R):.3g} ≥ 1: the difference does not shrink (observed p = {p:.3g})"
        )
    rp = ratio**p
    if R < 0:
        half_range = 0.5 * norm(np.max(v[-3:], axis=0) - np.min(v[-3:], axis=0)) / scale
        return result(
            p,
            f3,
            half_range,
            math.nan,
            math.nan,
            fs,
            "oscillatory",
            f"ε32/ε21 = {R:.3g} < 0: oscillatory convergence; finest level kept, uncertainty ±{half_range:.3g} (half the range); |R| would give p = {p:.3g}",
        )
    ext = f3 + e32 / (rp - 1)
    gci_f = fs * rel(e32) / (rp - 1)
    gci_c = fs * (norm(e21) / (norm(f2) or scale)) / (rp - 1)
    asym = gci_c / (rp * gci_f) if gci_f > 0 else math.nan
    msg = f"observed order {p:.3g}; GCI of the finest level {gci_f:.3g}"
    if formal_order is not None and abs(p - formal_order) > 0.5 * formal_order:
        msg += f" (formal order {formal_order:g}: not yet in the asymptotic range?)"
    return result(p, ext, gci_f, gci_c, asym, fs, "asymptotic", msg)


def convergence_study(
    run: Callable[[object], dict],
    levels: Sequence,
    ratio: float,
    formal_order: float | None = None,
    progress: Callable[[int, object], None] | None = None,
) -> ConvergenceStudy:
    """Run each level (coarse → fine) and analyse every output it returns.

    ``run(level)`` returns {name: float | (n_t,) array}; every level must return
    the same names and, for a history, the same number of samples (a common
    grid). ``ratio`` is the constant refinement ratio between consecutive levels.
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
    results = []
    for name in names:
        rows = [np.asarray(o[name], float) for o in outs]
        if len({r.shape for r in rows}) != 1:
            raise InputError(f"run: output {name!r} has shapes {[r.shape for r in rows]} over the levels (need a common grid)")
        results.append(richardson(np.stack(rows), ratio, formal_order, name))
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

    from ..errors import SoftimpactWarning

    progress = progress or (lambda done, total, label: None)
    factors = [ratio**k for k in range(levels)]
    problems = [kind.refine(problem, f) for f in factors]
    for k, p in enumerate(problems):
        with warnings.catch_warnings():
            if k < case_level:
                warnings.simplefilter("ignore", SoftimpactWarning)
            kind.check(p)
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

    result = convergence_study(run, range(levels), float(ratio), formal_order=2.0)
    progress(total, total, "done")
    return result, sizes
