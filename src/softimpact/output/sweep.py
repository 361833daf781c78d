"""Outputs of ``softimpact sweep``: runs.parquet, summary.json, thresholds.csv and thresholds.png;
and the sweep's checkpoints (one JSON file per finished chunk), written atomically.

A checkpoint is written through :func:`softimpact.output.files.write_outputs` (staged,
then moved into place): a chunk is checkpointed whole or not at all, and a full disk
is an InputError naming the folder (exit 2) that leaves no file a resume would trust.
"""

from __future__ import annotations

import io
import json
import textwrap
from pathlib import Path

import numpy as np

from .files import REPORT_TEXT_PT, REPORT_WIDTH_IN, csv_text, figure_bytes, json_text, write_outputs

__all__ = [
    "sweep_files",
    "threshold_figure",
    "threshold_map_figure",
    "kinematics_map_figure",
    "threshold_csv",
    "save_checkpoint",
    "load_checkpoint",
    "save_inputs",
    "earlier_inputs",
    "INPUTS",
    "parquet_bytes",
]


def save_checkpoint(folder: Path, name: str, rows: list[dict]) -> None:
    """``folder/name.json``: the rows of a finished chunk, written atomically."""
    write_outputs(folder, {f"{name}.json": json.dumps(rows)})


def load_checkpoint(folder: Path, name: str, runs) -> list[dict] | None:
    """The rows of ``folder/name.json`` if it holds exactly the runs ``runs``; None otherwise (run it again)."""
    path = Path(folder) / f"{name}.json"
    if not path.is_file():
        return None
    try:
        rows = json.loads(path.read_text(encoding="utf-8"))
        return rows if sorted(r["run"] for r in rows) == sorted(runs) else None
    except (OSError, ValueError, TypeError, KeyError):
        return None


INPUTS = "inputs.json"  # in a checkpoints folder: the spec and every file its runs read, with their SHA-256


def save_inputs(folder: Path, spec: str, inputs) -> None:
    """``folder/inputs.json``: the spec's file and the (file, sha256) its checkpoints were computed from, once."""
    if not (Path(folder) / INPUTS).is_file():
        write_outputs(folder, {INPUTS: json.dumps({"spec": spec, "inputs": dict(inputs)}, indent=1)})


def earlier_inputs(root: Path, spec: str, fingerprint: str) -> dict | None:
    """{file: sha256} of the newest other checkpoints folder under ``root`` made by the spec ``spec``; None if none."""
    found = []
    for path in Path(root).glob(f"*/{INPUTS}"):
        if path.parent.name == fingerprint:
            continue
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
            if data.get("spec") == spec and isinstance(data.get("inputs"), dict):
                found.append((path.stat().st_mtime_ns, data["inputs"]))
        except (OSError, ValueError, AttributeError):
            continue
    return max(found, key=lambda f: f[0])[1] if found else None


def parquet_bytes(cols: dict) -> bytes:
    """A table of columns (name → array or list) as Parquet."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    buf = io.BytesIO()
    pq.write_table(pa.table({k: pa.array(v) for k, v in cols.items()}), buf)
    return buf.getvalue()


def threshold_csv(th: list[dict]) -> str:
    """Threshold rows (:func:`softimpact.workflows.sweep_stats.thresholds`, or a threshold map's rows,
    :meth:`softimpact.studies.thresholds.MapRow.as_dict`) as CSV text: a map row's ``validity_flags`` (a list of names)
    joined by ", " (as runs.parquet's), ``inside_validity`` true/false (empty: not checked, no threshold)."""
    text = (
        "levels",
        "index",
        "structure",
        "regime",
        "kinematics",
        "stepping",
        "band_from",
        "validity_flags",
        "inside_validity",
        "against",
        "quantity",
        "unit",
        "limit",
    )

    def cell(t, k):
        v = t.get(k, np.nan)
        if isinstance(v, (list, tuple)):
            return ", ".join(v)
        if k == "inside_validity":
            return "" if v is None or v is np.nan else str(bool(v)).lower()
        return v

    return csv_text(
        {k: np.array([cell(t, k) for t in th], dtype=object if k in text or k.endswith("_bound") else float) for k in dict.fromkeys(k for t in th for k in t)}
    )


def sweep_files(cols: dict, summary: dict, th: list[dict], figures: bool, system: str = "in-lbf-s") -> dict:
    """runs.parquet, summary.json, with thresholds thresholds.csv (+ thresholds.png), with onsets (summary.json's
    ``onsets``) onsets.csv."""
    files = {"runs.parquet": parquet_bytes(cols)}
    if th:
        files["thresholds.csv"] = threshold_csv(th)
        if figures:
            files["thresholds.png"] = figure_bytes(threshold_figure(th, system))
    if summary.get("onsets"):
        files["onsets.csv"] = threshold_csv(summary["onsets"])
    files["summary.json"] = json_text(summary)
    return files


_KIND_OF_SUFFIX = {"m_s": "velocity", "J": "energy", "m": "length", "kg": "mass", "N": "force", "Pa": "stress", "s": "time", "N_s": "impulse"}


def threshold_figure(th: list[dict], system: str, title: str | None = None):
    """The rows' thresholds (median and 5-95 % band) per level combination and output, against the level the rows
    say (``quantity`` and ``unit``; velocity when they do not), in display units."""
    import matplotlib.pyplot as plt

    from ..units import DisplayUnit, display

    quantity, suffix = th[0].get("quantity", "velocity"), th[0].get("unit", "m_s")
    kind = _KIND_OF_SUFFIX.get(suffix)
    vu = display(system, kind) if kind else DisplayUnit(1.0, suffix.replace("_", "/") or "-")
    words = quantity.replace("_", " ")
    tail = f"_{suffix}" if suffix else ""
    title = title or f"Threshold {words} (index reaches 1, or the output its limit): median and 5-95 % band"
    fig, ax = plt.subplots(figsize=(7, 4))
    labels = list(dict.fromkeys(t["levels"] for t in th))
    indices = list(dict.fromkeys(t["index"] for t in th))
    width = 0.8 / max(len(indices), 1)
    for j, name in enumerate(indices):
        xs, ys, lo, hi = [], [], [], []
        for i, lab in enumerate(labels):
            t = next(t for t in th if t["levels"] == lab and t["index"] == name)
            xs.append(i + (j - (len(indices) - 1) / 2) * width)
            ys.append(t[f"threshold_{quantity}_median{tail}"] * vu.factor)
            lo.append(ys[-1] - t[f"threshold_{quantity}_p05{tail}"] * vu.factor)
            hi.append(t[f"threshold_{quantity}_p95{tail}"] * vu.factor - ys[-1])
        ax.errorbar(xs, ys, yerr=[np.nan_to_num(lo), np.nan_to_num(hi)], fmt="o", capsize=3, label=name)
        for x, y, lab in zip(xs, ys, labels):
            if not np.isfinite(y):  # the median is outside the swept velocities: its bound in words
                t = next(t for t in th if t["levels"] == lab and t["index"] == name)
                bound = t.get(f"threshold_{quantity}_median_bound") or "not reached"
                ax.annotate(bound, (x, 0.02), xycoords=("data", "axes fraction"), rotation=90, fontsize=7, ha="center")
    ax.set_xlim(-0.5, len(labels) - 0.5)
    ax.set_xticks(range(len(labels)), [lab or "all runs" for lab in labels], fontsize=8)
    ax.set_xlabel(f"levels of the swept parameters (besides {words})")
    ax.set_ylabel(f"threshold {words} [{vu.label}]")
    ax.set_title(title, fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def _outside(rows: list[dict]) -> np.ndarray:
    """Whether each map row lies outside the models' validity at its threshold (``inside_validity`` false)."""
    return np.array([r.get("inside_validity") is False for r in rows], bool)


def _median_line(ax, rows: list[dict], x_factor: float, v_factor: float, colour, label: str, style: str = "-", marker: str = "o"):
    """A map's median against the diameter (line), markers filled where the row is inside validity and open where outside."""
    d = np.array([r["diameter_m"] for r in rows]) * x_factor
    med = np.array([r["threshold_velocity_median_m_s"] for r in rows]) * v_factor
    out = _outside(rows)
    ax.plot(d, med, style, color=colour, label=label)
    ax.plot(d[~out], med[~out], marker, color=colour, ms=5, ls="none")
    ax.plot(d[out], med[out], marker, color=colour, mfc="none", ms=5, ls="none")
    return d


def threshold_map_figure(rows: list[dict], prescribed: list[dict], system: str, title: str):
    """Threshold velocity against impactor diameter, one panel per structure: each index's median
    (line) and 5–95 % band (shaded) from a threshold map (:meth:`softimpact.studies.thresholds.MapRow.as_dict`
    rows; open markers: the row's run at its threshold is outside the models' validity, ``inside_validity`` false), and
    beside it the carried-over prescribed-force thresholds (``prescribed``: rows with
    ``structure``, ``index``, ``diameter_m`` and the median, p05 and p95 velocities) as points with their band."""
    import matplotlib.pyplot as plt

    from ..units import display

    vu, lu = display(system, "velocity"), display(system, "length")
    structures = list(dict.fromkeys(r["structure"] for r in rows))
    indices = list(dict.fromkeys(r["index"] for r in rows))
    # as wide as the report shows it (no shrinking), text at REPORT_TEXT_PT: panels side by side, the legend below them
    with plt.rc_context({"font.size": REPORT_TEXT_PT}):
        fig, axes = plt.subplots(1, len(structures), figsize=(REPORT_WIDTH_IN, 3.6), sharey=True, squeeze=False, layout="constrained")
        _threshold_panels(fig, axes, structures, indices, rows, prescribed, vu, lu)
        fig.suptitle(textwrap.fill(title, 90), fontsize=REPORT_TEXT_PT + 1)
        fig.canvas.draw()  # laid out (and its text sized) inside the context
    return fig


def _threshold_panels(fig, axes, structures, indices, rows, prescribed, vu, lu) -> None:
    """The panels of :func:`threshold_map_figure`, one per structure, and one legend below them."""
    import matplotlib.pyplot as plt

    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for ax, name in zip(axes[0], structures):
        for j, index in enumerate(indices):
            mine = sorted((r for r in rows if r["structure"] == name and r["index"] == index), key=lambda r: r["diameter_m"])
            c = colours[j % len(colours)]
            d = _median_line(ax, mine, lu.factor, vu.factor, c, f"{index}: coupled, identified law")
            lo, hi = (np.array([r[f"threshold_velocity_{q}_m_s"] for r in mine]) * vu.factor for q in ("p05", "p95"))
            ax.fill_between(d, lo, hi, color=c, alpha=0.2)
            old = sorted((p for p in prescribed if p["structure"] == name and p["index"] == index), key=lambda p: p["diameter_m"])
            if old:
                x = np.array([p["diameter_m"] for p in old]) * lu.factor * 1.01
                y, plo, phi = (np.array([p[f"threshold_velocity_{q}_m_s"] for p in old]) * vu.factor for q in ("median", "p05", "p95"))
                ax.errorbar(
                    x,
                    y,
                    yerr=[np.nan_to_num(y - plo), np.nan_to_num(phi - y)],
                    fmt="s",
                    mfc="none",
                    color=c,
                    capsize=3,
                    label=f"{index}: prescribed force (Table I law)",
                )
        ax.set_title(name)
        ax.set_xlabel(f"diameter [{lu.label}]")
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel(f"threshold velocity [{vu.label}]")
    handles, labels = axes[0][0].get_legend_handles_labels()
    title = "open circles: outside validity" if _outside(rows).any() else None
    fig.legend(handles, labels, loc="outside lower center", ncol=2, title=title, frameon=False)


def kinematics_map_figure(rows: list[dict], system: str, title: str):
    """One structure's threshold maps on two kinematics, one column per index: above, each map's median against the diameter
    (solid: linear, dashed: von Kármán; markers open where the row is outside validity) and its 5–95 % band (shaded;
    hatched for the von Kármán map); below, the ratio of the second map's nominal threshold to the first's on the map's mesh
    and on the coarser one (``threshold_velocity_coarse_mesh_m_s``, when given); ``rows``:
    :meth:`softimpact.studies.thresholds.MapRow.as_dict` rows of both maps."""
    import matplotlib.pyplot as plt

    from ..units import display

    vu, lu = display(system, "velocity"), display(system, "length")
    indices = list(dict.fromkeys(r["index"] for r in rows))
    kinds = list(dict.fromkeys(r["kinematics"] for r in rows))
    with plt.rc_context({"font.size": REPORT_TEXT_PT}):  # as wide as the report shows it, text at REPORT_TEXT_PT
        fig, axes = plt.subplots(
            2, len(indices), figsize=(REPORT_WIDTH_IN, 6.0), sharex=True, squeeze=False, gridspec_kw={"height_ratios": [2, 1]}, layout="constrained"
        )
        _kinematics_panels(fig, axes, indices, kinds, rows, vu, lu)
        fig.suptitle(textwrap.fill(title, 90), fontsize=REPORT_TEXT_PT + 1)
        fig.canvas.draw()
    return fig


def _kinematics_panels(fig, axes, indices, kinds, rows, vu, lu) -> None:
    """The panels of :func:`kinematics_map_figure`: per index, the two maps above and their ratio below."""
    import matplotlib.pyplot as plt

    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for col, index in enumerate(indices):
        ax, below = axes[0][col], axes[1][col]
        maps = []
        for j, kind in enumerate(kinds):
            mine = sorted((r for r in rows if r["index"] == index and r["kinematics"] == kind), key=lambda r: r["diameter_m"])
            if not mine:
                continue
            maps.append(mine)
            c = colours[j % len(colours)]
            d = _median_line(ax, mine, lu.factor, vu.factor, c, f"{kind}", "-" if j == 0 else "--", "o" if j == 0 else "s")
            lo, hi = (np.array([r[f"threshold_velocity_{q}_m_s"] for r in mine]) * vu.factor for q in ("p05", "p95"))
            if j == 0:
                ax.fill_between(d, lo, hi, color=c, alpha=0.15)
            else:
                ax.fill_between(d, lo, hi, facecolor="none", edgecolor=c, hatch="//", lw=0.0)
        if len(maps) == 2 and len(maps[0]) == len(maps[1]):
            d = np.array([r["diameter_m"] for r in maps[0]]) * lu.factor
            for key, style, label in (("threshold_velocity_nominal_m_s", "-o", "map's mesh"), ("threshold_velocity_coarse_mesh_m_s", ":^", "coarser mesh")):
                ratio = np.array([b.get(key, np.nan) / a.get(key, np.nan) for a, b in zip(*maps)], float)
                if np.isfinite(ratio).any():
                    below.plot(d, ratio, style, color="k", ms=4, label=label)
            below.axhline(1.0, color="0.6", lw=0.8)
            below.set_ylabel(f"{kinds[1]} / {kinds[0]}")
            below.legend()
        ax.set_title(index)
        below.set_xlabel(f"impactor diameter [{lu.label}]")
        ax.grid(alpha=0.3)
        below.grid(alpha=0.3)
    axes[0][0].set_ylabel(f"threshold velocity [{vu.label}]")
    axes[0][0].legend(title="open markers: outside validity" if _outside(rows).any() else None)
