"""Guards run before the first expensive step: machine resources and discretisation.

:func:`require_resources` compares a problem's memory (and time) estimate with
what the machine has and refuses, in one line with the estimate, a run that
would exhaust it — instead of a MemoryError after a minute. The refusal is an
:class:`~softimpact.errors.InputError` (exit 2); ``softimpact --ignore-limits``
(or the environment variable ``SOFTIMPACT_IGNORE_LIMITS=1``) lets it go ahead.

:func:`require_resolution` checks a discretisation measure (elements per
wavelength, time steps per contact duration): below its floor the answer is
meaningless (exit 2 with the reason and the minimum); between the floor and the
comfortable value it runs with a :class:`~softimpact.errors.SoftimpactWarning`.
"""

from __future__ import annotations

import math
import os
import warnings

from .errors import InputError, SoftimpactWarning, TooLarge

__all__ = ["IGNORE_LIMITS_ENV", "MEMORY_SHARE", "TIME_LIMIT", "FLOP_RATE", "available_memory", "require_resources", "require_resolution", "describe_bytes"]

IGNORE_LIMITS_ENV = "SOFTIMPACT_IGNORE_LIMITS"  # set to 1 to run past the resource guard
MEMORY_SHARE = 0.8  # refuse a run whose estimate exceeds this share of the memory available now
TIME_LIMIT = 3600.0  # s: refuse a run estimated to take longer than an hour
FLOP_RATE = 1e9  # floating-point operations per second assumed for time estimates (one core, numpy)


def available_memory() -> int | None:
    """Memory available to a new allocation now [bytes] (MemAvailable on Linux), or None if unknown."""
    try:
        with open("/proc/meminfo", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    try:
        return os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (ValueError, OSError, AttributeError):
        return None


def describe_bytes(n: float) -> str:
    """'11.6 GB' style size."""
    for unit, size in (("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if n >= size:
            return f"{n / size:.3g} {unit}"
    return f"{n:.0f} B"


def _ignored() -> bool:
    return os.environ.get(IGNORE_LIMITS_ENV, "").strip() not in ("", "0")


def require_resources(what: str, memory: float, flops: float = 0.0) -> None:
    """Refuse ``what`` (e.g. "a 20000 x 100 beam, 1000 steps") if it needs more than the machine has.

    ``memory``: peak bytes estimated from the problem size; ``flops``: floating-
    point operations (time = flops / FLOP_RATE). Raises :class:`InputError`
    naming the estimate and the way past the guard.
    """
    if _ignored():
        return
    hint = f"make it smaller, or run `softimpact --ignore-limits ...` ({IGNORE_LIMITS_ENV}=1) to try anyway"
    avail = available_memory()
    if not math.isfinite(memory) or (avail is not None and memory > MEMORY_SHARE * avail):
        have = "unknown" if avail is None else describe_bytes(avail)
        raise TooLarge(f"{what} needs about {describe_bytes(memory)} of memory, {have} available: {hint}")
    seconds = flops / FLOP_RATE
    if not math.isfinite(seconds) or seconds > TIME_LIMIT:
        raise TooLarge(f"{what} would take about {seconds / 3600:.3g} h (limit {TIME_LIMIT / 3600:g} h): {hint}")


def require_resolution(measure: str, value: float, floor: float, comfortable: float, remedy: str, argument: str | None = None) -> None:
    """Check a discretisation ``measure`` ("elements per contact pulse length") against its floor.

    Below ``floor``: :class:`InputError` (with ``argument`` for the edge to name
    the file key) giving the value, the minimum and the ``remedy``. Below
    ``comfortable``: a :class:`SoftimpactWarning`. NaN counts as below the floor.
    """
    if not value >= floor:
        raise InputError(f"{measure} is {value:.3g}, below the minimum {floor:g}: {remedy}", argument)
    if value < comfortable:
        warnings.warn(f"{measure} is {value:.3g} ({comfortable:g} advised): {remedy}", SoftimpactWarning, stacklevel=2)
