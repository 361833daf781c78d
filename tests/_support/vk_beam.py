"""Oracle for the large-deflection beam tests: a von Kármán Euler–Bernoulli beam with immovable ends.

Written from the beam's energy, independently of the package's plane elements (the von Kármán beam of
Reddy's *An Introduction to Nonlinear Finite Element Analysis*, its chapter on the bending of straight beams): axial strain
ε = u' + ½ w'², curvature κ = w'', energy Π = ½ ∫ EA ε² + EI κ² dx − P w(x_P). With both ends
axially immovable (u(0) = u(L) = 0) and no axial load, the axial force is constant along the beam and
minimising over u gives ε ≡ ε̄ = (1/L) ∫ ½ w'² dx exactly, so

    Π(w) = ½ ∫ EI w''² dx + ½ EA L ε̄² − P w(x_P),

a function of w alone (no membrane locking: the axial field is eliminated, not interpolated). w is
interpolated by cubic Hermite elements (value and slope per node); with K_b the bending stiffness and
G = ∫ φ'φ'ᵀ dx (the classical geometric matrix), ε̄ = wᵀ G w / (2L) and

    ∇Π = K_b w + EA ε̄ G w − P e,   ∇²Π = K_b + EA ε̄ G + (EA/L) (G w)(G w)ᵀ,

solved by Newton over increasing loads. Its small-load limit is the clamped–clamped beam's
P L³/(192 EI) (the classical fixed–fixed beam under a central load) and at w ≫ h the string-like P ∝ w³.
"""

import numpy as np


def _element_matrices(le: float):
    """Hermite bending matrix ∫ φ''φ''ᵀ and geometric matrix ∫ φ'φ'ᵀ over one element of length le."""
    kb = (
        np.array([[12, 6 * le, -12, 6 * le], [6 * le, 4 * le**2, -6 * le, 2 * le**2], [-12, -6 * le, 12, -6 * le], [6 * le, 2 * le**2, -6 * le, 4 * le**2]])
        / le**3
    )
    g = np.array([[36, 3 * le, -36, 3 * le], [3 * le, 4 * le**2, -3 * le, -(le**2)], [-36, -3 * le, 36, -3 * le], [3 * le, -(le**2), -3 * le, 4 * le**2]]) / (
        30 * le
    )
    return kb, g


def clamped_centre_deflections(loads, *, length, EI, EA, elements=40):
    """Mid-span deflections [m] of the clamped–clamped beam (immovable ends) under the central point loads
    ``loads`` [N] (increasing, the same sign), by Newton from the previous load's solution."""
    if elements % 2:
        raise ValueError("elements must be even: the load sits on the middle node")
    le = length / elements
    kb, g = _element_matrices(le)
    n = 2 * (elements + 1)
    Kb, G = np.zeros((n, n)), np.zeros((n, n))
    for e in range(elements):
        i = slice(2 * e, 2 * e + 4)
        Kb[i, i] += EI * kb
        G[i, i] += g
    free = np.arange(2, n - 2)  # clamped: w = w' = 0 at both ends
    Kb, G = Kb[np.ix_(free, free)], G[np.ix_(free, free)]
    centre = 2 * (elements // 2) - 2  # the middle node's w among the free DOFs
    w = np.zeros(free.size)
    out = []
    for P in loads:
        f = np.zeros(free.size)
        f[centre] = P
        for _ in range(100):
            Gw = G @ w
            eps = 0.5 * (w @ Gw) / length
            r = Kb @ w + EA * eps * Gw - f
            J = Kb + EA * eps * G + (EA / length) * np.outer(Gw, Gw)
            dw = np.linalg.solve(J, -r)
            w = w + dw
            if np.linalg.norm(dw) <= 1e-11 * max(np.linalg.norm(w), 1e-300):
                break
        else:
            raise RuntimeError(f"Newton did not converge at P = {P!r} N")
        out.append(w[centre])
    return np.array(out)
