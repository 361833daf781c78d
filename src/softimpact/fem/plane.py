"""Four-node plane elements for a beam in its axis–thickness plane (ref 10).

scikit-fem's ``ElementVector(ElementQuad1())`` on a structured mesh of
nx × nz elements over x ∈ [0, L] (the axis) and z ∈ [0, h] (the thickness, z up);
two translations per node. The material matrix D (3×3) relates
(σxx, σzz, τxz) to (εxx, εzz, γxz) and may differ from layer to layer of
elements (the layered laminate). Stiffness K = b∫ εᵀDε dA and mass
M = b∫ ρ u·v dA (consistent, or row-sum lumped), b the width, so forces are
in N for the whole beam. Supports remove DOFs; the reduced (free) system is
what is integrated.

The default 200 × 6 mesh has 201 × 7 nodes × 2 − 14 clamped = 2800 DOFs, as in
the paper.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse

from ..errors import InputError

__all__ = ["PlaneBeam", "SUPPORTS", "centre_strain"]

SUPPORTS = ("clamped-free", "clamped-clamped", "simply-supported")


@dataclass(frozen=True)
class PlaneBeam:
    """Geometry, mesh, materials and support of the plane beam model.

    ``layers``: one 3×3 D [Pa] per element layer, bottom first (length nz), or a
    single matrix for all. ``density`` [kg/m³].
    """

    length: float
    thickness: float
    width: float
    nx: int
    nz: int
    layers: tuple
    density: float
    support: str = "clamped-free"
    lumped: bool = False

    def __post_init__(self):
        for k in ("length", "thickness", "width", "density"):
            if not getattr(self, k) > 0:
                raise InputError(f"{k} must be positive, got {getattr(self, k)!r}", k)
        if not (isinstance(self.nx, int) and isinstance(self.nz, int) and self.nx >= 1 and self.nz >= 1):
            raise InputError(f"elements must be two positive integers, got [{self.nx!r}, {self.nz!r}]", "elements")
        if self.support not in SUPPORTS:
            raise InputError(f"support: {self.support!r} is not one of {', '.join(SUPPORTS)}", "support")
        if len(self.layers) not in (1, self.nz):
            raise InputError(f"{len(self.layers)} layer matrices for {self.nz} element layers")


class PlaneModel:
    """Assembled plane beam: reduced ``K``, ``M`` (free DOFs), and functionals for outputs."""

    def __init__(self, beam: PlaneBeam):
        from skfem import Basis, BilinearForm, ElementQuad1, ElementVector, MeshQuad
        from skfem.helpers import dot

        self.beam = beam
        xs = np.linspace(0.0, beam.length, beam.nx + 1)
        zs = np.linspace(0.0, beam.thickness, beam.nz + 1)
        self.xs, self.zs = xs, zs
        mesh = MeshQuad.init_tensor(xs, zs)
        element = ElementVector(ElementQuad1())
        basis = Basis(mesh, element)
        self.basis = basis
        b = beam.width

        def strain(u):
            return [u.grad[0][0], u.grad[1][1], u.grad[0][1] + u.grad[1][0]]

        def stiffness_form(D):
            @BilinearForm
            def form(u, v, w):
                eu, ev = strain(u), strain(v)
                return b * sum(D[i, j] * eu[j] * ev[i] for i in range(3) for j in range(3) if D[i, j] != 0.0)

            return form

        rho = beam.density

        @BilinearForm
        def mass(u, v, w):
            return b * rho * dot(u, v)

        if len(beam.layers) == 1:
            K = stiffness_form(np.asarray(beam.layers[0])).assemble(basis)
        else:
            # Elements of each layer of the structured mesh, by the height of their centres.
            centres = mesh.p[1, mesh.t].mean(axis=0)
            layer = np.clip(np.floor(centres / beam.thickness * beam.nz).astype(int), 0, beam.nz - 1)
            K = None
            for j, D in enumerate(beam.layers):
                sub = Basis(mesh, element, elements=np.flatnonzero(layer == j))
                Kj = stiffness_form(np.asarray(D)).assemble(sub)
                K = Kj if K is None else K + Kj
        M = mass.assemble(basis)
        if beam.lumped:
            M = scipy.sparse.diags(np.asarray(M.sum(axis=1)).ravel())
        self.fixed = self._support_dofs()
        self.free = np.setdiff1d(np.arange(basis.N), self.fixed)
        self.K_full, self.M_full = K.tocsr(), M.tocsr()
        self.K = self.K_full[self.free][:, self.free].tocsr()
        self.M = self.M_full[self.free][:, self.free].tocsr()
        self.n = self.free.size
        self._index = np.full(basis.N, -1)
        self._index[self.free] = np.arange(self.n)
        p = mesh.p
        top = np.flatnonzero(np.isclose(p[1], beam.thickness))
        self.top_nodes = top[np.argsort(p[0, top])]
        bottom = np.flatnonzero(np.isclose(p[1], 0.0))
        self.bottom_nodes = bottom[np.argsort(p[0, bottom])]
        self.node_x = p[0]
        self.node_z = p[1]

    def _support_dofs(self) -> np.ndarray:
        beam, basis = self.beam, self.basis
        p = basis.mesh.p
        nd = basis.nodal_dofs  # (2, n_nodes): x and z DOF of each node
        left = np.flatnonzero(np.isclose(p[0], 0.0))
        right = np.flatnonzero(np.isclose(p[0], beam.length))
        if beam.support == "clamped-free":
            return np.sort(nd[:, left].ravel())
        if beam.support == "clamped-clamped":
            return np.sort(np.concatenate((nd[:, left].ravel(), nd[:, right].ravel())))
        # simply supported: the mid-thickness line (or the bottom) pinned at x = 0, on rollers at x = L
        mid = beam.thickness / 2 if beam.nz % 2 == 0 else 0.0
        a = left[np.argmin(np.abs(p[1, left] - mid))]
        c = right[np.argmin(np.abs(p[1, right] - mid))]
        return np.sort(np.array([nd[0, a], nd[1, a], nd[1, c]]))

    def dof(self, node: int, component: int) -> int:
        """Index in the reduced system of a node's x (0) or z (1) DOF; −1 if fixed."""
        return int(self._index[self.basis.nodal_dofs[component, node]])

    def surface_strain(self, x: float, surface: str, length: float) -> np.ndarray:
        """Row r (over the free DOFs) with r·u = axial strain averaged over a gauge of ``length``
        centred at ``x`` on the ``top`` or ``bottom`` face.

        On a face, u_x is linear between nodes, so the average of ∂u_x/∂x over
        [x − l/2, x + l/2] is (u_x(x + l/2) − u_x(x − l/2))/l exactly.
        """
        nodes = self.top_nodes if surface == "top" else self.bottom_nodes
        if surface not in ("top", "bottom"):
            raise InputError(f"gauge surface: {surface!r} is not 'top' or 'bottom'")
        lo, hi = x - length / 2, x + length / 2
        if lo < 0 or hi > self.beam.length or not length > 0:
            raise InputError(f"gauge at {x!r} m with length {length!r} m does not lie on the beam (0 to {self.beam.length!r} m)")
        row = np.zeros(self.n)
        for point, sign in ((hi, 1.0), (lo, -1.0)):
            for node, weight in self._face_interpolation(nodes, point):
                k = self.dof(node, 0)
                if k >= 0:
                    row[k] += sign * weight / length
        return row

    def displacement(self, x: float, surface: str, component: int = 1) -> np.ndarray:
        """Row picking the x (0) or z (1) displacement at ``x`` on a face (linear between nodes)."""
        nodes = self.top_nodes if surface == "top" else self.bottom_nodes
        row = np.zeros(self.n)
        for node, weight in self._face_interpolation(nodes, x):
            k = self.dof(node, component)
            if k >= 0:
                row[k] += weight
        return row

    def _face_interpolation(self, nodes, x):
        xs = self.node_x[nodes]
        i = int(np.clip(np.searchsorted(xs, x) - 1, 0, len(xs) - 2))
        s = (x - xs[i]) / (xs[i + 1] - xs[i])
        return [(nodes[i], 1.0 - s), (nodes[i + 1], s)]

    def expand(self, u: np.ndarray) -> np.ndarray:
        """Full DOF vector(s) (fixed DOFs zero) from reduced ones; time on the last axis."""
        full = np.zeros((self.basis.N,) + u.shape[1:])
        full[self.free] = u
        return full

    def field_frames(self, full: np.ndarray, measure: str = "linear"):
        """The fields of full DOF vectors ``full`` (N, n_frames) for a field file (:mod:`softimpact.output.fields`):
        points (n_nodes, 3) [m] in the x–z plane (file y = the thickness coordinate z), cells (n_cells, 4), point
        data ``displacement`` (n_frames, n_nodes, 3) = (u_x, u_z, 0) and cell data at the element centres
        (:func:`centre_strain` in the strain ``measure``), each (n_frames, n_cells)."""
        mesh = self.basis.mesh
        points = np.column_stack((mesh.p[0], mesh.p[1], np.zeros(mesh.p.shape[1])))
        cells = np.asarray(mesh.t.T, int)
        nd = self.basis.nodal_dofs
        ux, uz = full[nd[0]], full[nd[1]]
        disp = np.stack((ux.T, uz.T, np.zeros_like(ux.T)), axis=-1)
        strain = centre_strain(points[:, :2], cells, ux, uz, measure)
        return points, cells, {"displacement": disp}, {k: v.T for k, v in strain.items()}


def centre_strain(points: np.ndarray, cells: np.ndarray, ux: np.ndarray, uz: np.ndarray, measure: str = "linear") -> dict[str, np.ndarray]:
    """Strain at the centre of each axis-aligned bilinear quad: ε_xx = ∂u_x/∂x, ε_zz = ∂u_z/∂z,
    γ_xz = ∂u_x/∂z + ∂u_z/∂x (``measure`` "linear"), or the Green–Lagrange strain of the total Lagrangian beam
    (``"green-lagrange"``: E_xx = u_x,x + ½(u_x,x² + u_z,x²), E_zz = u_z,z + ½(u_x,z² + u_z,z²), 2E_xz = u_x,z + u_z,x +
    u_x,x·u_x,z + u_z,x·u_z,z; zero under a rigid rotation). At the centre ∂N_i/∂x = s_i/(2·h_x), s_i = ±1 on the
    right/left nodes (and so for z). ``points`` (n_nodes, 2) [m], ``cells`` (n_cells, 4) node indices,
    ``ux``, ``uz`` (n_nodes, n_frames) [m]; returns arrays (n_cells, n_frames)."""
    if measure not in ("linear", "green-lagrange"):
        raise ValueError(f"strain measure must be 'linear' or 'green-lagrange', got {measure!r}")
    x, z = points[cells, 0], points[cells, 1]  # (n_cells, 4)
    sx = np.sign(x - x.mean(axis=1, keepdims=True))
    sz = np.sign(z - z.mean(axis=1, keepdims=True))
    hx = x.max(axis=1) - x.min(axis=1)
    hz = z.max(axis=1) - z.min(axis=1)

    def d(u, s, h):  # (n_cells, n_frames)
        return np.einsum("ck,ckf->cf", s, u[cells]) / (2.0 * h)[:, None]

    uxx, uxz, uzx, uzz = d(ux, sx, hx), d(ux, sz, hz), d(uz, sx, hx), d(uz, sz, hz)
    if measure == "linear":
        return {"strain_xx": uxx, "strain_zz": uzz, "shear_strain_xz": uxz + uzx}
    return {
        "strain_xx": uxx + 0.5 * (uxx**2 + uzx**2),
        "strain_zz": uzz + 0.5 * (uxz**2 + uzz**2),
        "shear_strain_xz": uxz + uzx + uxx * uxz + uzx * uzz,
    }
