"""Laminated plate finite elements: first-order shear deformation (FSDT), MITC4 and MITC9.

Five DOFs per node, in this order: u, v (mid-plane in-plane displacements),
w (transverse, up +), φx, φy (rotations of the normal, so that the in-plane
displacement at height z is u + z·φx, v + z·φy). With the section of
:mod:`softimpact.models.plate_laminate`,

    K = ∫ [ε0; κ]ᵀ [[A, B], [B, D]] [ε0; κ] dA + ∫ γᵀ S γ dA,
    M = ∫ I0 (u² + v² + w²) + 2 I1 (u φx + v φy) + I2 (φx² + φy²) dA   (consistent,
        rotary inertia included),

over a structured mesh of nx × ny rectangles covering x ∈ [0, Lx], y ∈ [0, Ly]
(the grid may be graded), of one of two elements (``Plate.element``):

- ``mitc4``: bilinear 4-node rectangles (scikit-fem's ``ElementVector(ElementQuad1(), 5)``
  on a ``MeshQuad``, node (i, j) = i·(ny + 1) + j). Its flexural waves disperse at
  second order in h: on the issue's 8 × 8 in plate the gauge strains over 1000 µs
  need ~360 × 360 elements for 2 % (tests/test_plate_slow.py).
- ``mitc9``: biquadratic 9-node rectangles (nodes on the grid lines and the
  mid-lines, (2nx + 1) × (2ny + 1) of them, node (i, j) = i·(2ny + 1) + j), whose
  dispersion error is fourth order: 48 × 48 meets 2 % there, with as many DOFs as
  MITC4's 96 × 96. Assembled here directly: on rectangles every element matrix
  is one of a few (one per distinct element size), computed by tensor Gauss rules
  and scattered at once (checked against a plain scikit-fem ``ElementQuad2``
  assembly of the same forms in tests/test_plate.py).

Shear locking and how it is avoided
-----------------------------------
With bilinear w and φ, full 2×2 integration of the shear energy forces
γ = w,x + φx → 0 pointwise as h/L → 0, which a bilinear field can satisfy
only by not bending: the element locks. The element here is the MITC4 element
of Bathe and Dvorkin (1985): the shear strains are not taken from the
displacements directly but interpolated from their values at the edge
mid-points ("tying points"): γxz from the mid-points of the two edges parallel
to x, linearly in y, and γyz from the mid-points of the edges parallel to y,
linearly in x. On a rectangle aligned with the axes this is *exactly* a
direction-selective reduced integration of the displacement-based strains:

- ∫ S11 γxz²: γxz^MITC(ξ, η) = γxz(0, η) (w,x is independent of ξ on a rectangle),
  which is linear in η, so the energy is integrated exactly by 1 Gauss point in
  x times 2 in y;
- ∫ S22 γyz²: 2 points in x times 1 in y;
- ∫ 2 S12 γxz γyz: the product of a function of η and one of ξ, linear in each,
  integrates exactly by the single centre point.

So the three shear terms are assembled by scikit-fem with these three tensor
rules, the membrane, bending and mass terms with 2×2 Gauss (exact for them on
rectangles). MITC4 passes the patch test, has no spurious zero-energy modes
(a free plate has exactly six zero frequencies: ``tests/test_plate.py``) and
converges to the Kirchhoff (CLT) solution as h/L → 0 (tested to L/h = 1000).

MITC9 (Bucalem and Bathe 1993) ties γxz at the six points ξ = ±1/√3,
η ∈ {−√0.6, 0, √0.6} and interpolates it linearly in ξ, quadratically in η (γyz:
the transpose). On a rectangle the displacement-based γxz = w,x + φx is of
degree ≤ 2 in each of ξ, η, so (i) in η the quadratic interpolant through three
points reproduces it, and (ii) in ξ the linear interpolant through the two
Gauss points ±1/√3 of a quadratic is its L2 projection onto linears (the
remainder is a multiple of the Legendre P2, zero at those points). Hence:

- ∫ S11 (γxz^MITC)²: linear² in ξ is exact by 2 Gauss points, where γxz^MITC =
  γxz; quartic in η is exact by 3 points, where interpolant and γxz agree: the
  term is the 2 (x) × 3 (y) Gauss rule of the displacement-based strain;
- ∫ S22 (γyz^MITC)²: likewise 3 × 2;
- ∫ 2 S12 γxz^MITC γyz^MITC (S12 ≠ 0 for angle plies): the product is cubic in
  ξ (linear × quadratic) and in η, so 2 × 2 Gauss is exact, and at the 2 × 2
  points both tied strains equal the displacement-based ones (ξ, η = ±1/√3 are
  the linear directions' tying coordinates, and the quadratic directions
  reproduce exactly): the cross term is exactly the 2 × 2 rule — not an
  approximation (tested against the literal tying, with S12 ≠ 0, in
  ``tests/test_plate.py``).

Membrane, bending and mass use 3 × 3 Gauss (exact). MITC9 has no spurious
zero-energy modes (six zero frequencies of a free plate), does not lock (CLT to
0.01 % at L/h = 10 000 on 8 × 8) and converges at fourth order (static and
frequency errors, and the transient's spatial error, tests/test_plate*.py).

Supports, per edge ``x0`` (x = 0), ``x1`` (x = Lx), ``y0``, ``y1``:
``clamped`` (all five DOFs zero), ``simply-supported`` (Navier's hard simple
support: w = 0, the tangential in-plane displacement and the tangential
rotation zero, the normal rotation and normal displacement free: on an x-edge
w = v = φy = 0), ``free`` and ``symmetry`` (a mirror plane: the normal
in-plane displacement and the normal rotation zero, on an x-edge u = φx = 0;
a plate and load symmetric about both mid-lines can be modelled by a quarter,
as the convergence study of ``tests/test_plate_slow.py`` does). When the section is symmetric (B = 0, I1 = 0) and
nothing loads the mid-plane, stretching decouples from bending and the in-plane
DOFs are dropped (``membrane=None``, the default, decides; ``True`` keeps them).

Outputs are rows (over the free DOFs) of linear functionals: the transverse
deflection w at a point (the element's interpolation) and the surface strain at the
top (z = +h/2) or bottom (z = −h/2) face in a direction θ from x,
ε_θ = εx cos²θ + εy sin²θ + γxy sinθ cosθ, averaged over a gauge of length l
centred at the point along θ (integrated exactly, element piece by piece).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..models.plate_laminate import PlateSection

__all__ = ["EDGES", "ELEMENTS", "SUPPORT_KINDS", "GRADE_RATIO", "Plate", "PlateFE", "U", "V", "W", "PHI_X", "PHI_Y", "graded_lines"]

EDGES = ("x0", "x1", "y0", "y1")
ELEMENTS = ("mitc4", "mitc9")
SUPPORT_KINDS = ("clamped", "simply-supported", "free", "symmetry")
U, V, W, PHI_X, PHI_Y = range(5)
_GAUSS2 = (0.5 - 0.5 / math.sqrt(3.0), 0.5 + 0.5 / math.sqrt(3.0))  # on [0, 1]
GRADE_RATIO = 1.25  # a graded mesh's element size grows at most this much from one element to the next


def graded_lines(length: float, lo: float, hi: float, fine: float, coarse: float, ratio: float = GRADE_RATIO) -> np.ndarray:
    """Grid lines on [0, ``length``] [m]: equal elements of at most ``fine`` on [lo, hi], then elements growing by
    ``ratio`` outward up to ``coarse`` (each side's sizes shrunk to end exactly on the plate's edge)."""
    if not (0 <= lo < hi <= length and 0 < fine <= coarse and ratio > 1):
        raise InputError(
            f"graded mesh: need 0 <= lo < hi <= length and 0 < fine <= coarse, got lo {lo!r}, hi {hi!r}, length {length!r}, fine {fine!r}, coarse {coarse!r}"
        )
    n = max(1, math.ceil((hi - lo) / fine - 1e-9))
    middle = np.linspace(lo, hi, n + 1)

    def side(span: float) -> np.ndarray:
        """Element sizes growing from ``fine`` to ``coarse`` over ``span`` [m], scaled to fill it exactly."""
        if span <= 1e-12 * length:
            return np.zeros(0)
        sizes, h, total = [], fine, 0.0
        while total < span:
            h = min(h * ratio, coarse)
            sizes.append(h)
            total += h
        sizes = np.array(sizes)
        return sizes * span / sizes.sum()  # shrunk to fit: the growth stays at most ``ratio``

    right = hi + np.cumsum(side(length - hi))
    left = lo - np.cumsum(side(lo))[::-1]
    lines = np.concatenate((left, middle, right))
    lines[0], lines[-1] = 0.0, length
    return lines


@dataclass(frozen=True, eq=False)
class Plate:
    """Geometry [m], mesh (nx × ny elements, or explicit grid lines ``xs``, ``ys``),
    supports (x0, x1, y0, y1) and section of a rectangular plate."""

    length_x: float
    length_y: float
    nx: int
    ny: int
    section: PlateSection
    supports: tuple[str, str, str, str] = ("simply-supported",) * 4
    membrane: bool | None = None
    xs: tuple[float, ...] | None = None
    ys: tuple[float, ...] | None = None
    element: str = "mitc4"

    def __post_init__(self):
        if self.element not in ELEMENTS:
            raise InputError(f"plate element: {self.element!r} is not one of {', '.join(ELEMENTS)}")
        for k in ("length_x", "length_y"):
            v = getattr(self, k)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise InputError(f"plate {k} must be positive, got {v!r} m")
        for k in ("nx", "ny"):
            v = getattr(self, k)
            if not (isinstance(v, (int, np.integer)) and v >= 1):
                raise InputError(f"plate {k} (elements) must be a positive integer, got {v!r}")
        if len(self.supports) != 4:
            raise InputError(f"plate supports must name four edges (x0, x1, y0, y1), got {self.supports!r}")
        for edge, s in zip(EDGES, self.supports):
            if s not in SUPPORT_KINDS:
                raise InputError(f"plate support of edge {edge}: {s!r} is not one of {', '.join(SUPPORT_KINDS)}")

    def grid(self) -> tuple[np.ndarray, np.ndarray]:
        """Grid lines in x and y [m]."""
        xs = np.linspace(0.0, self.length_x, self.nx + 1) if self.xs is None else np.asarray(self.xs, float)
        ys = np.linspace(0.0, self.length_y, self.ny + 1) if self.ys is None else np.asarray(self.ys, float)
        return xs, ys


def _tensor_rule(nx_points: int, ny_points: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss rule on the reference square [0, 1]² (weights sum to 1), 1 or 2 points per direction."""
    pts = {1: (np.array([0.5]), np.array([1.0])), 2: (np.array(_GAUSS2), np.array([0.5, 0.5]))}
    (px, wx), (py, wy) = pts[nx_points], pts[ny_points]
    X = np.array([np.repeat(px, py.size), np.tile(py, px.size)])
    return X, np.outer(wx, wy).ravel()


class _Numbering:
    """DOF numbering of the MITC9 model, shaped like scikit-fem's basis: ``nodal_dofs[c, node]``
    = 5·node + c, ``N`` the number of DOFs."""

    def __init__(self, n_nodes: int):
        self.nodal_dofs = np.arange(5 * n_nodes).reshape(n_nodes, 5).T
        self.N = 5 * n_nodes


def _lagrange(order: int, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """1-D Lagrange functions on [0, 1] (nodes 0, 1 or 0, ½, 1) and their derivatives, shape (k, order + 1)."""
    s = np.asarray(s, float)[..., None]
    if order == 1:
        return np.concatenate((1 - s, s), -1), np.concatenate((-np.ones_like(s), np.ones_like(s)), -1)
    N = np.concatenate((2 * (s - 0.5) * (s - 1), -4 * s * (s - 1), 2 * s * (s - 0.5)), -1)
    dN = np.concatenate((4 * s - 3, 4 - 8 * s, 4 * s - 1), -1)
    return N, dN


def _gauss01(n: int) -> tuple[np.ndarray, np.ndarray]:
    """n-point Gauss rule on [0, 1] (weights sum to 1)."""
    g, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (g + 1), 0.5 * w


class PlateFE:
    """Assembled plate: reduced ``K``, ``M`` over the free DOFs, and output rows.

    ``n``: number of free DOFs; ``free``: their indices into the global DOF
    numbering; ``basis.nodal_dofs[c, node]`` is the global DOF of component c.
    ``xs``, ``ys``: the element grid lines; ``node_xs``, ``node_ys``: the node
    lines (the same for MITC4; with the mid-side lines for MITC9), node (i, j)
    at (node_xs[i], node_ys[j]) being ``grid_node[i, j]``.
    """

    def __init__(self, plate: Plate, elements: np.ndarray | None = None):
        """``elements``: an (nx, ny) bool mask of the elements assembled (None: all); the DOFs of nodes no assembled
        element touches are removed with the supported ones (a part of the plate: a stacked near field, its far field)."""
        self.plate = plate
        sec = plate.section
        xs, ys = plate.grid()
        if np.any(np.diff(xs) <= 0) or np.any(np.diff(ys) <= 0):
            raise InputError("plate grid lines must increase strictly")
        self.xs, self.ys = xs, ys
        self.order = 2 if plate.element == "mitc9" else 1
        if self.order == 1:
            self.node_xs, self.node_ys = xs, ys
            # Each element lists its nodes counter-clockwise from its lower-left corner.
            self._local = ((0, 0), (1, 0), (1, 1), (0, 1))
        else:
            self.node_xs = np.insert(xs, np.arange(1, xs.size), 0.5 * (xs[:-1] + xs[1:]))
            self.node_ys = np.insert(ys, np.arange(1, ys.size), 0.5 * (ys[:-1] + ys[1:]))
            self._local = tuple((a, b) for a in range(3) for b in range(3))
        # Node (i, j) at (node_xs[i], node_ys[j]) is number i·(len(node_ys)) + j.
        nxp, nyp = self.node_xs.size, self.node_ys.size
        self.grid_node = np.arange(nxp * nyp).reshape(nxp, nyp)
        self.membrane = (not sec.is_symmetric()) if plate.membrane is None else bool(plate.membrane)
        ne = (xs.size - 1, ys.size - 1)
        self.elements = np.ones(ne, bool) if elements is None else np.asarray(elements, bool)
        if self.elements.shape != ne or not self.elements.any():
            raise InputError(f"plate elements mask: expected a non-empty ({ne[0]}, {ne[1]}) bool array, got shape {self.elements.shape}")
        if self.order == 1:
            self._assemble_mitc4(sec)
        else:
            self.basis = _Numbering(nxp * nyp)
        self.fixed = self._support_dofs()
        self.free = np.setdiff1d(np.arange(self.basis.N), self.fixed)
        self.n = self.free.size
        self._index = np.full(self.basis.N, -1)
        self._index[self.free] = np.arange(self.n)
        if self.order == 1:
            self.K = self.K_full[self.free][:, self.free].tocsc()
            self.M = self.M_full[self.free][:, self.free].tocsc()
        else:
            self.K, self.M = self._assemble_mitc9(sec)

    def _assemble_mitc4(self, sec: PlateSection) -> None:
        from skfem import Basis, BilinearForm, ElementQuad1, ElementVector, MeshQuad

        g = self.grid_node
        points = np.array([np.repeat(self.xs, self.ys.size), np.tile(self.ys, self.xs.size)])
        # Counter-clockwise from the lower-left corner, so the reference ξ runs along x in every
        # element, as the direction-selective shear rules below require.
        cells = np.array([g[:-1, :-1].ravel(), g[1:, :-1].ravel(), g[1:, 1:].ravel(), g[:-1, 1:].ravel()])
        mesh = MeshQuad(points, cells)
        element = ElementVector(ElementQuad1(), 5)
        self.mesh, self.element = mesh, element
        # cells numbered i·ny + j, as the mask's ravel (row-major over (i, j))
        subset = None if self.elements.all() else np.flatnonzero(self.elements.ravel())

        def Basis(mesh, element, quadrature, _cls=Basis):
            return _cls(mesh, element, quadrature=quadrature, elements=subset)

        full = Basis(mesh, element, quadrature=_tensor_rule(2, 2))
        self.basis = full
        A, Bm, D, S = sec.A, sec.B, sec.D, sec.S

        def membrane(g):
            return [g[U][0], g[V][1], g[U][1] + g[V][0]]

        def curvature(g):
            return [g[PHI_X][0], g[PHI_Y][1], g[PHI_X][1] + g[PHI_Y][0]]

        def quad(Cm, a, b):
            return sum(Cm[i, j] * a[j] * b[i] for i in range(3) for j in range(3) if Cm[i, j] != 0.0)

        @BilinearForm
        def plane_and_bending(u, v, w):
            e0u, e0v = membrane(u.grad), membrane(v.grad)
            ku, kv = curvature(u.grad), curvature(v.grad)
            return quad(A, e0u, e0v) + quad(Bm, ku, e0v) + quad(Bm, e0u, kv) + quad(D, ku, kv)

        def gxz(f):
            return f.grad[W][0] + f[PHI_X]

        def gyz(f):
            return f.grad[W][1] + f[PHI_Y]

        @BilinearForm
        def shear_xz(u, v, w):
            return S[0, 0] * gxz(u) * gxz(v)

        @BilinearForm
        def shear_yz(u, v, w):
            return S[1, 1] * gyz(u) * gyz(v)

        @BilinearForm
        def shear_coupling(u, v, w):
            return S[0, 1] * (gxz(u) * gyz(v) + gyz(u) * gxz(v))

        I0, I1, I2 = sec.I0, sec.I1, sec.I2

        @BilinearForm
        def mass(u, v, w):
            a, b = u, v
            return (
                I0 * (a[U] * b[U] + a[V] * b[V] + a[W] * b[W])
                + I1 * (a[U] * b[PHI_X] + a[PHI_X] * b[U] + a[V] * b[PHI_Y] + a[PHI_Y] * b[V])
                + I2 * (a[PHI_X] * b[PHI_X] + a[PHI_Y] * b[PHI_Y])
            )

        K = plane_and_bending.assemble(full)
        K = K + shear_xz.assemble(Basis(mesh, element, quadrature=_tensor_rule(1, 2)))
        K = K + shear_yz.assemble(Basis(mesh, element, quadrature=_tensor_rule(2, 1)))
        if S[0, 1] != 0.0:
            K = K + shear_coupling.assemble(Basis(mesh, element, quadrature=_tensor_rule(1, 1)))
        M = mass.assemble(full)
        self.K_full, self.M_full = K.tocsr(), M.tocsr()

    # ---- MITC9 ----------------------------------------------------------------------
    def _element_matrices(self, sec: PlateSection, hx: float, hy: float, comps: tuple[int, ...]) -> tuple[np.ndarray, np.ndarray]:
        """Stiffness and consistent mass of one hx × hy MITC9 rectangle over the DOFs
        (local node k, component comps[c]) ordered k·len(comps) + c."""
        nc, npe = len(comps), len(self._local)
        pos = {c: i for i, c in enumerate(comps)}
        a_idx = np.array([a for a, _ in self._local])
        b_idx = np.array([b for _, b in self._local])

        def rule(px, py):
            (sx, wx), (sy, wy) = _gauss01(px), _gauss01(py)
            Nx, dNx = _lagrange(2, sx)
            Ny, dNy = _lagrange(2, sy)
            N = (Nx[:, None, a_idx] * Ny[None, :, b_idx]).reshape(-1, npe)
            Dx = (dNx[:, None, a_idx] * Ny[None, :, b_idx]).reshape(-1, npe) / hx
            Dy = (Nx[:, None, a_idx] * dNy[None, :, b_idx]).reshape(-1, npe) / hy
            return N, Dx, Dy, np.outer(wx, wy).ravel() * hx * hy

        def op(rows, nq):
            return np.zeros((nq, rows, npe, nc))

        def energy(B, C, w):
            B = B.reshape(B.shape[0], B.shape[1], npe * nc)
            return np.einsum("q,qip,ij,qjr->pr", w, B, C, B)

        # Membrane and bending: 3 × 3 Gauss, exact on a rectangle.
        N, Dx, Dy, w = rule(3, 3)
        nq = w.size
        B = op(6, nq)
        for row, comp, d in ((0, U, Dx), (1, V, Dy), (2, U, Dy), (2, V, Dx), (3, PHI_X, Dx), (4, PHI_Y, Dy), (5, PHI_X, Dy), (5, PHI_Y, Dx)):
            if comp in pos:
                B[:, row, :, pos[comp]] = d
        if U in pos:
            K = energy(B, sec.stiffness(), w)
        else:
            K = energy(B[:, 3:], sec.D, w)
        # Mass: 3 × 3 Gauss, exact.
        Nd = op(5, nq)
        for c in comps:
            Nd[:, c, :, pos[c]] = N
        I = np.diag([sec.I0, sec.I0, sec.I0, sec.I2, sec.I2])
        I[U, PHI_X] = I[PHI_X, U] = I[V, PHI_Y] = I[PHI_Y, V] = sec.I1
        M = energy(Nd, I, w)

        # Transverse shear, MITC9's tied strains on a rectangle (module docstring): γxz by 2 × 3
        # Gauss, γyz by 3 × 2, the cross term by 2 × 2, of the displacement-based strains.
        def gamma(px, py):
            N, Dx, Dy, w = rule(px, py)
            G = op(2, w.size)
            G[:, 0, :, pos[W]], G[:, 0, :, pos[PHI_X]] = Dx, N
            G[:, 1, :, pos[W]], G[:, 1, :, pos[PHI_Y]] = Dy, N
            return G, w

        S = sec.S
        G, w = gamma(2, 3)
        K = K + energy(G[:, :1], S[:1, :1], w)
        G, w = gamma(3, 2)
        K = K + energy(G[:, 1:], S[1:, 1:], w)
        if S[0, 1] != 0.0:
            G, w = gamma(2, 2)
            K = K + energy(G, np.array([[0.0, S[0, 1]], [S[0, 1], 0.0]]), w)
        return K, M

    def _assemble_mitc9(self, sec: PlateSection):
        """K and M over the free DOFs: element matrices per distinct (hx, hy), scattered at once."""
        import scipy.sparse

        comps = (U, V, W, PHI_X, PHI_Y) if self.membrane else (W, PHI_X, PHI_Y)
        hx, hy = np.diff(self.xs), np.diff(self.ys)
        ux, ix = np.unique(np.round(hx / hx.max(), 12), return_inverse=True)
        uy, iy = np.unique(np.round(hy / hy.max(), 12), return_inverse=True)
        mats = [[self._element_matrices(sec, a * hx.max(), b * hy.max(), comps) for b in uy] for a in ux]
        Ke = np.array([[k for k, _ in row] for row in mats])  # (n_hx, n_hy, ndof, ndof)
        Me = np.array([[m for _, m in row] for row in mats])
        I, J = np.nonzero(self.elements)  # the assembled elements (row-major: I·ny + J)
        nodes = np.stack([self.grid_node[2 * I + a, 2 * J + b] for a, b in self._local], axis=1)  # (ne, 9)
        dofs = self._index[(5 * nodes[:, :, None] + np.array(comps)).reshape(I.size, -1)]  # (ne, ndof)
        group = ix[I] * uy.size + iy[J]
        Ke = Ke.reshape(-1, *Ke.shape[2:])
        Me = Me.reshape(-1, *Me.shape[2:])
        nd = dofs.shape[1]
        rows = np.broadcast_to(dofs[:, :, None], (I.size, nd, nd)).ravel()
        cols = np.broadcast_to(dofs[:, None, :], (I.size, nd, nd)).ravel()
        keep = (rows >= 0) & (cols >= 0)
        rows, cols = rows[keep], cols[keep]
        out = []
        for E in (Ke, Me):
            data = E[group].ravel()[keep]
            out.append(scipy.sparse.csc_matrix((data, (rows, cols)), shape=(self.n, self.n)))
        return out

    # ---- supports -------------------------------------------------------------------
    def edge_nodes(self, edge: str) -> np.ndarray:
        """Nodes on an edge, in order along it."""
        g = self.grid_node
        return {"x0": g[0, :], "x1": g[-1, :], "y0": g[:, 0], "y1": g[:, -1]}[edge]

    def touched_nodes(self) -> np.ndarray:
        """(n_nodes,) bool: the nodes of the assembled elements."""
        I, J = np.nonzero(self.elements)
        p = self.order
        out = np.zeros(self.grid_node.size, bool)
        for a, b in self._local:
            out[self.grid_node[p * I + a, p * J + b]] = True
        return out

    def _support_dofs(self) -> np.ndarray:
        nd = self.basis.nodal_dofs
        fixed = [nd[:, ~self.touched_nodes()].ravel()]
        for edge, kind in zip(EDGES, self.plate.supports):
            nodes = self.edge_nodes(edge)
            if kind == "clamped":
                comps = [U, V, W, PHI_X, PHI_Y]
            elif kind == "simply-supported":
                comps = [W, V, PHI_Y] if edge[0] == "x" else [W, U, PHI_X]
            elif kind == "symmetry":
                comps = [U, PHI_X] if edge[0] == "x" else [V, PHI_Y]
            else:
                comps = []
            fixed += [nd[c, nodes] for c in comps]
        if not self.membrane:
            fixed += [nd[U], nd[V]]
        return np.unique(np.concatenate(fixed)) if fixed else np.zeros(0, int)

    # ---- DOFs and outputs -------------------------------------------------------------
    def dof(self, node: int, component: int) -> int:
        """Index in the reduced system of a node's component (U, V, W, PHI_X, PHI_Y); −1 if fixed."""
        return int(self._index[self.basis.nodal_dofs[component, node]])

    def node_xy(self) -> np.ndarray:
        """Node coordinates, shape (2, n_nodes) [m]: node grid_node[i, j] at (node_xs[i], node_ys[j])."""
        return np.array([np.repeat(self.node_xs, self.node_ys.size), np.tile(self.node_ys, self.node_xs.size)])

    def _locate(self, x: float, y: float) -> list[tuple[int, int, float, float]]:
        """Elements (i, j) whose closed rectangle holds (x, y), with local coordinates s, t ∈ [0, 1]."""
        xs, ys = self.xs, self.ys
        tol = 1e-9 * max(xs[-1] - xs[0], ys[-1] - ys[0])
        if not (xs[0] - tol <= x <= xs[-1] + tol and ys[0] - tol <= y <= ys[-1] + tol):
            raise InputError(f"point ({x!r}, {y!r}) m is off the plate (0 to {xs[-1]!r}, 0 to {ys[-1]!r} m)")
        out = []
        ii = {int(np.clip(np.searchsorted(xs, x - tol) - 1, 0, xs.size - 2)), int(np.clip(np.searchsorted(xs, x + tol) - 1, 0, xs.size - 2))}
        jj = {int(np.clip(np.searchsorted(ys, y - tol) - 1, 0, ys.size - 2)), int(np.clip(np.searchsorted(ys, y + tol) - 1, 0, ys.size - 2))}
        for i in sorted(ii):
            for j in sorted(jj):
                s = (x - xs[i]) / (xs[i + 1] - xs[i])
                t = (y - ys[j]) / (ys[j + 1] - ys[j])
                if -1e-9 <= s <= 1 + 1e-9 and -1e-9 <= t <= 1 + 1e-9:
                    out.append((i, j, min(max(s, 0.0), 1.0), min(max(t, 0.0), 1.0)))
        return out

    def _element_nodes(self, i: int, j: int) -> np.ndarray:
        g, p = self.grid_node, self.order
        return np.array([g[p * i + a, p * j + b] for a, b in self._local])

    def shape(self, i, j, s, t):
        """Nodes and shape functions of element(s) (i, j) at local (s, t) ∈ [0, 1]² (arrays
        broadcast): (nodes, N), each of shape (..., nodes per element)."""
        i, j, s, t = np.broadcast_arrays(*(np.asarray(a) for a in (i, j, s, t)))
        Nx, _ = _lagrange(self.order, s)
        Ny, _ = _lagrange(self.order, t)
        a = np.array([a for a, _ in self._local])
        b = np.array([b for _, b in self._local])
        nodes = self.grid_node[self.order * i[..., None] + a, self.order * j[..., None] + b]
        return nodes, Nx[..., a] * Ny[..., b]

    def _shape_gradient(self, i: int, j: int, s: float, t: float) -> tuple[np.ndarray, np.ndarray]:
        """∂N/∂x, ∂N/∂y of element (i, j) at local (s, t)."""
        Nx, dNx = _lagrange(self.order, np.array([s]))
        Ny, dNy = _lagrange(self.order, np.array([t]))
        a = np.array([a for a, _ in self._local])
        b = np.array([b for _, b in self._local])
        hx, hy = self.xs[i + 1] - self.xs[i], self.ys[j + 1] - self.ys[j]
        return dNx[0, a] * Ny[0, b] / hx, Nx[0, a] * dNy[0, b] / hy

    def _row(self, entries) -> np.ndarray:
        """Row over free DOFs from (global DOF, weight) pairs; fixed DOFs dropped."""
        row = np.zeros(self.n)
        for gdof, wgt in entries:
            k = self._index[gdof]
            if k >= 0:
                row[k] += wgt
        return row

    def interpolation(self, x: float, y: float) -> tuple[np.ndarray, np.ndarray]:
        """Nodes and shape-function weights at (x, y) (one element holding it)."""
        i, j, s, t = self._locate(x, y)[0]
        nodes, N = self.shape(i, j, s, t)
        return nodes, N

    def deflection(self, x: float, y: float) -> np.ndarray:
        """Row r with r·u = w(x, y) [m] (up +)."""
        nodes, N = self.interpolation(x, y)
        return self._row(zip(self.basis.nodal_dofs[W, nodes], N))

    def _strain_entries(self, i, j, s, t, z, c, sn, weight):
        """(global DOF, weight) of ε_θ at local (s, t) of element (i, j), height z."""
        dNx, dNy = self._shape_gradient(i, j, s, t)
        nodes = self._element_nodes(i, j)
        nd = self.basis.nodal_dofs
        # ε_θ = c² εx + s² εy + s c γxy with εx = u,x + z φx,x etc.
        out = []
        for a, b, f in ((U, PHI_X, c * c * dNx), (V, PHI_Y, sn * sn * dNy), (U, PHI_X, sn * c * dNy), (V, PHI_Y, sn * c * dNx)):
            out += list(zip(nd[a, nodes], weight * f))
            out += list(zip(nd[b, nodes], weight * z * f))
        return out

    def surface_strain(self, x: float, y: float, surface: str = "bottom", direction="x", length: float = 0.0) -> np.ndarray:
        """Row r with r·u = the strain at the ``top`` or ``bottom`` face in ``direction``
        (``"x"``, ``"y"`` or an angle in degrees from x) averaged over a gauge of
        ``length`` [m] centred at (x, y) along that direction (length 0: the point
        value, averaged over the elements that share the point)."""
        if surface not in ("top", "bottom"):
            raise InputError(f"gauge surface: {surface!r} is not 'top' or 'bottom'")
        if isinstance(direction, str):
            if direction not in ("x", "y"):
                raise InputError(f"gauge direction: {direction!r} is not 'x', 'y' or an angle in degrees")
            theta = 0.0 if direction == "x" else 90.0
        else:
            theta = float(direction)
            if not math.isfinite(theta):
                raise InputError(f"gauge direction: {direction!r} is not a finite angle")
        if not (math.isfinite(length) and length >= 0):
            raise InputError(f"gauge length must be non-negative, got {length!r} m")
        c, sn = math.cos(math.radians(theta)), math.sin(math.radians(theta))
        z = (1 if surface == "top" else -1) * self.plate.section.thickness / 2
        entries = []
        if length == 0.0:
            hits = self._locate(x, y)
            for i, j, s, t in hits:
                entries += self._strain_entries(i, j, s, t, z, c, sn, 1.0 / len(hits))
            return self._row(entries)
        p0 = np.array([x - c * length / 2, y - sn * length / 2])
        d = np.array([c, sn]) * length
        for p in (p0, p0 + d):
            self._locate(*p)  # raises if the gauge leaves the plate
        # Break the segment where it crosses grid lines; the strain is linear on each piece.
        cuts = [0.0, 1.0]
        for lines, k in ((self.xs, 0), (self.ys, 1)):
            if abs(d[k]) > 0:
                lam = (lines - p0[k]) / d[k]
                cuts += list(lam[(lam > 0) & (lam < 1)])
        cuts = np.unique(cuts)
        for a, b in zip(cuts[:-1], cuts[1:]):
            for g in _GAUSS2:
                lam = a + (b - a) * g
                px, py = p0 + lam * d
                mid = p0 + 0.5 * (a + b) * d  # the piece's element: where its middle is
                i, j, _, _ = self._locate(*mid)[0]
                s = (px - self.xs[i]) / (self.xs[i + 1] - self.xs[i])
                t = (py - self.ys[j]) / (self.ys[j + 1] - self.ys[j])
                entries += self._strain_entries(i, j, s, t, z, c, sn, 0.5 * (b - a))
        return self._row(entries)

    def expand(self, u: np.ndarray) -> np.ndarray:
        """Full DOF vector(s) (fixed DOFs zero) from reduced ones; time on the last axis."""
        full = np.zeros((self.basis.N,) + u.shape[1:])
        full[self.free] = u
        return full

    def field_frames(self, full: np.ndarray):
        """The fields of full DOF vectors ``full`` (N, n_frames) for a field file (:mod:`softimpact.output.fields`):
        points (n_nodes, 3) [m] of the mid-surface (z = 0), cells (n_cells, 4) (the node grid split into quads: an
        MITC9 element shows as its four sub-quads), point data ``displacement`` (u, v, w) and ``rotation``
        (φ_x, φ_y), each (n_frames, n_nodes, k); no cell data."""
        xy = self.node_xy()
        points = np.column_stack((xy[0], xy[1], np.zeros(xy.shape[1])))
        g = self.grid_node
        cells = np.column_stack((g[:-1, :-1].ravel(), g[1:, :-1].ravel(), g[1:, 1:].ravel(), g[:-1, 1:].ravel()))
        nd = self.basis.nodal_dofs
        disp = np.stack([full[nd[c]].T for c in (U, V, W)], axis=-1)
        rot = np.stack([full[nd[c]].T for c in (PHI_X, PHI_Y)], axis=-1)
        return points, cells, {"displacement": disp, "rotation": rot}, {}

    def load_vector(self, pressure) -> np.ndarray:
        """Consistent nodal loads (free DOFs) of a transverse pressure q(x, y) [Pa], up +,
        ``pressure`` a callable of (x, y) arrays or a constant (4 × 4 Gauss per element)."""
        g, wg = _gauss01(4)
        I, J, S, T = np.meshgrid(np.arange(self.xs.size - 1), np.arange(self.ys.size - 1), g, g, indexing="ij")
        I, J, S, T = (a[self.elements] for a in (I, J, S, T))  # the assembled elements only, (ne, 4, 4)
        hx, hy = np.diff(self.xs)[I], np.diff(self.ys)[J]
        X, Y = self.xs[I] + S * hx, self.ys[J] + T * hy
        q = pressure(X, Y) if callable(pressure) else np.full(X.shape, float(pressure))
        wgt = q * hx * hy * wg[None, :, None] * wg[None, None, :]
        nodes, N = self.shape(I, J, S, T)
        f = np.bincount(nodes.ravel(), weights=(N * wgt[..., None]).ravel(), minlength=self.grid_node.size)
        full = np.zeros(self.basis.N)
        full[self.basis.nodal_dofs[W]] = f
        return full[self.free]
