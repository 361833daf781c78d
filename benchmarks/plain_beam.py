"""A plain scikit-fem + scipy `splu` Newmark script: the paper's long beam, as one would write it by hand.

The reference of the start-up benchmark (bench_startup.py): the same mesh
(200 × 6 Q4, plane strain, smeared [90/0]5s T300/934), clamped at x = 0, the
eq-15 pulse of Table II history 1 on the top face at mid-length (one node, no
patch), 1000 steps of 1 µs, average acceleration. Prints the peak strain at
gauge 1. It imports nothing from softimpact.
"""

import numpy as np
import scipy.sparse.linalg as spl
from skfem import Basis, BilinearForm, ElementQuad1, ElementVector, MeshQuad, condense
from skfem.helpers import dot, sym_grad

L, H, B, RHO = 0.1524, 0.002794, 0.0254, 1580.0  # m, m, m, kg/m³
D = np.array([[6.597710e10, 3.962065e09, 0.0], [3.962065e09, 9.537402e09, 0.0], [0.0, 0.0, 3.729614e09]])  # Pa, (x, z, xz)
F0, TP, T = 195.72175107146202, 30e-6, 355e-6  # eq (15): N, s, s
DT, STEPS = 1e-6, 1000

mesh = MeshQuad.init_tensor(np.linspace(0, L, 201), np.linspace(0, H, 7))
basis = Basis(mesh, ElementVector(ElementQuad1()))


@BilinearForm
def stiffness(u, v, w):
    e, f = sym_grad(u), sym_grad(v)
    eu = [e[0, 0], e[1, 1], 2 * e[0, 1]]
    ev = [f[0, 0], f[1, 1], 2 * f[0, 1]]
    return B * sum(D[i, j] * eu[j] * ev[i] for i in range(3) for j in range(3))


@BilinearForm
def mass(u, v, w):
    return B * RHO * dot(u, v)


K, M = stiffness.assemble(basis), mass.assemble(basis)
clamped = basis.get_dofs(lambda x: np.isclose(x[0], 0.0)).all()
free = np.setdiff1d(np.arange(basis.N), clamped)
Kf, Mf = condense(K, M, D=clamped, expand=False)
top = np.flatnonzero(np.isclose(mesh.p[0], L / 2) & np.isclose(mesh.p[1], H))[0]
load_dof = np.searchsorted(free, basis.nodal_dofs[1, top])
bottom = np.flatnonzero(np.isclose(mesh.p[1], 0.0))
bottom = bottom[np.argsort(mesh.p[0, bottom])]
i = int(round(0.0508 / (L / 200)))  # gauge 1: 2 in from the clamp, bottom face, over two elements
gdofs = [np.searchsorted(free, basis.nodal_dofs[0, n]) for n in (bottom[i - 1], bottom[i + 1])]

t = np.arange(STEPS + 1) * DT
F = np.where(t < TP, F0 * np.sin(np.pi * t / (2 * TP)), np.where(t < T, F0 * np.cos(np.pi * (t - TP) / (2 * (T - TP))), 0.0))
a0, a2 = 4 / DT**2, 4 / DT
lu = spl.splu((Kf + a0 * Mf).tocsc())
u, v, a = (np.zeros(free.size) for _ in range(3))
strain = np.zeros(STEPS + 1)
for k in range(STEPS):
    f = np.zeros(free.size)
    f[load_dof] = -F[k + 1]
    u_new = lu.solve(f + Mf @ (a0 * u + a2 * v + a))
    a_new = a0 * (u_new - u) - a2 * v - a
    v = v + DT / 2 * (a + a_new)
    u, a = u_new, a_new
    strain[k + 1] = (u[gdofs[1]] - u[gdofs[0]]) / (L / 100)
print(f"peak strain at gauge 1: {strain[np.argmax(np.abs(strain))] * 1e6:.0f} microstrain")
