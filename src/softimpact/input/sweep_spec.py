"""Sweep specs (``softimpact sweep``): TOML → :class:`SweepSpec`, and the runs it asks for.

A spec names a base case (file or built-in name), a method, the outputs to keep
and the parameters to vary, each by the dotted path of a case key::

    [sweep]
    case = "paper-long-beam"
    method = "monte-carlo"              # grid | monte-carlo | latin-hypercube
    runs = 1000                         # draws (random methods)
    seed = 1
    outputs = ["peak_force_N", "strain_g1.peak"]
    [[sweep.parameter]]
    key = "load.history"                # a whole table replaced ...
    value = { shape = "empirical", projectile = "rubber-1/2in", velocity = "1166 in/s" }
    [[sweep.parameter]]
    key = "load.history.velocity"       # ... or one key: values | range | distribution
    distribution = { uniform = ["1000 in/s", "5000 in/s"] }
    [[sweep.parameter]]
    key = "load.history"                # the α's of a scaling.json, with their covariance
    from = "out/fit/scaling.json"
    [[sweep.parameter]]
    key = "contact"                     # an identified law's parameters (law.json), with their covariance
    from = "out/identify/law.json"

``values`` and ``range = [lo, hi, n]`` are levels: crossed as a grid with each
other and, in the random methods, with the draws (every level combination gets
the same ``runs`` draws: common random numbers, so threshold curves are
smooth). ``distribution`` is ``normal = [mean, sd]``, ``uniform = [lo, hi]`` or
``lognormal = [median, sigma of ln]``. Parameters are applied in the order listed: a whole
table may be followed by keys inside it, but a key set twice, or a table listed after a
key inside it (which it would silently replace), is refused. Quantities keep their units in the spec
and are written back to the case in SI; the run table holds SI numbers.

Thresholds and onsets (:func:`softimpact.cases.sweep.plan_thresholds`, :func:`~softimpact.cases.sweep.plan_onsets`)
are found against one level, the velocity level by default, or the one ``threshold_against`` names::

    [sweep]
    threshold_against = "impactor.energy"   # any level of quantities: a velocity, energy, diameter, mass, ...
    onset = ["damage.dent_depth_m"]          # sizes whose onset (first positive level) is reported; default:
                                             # every damage.* output in m, m^2 or m^3 (a depth, a length, an area)
    [sweep.limits]                           # an output reaching the user's limit: the index output/limit
    "damage.dent_depth_m" = "0.25 mm"
    "damage.projected_delamination_area_m2" = "100 mm^2"

The threshold of an index (a ``damage.*`` output without a unit: 1 at onset) is the level where it first
reaches 1; an output with a limit (any output: a force, a stress, a size) has the threshold where it first
reaches the limit, in the output's own unit (its SI suffix: ``_m``, ``_m2``, ``_J``, ``_N``, ``_Pa``, ...).
"""

from __future__ import annotations

import copy
import hashlib
import itertools
import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import units
from ..errors import InputError
from .toml import Table, load_toml, locate

__all__ = [
    "METHODS",
    "DISTRIBUTIONS",
    "Level",
    "Drawn",
    "Scaling",
    "LawDraw",
    "Fixed",
    "SweepSpec",
    "Run",
    "load_sweep_spec",
    "case_files",
    "read_sweep_spec",
    "scaling_covariance",
    "set_dotted",
    "get_dotted",
    "quantity",
    "Limit",
    "OUTPUT_UNITS",
    "SIZES",
    "output_unit",
]

METHODS = ("grid", "monte-carlo", "latin-hypercube")
DISTRIBUTIONS = ("normal", "uniform", "lognormal")
_KINDS = ("length", "mass", "time", "velocity", "stress", "density", "force", "impulse", "energy", "frequency")


def quantity(value, key: str) -> tuple[float, str]:
    """A spec value as (SI number, SI unit text; "" for a plain number)."""
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise InputError(f"{key}: expected a number or a quantity with a unit, got {value!r}")
    if isinstance(value, (int, float)):
        return units.parse(value, "dimensionless", key), ""
    for kind in _KINDS:
        try:
            return units.parse(value, kind, key), units.SI_UNITS[kind]
        except InputError:
            continue
    return units.parse(value, "dimensionless", key), ""


def _written(x: float, unit: str):
    """An SI number as the case value that reads back as it."""
    return float(x) if not unit else f"{float(x)!r} {unit}"


def get_dotted(data: dict, key: str):
    node = data
    for part in key.split("."):
        if not isinstance(node, dict) or part not in node:
            return None
        node = node[part]
    return node


def set_dotted(data: dict, key: str, value) -> None:
    """Set ``key`` (dotted) in nested dicts, creating tables on the way."""
    parts = key.split(".")
    node = data
    for i, part in enumerate(parts[:-1]):
        nxt = node.get(part)
        if not isinstance(nxt, dict):
            if nxt is not None:
                raise InputError(f"{'.'.join(parts[: i + 1])}: is {nxt!r}, not a table, so {key} cannot be set")
            nxt = node[part] = {}
        node = nxt
    node[parts[-1]] = value


@dataclass(frozen=True)
class Fixed:
    """A key set to one value in every run (a whole table, or a scalar)."""

    key: str
    value: object

    columns = ()


@dataclass(frozen=True)
class Level:
    """A key taking each of ``values`` (case values) in turn; ``si`` for the run table; ``unit`` the SI unit of its
    quantities ("" plain numbers or names; None values of different kinds)."""

    key: str
    values: tuple
    si: tuple
    unit: str | None = ""

    @property
    def columns(self):
        return (self.key,)


@dataclass(frozen=True)
class Drawn:
    """A key drawn from ``law`` (normal|uniform|lognormal) with parameters (a, b) in SI."""

    key: str
    law: str
    a: float
    b: float
    unit: str

    columns = property(lambda self: (self.key,))
    dims = 1

    def transform(self, u: np.ndarray) -> np.ndarray:
        """Uniforms u ∈ (0, 1) → draws (inverse CDF), shape of ``u``."""
        from scipy.stats import norm

        if self.law == "uniform":
            return self.a + (self.b - self.a) * u
        if self.law == "normal":
            return self.a + self.b * norm.ppf(u)
        return self.a * np.exp(self.b * norm.ppf(u))


PSD_TOL = 1e-10  # relative to the largest eigenvalue: a covariance's eigenvalues above −this are round-off of a zero


def covariance_factor(C) -> np.ndarray:
    """L with L·Lᵀ = C for a symmetric positive SEMI-definite covariance ``C`` (n, n): its Cholesky factor when C is
    definite (the draws as before), else V·sqrt(max(λ, 0)) of its eigen-decomposition, so a singular covariance
    (parameters perfectly correlated, or one with no spread) draws on the subspace it spans, where Cholesky fails.
    Eigenvalues below −:data:`PSD_TOL`·λ_max are not round-off: a ValueError (the caller names the file)."""
    C = np.asarray(C, float)
    if C.size == 0 or not np.any(C):
        return np.zeros_like(C)
    try:
        return np.linalg.cholesky(C + 1e-300 * np.eye(len(C)))
    except np.linalg.LinAlgError:  # singular (or not a covariance): the eigen-decomposition says which
        pass
    lam, V = np.linalg.eigh(0.5 * (C + C.T))
    if lam.min() < -PSD_TOL * max(lam.max(), 0.0):
        raise ValueError(f"the covariance is not positive semi-definite (eigenvalue {lam.min():.3g} against the largest {lam.max():.3g})")
    return V * np.sqrt(np.clip(lam, 0.0, None))


@dataclass(frozen=True)
class Scaling:
    """α1–α4 of a scaling.json as a joint normal (mean, covariance), set as ``key``.alpha1..4."""

    key: str
    mean: tuple[float, float, float, float]
    covariance: tuple
    source: str

    dims = 4

    @property
    def columns(self):
        return tuple(f"{self.key}.alpha{i}" for i in range(1, 5))

    def transform(self, u: np.ndarray) -> np.ndarray:
        """Uniforms (n, 4) → correlated normal draws (n, 4) through the Cholesky factor."""
        from scipy.stats import norm

        L = covariance_factor(self.covariance)  # checked when read: semi-definite (a singular one draws on its span)
        return np.asarray(self.mean) + norm.ppf(u) @ L.T


@dataclass(frozen=True)
class LawDraw:
    """The parameters of an identified contact law (a law.json) as a joint normal, set as
    ``key``.parameters.<name> (the impact case's ``[contact]`` with ``law = "identified"``).

    Mean: the file's values. Covariance: the file's ``covariance`` (``names`` and ``matrix``) when
    it has one, else diagonal from the 95 % half-widths, σ = half-width/1.96 (the fit's linearised
    intervals, ±1.96·sqrt(diag(s²(JᵀJ)⁻¹)), :mod:`softimpact.workflows.identification`). Parameters
    with no spread (held at zero in the fit) are not drawn."""

    key: str
    names: tuple[str, ...]
    mean: tuple
    covariance: tuple
    source: str

    @property
    def dims(self) -> int:
        return len(self.names)

    @property
    def columns(self):
        return tuple(f"{self.key}.parameters.{n}" for n in self.names)

    def transform(self, u: np.ndarray) -> np.ndarray:
        """Uniforms (n, dims) → correlated normal draws (n, dims) through the Cholesky factor."""
        from scipy.stats import norm

        L = covariance_factor(self.covariance)  # checked when read: semi-definite (a singular one draws on its span)
        return np.asarray(self.mean) + norm.ppf(u) @ L.T


# An output's SI unit from its key's suffix (docs/naming.md), longest suffix first; a size is a length, area or volume.
OUTPUT_UNITS = (
    ("_m_s", "m/s"),
    ("_N_s", "N*s"),
    ("_J_m2", "J/m^2"),
    ("_kg_m3", "kg/m^3"),
    ("_m2", "m^2"),
    ("_m3", "m^3"),
    ("_m", "m"),
    ("_J", "J"),
    ("_N", "N"),
    ("_Pa", "Pa"),
    ("_kg", "kg"),
    ("_s", "s"),
    ("_Hz", "Hz"),
)
SIZES = ("m", "m^2", "m^3")


def output_unit(output: str) -> str:
    """The SI unit of a summary key by its suffix (:data:`OUTPUT_UNITS`): "m" for ``damage.dent_depth_m``, "m^2" for
    ``damage.projected_delamination_area_m2``; "" for a key without one (an index, a strain, a ratio)."""
    return next((unit for suffix, unit in OUTPUT_UNITS if output.endswith(suffix)), "")


@dataclass(frozen=True)
class Limit:
    """A user's limit on an output (``[sweep.limits]``): ``value`` in the output's SI ``unit`` ("" a plain number),
    ``given`` as written."""

    output: str
    value: float
    unit: str
    given: object


def _limit(output: str, value, key: str) -> Limit:
    """``value`` (a quantity with a unit, or a plain number for an output without one) in the unit of ``output``'s
    suffix (:func:`output_unit`), positive and finite; pint's dimensionality decides."""
    unit = output_unit(output)
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise InputError(f"{key}: expected a quantity with a unit{f' of {unit}' if unit else ''}, got {value!r}")
    if not unit:
        if not isinstance(value, (int, float)):
            raise InputError(f"{key}: {output!r} has no unit (no SI suffix: an index or a ratio), so its limit is a plain number, got {value!r}")
        x = float(value)
    else:
        if not isinstance(value, str):
            raise InputError(f'{key}: missing unit in {value!r} (the output {output!r} is in {unit}, e.g. "0.25 mm" for a length)')
        ureg = units.registry()
        try:
            q = ureg.Quantity(value.strip())
        except Exception:  # pint raises several unrelated types for unknown names
            raise InputError(f"{key}: cannot read {value!r} as a number and a unit (the output {output!r} is in {unit})") from None
        want = ureg.Quantity(1.0, unit)
        if not hasattr(q, "dimensionality") or q.dimensionality != want.dimensionality:
            dim = getattr(q, "dimensionality", "dimensionless")
            raise InputError(f"{key}: {value!r} is not in the unit of {output!r} ({unit}, {want.dimensionality}; {value!r} is {dim})")
        x = float(q.to(unit).magnitude)
    if not (math.isfinite(x) and x > 0):
        raise InputError(f"{key}: a limit must be positive and finite, got {value!r}")
    return Limit(output, x, unit, value)


def _dotted_items(node: dict, prefix: str = ""):
    """(dotted key, value) of a table whose keys may be quoted dotted keys or nested tables (TOML's bare dotted keys)."""
    for k, v in node.items():
        if isinstance(v, dict):
            yield from _dotted_items(v, f"{prefix}{k}.")
        else:
            yield f"{prefix}{k}", v


def _near(name: str, known) -> str:
    import difflib

    near = difflib.get_close_matches(name, list(known), n=1, cutoff=0.6)
    return f"did you mean {near[0]!r}? " if near else ""


def _threshold_reading(s: Table, outputs: list, params) -> tuple[str | None, tuple[Limit, ...], tuple[str, ...] | None]:
    """``threshold_against``, ``limits`` and ``onset`` of ``[sweep]``, checked against the outputs and the levels."""
    against = s.raw("threshold_against", None)
    if against is not None:
        levels = {p.key: p for p in params if isinstance(p, Level)}
        if not isinstance(against, str):
            raise InputError(f"{s.key('threshold_against')}: expected a dotted case key of a level, got {against!r}")
        if against not in levels:
            drawn = any(isinstance(p, Drawn) and p.key == against for p in params)
            why = "is drawn, not swept by levels (give it values or a range)" if drawn else "is not a level of the sweep"
            raise InputError(f"{s.key('threshold_against')}: {against!r} {why} ({_near(against, levels)}levels: {', '.join(levels) or 'none'})")
        p = levels[against]
        if p.unit is None or not all(isinstance(v, float) for v in p.si):
            raise InputError(f"{s.key('threshold_against')}: {against!r} takes {list(p.values)!r}: a threshold needs levels of one quantity (numbers)")
    limits = s.raw("limits", None)
    found = []
    if limits is not None:
        if not isinstance(limits, dict):
            raise InputError(f'{s.key("limits")}: expected a table of output = limit, e.g. "damage.dent_depth_m" = "0.25 mm", got {limits!r}')
        for output, value in _dotted_items(limits):
            key = f"{s.key('limits')}.{output}"
            if output not in outputs:
                raise InputError(f"{key}: {output!r} is not one of sweep.outputs ({_near(output, outputs)}outputs: {', '.join(outputs)})")
            found.append(_limit(output, value, key))
    onset = s.raw("onset", None)
    if onset is not None:
        if not (isinstance(onset, list) and all(isinstance(o, str) for o in onset)):
            raise InputError(f"{s.key('onset')}: expected a list of outputs, got {onset!r}")
        for o in onset:
            if o not in outputs:
                raise InputError(f"{s.key('onset')}: {o!r} is not one of sweep.outputs ({_near(o, outputs)}outputs: {', '.join(outputs)})")
        onset = tuple(dict.fromkeys(onset))
    return against, tuple(found), onset


@dataclass(frozen=True)
class Run:
    """One run: its number, the case keys it sets (in order) and its row of varied values (SI)."""

    index: int
    sets: tuple[tuple[str, object], ...]
    row: dict
    draw: int = 0  # which of the random draws (shared across level combinations)


@dataclass(frozen=True)
class SweepSpec:
    """A parsed sweep spec; :meth:`runs` lists the runs it asks for."""

    path: Path
    case_path: Path
    case_data: dict
    method: str
    draws: int
    seed: int
    outputs: tuple[str, ...]
    parameters: tuple
    chunk: int
    fingerprint: str
    inputs: tuple[tuple[str, str], ...] = ()  # (file, sha256) of every file the runs read: the fingerprint covers their content
    threshold_against: str | None = None  # the level thresholds and onsets are found against (None: the velocity level)
    limits: tuple[Limit, ...] = ()  # outputs' limits: the threshold where the output first reaches its limit
    onset: tuple[str, ...] | None = None  # outputs whose onset is reported (None: every damage.* size, OUTPUT_UNITS)

    def runs(self, central: bool = False) -> list[Run]:
        """The runs; with ``central``, one per level combination with every draw at its median."""
        levels = [p for p in self.parameters if isinstance(p, Level)]
        random = [p for p in self.parameters if isinstance(p, (Drawn, Scaling, LawDraw))]
        draws = self._draws(random, central)
        out = []
        combos = list(itertools.product(*[range(len(p.values)) for p in levels]))
        for combo in combos:
            for d in range(len(draws) if random else 1):
                sets, row = [], {}
                pick = dict(zip((id(p) for p in levels), combo))
                col = 0
                for p in self.parameters:
                    if isinstance(p, Fixed):
                        sets.append((p.key, p.value))
                    elif isinstance(p, Level):
                        j = pick[id(p)]
                        sets.append((p.key, p.values[j]))
                        row[p.key] = p.si[j]
                    elif isinstance(p, Drawn):
                        x = float(draws[d, col])
                        col += 1
                        sets.append((p.key, _written(x, p.unit)))
                        row[p.key] = x
                    else:
                        for name, x in zip(p.columns, draws[d, col : col + p.dims]):
                            sets.append((name, float(x)))
                            row[name] = float(x)
                        col += p.dims
                out.append(Run(len(out), tuple(sets), row, d))
        return out

    def _draws(self, random, central: bool = False) -> np.ndarray:
        dims = sum(p.dims for p in random)
        if not random:
            return np.zeros((1, 0))
        n = 1 if central else self.draws
        if central:
            u = np.full((1, dims), 0.5)
        elif self.method == "latin-hypercube":
            from scipy.stats import qmc

            u = qmc.LatinHypercube(d=dims, seed=np.random.default_rng(self.seed)).random(self.draws)
        else:
            u = np.random.default_rng(self.seed).random((self.draws, dims))
        u = np.clip(u, 1e-12, 1 - 1e-12)
        cols, k = [], 0
        for p in random:
            x = p.transform(u[:, k : k + p.dims])
            cols.append(x.reshape(n, p.dims))
            k += p.dims
        return np.hstack(cols)

    def case_for(self, run: Run, expand=None) -> dict:
        """The base case with the run's keys set (``expand(data, key)`` first makes a key settable)."""
        data = copy.deepcopy(self.case_data)
        for key, value in run.sets:
            if expand is not None:
                expand(data, key)
            set_dotted(data, key, copy.deepcopy(value))
        return data


def _levels(p: Table, key: str) -> Level:
    if "values" in p:
        vals = p.raw("values")
        if not isinstance(vals, list) or not vals:
            raise InputError(f"{p.key('values')}: expected a non-empty list, got {vals!r}")
        si, kinds = [], set()
        for i, v in enumerate(vals):
            if isinstance(v, dict):
                si.append(json.dumps(v, sort_keys=True))  # a whole table: its text in the run table
            elif isinstance(v, str) and not _is_quantity(v):
                si.append(v)  # a name (projectile, ply, shape)
            else:
                x, unit = quantity(v, f"{p.key('values')}[{i}]")
                si.append(x)
                kinds.add(unit)
        return Level(key, tuple(vals), tuple(si), kinds.pop() if len(kinds) == 1 else "" if not kinds else None)
    r = p.raw("range")
    if not (isinstance(r, list) and len(r) == 3 and isinstance(r[2], int) and not isinstance(r[2], bool) and r[2] >= 2):
        raise InputError(f"{p.key('range')}: expected [low, high, count >= 2], got {r!r}")
    (lo, ulo), (hi, uhi) = quantity(r[0], p.key("range")), quantity(r[1], p.key("range"))
    if ulo != uhi:
        raise InputError(f"{p.key('range')}: low and high differ in kind ({r[0]!r}, {r[1]!r})")
    xs = np.linspace(lo, hi, r[2])
    return Level(key, tuple(_written(x, ulo) for x in xs), tuple(float(x) for x in xs), ulo)


def _is_quantity(v) -> bool:
    if not isinstance(v, str):
        return False
    try:
        quantity(v, "")
        return True
    except InputError:
        return False


def _drawn(p: Table, key: str) -> Drawn:
    d = p.raw("distribution")
    if not (isinstance(d, dict) and len(d) == 1):
        raise InputError(f"{p.key('distribution')}: expected one of {{ {' | '.join(f'{k} = [a, b]' for k in DISTRIBUTIONS)} }}, got {d!r}")
    ((law, args),) = d.items()
    where = f"{p.key('distribution')}.{law}"
    if law not in DISTRIBUTIONS:
        raise InputError(f"{p.key('distribution')}: {law!r} is not one of {', '.join(DISTRIBUTIONS)}")
    if not (isinstance(args, list) and len(args) == 2):
        raise InputError(f"{where}: expected two parameters, got {args!r}")
    a, ua = quantity(args[0], where)
    if law == "lognormal":
        b, ub = quantity(args[1], where)
        if ub or not b > 0 or not a > 0:
            raise InputError(f"{where}: expected [median > 0, sigma of ln > 0 (a plain number)], got {args!r}")
    else:
        b, ub = quantity(args[1], where)
        if ub != ua:
            raise InputError(f"{where}: both parameters must be of one kind, got {args!r}")
        if law == "normal" and not b > 0:
            raise InputError(f"{where}: the standard deviation must be positive, got {args[1]!r}")
        if law == "uniform" and not b > a:
            raise InputError(f"{where}: expected [low, high] with high > low, got {args!r}")
    return Drawn(key, law, a, b, ua)


def scaling_covariance(data: dict, group: str = "pooled") -> tuple[tuple, tuple]:
    """Mean and covariance of α1–α4 from the contents of a scaling.json.

    Each α is a least-squares slope through the origin with a 95 % interval from
    Student's t on n − 1 degrees of freedom, so its standard error is
    ci_half/t(0.975, n − 1). The four slopes are fitted to the same tests, so
    their errors correlate as their residuals do: ρ_jk = corr(r_j, r_k) over the
    tests, and Cov(α_j, α_k) = ρ_jk·se_j·se_k. Raises KeyError/ValueError/TypeError
    on a malformed file.
    """
    from scipy.stats import t

    g = data["pooled"] if group == "pooled" else data["groups"][group]
    mean = [float(g[f"alpha{i}"]["value"]) for i in range(1, 5)]
    half = [0.5 * (float(g[f"alpha{i}"]["ci95"][1]) - float(g[f"alpha{i}"]["ci95"][0])) for i in range(1, 5)]
    res = np.array([[float(r) for r in g[f"alpha{i}"]["residuals"]] for i in range(1, 5)])
    n = res.shape[1]
    if n < 3 or not all(math.isfinite(h) for h in half):
        raise ValueError(f"group {group!r} has {n} tests; a covariance needs at least 3")
    se = np.array(half) / float(t.ppf(0.975, n - 1))
    rho = np.corrcoef(res) if np.all(res.std(axis=1) > 0) else np.eye(4)
    return tuple(mean), tuple(map(tuple, rho * np.outer(se, se)))


def _scaling(path: Path, group: str, where: str) -> tuple[tuple, tuple, str]:
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
        mean, cov = scaling_covariance(data, group)
    except OSError as exc:
        raise InputError(f"{where}: cannot read {path} ({exc.strerror})") from None
    except ValueError as exc:
        raise InputError(f"{where}: {path}: {exc}") from None
    except (KeyError, TypeError, IndexError, UnicodeDecodeError):
        raise InputError(f"{where}: {path} is not a scaling.json with group {group!r}") from None
    return mean, cov, f"{path}:{group}"


def _law_draw(path: Path, key: str, where: str) -> LawDraw:
    """A law.json's parameters as a :class:`LawDraw` (the ones with a spread)."""
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
        pars = data["parameters"]
        names = [n for n, v in pars.items() if float(v.get("ci95_half_width", 0.0)) > 0.0]
        mean = [float(pars[n]["value"]) for n in names]
        if "covariance" in data:
            order = list(data["covariance"]["names"])
            full = np.asarray(data["covariance"]["matrix"], float)
            idx = [order.index(n) for n in names]
            cov = full[np.ix_(idx, idx)]
        else:
            cov = np.diag([(float(pars[n]["ci95_half_width"]) / 1.96) ** 2 for n in names])
    except OSError as exc:
        raise InputError(f"{where}: cannot read {path} ({exc.strerror})") from None
    except (KeyError, TypeError, ValueError, IndexError, AttributeError, UnicodeDecodeError):
        raise InputError(f"{where}: {path} is not a law.json with parameters (value, ci95_half_width)") from None
    if not names:
        raise InputError(f"{where}: {path}: no parameter has a spread (ci95_half_width > 0): nothing to draw")
    if cov.shape != (len(names), len(names)) or not np.all(np.isfinite(cov)) or not np.allclose(cov, cov.T, rtol=1e-9, atol=0.0):
        raise InputError(f"{where}: {path}: the covariance is not a finite symmetric matrix of the parameters with a spread ({', '.join(names)})")
    try:
        covariance_factor(cov)
    except ValueError as exc:
        raise InputError(f"{where}: {path}: {exc}") from None
    return LawDraw(key, tuple(names), tuple(mean), tuple(map(tuple, cov)), str(path))


def _is_law_json(path: Path) -> bool:
    try:
        return "family" in json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError, UnicodeDecodeError, TypeError):
        return False


def _parameter(p: Table, base: Path):
    key = p.string("key")
    if not key or any(not part for part in key.split(".")):
        raise InputError(f"{p.key('key')}: expected a dotted case key such as 'load.history.velocity', got {key!r}")
    given = [k for k in ("value", "values", "range", "distribution", "from") if k in p]
    if len(given) != 1:
        raise InputError(f"{p.path}: give exactly one of value, values, range, distribution, from (got {', '.join(given) or 'none'})")
    kind = given[0]
    if kind == "value":
        out = Fixed(key, p.raw("value"))
    elif kind in ("values", "range"):
        out = _levels(p, key)
    elif kind == "distribution":
        out = _drawn(p, key)
    else:
        src = base / p.string("from")
        if _is_law_json(src):
            out = _law_draw(src, key, p.key("from"))
        else:
            group = p.string("group", "pooled")
            out = Scaling(key, *_scaling(src, group, p.key("from")))
    p.done()
    return out


def _sets(p) -> tuple[str, ...]:
    """The case keys a parameter sets (a scaling.json's: its table's alpha1..4)."""
    return p.columns if isinstance(p, (Scaling, LawDraw)) else (p.key,)


def _check_overlaps(params) -> None:
    """A spec means one thing: parameters are applied in the order listed, so a whole table may be
    followed by keys inside it (they change the table just set), but no key may be set twice and no
    table may come after a key inside it (it would silently replace that key's values)."""
    for j, later in enumerate(params):
        for i, earlier in enumerate(params[:j]):
            for a in _sets(earlier):
                for b in _sets(later):
                    if a == b:
                        raise InputError(
                            f"sweep.parameter[{i}] and sweep.parameter[{j}] both set {a!r}: give one parameter per key "
                            "(levels and a distribution of one key cannot be combined)"
                        )
                    if a.startswith(b + "."):
                        raise InputError(
                            f"sweep.parameter[{j}] ({b!r}, a whole table) comes after sweep.parameter[{i}] ({a!r}, a key inside it) "
                            "and would replace it: list the table first, then the keys inside it"
                        )


def load_sweep_spec(spec: str) -> SweepSpec:
    """Read and check a sweep spec file: every error is raised here, before any run."""
    path = Path(spec)
    if not path.is_file():
        raise InputError(f"SPEC: {spec!r} is not a file")
    return read_sweep_spec(load_toml(path), path.parent, path, path.read_bytes())


def read_sweep_spec(data: dict, base: Path, path: Path | None = None, text: bytes = b"") -> SweepSpec:
    """A parsed spec (TOML as a dict); ``base`` resolves relative files; ``text`` enters the fingerprint."""
    top = Table(data)
    s = top.table("sweep")
    name = s.string("case")
    case_path = base / name if (base / name).is_file() else locate(name)
    method = s.string("method", "grid", choices=METHODS)
    draws = s.integer("runs", 100) if method != "grid" else 1
    seed = s.integer("seed", 1, minimum=0)
    chunk = s.integer("chunk", 50)
    outputs = s.raw("outputs")
    if not (isinstance(outputs, list) and outputs and all(isinstance(o, str) and o for o in outputs)):
        raise InputError(f"sweep.outputs: expected a non-empty list of summary keys, got {outputs!r}")
    if len(set(outputs)) != len(outputs):
        raise InputError("sweep.outputs: keys must be unique")
    params = tuple(_parameter(p, base) for p in s.tables("parameter"))
    _check_overlaps(params)
    if method == "grid" and any(isinstance(p, (Drawn, Scaling, LawDraw)) for p in params):
        bad = next(i for i, p in enumerate(params) if isinstance(p, (Drawn, Scaling, LawDraw)))
        raise InputError(f"sweep.parameter[{bad}]: draws need method = 'monte-carlo' or 'latin-hypercube' (method is 'grid')")
    if method == "grid" and "runs" in s.data:
        raise InputError("sweep.runs: only for the random methods (the grid's size is its levels')")
    if not any(isinstance(p, (Level, Drawn, Scaling, LawDraw)) for p in params):
        raise InputError("sweep.parameter: nothing varies (give values, range, distribution or from)")
    against, limits, onset = _threshold_reading(s, outputs, params)
    s.done()
    top.done()
    case_data = load_toml(case_path)
    inputs = input_files(case_path, case_data, params)
    h = hashlib.sha256(text or json.dumps(data, sort_keys=True, default=str).encode())
    for name, digest in inputs:  # the content of every file the runs read, not only their names
        h.update(f"{name}\0{digest}\0".encode())
    for p in params:
        if isinstance(p, (Scaling, LawDraw)):
            h.update(repr(p.mean + p.covariance).encode())
    spec_path = path or base / "spec"
    return SweepSpec(spec_path, case_path, case_data, method, draws, seed, tuple(outputs), params, chunk, h.hexdigest()[:16], inputs, against, limits, onset)


def _strings(node, key: str = ""):
    """(key, string) of every string in a case's nested tables and lists."""
    if isinstance(node, dict):
        for k, v in node.items():
            yield from _strings(v, k)
    elif isinstance(node, (list, tuple)):
        for v in node:
            yield from _strings(v, key)
    elif isinstance(node, str):
        yield key, node


def _file_of(value: str, key: str, base: Path) -> Path | None:
    """The file a case's string names (relative to its case's folder; a ``case`` key may be a built-in name), None if none."""
    if not value or "\n" in value or len(value) > 4096:
        return None
    try:
        path = base / value
        if path.is_file():
            return path
        if key == "case":
            return locate(value)
    except (OSError, ValueError, InputError):
        return None
    return None


def input_files(case_path: Path, case_data: dict, params=()) -> tuple[tuple[str, str], ...]:
    """(file, sha256 of its bytes) of every file a sweep's runs read: the case, every file its strings name
    (an impact case's target case, a law.json, a record), the files those cases name in turn, the files a
    parameter's values name, and a parameter's ``from`` (scaling.json, law.json); sorted by file."""
    found: dict[Path, str] = {}
    todo: list[tuple[Path, dict | None]] = [(Path(case_path), case_data)]
    for p in params:
        if isinstance(p, (Scaling, LawDraw)):
            todo.append((Path(p.source.rsplit(":", 1)[0] if isinstance(p, Scaling) else p.source), None))
        elif isinstance(p, (Level, Fixed)):
            values = p.values if isinstance(p, Level) else [p.value]
            todo += [(f, None) for k, v in _strings(list(values), p.key.split(".")[-1]) if (f := _file_of(v, k, Path(case_path).parent)) is not None]
    while todo:
        path, data = todo.pop()
        path = path.resolve()
        if path in found or not path.is_file():
            continue
        raw = path.read_bytes()
        found[path] = hashlib.sha256(raw).hexdigest()
        if path.suffix == ".toml":
            if data is None:
                try:
                    data = load_toml(path)
                except InputError:
                    continue  # a file that does not parse is refused where it is read; its bytes are already counted
            todo += [(f, None) for k, v in _strings(data) if (f := _file_of(v, k, path.parent)) is not None]
    return tuple(sorted((str(p), d) for p, d in found.items()))


def case_files(case_path, known=()) -> tuple[Path, ...]:
    """Every file a case reads: the case itself first (as given), the files ``known`` to have been read (as their
    reader named them: a law.json relative to the case's folder), then each other file it names (a target case, a
    force table, a record) and those name in turn (:func:`input_files`), resolved. A run's inputs: never replaced nor
    removed by its outputs (:func:`softimpact.output.files.write_outputs`)."""
    first = [Path(case_path), *(Path(k) for k in known)]
    seen = {p.resolve() for p in first}
    try:
        data = load_toml(Path(case_path))
    except InputError:
        return tuple(dict.fromkeys(first))
    more = [Path(f) for f, _ in input_files(Path(case_path), data) if Path(f).resolve() not in seen]
    return tuple(dict.fromkeys(first + more))
