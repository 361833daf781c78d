"""A plate split into sublaminates tied by cohesive interfaces, as the target of a coupled impact: the
problem (:class:`CohesivePlateProblem`, a :class:`~softimpact.workflows.plate.problem.PlateProblem` with its
interfaces and their law) and its structure model (:class:`CohesivePlateModel`, stepped by the one nonlinear
engine, :data:`softimpact.fem.steppers.STEPPERS` ``"cohesive"``)."""

from __future__ import annotations

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
    snapshots) to the top sublaminate's full vector, so deflected shapes and fields show the struck sublaminate."""

    def __init__(self, stack, plate):
        super().__init__(stack.layers[0], plate)
        self.n, self._top = stack.n, stack.top

    def expand(self, u: np.ndarray) -> np.ndarray:
        return super().expand(np.asarray(u)[self._top])


@dataclass(frozen=True)
class CohesivePlateProblem(PlateProblem):
    """A plate problem whose laminate is split below the plies ``splits`` (1 = the top ply) into sublaminates
    tied by the cohesive ``law`` (:mod:`softimpact.fem.cohesive_plate`); linear kinematics only (the sublaminates
    are linear: the interfaces are the nonlinearity). A coupled impact on it steps ``"cohesive"``."""

    splits: tuple[int, ...] = ()
    law: BilinearCohesive | None = None

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

    @classmethod
    def of(cls, problem: PlateProblem, splits, law: BilinearCohesive) -> CohesivePlateProblem:
        """``problem`` with the interfaces below the plies ``splits`` (sorted) tied by ``law``."""
        fields = {f: getattr(problem, f) for f in PlateProblem.__dataclass_fields__}
        return cls(**fields, splits=tuple(sorted(int(k) for k in splits)), law=law)

    def check(self) -> None:
        """The resource guard on what is factored (:func:`softimpact.guards.require_resources`): the STACK, not one plate.
        Every sublaminate keeps its five DOFs a node (u, v, w, φx, φy: a sublaminate of a symmetric laminate is
        unsymmetric), the stack numbered node by node, so n = 5·S·nodes for S sublaminates and the band 5·S times the
        single plate's node band (:func:`~softimpact.workflows.plate.problem.check_problem`'s estimate, S-fold in both):
        memory 16·n·(b + 1) bytes, time n·b·(b + 4·(steps + 1)) flops. 19 interfaces on a 24 × 24 MITC9 quarter plate
        (20 sublaminates) are refused at once (tens of GB) instead of running out of memory after minutes."""
        from ...guards import require_resources

        spec = self.plate
        nx, ny = (int(n) for n in spec.elements)
        k = 2 if spec.element == "mitc9" else 1
        layers = len(self.splits) + 1
        n = 5 * layers * (k * nx + 1) * (k * ny + 1)
        band = 5 * layers * (k * (k * ny + 1) + k + 1)
        steps = self.solver.steps
        what = f"a {nx} x {ny} {spec.element.upper()} plate of {layers} sublaminates tied by {layers - 1} cohesive interfaces over {steps} steps"
        require_resources(what, 2 * 8.0 * n * (band + 1), n * band * (band + 4.0 * (steps + 1)))

    def model(self, patch_radius: float | None = None, damage: bool = False) -> CohesivePlateModel:
        """The :class:`CohesivePlateModel` (``patch_radius`` unused: the disc is the contact's)."""
        return CohesivePlateModel(self, damage=damage)

    def summary_extras(self, model, result) -> dict:
        """The plate's ``target`` block with its sublaminates and interfaces."""
        out = super().summary_extras(model, result)
        out["target"] = {
            **out["target"],
            "model": f"fsdt ({self.plate.element.upper()}), {len(self.splits) + 1} sublaminates tied by cohesive interfaces",
            "interfaces": [interface_label(k) for k in self.splits],
            "in_plane": "movable",
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
        plate = problem.plate.plate()
        self.stack = st = CohesivePlate(plate, problem.plate.stack, problem.splits, problem.law)
        top = st.layers[0]
        self.fe = _TopView(st, plate)
        self._view = _SupportedView(top, plate)  # the contact disc's nodes: the top sublaminate's own DOFs
        a, b = problem.plate.damping
        self.C = None if a == 0 and b == 0 else (a * st.M + b * st.K).tocsr()
        self.solver = problem.solver
        self.stepper = NonlinearNewmark(st, problem.solver.time_step, self.C, problem.solver.newmark, tangent="modified")
        gauges = problem.gauges + self.damage
        last = len(st.layers) - 1

        def row(g):
            layer = 0 if g.surface == "top" else last
            lay = st.layers[layer]
            return st.layer_row(layer, lay.fe.surface_strain(*g.position, g.surface, g.direction, g.length)[lay.free])

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
            raise NoContactRoom(f"contact patch about {tuple(point)!r} m reaches a supported edge")
        return ContactStructure(
            M=st.M,
            K=st.K,
            surface_x=top.fe.node_xy()[0, patch.nodes],
            surface_dofs=st.layer_dofs(0)[dofs],
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
