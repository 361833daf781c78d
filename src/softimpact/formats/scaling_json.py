"""scaling.json: the scaling constants α1–α4 of eqs (4)–(7), written and read in this one place
(``softimpact fit`` and ``calibrate`` write it; ``predict --constants`` reads it).

Layout: ``groups`` (one per ball diameter, keyed like ``"0.5 in"``) and
``pooled``, each with α1–α4 (``value``, ``ci95``, ``r2``, ``residuals``), the
names of its ``tests``, the ``affine`` fits and ``fitted_on`` (the velocity and diameter
ranges of its tests: ``predict`` warns outside them; files written before it are not checked);
``regressors`` says what each constant multiplies.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from ..errors import InputError
from ..models.empirical import ScalingLaw
from ._json import check_si, json_text

__all__ = ["scaling_summary", "scaling_json", "read_scaling_law"]


def scaling_summary(fits) -> dict:
    """scaling.json: per group and pooled, α1–α4 with their 95 % intervals, R², residuals, affine fits."""

    def line(f):
        return {"value": f.slope, "ci95": list(f.slope_ci), "r2": f.r2, "residuals": f.residuals}

    def affine(f):
        return {"slope": f.slope, "slope_ci95": list(f.slope_ci), "intercept": f.intercept, "intercept_ci95": list(f.intercept_ci), "r2": f.r2}

    def group(g):
        d = {name: line(f) for name, f in g.origin.items()}
        d["tests"] = [p.name for p in g.points]
        v, dia = [p.velocity for p in g.points], [p.diameter for p in g.points]
        d["fitted_on"] = {"velocity_m_s": [min(v), max(v)], "diameter_m": [min(dia), max(dia)]}
        d["affine"] = {name: affine(f) for name, f in g.affine.items()}
        return d

    return {
        "groups": {label: group(g) for label, g in fits.items() if label != "pooled"},
        "pooled": group(fits["pooled"]) if "pooled" in fits else group(next(iter(fits.values()))),
        "units": "SI",
        "regressors": {"alpha1": "F0 = alpha1*m*V^2/(2d)", "alpha2": "T = alpha2*d/V", "alpha3": "tF0 = alpha3*T", "alpha4": "I = alpha4*2*m*V"},
    }


def scaling_json(fits) -> str:
    """The text of scaling.json for the fits of :func:`softimpact.workflows.scaling.fit_groups`."""
    return json_text(scaling_summary(fits))


def read_scaling_law(path: Path, group: str = "pooled", argument: str = "--constants") -> ScalingLaw:
    """The α's of one group (a diameter such as ``"0.5 in"``, or ``"pooled"``) of a scaling.json."""
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
    except OSError as exc:
        raise InputError(f"{argument}: cannot read {path} ({exc.strerror})") from None
    except (ValueError, UnicodeDecodeError):
        raise InputError(f"{argument}: {path} is not a scaling.json with group {group!r}") from None
    check_si(data, path, argument)
    try:
        g = data["pooled"] if group == "pooled" else data["groups"][group]
        values = [float(g[f"alpha{i}"]["value"]) for i in range(1, 5)]
        fitted = g.get("fitted_on")  # absent from files written before it was recorded: not checked
        ranges = {}
        if fitted is not None:
            ranges = {k: tuple(float(x) for x in fitted[f"{k}_m_s" if k == "velocity" else f"{k}_m"]) for k in ("velocity", "diameter")}
    except OSError as exc:
        raise InputError(f"{argument}: cannot read {path} ({exc.strerror})") from None
    except (KeyError, TypeError, ValueError, UnicodeDecodeError):
        raise InputError(f"{argument}: {path} is not a scaling.json with group {group!r}") from None
    return ScalingLaw(
        *values,
        name=f"{Path(path).name}:{group}",
        source=str(path),
        velocity_range=ranges.get("velocity", (0.0, math.inf)),
        diameter_range=ranges.get("diameter", (0.0, math.inf)),
    )
