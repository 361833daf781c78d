"""A plain scikit-fem assembly of the paper's 8 × 8 in SS plate: a second FE code to check the package's MITC9 against.

The FSDT plate (w, φx, φy at each node) with scikit-fem's forms: MITC9 as the 9-node Lagrange
``ElementQuad2`` with bending and mass by 3 × 3 Gauss, the transverse shear γxz by 2 × 3 Gauss and
γyz by 3 × 2 (MITC9's tying on a rectangle, see ``softimpact.fem.plate``); ``element="mitc4"`` gives
the bilinear version (2 × 2 Gauss, shear 1 × 2 / 2 × 1). Also the baseline script of
``benchmarks/plain_plate.py`` (bench_plate.py's whole-process timing).
"""

import numpy as np
from skfem import Basis, BilinearForm, ElementQuad1, ElementQuad2, ElementVector, MeshQuad

from softimpact.models.laminate import PLIES, Stack, parse_layup
from softimpact.models.plate_laminate import plate_section

from .constants import INCH as IN


def gauss01(nx, ny):
    """nx × ny Gauss points and weights on the reference square [0, 1]², as scikit-fem quadrature."""
    (gx, wx), (gy, wy) = np.polynomial.legendre.leggauss(nx), np.polynomial.legendre.leggauss(ny)
    X = np.array([np.repeat(0.5 * (gx + 1), ny), np.tile(0.5 * (gy + 1), nx)])
    return X, np.outer(0.5 * wx, 0.5 * wy).ravel()


def assemble(n, element="mitc9"):
    """K, M (3 DOFs a node: w, φx, φy), the basis, and the laminate section, on n × n elements."""
    a = 8 * IN
    sec = plate_section(Stack(PLIES["T300/934"], parse_layup("[90/0]5s")))
    xs = np.linspace(0, a, n + 1)
    g = np.arange((n + 1) ** 2).reshape(n + 1, n + 1)
    points = np.array([np.repeat(xs, n + 1), np.tile(xs, n + 1)])
    cells = np.array([g[:-1, :-1].ravel(), g[1:, :-1].ravel(), g[1:, 1:].ravel(), g[:-1, 1:].ravel()])  # ξ along x
    mesh = MeshQuad(points, cells)
    e = ElementVector(ElementQuad2() if element == "mitc9" else ElementQuad1(), 3)
    full, one, two = (3, 2, 1) if element == "mitc9" else (2, 1, 2)
    D, S, I0, I2 = sec.D, sec.S, sec.I0, sec.I2

    @BilinearForm
    def bending(u, v, w):
        ku = [u.grad[1][0], u.grad[2][1], u.grad[1][1] + u.grad[2][0]]
        kv = [v.grad[1][0], v.grad[2][1], v.grad[1][1] + v.grad[2][0]]
        return sum(D[i, j] * ku[j] * kv[i] for i in range(3) for j in range(3))

    @BilinearForm
    def shear_xz(u, v, w):
        return S[0, 0] * (u.grad[0][0] + u[1]) * (v.grad[0][0] + v[1])

    @BilinearForm
    def shear_yz(u, v, w):
        return S[1, 1] * (u.grad[0][1] + u[2]) * (v.grad[0][1] + v[2])

    @BilinearForm
    def mass(u, v, w):
        return I0 * u[0] * v[0] + I2 * (u[1] * v[1] + u[2] * v[2])

    basis = Basis(mesh, e, quadrature=gauss01(full, full))
    if element == "mitc9":
        K = bending.assemble(basis) + shear_xz.assemble(Basis(mesh, e, quadrature=gauss01(2, 3))) + shear_yz.assemble(Basis(mesh, e, quadrature=gauss01(3, 2)))
    else:
        K = bending.assemble(basis) + shear_xz.assemble(Basis(mesh, e, quadrature=gauss01(1, 2))) + shear_yz.assemble(Basis(mesh, e, quadrature=gauss01(2, 1)))
    M = mass.assemble(basis)
    return K, M, basis, sec


def simply_supported(basis):
    """Navier's hard simple support: w and the tangential rotation zero on every edge."""
    a = 8 * IN
    on_x = basis.get_dofs(lambda x: np.isclose(x[0], 0) | np.isclose(x[0], a))
    on_y = basis.get_dofs(lambda x: np.isclose(x[1], 0) | np.isclose(x[1], a))
    return np.unique(np.concatenate((on_x.all(["u^1", "u^3"]), on_y.all(["u^1", "u^2"]))))
