"""A hemispherical-ended cylinder (the substitute bird's shape) crushed or flowing from its front pole, SI.

Diameter d (radius R = d/2) and overall length L ≥ d (a cylinder of length c = L − d between two hemispheres);
L = d is the sphere. Its volume is

    V = π·R²·c + 4·π·R³/3 = π·d³·(3λ − 1)/12,   λ = L/d        (λ = 2: V = 5·π·d³/12),

so a body of mass m and density ρ has the diameter d = (12·m / (π·ρ·(3λ − 1)))^(1/3) (:func:`capsule_diameter`).

Crushed to the depth s ∈ [0, L] from its front pole (the nose first), its section at the crushing front and the
volume crushed are, with t = L − s on the rear hemisphere,

    A(s) = π·s·(d − s),        V_c(s) = π·(R·s² − s³/3)                   (s ≤ R: the nose),
    A(s) = π·R²,               V_c(s) = 2·π·R³/3 + π·R²·(s − R)           (R ≤ s ≤ R + c: the cylinder),
    A(s) = π·t·(d − t),        V_c(s) = V − π·(R·t² − t³/3)               (s ≥ R + c: the tail).

As for the sphere (:mod:`softimpact.models.crushing_law`), the uncrushed remainder, the fraction φ(s) = 1 − V_c/V of
the mass, moves at ṡ and the crushed material has stopped at the target: the centre of mass has advanced

    X(s) = ∫₀ˢ φ ds' = s − I(s)/V,     I(s) = ∫₀ˢ V_c ds',

    I(s) = π·(R·s³/3 − s⁴/12)                                                           (s ≤ R),
    I(s) = π·R⁴/4 + 2·π·R³·(s − R)/3 + π·R²·(s − R)²/2                                   (cylinder),
    I(s) = I(R + c) + V·(s − R − c) − π·R⁴/4 + π·(R·t³/3 − t⁴/12)                          (tail),

X(L) = L/2 (the whole body deposited; derived here, and reduced to the sphere's X/d = u − u³ + u⁴/2 at c = 0).
"""

from __future__ import annotations

import functools
import math

__all__ = ["capsule_volume", "capsule_diameter", "capsule_section", "capsule_crushed_volume", "capsule_advance", "capsule_depth"]

DEPTH_TOL = 1e-14  # relative tolerance on s/L in the inversion of X(s)


def capsule_volume(d: float, length: float) -> float:
    """V = π·d²/4·(L − d) + π·d³/6 [m³] of a hemispherical-ended cylinder of diameter ``d`` and length ``length`` [m]."""
    return math.pi * d * d / 4.0 * (length - d) + math.pi * d**3 / 6.0


def capsule_diameter(mass: float, density: float, aspect_ratio: float) -> float:
    """d = (12·m / (π·ρ·(3λ − 1)))^(1/3) [m] of a hemispherical-ended cylinder of ``mass`` [kg], ``density``
    [kg/m³] and ``aspect_ratio`` λ = L/d ≥ 1 (module docstring)."""
    return (12.0 * mass / (math.pi * density * (3.0 * aspect_ratio - 1.0))) ** (1.0 / 3.0)


def capsule_section(s: float, d: float, length: float) -> tuple[float, float]:
    """(A [m²], dA/ds [m]) of the section at the depth ``s`` [m] from the front pole (module docstring); (0, 0)
    outside (0, L)."""
    if not 0.0 < s < length:
        return 0.0, 0.0
    r = 0.5 * d
    if s <= r:
        return math.pi * s * (d - s), math.pi * (d - 2.0 * s)
    t = length - s
    if t <= r:
        return math.pi * t * (d - t), -math.pi * (d - 2.0 * t)
    return math.pi * r * r, 0.0


def capsule_crushed_volume(s: float, d: float, length: float) -> float:
    """V_c(s) [m³], the volume ahead of the depth ``s`` [m] (module docstring); 0 below 0, V beyond L."""
    r, V = 0.5 * d, capsule_volume(d, length)
    if s <= 0.0:
        return 0.0
    if s >= length:
        return V
    if s <= r:
        return math.pi * (r * s * s - s**3 / 3.0)
    t = length - s
    if t <= r:
        return V - math.pi * (r * t * t - t**3 / 3.0)
    return 2.0 * math.pi * r**3 / 3.0 + math.pi * r * r * (s - r)


def _integral(s: float, d: float, length: float) -> float:
    """I(s) = ∫₀ˢ V_c ds' [m⁴] (module docstring), s ∈ [0, L]."""
    r, V = 0.5 * d, capsule_volume(d, length)
    c = length - d
    if s <= r:
        return math.pi * (r * s**3 / 3.0 - s**4 / 12.0)
    front = math.pi * r**4 / 4.0
    if s <= r + c:
        x = s - r
        return front + 2.0 * math.pi * r**3 * x / 3.0 + math.pi * r * r * x * x / 2.0
    t = length - s
    body = front + 2.0 * math.pi * r**3 * c / 3.0 + math.pi * r * r * c * c / 2.0
    return body + V * (s - r - c) - math.pi * r**4 / 4.0 + math.pi * (r * t**3 / 3.0 - t**4 / 12.0)


def capsule_advance(s: float, d: float, length: float) -> tuple[float, float]:
    """(X [m], φ = dX/ds) of the depth ``s`` [m]: the centre of mass's advance and the remaining fraction of the mass
    (module docstring); s clipped to [0, L]."""
    s = min(max(s, 0.0), length)
    V = capsule_volume(d, length)
    return s - _integral(s, d, length) / V, 1.0 - capsule_crushed_volume(s, d, length) / V


@functools.lru_cache(maxsize=256)  # a coupled step asks for the same depth several times (radius, force, stiffness at one α)
def capsule_depth(x: float, d: float, length: float) -> float:
    """s [m] of a capsule whose centre of mass has advanced ``x`` [m] ∈ [0, L/2] (the inverse of
    :func:`capsule_advance`, monotone since φ ≥ 0): Newton safeguarded by bisection; 0 for x ≤ 0, L for x ≥ L/2."""
    if x <= 0.0:
        return 0.0
    if x >= 0.5 * length:
        return length
    lo, hi = 0.0, length
    s = min(x, 0.999 * length)  # X ≈ s for a shallow crush
    for _ in range(200):
        X, phi = capsule_advance(s, d, length)
        r = X - x
        if r > 0.0:
            hi = s
        else:
            lo = s
        step = r / max(phi, 1e-300)
        nxt = s - step
        if abs(step) <= DEPTH_TOL * max(s, 1e-300):
            return min(max(nxt, 0.0), length)
        if not lo < nxt < hi:
            nxt = 0.5 * (lo + hi)
        if abs(nxt - s) <= DEPTH_TOL * max(s, 1e-300) or hi - lo <= DEPTH_TOL * length:
            return nxt
        s = nxt
    return s
