"""Oracle for the von Kármán plate tests: a Ritz double-series solution of the von Kármán plate.

Written from the energy of a thin (Kirchhoff) isotropic plate with von Kármán membrane strains
(Timoshenko & Woinowsky-Krieger, *Theory of Plates and Shells*, 2nd ed., ch. 13; Reddy,
*Theory and Analysis of Elastic Plates and Shells*, 2nd ed., §7.2), independently of the
package's elements: on the square [0, a]², immovable edges (u = v = 0 on the boundary),

    w = Σ W_mn X_m(x) X_n(y)  (m, n odd),    X_m = sin mπx/a (simply supported)
                                            or sin πx/a · sin mπx/a (clamped: zero value and slope),
    u = Σ U_mn sin 2mπx/a · sin (2n−1)πy/a,   v likewise with x and y exchanged,

    Π = D/2 ∫ (Δw)² − 2(1−ν)(w,xx w,yy − w,xy²) + ½ ∫ ε0ᵀ A ε0 − q ∫ w,
    ε0 = (u,x + ½w,x², v,y + ½w,y², u,y + v,x + w,x w,y),

stationary by Newton (exact gradient and Hessian of Π, Gauss–Legendre quadrature on a
tensor grid), the loads taken in increasing order from the previous solution. The series
converges as terms are added (the tests compare two truncations), and its linear limit gives
the Navier coefficients 0.00406 (simply supported) and 0.00126 (clamped) of q a⁴/D
(Timoshenko & Woinowsky-Krieger §30 and §44, as quoted in NAFEMS R0015 LE5 and the
femorph-solver verification pages).
"""

import numpy as np


def _x_functions(m, t, k, clamped):
    """X_m and its first two derivatives at t."""
    if not clamped:
        return np.sin(m * k * t), m * k * np.cos(m * k * t), -((m * k) ** 2) * np.sin(m * k * t)
    s1, c1, sm, cm = np.sin(k * t), np.cos(k * t), np.sin(m * k * t), np.cos(m * k * t)
    return s1 * sm, k * (c1 * sm + m * s1 * cm), k * k * (-(1 + m * m) * s1 * sm + 2 * m * c1 * cm)


def centre_deflections(loads, *, a, h, E, nu, clamped, n_w=3, n_u=6, n_quad=40):
    """Centre deflections [m] under the uniform pressures ``loads`` [Pa] (increasing)."""
    g, wg = np.polynomial.legendre.leggauss(n_quad)
    s, ws = 0.5 * (g + 1) * a, 0.5 * wg * a
    X, Y = np.meshgrid(s, s, indexing="ij")
    X, Y, Wq = X.ravel(), Y.ravel(), np.outer(ws, ws).ravel()
    k = np.pi / a
    odd = range(1, 2 * n_w, 2)
    Wb = []
    for m in odd:
        for n in odd:
            fx, fx1, fx2 = _x_functions(m, X, k, clamped)
            fy, fy1, fy2 = _x_functions(n, Y, k, clamped)
            Wb.append((fx * fy, fx1 * fy, fx * fy1, fx2 * fy, fx * fy2, fx1 * fy1))
    Wb = np.array(Wb)  # (n_w², 6, points): w, w,x, w,y, w,xx, w,yy, w,xy
    Ub, Vb = [], []
    for m in range(1, n_u + 1):
        for n in range(1, n_u + 1):
            p, q = 2 * m * k, (2 * n - 1) * k
            Ub.append((p * np.cos(p * X) * np.sin(q * Y), q * np.sin(p * X) * np.cos(q * Y)))  # u,x  u,y
            Vb.append((q * np.cos(q * X) * np.sin(p * Y), p * np.sin(q * X) * np.cos(p * Y)))  # v,x  v,y
    Ub, Vb = np.array(Ub), np.array(Vb)
    D = E * h**3 / (12 * (1 - nu**2))
    A = E * h / (1 - nu**2) * np.array([[1, nu, 0], [nu, 1, 0], [0, 0, (1 - nu) / 2]])
    kxx, kyy, kxy = Wb[:, 3], Wb[:, 4], Wb[:, 5]
    Kb = D * ((kxx + kyy) * Wq) @ (kxx + kyy).T - D * (1 - nu) * ((kxx * Wq) @ kyy.T + (kyy * Wq) @ kxx.T - 2 * (kxy * Wq) @ kxy.T)
    F1 = Wb[:, 0] @ Wq
    nw, nuu = Wb.shape[0], Ub.shape[0]
    centre = np.array([_x_functions(m, a / 2, k, clamped)[0] * _x_functions(n, a / 2, k, clamped)[0] for m in odd for n in odd])
    c = np.zeros(nw + 2 * nuu)
    out = []
    for q in loads:
        for _ in range(50):
            cw, cu, cv = c[:nw], c[nw : nw + nuu], c[nw + nuu :]
            wx, wy = cw @ Wb[:, 1], cw @ Wb[:, 2]
            e = np.array([cu @ Ub[:, 0] + 0.5 * wx * wx, cv @ Vb[:, 1] + 0.5 * wy * wy, cu @ Ub[:, 1] + cv @ Vb[:, 0] + wx * wy])
            N = A @ e
            Bt = np.zeros((3, c.size, X.size))  # δε0 per unknown
            Bt[0, :nw], Bt[1, :nw], Bt[2, :nw] = Wb[:, 1] * wx, Wb[:, 2] * wy, Wb[:, 1] * wy + Wb[:, 2] * wx
            Bt[0, nw : nw + nuu], Bt[2, nw : nw + nuu] = Ub[:, 0], Ub[:, 1]
            Bt[1, nw + nuu :], Bt[2, nw + nuu :] = Vb[:, 1], Vb[:, 0]
            r = np.einsum("iap,ip->a", Bt, N * Wq)
            r[:nw] += Kb @ cw - q * F1
            BW = Bt * Wq
            J = sum(A[i, j] * BW[i] @ Bt[j].T for i in range(3) for j in range(3) if A[i, j] != 0.0)
            J[:nw, :nw] += Kb + ((N[0] * Wq) * Wb[:, 1]) @ Wb[:, 1].T + ((N[1] * Wq) * Wb[:, 2]) @ Wb[:, 2].T
            J[:nw, :nw] += ((N[2] * Wq) * Wb[:, 1]) @ Wb[:, 2].T + ((N[2] * Wq) * Wb[:, 2]) @ Wb[:, 1].T
            dc = np.linalg.solve(J, -r)
            c = c + dc
            if np.linalg.norm(dc) <= 1e-12 * np.linalg.norm(c):
                break
        out.append(centre @ c[:nw])
    return np.array(out)


def duffing_period(omega0, eps, amplitude, n=2000):
    """Exact period of x'' + ω0² x + ε x³ = 0 released at rest from x = amplitude:
    T = 4 ∫_0^{π/2} dθ / sqrt(ω0² + ½ ε A² (1 + sin²θ))  (x = A sin θ in the energy integral)."""
    g, wg = np.polynomial.legendre.leggauss(n // 20 + 20)
    th, w = 0.25 * np.pi * (g + 1), 0.25 * np.pi * wg
    return 4 * float(np.sum(w / np.sqrt(omega0**2 + 0.5 * eps * amplitude**2 * (1 + np.sin(th) ** 2))))
