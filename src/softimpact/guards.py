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

__all__ = [
    "IGNORE_LIMITS_ENV",
    "MEMORY_SHARE",
    "TIME_LIMIT",
    "FLOP_RATE",
    "available_memory",
    "require_resources",
    "require_resolution",
    "describe_bytes",
    "power_law_rise",
    "contact_rise",
    "require_contact_steps",
]

IGNORE_LIMITS_ENV = "SOFTIMPACT_IGNORE_LIMITS"  # set to 1 to run past the resource guard
MEMORY_SHARE = 0.8  # refuse a run whose estimate exceeds this share of the memory available now
TIME_LIMIT = 3600.0  # s: refuse a run estimated to take longer than an hour
RISE_SAMPLES = 4001  # approaches sampled for a contact law's rigid-wall rise (contact_rise): ~1e-4 relative
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


def power_law_rise(stiffness: float, exponent: float, mass: float, velocity: float) -> float:
    """Time [s] from first touch to the peak force of a mass ``mass`` [kg] striking a rigid wall at ``velocity`` [m/s]
    through F = K·α^n (Hertz: n = 3/2, eq 1): the approach peaks at α_m = ((n+1)·m·V²/(2K))^(1/(n+1)) (energy), and
    t = ∫₀^α_m dα/sqrt(V² − 2Kα^(n+1)/((n+1)m)) = (α_m/V)·√π·Γ(1 + 1/(n+1))/Γ(½ + 1/(n+1)) (1.4716·α_m/V for Hertz,
    half of the 2.94·α_m/V contact duration). The rigid wall gives the shortest rise: a compliant target's is longer."""
    p = 1.0 / (exponent + 1.0)
    alpha_m = ((exponent + 1.0) * mass * velocity**2 / (2.0 * stiffness)) ** p
    return alpha_m / velocity * math.sqrt(math.pi) * math.gamma(1.0 + p) / math.gamma(0.5 + p)


def contact_rise(law, mass: float, velocity: float, diameter: float, time_step: float | None = None) -> float | None:
    """The rigid-wall time to peak force [s] of an impactor (``mass`` [kg], ``velocity`` [m/s], ``diameter`` [m]) through
    a contact ``law`` (bound to ``time_step`` [s] when its memory needs one): Hertz's F = K·α^n in closed form
    (:func:`power_law_rise`); any other law that starts from zero force, from its loading branch's elastic work
    W(α) = ∫F(α, 0) dα (t = ∫₀^α_m dα/sqrt(V² − 2W/m), W(α_m) = m·V²/2, on a grid of :data:`RISE_SAMPLES` approaches);
    None for a law whose force jumps at first touch (a soft missile's flow: its shock has no rise to resolve), or one
    that does not stop the impactor within its radius, or cannot say."""
    import numpy as np

    if not (velocity > 0 and mass > 0 and diameter > 0):
        return None
    try:
        from .models.protocols import HistoryLaw, StepBoundLaw

        if time_step is not None and isinstance(law, StepBoundLaw):
            law = law.for_time_step(time_step)
        if isinstance(law, HistoryLaw):
            law = law.branch(law.initial_state())
        if type(law).__name__ == "HertzLaw":
            return power_law_rise(float(law.K), float(law.exponent), mass, velocity)
        energy = 0.5 * mass * velocity**2
        touch = float(law.force(1e-9 * diameter, velocity))
        if not math.isfinite(touch) or touch > 1e-6 * energy / diameter:
            return None  # the force jumps at first touch (a flow's shock): no rise
        alpha = 0.5 * diameter * np.linspace(0.0, 1.0, RISE_SAMPLES) ** 2  # finer near first touch
        force = np.array([float(law.force(a, 0.0)) for a in alpha])
        work = np.concatenate(([0.0], np.cumsum(0.5 * (force[1:] + force[:-1]) * np.diff(alpha))))
        if not work[-1] >= energy:
            return None  # the law does not stop the impactor within its radius: no elastic rise to estimate
        k = int(np.searchsorted(work, energy))
        alpha_m = alpha[k - 1] + (energy - work[k - 1]) / (work[k] - work[k - 1]) * (alpha[k] - alpha[k - 1])
        # α = α_m(1 − u²): the integrand 2α_m·u/speed stays finite at the turning point (u → 0)
        u = np.linspace(0.0, 1.0, RISE_SAMPLES)
        a = alpha_m * (1.0 - u * u)
        speed = np.sqrt(np.maximum(velocity**2 - 2.0 * np.interp(a, alpha, work) / mass, 0.0))
        f = np.divide(2.0 * alpha_m * u, speed, out=np.zeros_like(u), where=speed > 0)
        f[0] = f[1]  # the finite limit at the turning point
        return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(u)))
    except (ArithmeticError, ValueError, TypeError, AttributeError, InputError):
        return None


def _down(x: float, digits: int = 3) -> str:
    """``x`` > 0 rounded down to ``digits`` significant digits: an advised maximum that, taken as written, passes."""
    scale = 10.0 ** (digits - 1 - math.floor(math.log10(x)))
    return f"{math.floor(x * scale) / scale:g}"


def require_contact_steps(law, mass: float, velocity: float, diameter: float, time_step: float, argument: str | None = "time_step") -> None:
    """Refuse a coupled impact whose time step cannot resolve its contact force's rise: the rigid-wall rise
    (:func:`contact_rise`, the shortest the target allows) in fewer than
    :data:`softimpact.fem.linear.MIN_STEPS_PER_RISE` steps, the floor of the beam and plate commands' prescribed
    pulses. InputError (exit 2) with the rise and the largest step that resolves it."""
    from .fem.linear import MIN_STEPS_PER_RISE

    rise = contact_rise(law, mass, velocity, diameter, time_step)
    if rise is not None and rise < MIN_STEPS_PER_RISE * time_step:
        raise InputError(
            f"a time step of {time_step * 1e6:.4g} us cannot resolve the contact force's rise: on a rigid wall it peaks "
            f"{rise * 1e6:.4g} us after first touch (the target's compliance only lengthens it); give solver.time_step = "
            f"{_down(rise / MIN_STEPS_PER_RISE * 1e6)} us or less (time_of_peak/{MIN_STEPS_PER_RISE})",
            argument,
        )
