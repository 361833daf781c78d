"""A plain scikit-fem + splu script for the 8 × 8 in SS plate, the baseline of bench_plate.py's whole-process timing.

The same MITC4 K and M (assembled by scikit-fem through softimpact's PlateFE forms,
so the mesh and matrices are the same), the eq-15 pulse as a point load at the
centre node, 1000 average-acceleration steps with K_eff factored by scipy's
``splu``, the deflection under the load and two gauge strains written to a CSV.
Usage: python benchmarks/plain_plate.py N OUT.csv
"""

import sys

import numpy as np
import scipy.sparse.linalg as spl

from softimpact.fem.plate import Plate, PlateFE, W
from softimpact.models.laminate import PLIES, Stack, parse_layup
from softimpact.models.plate_laminate import plate_section

IN, LBF = 0.0254, 4.4482216152605


def main(n: int, out: str) -> None:
    a = 8 * IN
    fe = PlateFE(Plate(a, a, n, n, plate_section(Stack(PLIES["T300/934"], parse_layup("[90/0]5s")))))
    dt, N = 1e-6, 1000
    t = np.arange(N + 1) * dt
    F0, tp, T = 100 * LBF, 20e-6, 250e-6
    F = np.where(t < tp, F0 * np.sin(np.pi * t / (2 * tp)), np.where(t < T, F0 * np.cos(np.pi * (t - tp) / (2 * (T - tp))), 0.0))
    centre = fe.dof(int(fe.grid_node[n // 2, n // 2]), W)
    rows = np.array([fe.deflection(a / 2, a / 2), fe.surface_strain(5 * IN, 4 * IN, "bottom", "x"), fe.surface_strain(4 * IN, 6 * IN, "bottom", "y")])
    K, M = fe.K, fe.M
    a0, a2, a3 = 4 / dt**2, 4 / dt, 1.0
    lu = spl.splu((K + a0 * M).tocsc())
    u, v, acc = np.zeros(fe.n), np.zeros(fe.n), np.zeros(fe.n)
    y = np.zeros((3, N + 1))
    for k in range(N):
        rhs = M @ (a0 * u + a2 * v + a3 * acc)
        rhs[centre] -= F[k + 1]
        u1 = lu.solve(rhs)
        a1 = a0 * (u1 - u) - a2 * v - a3 * acc
        v = v + dt / 2 * (acc + a1)
        u, acc = u1, a1
        y[:, k + 1] = rows @ u
    np.savetxt(out, np.column_stack((t, F, y.T)), delimiter=",", header="time_s,force_N,deflection_m,strain_g1,strain_g2", comments="")


if __name__ == "__main__":
    main(int(sys.argv[1]), sys.argv[2])
