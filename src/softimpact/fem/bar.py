"""Longitudinal rod of Hermite elements (ref 4): DOFs u and du/dx at each node.

scikit-fem's ``ElementLineHermite`` has exactly these DOFs, so N elements give
2(N + 1) DOFs (39 elements → 80 DOFs, as in the paper). Stiffness
K = ∫ EA u' v' dx, consistent mass M = ∫ ρA u v dx, free–free. A lumped mass
(the end cap) may be added to the axial DOF of the struck end, x = 0.

An area change (a real end cap of larger diameter) would be modelled as a short
segment of its own EA and ρA: across the junction the axial *force* EA·u' is
continuous while the strain u' jumps, so the strain DOF cannot be shared there;
such a segment needs a C⁰ (Lagrange) junction or a split strain DOF. The paper's
text treats the cap as added inertia, which is what the lumped mass does.

Positions x [m] are measured from the struck end.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse

from ..errors import InputError
from .contact import rod_contact_structure
from .linear import LinearModel, PointLoad
from .newmark import SolverSpec

__all__ = ["Rod", "RodModel", "BarModel", "assemble_rod", "field_points"]


@dataclass(frozen=True)
class Rod:
    """A uniform, free–free rod: length [m], area [m²], E [Pa], ρ [kg/m³].

    ``end_mass`` [kg] is lumped on the axial DOF at x = 0.
    """

    length: float
    area: float
    youngs_modulus: float
    density: float
    elements: int
    end_mass: float = 0.0

    @classmethod
    def of(cls, spec) -> Rod:
        """The FE rod of a bar (:class:`softimpact.models.specimens.BarSpec`), the end cap's mass
        lumped at x = 0."""
        cap = spec.end_cap
        return cls(spec.length, spec.area, spec.material.youngs_modulus, spec.material.density, spec.elements, 0.0 if cap is None else cap.mass)

    def __post_init__(self):
        for name in ("length", "area", "youngs_modulus", "density"):
            if not getattr(self, name) > 0:
                raise InputError(f"{name} must be positive, got {getattr(self, name)!r}", name)
        if not (isinstance(self.elements, int) and self.elements >= 1):
            raise InputError(f"elements must be a positive integer, got {self.elements!r}", "elements")
        if self.end_mass < 0:
            raise InputError(f"end mass must be non-negative, got {self.end_mass!r}", "end_mass")

    @property
    def wave_speed(self) -> float:
        """c = sqrt(E/ρ) [m/s]."""
        return float(np.sqrt(self.youngs_modulus / self.density))

    @property
    def axial_stiffness(self) -> float:
        """EA [N]."""
        return self.youngs_modulus * self.area

    @property
    def impedance(self) -> float:
        """Z = ρ·c·A [N·s/m]: force per unit particle velocity of a travelling wave."""
        return self.density * self.wave_speed * self.area


class RodModel:
    """Assembled rod: sparse ``M`` and ``K`` (n × n), DOF indices and probes."""

    def __init__(self, rod: Rod):
        from skfem import Basis, BilinearForm, ElementLineHermite, MeshLine

        self.rod = rod
        self.nodes = np.linspace(0.0, rod.length, rod.elements + 1)
        self._basis = Basis(MeshLine(self.nodes), ElementLineHermite())
        EA, rhoA = rod.axial_stiffness, rod.density * rod.area

        @BilinearForm
        def stiffness(u, v, w):
            return EA * u.grad[0] * v.grad[0]

        @BilinearForm
        def mass(u, v, w):
            return rhoA * u * v

        self.K = stiffness.assemble(self._basis).tocsr()
        M = mass.assemble(self._basis).tolil()
        self.axial_dofs = self._basis.nodal_dofs[0]
        self.strain_dofs = self._basis.nodal_dofs[1]
        self.end_dof = int(self.axial_dofs[0])
        M[self.end_dof, self.end_dof] += rod.end_mass
        self.M = M.tocsr()
        self.n = self.K.shape[0]

    def strain_probe(self, x) -> scipy.sparse.csr_matrix:
        """Matrix P, shape (len(x), n), with P @ u = du/dx at the points ``x`` [m].

        At a node this picks the strain DOF itself; between nodes it uses the
        cubic Hermite interpolation, whose derivative is quadratic.
        """
        x = np.atleast_1d(np.asarray(x, dtype=float))
        if np.any(x < 0) or np.any(x > self.rod.length):
            raise InputError(f"gauge position outside the bar [0, {self.rod.length}] m: {x}")
        basis = self._basis
        cells = basis.mesh.element_finder(mapping=basis.mapping)(x)
        ref = basis.mapping.invF(x[None, :, None], tind=cells)
        rows, cols, vals = [], [], []
        for k in range(basis.Nbfun):
            grad = basis.elem.gbasis(basis.mapping, ref, k, tind=cells)[0].grad[0]
            rows.append(np.arange(x.size))
            cols.append(basis.element_dofs[k, cells])
            vals.append(grad.ravel())
        P = scipy.sparse.coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(x.size, self.n))
        return P.tocsr()


def assemble_rod(rod: Rod) -> RodModel:
    """Assemble the rod's mass and stiffness (scikit-fem, Hermite elements)."""
    return RodModel(rod)


def field_points(rod: Rod, per_element: int = 4) -> np.ndarray:
    """Where the strain field along the bar is sampled: ``per_element`` intervals per element [m]."""
    return np.linspace(0.0, rod.length, rod.elements * per_element + 1)


class BarModel(LinearModel):
    """The rod at one time step (:class:`softimpact.fem.linear.LinearModel`): a compressive force on
    the struck end (its axial DOF, pushing into the bar), the strains at ``gauges`` [m] and at
    ``field`` [m] (default :func:`field_points`) as outputs, gauges first."""

    def __init__(self, rod: Rod, solver: SolverSpec, gauges=(), field=None):
        self.rod = rod
        self.assembled = model = assemble_rod(rod)
        self.gauges = np.asarray(gauges, float).reshape(-1)
        self.field = field_points(rod) if field is None else np.asarray(field, float)
        O = model.strain_probe(np.r_[self.gauges, self.field]).toarray()
        super().__init__(model.M, model.K, None, solver, [model.end_dof], 1.0, O, PointLoad())

    def contact_structure(self, point: float = 0.0, reach: float = 0.0):
        """The rod struck at its end x = 0 (``point`` must be 0; ``reach`` is not used: one node)."""
        if point != 0.0:
            raise InputError(f"a bar is struck at its end, x = 0, got {point!r} m", "position")
        return rod_contact_structure(self.assembled, self.O)

    def _drop_mesh(self, light) -> None:
        light.assembled = None
