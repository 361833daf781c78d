"""What the case kinds share: the :class:`CaseKind` protocol and small helpers."""

from __future__ import annotations

import copy
import json
from collections.abc import Callable
from pathlib import Path
from typing import Protocol

import numpy as np

from ..input.sweep_spec import get_dotted, set_dotted

__all__ = ["CaseKind", "flatten", "without", "GAUGE_FIELDS", "gauge_outputs", "gauge_keys", "expand_ply", "magnitude_and_history"]

GAUGE_FIELDS = ("peak_tensile_strain", "peak_compressive_strain", "time_of_peak_tensile_strain_s", "time_of_peak_compressive_strain_s")
LOAD_KEYS = ("load.history", "load.table", "title", "units")  # keys of a beam or plate case that leave its structure unchanged


class CaseKind(Protocol):
    """One kind of case (see :mod:`softimpact.cases`)."""

    name: str
    table: str

    def detect(self, data: dict) -> bool: ...
    def load(self, case: str, history: int | None = None) -> tuple[object, tuple[Path, ...]]: ...
    def problem(self, data: dict, base: Path): ...
    def check(self, problem) -> None: ...
    def refine(self, problem, factor: int): ...
    def study(self, problem, stride: int, progress: Callable[[int], None] | None = None) -> tuple[dict, dict]: ...
    def structure_key(self, data: dict) -> str: ...
    def prepare(self, data: dict, base: Path, runs: int, outputs: tuple[str, ...] = (), cases: tuple[dict, ...] = ()): ...
    def run(self, prepared, data: dict, base: Path, outputs: tuple[str, ...] = ()) -> dict: ...
    def summary(self, problem, result, model=None) -> dict: ...
    def output_keys(self, problem) -> tuple[str, ...]: ...
    def expand(self, data: dict, key: str) -> None: ...
    def problem_class(self) -> type: ...
    def execute(self, problem, **options): ...
    def damage_refusal(self, problem) -> str | None: ...
    def refusal(self, problem, study: str) -> str | None: ...


def flatten(tree: dict, prefix: str = "") -> dict:
    """Nested dict → {dotted key: leaf}."""
    out = {}
    for k, v in tree.items():
        name = f"{prefix}{k}"
        if isinstance(v, dict):
            out.update(flatten(v, name + "."))
        else:
            out[name] = v
    return out


def without(data: dict, keys) -> str:
    """The case as canonical JSON text with the dotted ``keys`` left out (a structure key)."""
    d = copy.deepcopy(data)
    for key in keys:
        *parents, last = key.split(".")
        node = get_dotted(d, ".".join(parents)) if parents else d
        if isinstance(node, dict):
            node.pop(last, None)
    return json.dumps(d, sort_keys=True, default=str)


def gauge_outputs(time: np.ndarray, names, strains) -> dict:
    """Per gauge: ``gauges.<g>`` peaks (:func:`softimpact.output.files.strain_peaks`) and
    ``strain_<g>.peak`` (signed extreme) / ``.peak_abs``; strains shape (n_gauges, n_steps)."""
    from ..output.files import strain_peaks

    out: dict = {"gauges": {}}
    for name, eps in zip(names, strains):
        k = int(np.argmax(np.abs(eps)))
        out["gauges"][name] = strain_peaks(time, eps)
        out[f"strain_{name}"] = {"peak": float(eps[k]), "peak_abs": float(abs(eps[k]))}
    return out


def gauge_keys(names) -> list[str]:
    """The dotted sweep outputs of :func:`gauge_outputs`."""
    keys = []
    for g in names:
        keys += [f"gauges.{g}.{f}" for f in GAUGE_FIELDS] + [f"strain_{g}.peak", f"strain_{g}.peak_abs"]
    return keys


def magnitude_and_history(out: dict, names, strains, stride: int) -> None:
    """Converge's gauge outputs: ``strain_<g>_peak_magnitude`` (unsigned: the signed extreme jumps
    between levels when two peaks of opposite sign are close) and ``strain_<g>_history``."""
    for name, eps in zip(names, strains):
        out[f"strain_{name}_peak_magnitude"] = float(np.max(np.abs(eps)))
        out[f"strain_{name}_history"] = eps[::stride]


def expand_ply(data: dict, key: str, where: str) -> None:
    """A catalogue ply name at ``where`` turned into its inline table, before one of its properties is set."""
    from ..models.laminate import PLIES

    if key.startswith(where + ".") and isinstance(get_dotted(data, where), str):
        name = get_dotted(data, where)
        if name not in PLIES:
            return
        p = PLIES[name]
        inline = {"name": p.name, "source": p.source, "nu12": p.nu12, "nu13": p.nu13, "nu23": p.nu23}
        inline.update({k: f"{getattr(p, k)!r} Pa" for k in ("E1", "E2", "E3", "G12", "G13", "G23")})
        inline["density"] = f"{p.density!r} kg/m^3"
        inline["thickness"] = f"{p.thickness!r} m"
        if p.strength is not None:  # the catalogue ply's strengths stay with it (damage outputs)
            x = p.strength
            inline.update({k: f"{v!r} Pa" for k, v in (("Xt", x.Xt), ("Xc", x.Xc), ("Yt", x.Yt), ("Yc", x.Yc), ("S", x.S12), ("S23", x.S23))})
            inline["G_IIc"] = f"{x.GIIc!r} J/m^2"
        set_dotted(data, where, inline)
