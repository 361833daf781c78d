"""Oracle for the plate tests: FSDT Navier solution of a simply supported symmetric cross-ply plate.

Written from the governing equations (Reddy, *Mechanics of Laminated Composite
Plates and Shells*, §6.3), independently of the package's element: with
w = W sin αx sin βy, φx = X cos αx sin βy, φy = Y sin αx cos βy,
α = mπ/a, β = nπ/b, each (m, n) is a 3-DOF system M ẍ + K x = (q_mn, 0, 0) with

    K = [[S11α² + S22β², S11α,                  S22β                 ],
         [S11α,          D11α² + D66β² + S11,   (D12 + D66)αβ        ],
         [S22β,          (D12 + D66)αβ,          D66α² + D22β² + S22 ]],
    M = diag(I0, I2, I2),

q_mn = (4/ab)∬ q sin αx sin βy dx dy. The transient is the exact response of
each mode to the force sampled on a fine grid and linear in between
(Nigam–Jennings), i.e. the exact Duhamel integral of that interpolant.
"""

import math

import numpy as np


def clt_uniform_deflection(D, a, b, q, x, y, terms=199):
    """CLT (Kirchhoff) Navier series for w under uniform pressure q (specially orthotropic)."""
    m = np.arange(1, terms + 1, 2)[:, None]
    n = np.arange(1, terms + 1, 2)[None, :]
    qmn = 16 * q / (math.pi**2 * m * n)
    den = math.pi**4 * (D[0, 0] * (m / a) ** 4 + 2 * (D[0, 1] + 2 * D[2, 2]) * (m * n / (a * b)) ** 2 + D[1, 1] * (n / b) ** 4)
    return float(np.sum(qmn / den * np.sin(m * math.pi * x / a) * np.sin(n * math.pi * y / b)))


def mode_matrices(D, S, I0, I2, alpha, beta):
    """K and M of the (α, β) Navier mode, shape (..., 3, 3)."""
    al, be = np.broadcast_arrays(alpha, beta)
    K = np.zeros(al.shape + (3, 3))
    K[..., 0, 0] = S[0, 0] * al**2 + S[1, 1] * be**2
    K[..., 0, 1] = K[..., 1, 0] = S[0, 0] * al
    K[..., 0, 2] = K[..., 2, 0] = S[1, 1] * be
    K[..., 1, 1] = D[0, 0] * al**2 + D[2, 2] * be**2 + S[0, 0]
    K[..., 1, 2] = K[..., 2, 1] = (D[0, 1] + D[2, 2]) * al * be
    K[..., 2, 2] = D[2, 2] * al**2 + D[1, 1] * be**2 + S[1, 1]
    M = np.zeros_like(K)
    M[..., 0, 0], M[..., 1, 1], M[..., 2, 2] = I0, I2, I2
    return K, M


def modes(D, S, I0, I2, alpha, beta):
    """ω (..., 3) [rad/s] and M-orthonormal shapes (..., 3, 3) (columns) of each (α, β)."""
    K, M = mode_matrices(D, S, I0, I2, alpha, beta)
    s = 1.0 / np.sqrt(np.diagonal(M, axis1=-2, axis2=-1))  # M is diagonal: symmetric scaling
    Kt = K * s[..., :, None] * s[..., None, :]
    lam, vec = np.linalg.eigh(Kt)
    return np.sqrt(lam), vec * s[..., :, None]


def frequencies(D, S, I0, I2, a, b, count, terms=12):
    """The ``count`` lowest natural frequencies [Hz] over all (m, n) (lowest branch of each)."""
    m, n = np.meshgrid(np.arange(1, terms + 1), np.arange(1, terms + 1), indexing="ij")
    w, _ = modes(D, S, I0, I2, m * math.pi / a, n * math.pi / b)
    return np.sort(w[..., 0].ravel())[:count] / (2 * math.pi)


def cosine_patch_coefficients(a, b, xc, yc, r, m, n, n_rho=64, n_theta=160):
    """q_mn of a unit force spread as cos(πρ/2r)/(4r²(1 − 2/π)) over a disc (polar quadrature)."""
    g, wg = np.polynomial.legendre.leggauss(n_rho)
    rho, wr = 0.5 * r * (g + 1), 0.5 * r * wg
    th = np.arange(n_theta) * 2 * math.pi / n_theta
    R, T = np.meshgrid(rho, th, indexing="ij")
    wgt = (wr[:, None] * R * (2 * math.pi / n_theta)) * np.cos(math.pi * R / (2 * r)) / (4 * r**2 * (1 - 2 / math.pi))
    X, Y = (xc + R * np.cos(T)).ravel(), (yc + R * np.sin(T)).ravel()
    Sx = np.sin(np.outer(m * math.pi / a, X)) * wgt.ravel()
    Sy = np.sin(np.outer(n * math.pi / b, Y))
    return 4.0 / (a * b) * Sx @ Sy.T


def exact_modal_response(omega, f, dt, every=1):
    """η(t_k), k = 0, every, 2·every, …, of η'' + ω²η = f(t), at rest at t = 0, f sampled at
    t_k = k·dt and linear between samples (exact for that interpolant)."""
    eta = np.zeros(omega.shape)
    deta = np.zeros(omega.shape)
    c, s = np.cos(omega * dt), np.sin(omega * dt)
    w2 = omega**2
    out = np.zeros(((f.size - 1) // every + 1,) + omega.shape)
    for k in range(f.size - 1):
        slope = (f[k + 1] - f[k]) / (dt * w2)
        C = eta - f[k] / w2
        Dd = (deta - slope) / omega
        eta, deta = C * c + Dd * s + f[k + 1] / w2, -C * omega * s + Dd * omega * c + slope
        if (k + 1) % every == 0:
            out[(k + 1) // every] = eta
    return out


def newmark_modal_response(omega, f, dt, every=1):
    """η(t_k), k = 0, every, …, of η'' + ω²η = f(t) stepped by Newmark average acceleration from rest,
    f sampled at t_k = k·dt: what the plate FE does to each of its modes, so that the FE's difference
    from the series stepped this way is its spatial error alone."""
    a0, a2 = 4 / dt**2, 4 / dt
    eta, deta = np.zeros(omega.shape), np.zeros(omega.shape)
    acc = np.full(omega.shape, float(f[0]))
    keff = omega**2 + a0
    out = np.zeros(((f.size - 1) // every + 1,) + omega.shape)
    for k in range(f.size - 1):
        eta1 = (f[k + 1] + a0 * eta + a2 * deta + acc) / keff
        acc1 = a0 * (eta1 - eta) - a2 * deta - acc
        deta = deta + dt / 2 * (acc + acc1)
        eta, acc = eta1, acc1
        if (k + 1) % every == 0:
            out[(k + 1) // every] = eta
    return out


def transient(section, a, b, center, radius, pulse, times, deflection_points, strain_gauges, terms=159, substeps=4, newmark_dt=None):
    """Navier FSDT response to ``pulse`` (pushing down, −z) on a fixed cosine patch of ``radius`` about ``center``.

    ``strain_gauges``: (x, y, direction "x"|"y", length) on the bottom face. ``newmark_dt``: instead of
    the exact modal responses, each mode stepped by average acceleration with that step (dividing
    the spacing of ``times``).
    Returns (deflections (n_points, n_t), strains (n_gauges, n_t)).
    """
    D, S, I0, I2, h = section.D, section.S, section.I0, section.I2, section.thickness
    m = np.arange(1, terms + 1, 2 if abs(center[0] - a / 2) < 1e-12 * a else 1)
    n = np.arange(1, terms + 1, 2 if abs(center[1] - b / 2) < 1e-12 * b else 1)
    al, be = np.meshgrid(m * math.pi / a, n * math.pi / b, indexing="ij")
    q = cosine_patch_coefficients(a, b, *center, radius, m, n)
    omega, vec = modes(D, S, I0, I2, al, be)  # (M, N, 3), (M, N, 3, 3)
    part = -vec[..., 0, :] * q[..., None]  # modal load of a unit force pushing down (−z): −φ_k[W]·q_mn
    dt = times[1] - times[0]
    if newmark_dt is not None:
        substeps = int(round(dt / newmark_dt))
    fine = np.arange((times.size - 1) * substeps + 1) * dt / substeps
    if newmark_dt is None:
        eta = exact_modal_response(omega.ravel(), np.asarray(pulse(fine), float), dt / substeps, substeps)
    else:
        eta = newmark_modal_response(omega.ravel(), np.asarray(pulse(fine), float), dt / substeps, substeps)
    amp = eta.reshape((times.size,) + omega.shape) * part  # (n_t, M, N, 3)
    W = np.einsum("tmnk,mnk->tmn", amp, vec[..., 0, :])
    X = np.einsum("tmnk,mnk->tmn", amp, vec[..., 1, :])
    Y = np.einsum("tmnk,mnk->tmn", amp, vec[..., 2, :])
    defl = [np.einsum("tmn,m,n->t", W, np.sin(m * math.pi * x / a), np.sin(n * math.pi * y / b)) for x, y in deflection_points]
    strains = []
    for x, y, direction, length in strain_gauges:
        # bottom face z = −h/2: εx = −h/2·φx,x = (h/2)α X sin αx sin βy, εy likewise with β Y
        if direction == "x":
            k = m * math.pi / a
            avg = np.sinc(k * length / (2 * math.pi)) if length > 0 else 1.0
            strains.append(0.5 * h * np.einsum("tmn,m,n->t", X, k * np.sin(k * x) * avg, np.sin(n * math.pi * y / b)))
        else:
            k = n * math.pi / b
            avg = np.sinc(k * length / (2 * math.pi)) if length > 0 else 1.0
            strains.append(0.5 * h * np.einsum("tmn,m,n->t", Y, np.sin(m * math.pi * x / a), k * np.sin(k * y) * avg))
    return np.array(defl), np.array(strains)
