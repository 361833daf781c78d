"""A plain scikit-fem + splu script for the 8 × 8 in SS plate, the baseline of bench_plate.py's whole-process timing.

What one writes with scikit-fem and scipy for the same model as ``softimpact
plate``: the FSDT plate on the same N × N mesh of the same element (MITC9: 9-node
Lagrange ``ElementQuad2`` for w, φx, φy; bending and mass by 3 × 3 Gauss, the
transverse shear γxz by 2 × 3 Gauss, γyz by 3 × 2, which is MITC9's tying on a
rectangle, see ``softimpact.fem.plate``), assembled by scikit-fem's forms; the
eq-15 pulse as a point load at the centre; 1000 average-acceleration steps with
K_eff factored by scipy's ``splu`` (its default ordering); the deflection under
the load and the two gauge strains (bottom face, each the difference of the
rotation across the gauge, i.e. the strain averaged over its length) written to
a CSV. ``--element mitc4`` gives the bilinear MITC4 version (2 × 2 Gauss, shear
1 × 2 / 2 × 1) on the same grid.

Usage: python benchmarks/plain_plate.py N OUT.csv [--element mitc4|mitc9]
"""

import sys
from pathlib import Path

import numpy as np
import scipy.sparse.linalg as spl
from skfem import condense

# the assembly is shared with the tests (tests/_support/plain_plate.py), which check it against the package's MITC9
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from _support.plain_plate import IN, assemble, simply_supported  # noqa: E402

LBF = 4.4482216152605


def probe(basis, component, x, y):
    """Row r with r·u = the component's value at (x, y)."""
    (sub, idx) = basis.split_bases()[component], basis.split_indices()[component]
    row = np.zeros(basis.N)
    row[idx] = sub.probes(np.array([[x], [y]])).toarray()[0]
    return row


def main(n: int, out: str, element: str = "mitc9") -> None:
    a = 8 * IN
    K, M, basis, sec = assemble(n, element)
    h, length = sec.thickness, 0.031 * IN
    dt, N = 1e-6, 1000
    t = np.arange(N + 1) * dt
    F0, tp, T = 100 * LBF, 20e-6, 250e-6
    F = np.where(t < tp, F0 * np.sin(np.pi * t / (2 * tp)), np.where(t < T, F0 * np.cos(np.pi * (t - tp) / (2 * (T - tp))), 0.0))
    rows = np.array(
        [
            probe(basis, 0, a / 2, a / 2),
            -h / 2 * (probe(basis, 1, 5 * IN + length / 2, 4 * IN) - probe(basis, 1, 5 * IN - length / 2, 4 * IN)) / length,
            -h / 2 * (probe(basis, 2, 4 * IN, 6 * IN + length / 2) - probe(basis, 2, 4 * IN, 6 * IN - length / 2)) / length,
        ]
    )
    free = np.setdiff1d(np.arange(basis.N), simply_supported(basis))
    K, M = condense(K, M, D=np.setdiff1d(np.arange(basis.N), free), expand=False)
    rows = rows[:, free]
    load = -rows[0]  # a point force at the centre, pushing down: the deflection row is its consistent load
    a0, a2, a3 = 4 / dt**2, 4 / dt, 1.0
    lu = spl.splu((K + a0 * M).tocsc())
    u, v, acc = np.zeros(free.size), np.zeros(free.size), np.zeros(free.size)
    y = np.zeros((3, N + 1))
    for k in range(N):
        u1 = lu.solve(M @ (a0 * u + a2 * v + a3 * acc) + F[k + 1] * load)
        a1 = a0 * (u1 - u) - a2 * v - a3 * acc
        v = v + dt / 2 * (acc + a1)
        u, acc = u1, a1
        y[:, k + 1] = rows @ u
    np.savetxt(out, np.column_stack((t, F, y.T)), delimiter=",", header="time_s,force_N,deflection_m,strain_g1,strain_g2", comments="")


if __name__ == "__main__":
    args = sys.argv[1:]
    element = "mitc9"
    if "--element" in args:
        i = args.index("--element")
        element = args[i + 1]
        del args[i : i + 2]
    main(int(args[0]), args[1], element)
