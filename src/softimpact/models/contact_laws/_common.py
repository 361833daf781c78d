"""What the contact laws share: the positive-parameter check."""

from __future__ import annotations

import math

from ...errors import InputError


def _positive(name: str, value: float) -> None:
    if not (math.isfinite(value) and value > 0):
        raise InputError(f"contact: {name} must be positive, got {value!r}")
