"""Outputs of ``softimpact converge``: convergence.csv, summary.json, convergence.png, histories.png.

One row per output: its status, observed order, the value at each level (scalars),
the Richardson-extrapolated value, the relative error of each level against it
(normalised RMS for a history) and the grid convergence indices. Level 1 is the
case's own discretisation.
"""

from __future__ import annotations

import numpy as np

from ..units import display
from .files import case_record, csv_text, figure_bytes, json_text, with_units
from .report import Section

__all__ = ["converge_files", "converge_section", "order_phrase", "order_text", "output_label", "quantity_kind"]

_UNIT_SUFFIXES = ("_N_s", "_N", "_m", "_s")
# Why a level's error has no value, by status (the table shows a dash and this reason, never "nan %").
_NO_ERROR = {
    "diverging": "not converging",
    "oscillatory": "oscillating",
    "undefined": "undefined at some level",
}


def quantity_kind(name: str) -> str:
    """The display kind of an output, from its name."""
    if name.endswith("_N_s"):
        return "impulse"
    if name.startswith("strain_") and not name.endswith("_s"):
        return "strain"
    if name.endswith("_s"):
        return "time"
    if "force" in name:
        return "force"
    if name.endswith("_m"):
        return "length"
    return ""


def output_label(name: str, system: str | None = None) -> str:
    """A readable label of an output name with its display unit: ``strain_g1_history`` → "g1: strain history [µε]",
    ``peak_deflection_under_load_m`` → "peak deflection under load [in]" (``system``: the case's units; None: no unit)."""
    q = quantity_kind(name)
    stem = name
    for suffix in _UNIT_SUFFIXES:
        if stem.endswith(suffix) and stem != suffix:
            stem = stem[: -len(suffix)]
            break
    words = stem.split("_")
    if words[0] == "strain" and len(words) > 2:  # strain_<gauge>_<what>: the gauge first
        text = f"{words[1]}: strain {' '.join(words[2:])}"
    else:
        text = " ".join(words)
    if system is not None and q:
        text += f" [{display(system, q).label}]"
    return text


def order_text(o) -> str:
    """The order of an output as a report shows it: observed ("1.94"), assumed with two levels ("2 (assumed)") or a dash."""
    if o.status == "two levels":
        return f"{o.order:g} (assumed)"
    return f"{o.order:.2f}" if np.isfinite(o.order) else "–"


def order_phrase(o) -> str:
    """The order in words for a result line: "observed order 1.94", "assumed order 2" (two levels) or "no order observed"."""
    if o.status == "two levels":
        return f"assumed order {o.order:g}"
    return f"observed order {o.order:.2f}" if np.isfinite(o.order) else "no order observed"


def _percent(x: float, fmt: str, status: str) -> str:
    """``x`` (a fraction) as a percentage, or a dash with the reason when it has no value."""
    if np.isfinite(x):
        return f"{100 * x:{fmt}} %"
    return f"– ({_NO_ERROR.get(status, status)})"


def _rows(result) -> dict[str, list]:
    n = len(result.levels)
    cols = {"output": [], "kind": [], "status": [], "observed_order": []}
    cols.update({f"value_level_{i + 1}": [] for i in range(n)})
    cols["extrapolated"] = []
    cols.update({f"relative_error_level_{i + 1}": [] for i in range(n)})
    for key in ("gci_fine", "gci_coarse", "asymptotic_ratio", "safety_factor"):
        cols[key] = []
    for o in result.outputs:
        cols["output"].append(o.name)
        cols["kind"].append(o.kind)
        cols["status"].append(o.status)
        cols["observed_order"].append(o.order)
        for i in range(n):
            cols[f"value_level_{i + 1}"].append(o.values[i] if o.kind == "scalar" else np.nan)
            cols[f"relative_error_level_{i + 1}"].append(o.errors[i])
        cols["extrapolated"].append(o.extrapolated if o.kind == "scalar" else np.nan)
        cols["gci_fine"].append(o.gci_fine)
        cols["gci_coarse"].append(o.gci_coarse)
        cols["asymptotic_ratio"].append(o.asymptotic_ratio)
        cols["safety_factor"].append(o.safety_factor)
    return cols


def _summary(result, sizes, problem, kind: str) -> dict:
    return {
        "kind": kind,
        "title": problem.title,
        "ratio": result.ratio,
        "levels": sizes,
        "case_discretisation_error": {o.name: float(o.errors[0]) for o in result.outputs},
        "outputs": {
            o.name: {
                "kind": o.kind,
                "status": o.status,
                "meaning": o.meaning,
                "observed_order": o.order,
                "values": o.values.tolist() if o.kind == "scalar" else None,
                "extrapolated": o.extrapolated if o.kind == "scalar" else None,
                "relative_errors": o.errors.tolist(),
                "gci_fine": o.gci_fine,
                "gci_coarse": o.gci_coarse,
                "safety_factor": o.safety_factor,
                "message": o.message,
            }
            for o in result.outputs
        },
        "case_SI": case_record(problem),
    }


def _decades(ax, values) -> None:
    """Log y-axis limits widened to whole decades, so at least two decades carry a label; plain-number labels."""
    from matplotlib.ticker import FuncFormatter, LogLocator

    lo, hi = min(values), max(values)
    lo_d, hi_d = np.floor(np.log10(lo)), np.ceil(np.log10(hi))
    if hi_d == lo_d:
        lo_d -= 1
    ax.set_ylim(10.0**lo_d, 10.0**hi_d)
    ax.yaxis.set_major_locator(LogLocator(base=10.0, numticks=12))
    ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))


def _error_figure(result, title: str, case_level: int = 0, system: str | None = None):
    from fractions import Fraction

    from .plots import _figure, curve_colors

    fig, ax = _figure(7.0, 4.6)
    h = result.ratio ** (case_level - np.arange(len(result.levels), dtype=float))
    shown = [o for o in result.outputs if (np.isfinite(np.asarray(o.errors, float)) & (np.asarray(o.errors, float) > 0)).sum() >= 2]
    for o, color in zip(shown, curve_colors(len(shown))):  # a colour of its own for each output, however many
        e = np.asarray(o.errors, float)
        ok = np.isfinite(e) & (e > 0)
        history = o.kind == "history"
        ax.loglog(h[ok], 100 * e[ok], "o-" if history else ".--", color=color, lw=1.6 if history else 1, label=output_label(o.name, system))
    finite = [100 * e for o in result.outputs for e in o.errors if np.isfinite(e) and e > 0]
    if finite:
        top = max(finite)
        ax.loglog(h, top * (h / h[0]) ** 2, "k:", lw=1, label="slope 2 (formal order)")
        _decades(ax, finite + list(top * (h / h[0]) ** 2))
    ax.set_xlabel("h / h of the case (mesh and time step refined together)")
    ax.set_ylabel("error against the extrapolated value [%]")
    ax.set_title(title)
    ax.set_xticks(h, [str(Fraction(x).limit_denominator(64)) for x in h])
    ax.minorticks_off()
    ax.invert_xaxis()
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig


def _history_figure(result, time: np.ndarray, system: str, title: str):
    from .plots import _figure

    histories = [o for o in result.outputs if o.kind == "history"]
    fig, ax = _figure(7.0, 4.0 + 1.2 * max(0, len(histories) - 1))
    fig.clear()
    axes = fig.subplots(len(histories), 1, sharex=True, squeeze=False)[:, 0]
    tu = display(system, "time")
    for axis, o in zip(axes, histories):
        q = quantity_kind(o.name)
        du = display(system, q) if q else None
        f = du.factor if du else 1.0
        for i, y in enumerate(o.values):
            axis.plot(time * tu.factor, y * f, lw=1, label=f"level {i + 1} (×{round(result.ratio**i)})")
        axis.plot(time * tu.factor, np.asarray(o.extrapolated) * f, "k--", lw=1, label="Richardson extrapolation")
        axis.set_ylabel(output_label(o.name, system), fontsize=8)
        axis.grid(True, alpha=0.3)
    axes[0].set_title(title)
    axes[0].legend(fontsize=7, loc="upper right")
    axes[-1].set_xlabel(f"time [{tu.label}]")
    return fig


def converge_files(
    result, sizes, problem, kind: str, figures: bool = True, prefix: str = "", case_level: int = 0, *, units: str = "in-lbf-s"
) -> dict[str, bytes | str]:
    """convergence.csv, summary.json and (optionally) the error and history figures of ``problem`` (any kind:
    each has its ``title``), in display ``units`` (also summary.json's ``case_SI.units``); ``case_level``: which level is the case's own discretisation
    (0 unless the study started below it)."""
    files = {prefix + "convergence.csv": csv_text(_rows(result)), prefix + "summary.json": json_text(with_units(_summary(result, sizes, problem, kind), units))}
    if figures:
        title = problem.title or kind
        files[prefix + "convergence.png"] = figure_bytes(_error_figure(result, f"Discretisation error: {title}", case_level, units))
        if any(o.kind == "history" for o in result.outputs):
            time = problem.solver.times()
            files[prefix + "histories.png"] = figure_bytes(_history_figure(result, time, units, f"Histories at each level: {title}"))
    return files


def converge_section(result, sizes, title: str, prefix: str, figures: bool, case_level: int = 0) -> Section:
    """A report section: the distance from converged of level ``case_level`` (the case's own), output by output."""
    rows = []
    for o in result.outputs:
        rows.append(
            [
                o.name,
                o.status,
                order_text(o),
                _percent(o.errors[case_level], ".3g", o.status),
                _percent(o.errors[-1], ".2g", o.status),
                f"{100 * o.gci_fine:.2g} %" if np.isfinite(o.gci_fine) else "",
                f"{o.safety_factor:g}" if np.isfinite(o.safety_factor) else "",
            ]
        )
    levels = ", ".join(f"{' × '.join(map(str, s['elements']))} elements, dt {s['time_step_s'] * 1e6:g} µs" for s in sizes)
    header = [
        "output",
        "status",
        "order p (observed, or assumed)",
        f"error of the case's mesh (level {case_level + 1})",
        f"error of level {len(sizes)}",
        "GCI of the finest",
        "Fs",
    ]
    figs = [(prefix + "convergence.png", f"{title}: error of each level against the Richardson extrapolation")] if figures else []
    return Section(
        title,
        [
            f"Levels (mesh and time step refined together): {levels}. Errors are relative to the Richardson extrapolation "
            "(normalised RMS for a history). 'asymptotic' (safety factor Fs = 1.25) means monotone convergence with the observed order "
            "within 25 % of the formal 2, a mesh-only and a step-only refinement of the coarsest level that do not move the output "
            "in opposite directions (else the errors of mesh and step cancel along the diagonal and the order is a coincidence), "
            "and at least 10 time steps in the pulse rise; 'monotone' is convergence without that evidence, given Fs = 3."
        ],
        [(title, header, rows)],
        figs,
    )
