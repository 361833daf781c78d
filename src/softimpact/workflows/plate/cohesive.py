"""A plate split into sublaminates tied by cohesive interfaces, as the target of a coupled impact: the
problem (:class:`CohesivePlateProblem`, a :class:`~softimpact.workflows.plate.problem.PlateProblem` with its
interfaces and their law) and its structure model (:class:`CohesivePlateModel`, stepped by the one nonlinear
engine, :data:`softimpact.fem.steppers.STEPPERS` ``"cohesive"``)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...errors import InputError
from ...fem.contact import output_groups, plate_reach
from ...fem.plate_loads import CircularPatch
from ...models.cohesive import BilinearCohesive
from .nonlinear import _SupportedView
from .problem import PlateProblem

__all__ = ["CohesivePlateProblem", "CohesivePlateModel", "interface_label"]


def interface_label(split: int) -> str:
    """The name of the interface below ply ``split`` (1 = the top ply) in outputs: ``plies_3_4``."""
    return f"plies_{split}_{split + 1}"


class _TopView(_SupportedView):
    """The top sublaminate's mesh seen over the stacked DOFs (``n``): :meth:`expand` maps a stacked vector (or
    snapshots) to a full vector of the mesh, the struck sublaminate's in the near field and the laminate's in the far
    field (:meth:`~softimpact.fem.cohesive_plate.CohesivePlate.surface_vector`), so deflected shapes and fields show the
    struck face."""

    def __init__(self, stack, plate):
        super().__init__(stack.layers[0], plate)
        self.n, self._stack = stack.n, stack

    def expand(self, u: np.ndarray) -> np.ndarray:
        return self._stack.surface_vector(np.asarray(u))


@dataclass(frozen=True)
class CohesivePlateProblem(PlateProblem):
    """A plate problem whose laminate is split below the plies ``splits`` (1 = the top ply) into sublaminates
    tied by the cohesive ``law`` (:mod:`softimpact.fem.cohesive_plate`); linear kinematics only (the sublaminates
    are linear: the interfaces are the nonlinearity). A coupled impact on it steps ``"cohesive"``.

    ``near_field`` [m]: the half-width of the square about the impact point where the laminate is stacked and the
    mesh graded down to ``element_size`` [m] (None for that size: the process zone's, :meth:`resolution`); outside
    it, one plate of the laminate on the problem's own mesh (:class:`~softimpact.fem.cohesive_plate.CohesivePlate`'s
    far field). None: the whole plate stacked on the problem's mesh (the process zone then as resolved as that mesh
    lets it be: :meth:`resolution` says). ``turon``: the interface strengths lowered to Turon et al.'s for the
    near field's node spacing (:meth:`~softimpact.models.cohesive.BilinearCohesive.adjusted`), so a coarser mesh
    resolves the zone; off by default, and every run that uses it says so."""

    splits: tuple[int, ...] = ()
    law: BilinearCohesive | None = None
    near_field: float | None = None
    element_size: float | None = None
    turon: bool = False

    coupled_stepper = "cohesive"  # the target's own stepper (fem.steppers.STEPPERS)

    def __post_init__(self):
        super().__post_init__()
        if self.kinematics != "linear":
            raise InputError("cohesive interfaces tie linear sublaminates: the target plate's kinematics must be 'linear'", "kinematics")
        if not self.splits or self.law is None:
            raise InputError("cohesive interfaces: at least one interface and its law are needed", "cohesive")
        n = len(self.plate.stack.angles)
        if list(self.splits) != sorted(set(self.splits)) or self.splits[0] < 1 or self.splits[-1] >= n:
            raise InputError(f"cohesive interfaces below plies {list(self.splits)!r}: each between plies k and k + 1, 1 ≤ k < {n}, each once", "cohesive")
        for key in ("near_field", "element_size"):
            v = getattr(self, key)
            if v is not None and not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise InputError(f"{key} must be a positive length, got {v!r} m", key)
        if self.element_size is not None and self.near_field is None:
            raise InputError("element_size: the near field's element size needs a near field (near_field)", "element_size")
        if self.near_field is not None and self.load is not None:
            x, y = self.load.position
            spec = self.plate
            if min(x, y) < 0 or x > spec.length_x or y > spec.length_y:
                raise InputError(f"near_field: the impact point {self.load.position!r} m is off the plate", "near_field")

    @classmethod
    def of(cls, problem: PlateProblem, splits, law: BilinearCohesive, *, near_field=None, element_size=None, turon: bool = False) -> CohesivePlateProblem:
        """``problem`` with the interfaces below the plies ``splits`` (sorted) tied by ``law`` (class docstring for the rest)."""
        fields = {f: getattr(problem, f) for f in PlateProblem.__dataclass_fields__}
        return cls(**fields, splits=tuple(sorted(int(k) for k in splits)), law=law, near_field=near_field, element_size=element_size, turon=bool(turon))

    # --- the process zone and the mesh that resolves it ---

    @property
    def transverse_modulus(self) -> float:
        """E3 of the ply [Pa]: the modulus of the process zone's length."""
        return float(self.plate.stack.ply.E3)

    def resolution(self) -> dict:
        """What the mesh makes of the process zone: the law's shorter pure-mode zone l_cz
        (:meth:`~softimpact.models.cohesive.BilinearCohesive.process_zone`, of the law the run uses: Turon's if asked),
        the node spacing it needs (l_cz/:data:`~softimpact.models.cohesive.ZONE_ELEMENTS`), the mesh's node spacing where
        the interfaces are (the near field's, or the whole plate's largest) and the zone's span in node spacings."""
        from ...models.cohesive import ZONE_ELEMENTS

        law, spacing = self.run_law(), self.node_spacing()
        zone = law.process_zone(self.transverse_modulus)
        return {
            "process_zone_m": zone,
            "node_spacing_needed_m": zone / ZONE_ELEMENTS,
            "node_spacing_m": spacing,
            "zone_spacings": zone / spacing,
            "turon": self.turon,
        }

    def node_spacing(self) -> float:
        """The node spacing [m] where the interfaces are: the near field's element size over the element's order (MITC9:
        half of it), or the problem's largest element's without a near field."""
        order = 2 if self.plate.element == "mitc9" else 1
        if self.near_field is not None:
            return self.near_element_size() / order
        nx, ny = self.plate.elements
        return max(self.plate.length_x / nx, self.plate.length_y / ny) / order

    def near_element_size(self) -> float:
        """The near field's element size [m]: ``element_size``, or the one whose node spacing resolves the law's own
        process zone over :data:`~softimpact.models.cohesive.ZONE_ELEMENTS` (Turon's law being set by the size, not setting it)."""
        from ...models.cohesive import ZONE_ELEMENTS

        if self.element_size is not None:
            return self.element_size
        order = 2 if self.plate.element == "mitc9" else 1
        return order * self.law.process_zone(self.transverse_modulus) / ZONE_ELEMENTS

    def run_law(self) -> BilinearCohesive:
        """The law the run uses: ``law``, or with ``turon`` its strengths adjusted to the near field's node spacing."""
        if not self.turon:
            return self.law
        return self.law.adjusted(self.transverse_modulus, self.node_spacing())

    def stacked_mesh(self):
        """(plate, near mask or None): the :class:`~softimpact.fem.plate.Plate` the stack is built on (graded about the
        impact point to the near field's element size) and the near field's elements."""
        from dataclasses import replace

        from ...fem.plate import graded_lines

        plate = self.plate.plate()
        if self.near_field is None:
            return plate, None
        spec, (x0, y0), R = self.plate, self.load.position, self.near_field
        fine = self.near_element_size()
        xs = graded_lines(spec.length_x, max(0.0, x0 - R), min(spec.length_x, x0 + R), fine, max(fine, spec.length_x / spec.elements[0]))
        ys = graded_lines(spec.length_y, max(0.0, y0 - R), min(spec.length_y, y0 + R), fine, max(fine, spec.length_y / spec.elements[1]))
        plate = replace(plate, nx=xs.size - 1, ny=ys.size - 1, xs=tuple(xs), ys=tuple(ys))
        cx, cy = 0.5 * (xs[:-1] + xs[1:]), 0.5 * (ys[:-1] + ys[1:])
        near = (np.abs(cx - x0)[:, None] < R) & (np.abs(cy - y0)[None, :] < R)
        return plate, near

    def model(self, patch_radius: float | None = None, damage: bool = False) -> CohesivePlateModel:
        """The :class:`CohesivePlateModel` (``patch_radius`` unused: the disc is the contact's)."""
        return CohesivePlateModel(self, damage=damage)

    def validity(self, max_deflection: float):
        """The plate's deflection envelope, and the process zone's resolution (:func:`~softimpact.models.validity.zone_flags`)."""
        from ...models.validity import zone_flags

        res = self.resolution()
        return super().validity(max_deflection) + zone_flags("the cohesive interfaces", res["process_zone_m"], res["node_spacing_m"])

    def check(self) -> None:
        """Refuse, before anything is built, a stack too big for the machine (the resource guard on what is factored:
                the STACK, not one plate): the near field's nodes carry 5 DOFs per sublaminate (u, v, w, φx, φy: a sublaminate
                of a symmetric laminate is unsymmetric), the far field's 5; the factor of a 2-D grid of N nodes of b DOFs each,
                ordered by minimum degree, holds about 3·N·log₂N·b² entries (seen: 29 M for 17 775 DOFs of 15 sublaminates on
                a 16 × 16 MITC4 grid), a step four solves of it, and the columns the engine keeps to update that factor where the
        interfaces change (:data:`~softimpact.fem.rank_update.COLUMN_BYTES` at most). A refusal names the node spacing the process zone needs and
                what Turon's strengths would allow."""
        from ...errors import TooLarge
        from ...guards import require_resources

        plate, near = self.stacked_mesh()
        order = 2 if self.plate.element == "mitc9" else 1
        layers = len(self.splits) + 1
        if near is None:
            near = np.ones((plate.nx, plate.ny), bool)
        n_near = (order * near.any(axis=1).sum() + 1) * (order * near.any(axis=0).sum() + 1)
        n_all = (order * plate.nx + 1) * (order * plate.ny + 1)
        n_far = max(n_all - n_near, 0)
        dofs = 5 * (layers * n_near + n_far)
        fill = 3.0 * (n_near * math.log2(max(n_near, 2)) * (5 * layers) ** 2 + n_far * math.log2(max(n_far, 2)) * 25)
        steps = self.solver.steps if self.solver is not None else 1
        what = f"a stack of {layers} sublaminates ({dofs} DOF, {near.sum()} near-field elements of {self.node_spacing() * order * 1e3:.3g} mm)"
        from ...fem.rank_update import COLUMN_BYTES

        columns = min(COLUMN_BYTES, 8.0 * dofs * 3 * n_near * (layers - 1))  # the kept factor's update (fem.rank_update)
        try:
            require_resources(what, 2 * 8.0 * fill + columns, 4 * 2 * fill * steps)
        except TooLarge as exc:
            res = self.resolution()
            advice = "" if self.turon else "; Turon's strengths (turon = true) resolve it on a coarser near field (element_size, e.g. 2 mm)"
            raise TooLarge(
                f"{exc}. The process zone ({res['process_zone_m'] * 1e3:.3g} mm) needs a node spacing of {res['node_spacing_needed_m'] * 1e3:.3g} mm"
                f"{advice}, or a smaller near field"
            ) from None

    def summary_extras(self, model, result) -> dict:
        """The plate's ``target`` block with its sublaminates and interfaces, the near field and the process zone's
        resolution (and the interface law the run used, Turon's where asked)."""
        out = super().summary_extras(model, result)
        law = self.run_law()
        out["target"] = {
            **out["target"],
            "model": f"fsdt ({self.plate.element.upper()}), {len(self.splits) + 1} sublaminates tied by cohesive interfaces"
            + ("" if self.near_field is None else f" in a {2 * self.near_field * 1e3:.4g}-mm near field, one plate of the laminate beyond it"),
            "interfaces": [interface_label(k) for k in self.splits],
            "in_plane": "movable",
            "elements": [int(n) for n in model.stack.near.shape],
            "near_field_half_width_m": self.near_field,
            "cohesive_resolution": self.resolution(),
            "cohesive_law": {
                "penalty_N_m3": law.K,
                "normal_strength_Pa": law.N,
                "shear_strength_Pa": law.S,
                "G_Ic_J_m2": law.GIc,
                "G_IIc_J_m2": law.GIIc,
                "bk_exponent": law.eta,
            },
        }
        return out


class CohesivePlateModel:
    """The sublaminates and interfaces of a :class:`CohesivePlateProblem` (:class:`~softimpact.fem.cohesive_plate.CohesivePlate`
    ``stack``), their Newmark–Newton ``stepper`` (:class:`~softimpact.fem.nonlinear.NonlinearNewmark`, modified Newton with its line search),
    the output rows (gauges on the top face read the top sublaminate, on the bottom face the bottom one; then the
    ``"damage"`` group's point strains the same way; then the ``"columns"`` group: the delaminated and process-zone
    areas and the interfaces' energies, :data:`~softimpact.fem.cohesive_plate.HISTORY_ROWS`, then the areas per
    interface). ``fe``: the top sublaminate's mesh over the stacked DOFs (snapshots, deflected shapes and fields show
    the struck sublaminate). No response engine or kernels."""

    coupled_stepper = "cohesive"

    @property
    def mesh(self):
        """The top sublaminate's mesh over the stacked DOFs (``fe``: ``expand``, ``field_frames``)."""
        return self.fe

    def __init__(self, problem: CohesivePlateProblem, damage: bool = False):
        from ...fem.cohesive_plate import HISTORY_ROWS, CohesivePlate
        from ...fem.nonlinear import NonlinearNewmark

        self.problem = problem
        self.damage = problem.damage_gauges() if damage else ()
        plate, near = problem.stacked_mesh()
        self.stack = st = CohesivePlate(plate, problem.plate.stack, problem.splits, problem.run_law(), near=near)
        top = st.layers[0]
        self.fe = _TopView(st, plate)
        self._view = _SupportedView(top, plate)  # the contact disc's nodes: the top sublaminate's own DOFs
        a, b = problem.plate.damping
        self.C = None if a == 0 and b == 0 else (a * st.M + b * st.K).tocsr()
        self.solver = problem.solver
        self.stepper = NonlinearNewmark(st, problem.solver.time_step, self.C, problem.solver.newmark, tangent="modified")
        gauges = problem.gauges + self.damage

        def row(g):
            return st.surface_strain(*g.position, g.surface, g.direction, g.length)

        labels = [interface_label(k) for k in problem.splits]
        self.column_names = HISTORY_ROWS + tuple(f"{q}_{lab}" for q in HISTORY_ROWS[:2] for lab in labels)
        rows = [row(g) for g in gauges] + [np.zeros(st.n)] * len(self.column_names)
        self.O = np.array(rows).reshape(len(rows), st.n)
        self._names = tuple(g.name for g in gauges) + self.column_names

    @property
    def size(self) -> int:
        """The stacked sublaminates' free DOFs."""
        return self.stack.n

    @property
    def steps(self) -> int:
        return self.solver.steps

    def damage_map(self) -> np.ndarray:
        """The committed damage (interfaces, nodes) of the last run (node numbering of ``fe``)."""
        return self.stack.damage

    def cscan(self):
        """What a C-scan of the last run shows (:func:`~softimpact.workflows.plate.cscan.cscan`): each interface's
        delaminated region, its area and shape beside the fibre angle of the ply below it, and the projected envelope,
        of the whole plate (symmetry edges mirrored)."""
        from .cscan import cscan

        fe, st, p = self.fe, self.stack, self.problem
        angles = p.plate.stack.angles
        return cscan(
            st.damage,
            fe.node_xs,
            fe.node_ys,
            fe.grid_node,
            st.area,
            tuple(p.plate.supports),
            tuple(interface_label(k) for k in p.splits),
            tuple(float(angles[k]) for k in p.splits),  # split k: below ply k (1 = top), the lower ply is angles[k]
        )

    def direct(self, *args, **kwargs):
        raise InputError("a plate with cohesive interfaces runs as the target of a coupled impact only (softimpact impact)")

    def contact_structure(self, point: tuple[float, float], reach: float):
        """The top sublaminate struck downward at ``point`` (x, y) [m], contact discs up to ``reach`` [m]."""
        from ...errors import NoContactRoom
        from ...fem.impact import ContactStructure
        from ...fem.plate_loads import DiscShares

        st = self.stack
        top = st.layers[0]
        patch = CircularPatch(self._view, point, reach, grow=True)
        dofs = top._index[patch.dofs]
        if np.any(dofs < 0):
            raise NoContactRoom(f"contact patch about {tuple(point)!r} m reaches a supported edge or the cohesive near field's rim")
        dofs = st.layer_dofs(0)[dofs]
        if np.any(dofs < 0):
            raise NoContactRoom(f"contact patch about {tuple(point)!r} m reaches the cohesive near field's rim: widen cohesive.near_field")
        return ContactStructure(
            M=st.M,
            K=st.K,
            surface_x=top.fe.node_xy()[0, patch.nodes],
            surface_dofs=dofs,
            load_sign=-1.0,  # w is up +, the impact pushes down
            center=float(point[0]),
            approach_row=-st.deflection(*point),
            outputs=self.O,
            output_names=self._names,
            C=self.C,
            patch=DiscShares(patch),
            groups=self.contact_groups(),
        )

    def contact_groups(self) -> dict[str, tuple[int, ...]]:
        """``"gauges"``, ``"damage"`` (when built with it) and ``"columns"`` (history.csv's extra columns)."""
        return output_groups(gauges=len(self.problem.gauges), damage=len(self.damage), columns=len(self.column_names))

    def contact_reach(self, point: tuple[float, float], diameter: float) -> float:
        """The impactor's diameter cut by the plate's edges (:func:`softimpact.fem.contact.plate_reach`)."""
        return plate_reach(self.fe, self.problem.plate.supports, point, diameter)
