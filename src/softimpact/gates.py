"""Quality gates: the checks a fit reports on its own answer.

A fit (``reduce``, ``fit``, ``calibrate``, ``identify``) returns, beside its
result, a tuple of :class:`Gate` — one per check: its ``name``, whether it
``passed``, the ``value`` measured, the ``limit`` it was held to, and a
one-line ``reason`` that says what failed in the user's terms. The app puts
them on its :class:`softimpact.app.Outcome` (``gates=``) and writes
:func:`quality` into its summary; the command line then

- writes every file as usual, with ``"status"`` in ``manifest.json``;
- if a gate failed: prints ``softimpact: check failed: <reason>`` and exits 3
  (:data:`softimpact.errors.EXIT_CHECK`), unless ``--accept-poor`` was given,
  in which case it exits 0 and the manifest says ``"status": "accepted-poor"``.

Making a gate::

    gates = (
        at_most("residual", rms / noise, 3.0, "residual is {value:.3g} times the noise (limit {limit:g})"),
        at_least("velocity-spread", spread, 0.05, "tests span {value:.1%} of their mean velocity ..."),
        passed_if("optimiser", result.success, result.message),
    )

A gate that cannot be evaluated (NaN value) fails: a result is never labelled
good when it could not be checked.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["Gate", "at_most", "at_least", "passed_if", "failed", "status", "quality", "MAX_SKEW", "pulse_skew"]

MAX_SKEW = 0.95  # tF0/T of an eq-15 pulse at or above: degenerate (the peak at the very end, tF0 ≈ T)


@dataclass(frozen=True)
class Gate:
    """One check of a result: passed when ``value`` is within ``limit`` (see the makers)."""

    name: str
    passed: bool
    value: float
    limit: float
    reason: str  # one line, shown when the gate fails; it names the quantity, the value and the limit

    def as_dict(self) -> dict:
        finite = lambda x: float(x) if isinstance(x, (int, float)) and math.isfinite(x) else None  # noqa: E731
        return {"name": self.name, "passed": bool(self.passed), "value": finite(self.value), "limit": finite(self.limit), "reason": self.reason}


def at_most(name: str, value: float, limit: float, reason: str) -> Gate:
    """A gate that passes when ``value <= limit``; ``reason`` may use ``{value}`` and ``{limit}``."""
    value = float(value)
    return Gate(name, bool(value <= limit), value, float(limit), reason.format(value=value, limit=limit))


def at_least(name: str, value: float, limit: float, reason: str) -> Gate:
    """A gate that passes when ``value >= limit``; ``reason`` may use ``{value}`` and ``{limit}``."""
    value = float(value)
    return Gate(name, bool(value >= limit), value, float(limit), reason.format(value=value, limit=limit))


def passed_if(name: str, ok: bool, reason: str) -> Gate:
    """A yes/no gate (an optimiser's success flag): value 1 if ``ok`` else 0, limit 1."""
    return Gate(name, bool(ok), 1.0 if ok else 0.0, 1.0, reason)


def pulse_skew(name: str, time_of_peak: float, duration: float) -> Gate:
    """The gate ``pulse-skew[name]``: an eq-15 pulse whose skewness tF0/T reaches MAX_SKEW is
    degenerate (reduce, fit and calibrate all hold their pulses to it); NaN (fails) for T ≤ 0."""
    skew = time_of_peak / duration if duration > 0 else float("nan")
    return at_most(f"pulse-skew[{name}]", skew, MAX_SKEW, f"{name}: degenerate pulse, tF0/T = {{value:.2f}} (limit {{limit:.2f}})")


def failed(gates) -> tuple[Gate, ...]:
    """The gates that did not pass."""
    return tuple(g for g in gates if not g.passed)


def status(gates, accept_poor: bool = False) -> str:
    """'passed', 'failed', or 'accepted-poor' (failed gates accepted by ``--accept-poor``)."""
    if not failed(gates):
        return "passed"
    return "accepted-poor" if accept_poor else "failed"


def quality(gates) -> dict:
    """The gates as JSON-ready data for a summary: ``{"status", "gates": [...]}``."""
    gates = tuple(gates)
    return {"status": status(gates), "gates": [g.as_dict() for g in gates]}
