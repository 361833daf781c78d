"""Field output for ParaView: displacement (and, on a beam, strain) over time as an XDMF time series.

``fields.xdmf`` (the light XML: mesh, time values, array names) and ``fields.h5`` (the
arrays, HDF5) are written through meshio's :class:`meshio.xdmf.TimeSeriesWriter`
(the ``fields`` extra: ``pip install 'softimpact[fields]'``); ParaView opens the .xdmf
as a time series of meshes (Warp By Vector on ``displacement`` shows the deformed shape).

A sampled set of steps is written, not every step: every k-th step from 0 with
k = ⌈(n_steps + 1)/frames⌉, so at most ``frames`` (default :data:`FRAMES` = 200)
frames (:func:`sampled_steps`). A 1000-step beam run gives 167 frames at k = 6.

Meshes (SI, metres), one layout for every model:

- beam (:class:`softimpact.workflows.beam_impact.BeamModel`): the plane-strain Q4 mesh in
  the x–y plane of the file (file y = the beam's thickness coordinate z, 0 at the bottom
  face); point data ``displacement`` (u_x, u_z, 0) [m]; cell data at each element's
  centre ``strain_xx``, ``strain_zz``, ``shear_strain_xz`` (engineering γ) — exact for the
  bilinear field at the centre and cheap (no quadrature); on a beam with ``kinematics =
  "von-karman"`` the same names hold the Green–Lagrange strain (the model's own measure; history.csv's gauges
  read their chords' stretch, which differs from it at second order in the rotation);
- plate (:class:`softimpact.workflows.plate.PlateModel`): the mid-surface, the node
  grid split into quads (an MITC9 element shows as its four sub-quads), z = 0; point
  data ``displacement`` (u, v, w) [m] (w up +) and ``rotation`` (φ_x, φ_y) [rad].
  Surface strains of a plate need the shape-function gradients per element and are not
  written.

Fixed DOFs are zero. The displacement arrays are the model's own numbers (no
interpolation): node n's u_x is ``model.plane.expand(u)[nodal_dofs[0, n]]``.
"""

from __future__ import annotations

import math
import os
import tempfile
from dataclasses import replace
from pathlib import Path

import numpy as np

from ..fem.plane import centre_strain as beam_cell_strain  # noqa: F401  (re-exported: the cell strain of the beam's fields)

__all__ = ["FRAMES", "sampled_steps", "field_frames", "write_fields", "field_files", "select_kept", "beam_cell_strain"]

FRAMES = 200  # frames at most in a field file: ParaView scrubs them smoothly, and a 200-frame beam file stays a few MB


def sampled_steps(steps: int, frames: int = FRAMES) -> np.ndarray:
    """Step indices 0, k, 2k, … ≤ ``steps`` with k = ⌈(steps + 1)/frames⌉: at most ``frames`` of them."""
    if not (isinstance(frames, int) and frames >= 1):
        from ..errors import InputError

        raise InputError(f"frames: expected a positive integer, got {frames!r}")
    k = max(1, math.ceil((steps + 1) / frames))
    return np.arange(0, steps + 1, k)


def _columns(result, steps) -> list[int]:
    """The columns of ``result.displacement`` holding the snapshots at ``steps`` (all of them kept)."""
    at = {int(k): i for i, k in enumerate(result.kept)}
    return [at[int(s)] for s in steps]


def kept_frames(result, steps) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The frames ``(steps, time [s], displacement (n_dofs, n_frames) [m])`` of :func:`write_fields` from a
    run (with ``time``, ``displacement`` and ``kept``) that kept the snapshots at ``steps``."""
    steps = np.asarray(steps, int)
    return steps, result.time[steps], result.displacement[:, _columns(result, steps)]


def keeps(result, steps) -> bool:
    """Whether ``result`` kept the snapshots at every one of ``steps``."""
    return result.kept is not None and set(np.asarray(steps, int).tolist()) <= set(np.asarray(result.kept, int).tolist())


def select_kept(result, steps):
    """``result`` (with ``displacement`` and ``kept``) keeping only the snapshots at ``steps``, for
    figures drawn from a run that also kept the field frames."""
    if result.displacement is None or result.kept is None:
        return result
    kept = {int(k) for k in result.kept}
    steps = np.asarray([int(s) for s in steps if int(s) in kept], int)
    return replace(result, displacement=result.displacement[:, _columns(result, steps)], kept=steps)


def field_frames(model, u: np.ndarray):
    """The mesh and per-frame data of a beam or plate model's reduced displacements ``u`` (n_free, n_frames):
    (points (n_nodes, 3), cells [("quad", (n_cells, 4))], point data {name: (n_frames, n_nodes, k)},
    cell data {name: (n_frames, n_cells)}), from the model's ``mesh``
    (:class:`~softimpact.models.protocols.MeshedModel`: its full vectors and their fields)."""
    mesh = model.mesh
    u = np.asarray(u, float).reshape(model.size, -1)
    points, cells, point_data, cell_data = mesh.field_frames(mesh.expand(u))
    return points, [("quad", cells)], point_data, cell_data


def write_fields(path, model, frames, *, force: bool = False) -> np.ndarray:
    """Write ``frames`` = (step indices, times [s], reduced displacements (n_free, n_frames)) of a beam
    or plate ``model`` as ``path`` (.xdmf) and its .h5 beside it (module docstring); returns the steps.

    Both files are written together and atomically (staged beside them, then moved into place); an
    existing .xdmf or its companion .h5 is never replaced unless ``force`` (InputError naming it):
    softimpact cannot prove it wrote a file no manifest lists, so it leaves it to its owner."""
    path = Path(path)
    if path.suffix.lower() != ".xdmf":
        from ..errors import InputError

        raise InputError(f"write_fields: {path}: give an .xdmf path (its heavy data go beside it as {path.with_suffix('.h5').name})")
    pair = (path, path.with_suffix(".h5"))
    if not force:
        for p in pair:
            if p.exists() or p.is_symlink():
                from ..errors import InputError

                raise InputError(f"write_fields: {p} exists and softimpact cannot prove it wrote it: choose another path, or force=True to replace it")
    path.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix=".softimpact-fields-", dir=path.parent) as tmp:
        _write_xdmf(Path(tmp) / path.name, model, frames)
        for p in pair:
            os.replace(Path(tmp) / p.name, p)
    return np.asarray(frames[0])


def _write_xdmf(path: Path, model, frames) -> None:
    """The .xdmf and its .h5 (named by the .xdmf's stem, beside it) of ``frames`` (:func:`write_fields`)."""
    try:
        import h5py
        from meshio.xdmf import TimeSeriesWriter
    except ImportError:  # pragma: no cover - depends on the environment
        from ..errors import InputError

        raise InputError("fields: writing XDMF needs meshio and h5py: pip install 'softimpact[fields]'") from None

    class Writer(TimeSeriesWriter):
        """meshio 5.3 opens the .h5 in the working directory (``filename.stem + ".h5"``); here it
        goes beside the .xdmf, which names it by its base name, as the reader expects."""

        def __enter__(self):
            self.h5_filename = str(self.filename.with_suffix(".h5"))
            self.h5_file = h5py.File(self.h5_filename, "w")
            return self

    steps, times, u = frames
    points, cells, point_data, cell_data = field_frames(model, u)
    with Writer(str(path)) as writer:
        writer.write_points_cells(points, cells)
        for i, t in enumerate(times):
            writer.write_data(
                float(t),
                point_data={k: v[i] for k, v in point_data.items()},
                cell_data={k: [v[i]] for k, v in cell_data.items()},
            )


def field_files(model, frames, name: str = "fields") -> dict[str, bytes]:
    """The field files as bytes (``name``.xdmf, ``name``.h5), written in a temporary folder, for an
    outcome's files (so the command line's atomic writer puts them into --out with the rest).
    The .xdmf names its .h5 relative to itself, so the pair moves together."""
    with tempfile.TemporaryDirectory(prefix="softimpact-fields-") as tmp:
        _write_xdmf(Path(tmp) / f"{name}.xdmf", model, frames)
        return {f"{name}.xdmf": (Path(tmp) / f"{name}.xdmf").read_bytes(), f"{name}.h5": (Path(tmp) / f"{name}.h5").read_bytes()}
