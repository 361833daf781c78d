"""Force pulses F(t) [N], t [s] from first contact. Each has ``__call__(t)``,
``impulse`` [N·s], ``duration`` [s] (the time after which F = 0) and ``time_of_peak`` [s]
(:class:`softimpact.models.protocols.Pulse`).
The eq-15 fit to a record is :func:`softimpact.models.pulse_fit.fit_pulse`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError

__all__ = ["SkewedPulse", "TailedPulse", "TabulatedPulse"]


@dataclass(frozen=True)
class SkewedPulse:
    """Eq (15): quarter sine up to t_F0, quarter cosine down to T, zero after.

    F0 [N], time_of_peak t_F0 [s], duration T [s], with 0 < t_F0 < T. Its impulse
    is 2·F0·T/π, whatever t_F0 (each quarter wave holds 2/π of its rectangle).
    t_F0 = T/2 is the symmetric half sine of a Hertzian impact.
    """

    peak_force: float
    time_of_peak: float
    duration: float

    def __post_init__(self):
        if not (math.isfinite(self.peak_force) and self.peak_force > 0):
            raise InputError(f"pulse: peak_force must be positive, got {self.peak_force!r}")
        if not (0 < self.time_of_peak < self.duration and math.isfinite(self.duration)):
            raise InputError(f"pulse: need 0 < time_of_peak < duration, got time_of_peak={self.time_of_peak!r}, duration={self.duration!r}")

    def __call__(self, t):
        t = np.asarray(t, dtype=float)
        F0, tp, T = self.peak_force, self.time_of_peak, self.duration
        rise = F0 * np.sin(np.pi * t / (2.0 * tp))
        fall = F0 * np.cos(np.pi * (t - tp) / (2.0 * (T - tp)))
        return np.where(t <= 0, 0.0, np.where(t < tp, rise, np.where(t < T, fall, 0.0)))

    @property
    def impulse(self) -> float:
        return 2.0 * self.peak_force * self.duration / math.pi

    @property
    def skewness(self) -> float:
        """t_F0 / T (α3 of eq 6)."""
        return self.time_of_peak / self.duration


@dataclass(frozen=True)
class TailedPulse:
    """An eq-(15) main pulse that, once it has fallen to ``level``·F0, decays
    exponentially with time constant ``decay`` [s] instead of dropping to zero:
    the long trailing tail of a soft impact that the paper's T ignores (Fig 7).

    Continuous; the tail adds ``extra_impulse`` to the main pulse's 2F0T/π.
    ``duration`` is where the tail has fallen to 1e-3 of its start.
    """

    main: SkewedPulse
    level: float
    decay: float

    def __post_init__(self):
        if not (0 < self.level < 1 and self.decay > 0):
            raise InputError(f"tail: need 0 < level < 1 and decay > 0, got {self.level!r}, {self.decay!r}")

    @property
    def tail_start(self) -> float:
        """Where the falling quarter cosine reaches level·F0."""
        m = self.main
        return m.time_of_peak + 2.0 * (m.duration - m.time_of_peak) / math.pi * math.acos(self.level)

    def __call__(self, t):
        t = np.asarray(t, dtype=float)
        ts = self.tail_start
        tail = self.level * self.main.peak_force * np.exp(-np.maximum(t - ts, 0.0) / self.decay)
        return np.where(t < ts, self.main(t), tail)

    @property
    def extra_impulse(self) -> float:
        m = self.main
        cut = m.peak_force * 2.0 * (m.duration - m.time_of_peak) / math.pi * (1.0 - math.sin(math.acos(self.level)))
        return self.level * m.peak_force * self.decay - cut

    @property
    def impulse(self) -> float:
        return self.main.impulse + self.extra_impulse

    @property
    def duration(self) -> float:
        return self.tail_start + self.decay * math.log(1e3)

    @property
    def time_of_peak(self) -> float:
        """The main pulse's t_F0: the tail starts below F0 (level < 1) and only falls."""
        return self.main.time_of_peak

    @classmethod
    def with_impulse(cls, main: SkewedPulse, level: float, impulse: float) -> TailedPulse:
        """The tail whose decay makes the total impulse ``impulse`` (≥ the main pulse's)."""
        probe = cls(main, level, 1.0)
        cut = level * main.peak_force * 1.0 - probe.extra_impulse
        decay = (impulse - main.impulse + cut) / (level * main.peak_force)
        if decay <= 0:
            raise InputError(f"tail: impulse {impulse!r} N·s is below what the main pulse alone carries ({main.impulse!r})")
        return cls(main, level, decay)


@dataclass(frozen=True)
class TabulatedPulse:
    """A force history given as samples; linear in between, zero outside."""

    time: np.ndarray
    force: np.ndarray

    def __post_init__(self):
        t, f = np.asarray(self.time, float), np.asarray(self.force, float)
        if t.ndim != 1 or t.shape != f.shape or t.size < 2:
            raise InputError("force table: time and force must be 1-D of equal length >= 2")
        if not np.all(np.diff(t) > 0):
            raise InputError("force table: time must increase strictly")
        if not (np.all(np.isfinite(t)) and np.all(np.isfinite(f))):
            raise InputError("force table: contains NaN or infinite values")

    def __call__(self, t):
        return np.interp(np.asarray(t, float), self.time, self.force, left=0.0, right=0.0)

    @property
    def impulse(self) -> float:
        return float(np.trapezoid(self.force, self.time))

    @property
    def duration(self) -> float:
        return float(self.time[-1])

    @property
    def time_of_peak(self) -> float:
        """The time of the largest sample (the first, where several are equal): linear in between, F peaks on a sample."""
        return float(self.time[int(np.argmax(self.force))])
