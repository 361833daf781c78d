"""The case-file reference, recorded from the readers themselves so it cannot drift.

Every reader in :mod:`softimpact.input` asks its :class:`~softimpact.input.toml.Table` for each
key (``quantity(key, kind)``, ``number``, ``integer``, ``string(..., choices=)``, ``table``,
``tables``, ``raw``). :func:`record` wraps those methods for the time of a read, runs each reader
over the built-in cases and over variants that take every branch (every contact law, history
shape, inline material and ply, bridge keys, …), and keeps what was asked: the key's full path
(array rows as ``[]``), its type, SI unit, default and limits. :func:`markdown` renders it, and
the Sphinx hook :func:`setup` writes ``docs/_generated/case-files.md`` before each build.
``tests/test_docs.py`` checks the record against a static scan of the readers' source.
"""

from __future__ import annotations

import copy
import inspect
import re
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass
from pathlib import Path
from unittest import mock

FORMATS = {
    "bar": "Bar case (`softimpact bar`)",
    "beam": "Beam case (`softimpact beam`, `calibrate`)",
    "plate": "Plate case (`softimpact plate`)",
    "impact": "Impact case (`softimpact impact`)",
    "series": "Bar test series (`softimpact reduce`, `fit`, `identify`)",
    "calibration": "Calibration series (`softimpact calibrate SERIES`)",
    "sweep": "Sweep spec (`softimpact sweep`)",
    "bar-calibration": "Bar calibration file (`softimpact calibrate-bar`)",
    "two-bar": "Two-bar series (`softimpact shpb`)",
}
_METHODS = ("quantity", "number", "integer", "string", "table", "tables", "raw")


@dataclass
class Key:
    """One key a reader asked for."""

    path: str  # "bar.end_cap.diameter", "gauges[].position"
    fmt: str  # the file format (a key of FORMATS)
    method: str  # the Table method that read it
    kind: str = ""  # the quantity's kind (length, time, …) for ``quantity``
    default: object = None
    required: bool = True
    choices: tuple = ()
    limit: str = ""


class Recorder:
    """Collects the keys read while :attr:`current` names a format."""

    def __init__(self):
        self.current: str | None = None
        self.keys: dict[str, dict[str, Key]] = {f: {} for f in FORMATS}

    def note(self, table, name: str, method: str, args: dict) -> None:
        if self.current is None:
            return
        path = re.sub(r"\[\d+\]", "[]", table.key(name))
        known = self.keys[self.current]
        if path in known and (method == "raw" or known[path].method != "raw"):
            return
        from softimpact.input import toml

        default = args.get("default", toml._MISSING)
        if method in ("table", "tables"):
            required, default = not args.get("optional", False), None
        else:
            required = default is toml._MISSING
            default = None if required else default
        limit = ""
        if method == "quantity":
            limit = "> 0" if args.get("positive", True) else ""
        elif method == "integer":
            limit = f"≥ {args.get('minimum', 1)}"
        choices = tuple(args.get("choices") or ())
        known[path] = Key(path, self.current, method, args.get("kind", ""), default, required, choices, limit)


@contextmanager
def _recording(rec: Recorder):
    """Wrap the Table methods (and keep the readers of an impact case's target out of its record)."""
    from softimpact.input import impact_case, toml

    def wrap(method):
        original = getattr(toml.Table, method)
        signature = inspect.signature(original)

        def wrapper(self, name, *args, **kwargs):
            bound = signature.bind(self, name, *args, **kwargs)
            rec.note(self, name, method, dict(bound.arguments))
            return original(self, name, *args, **kwargs)

        return wrapper

    def quiet(reader):
        def wrapper(*args, **kwargs):
            current, rec.current = rec.current, None
            try:
                return reader(*args, **kwargs)
            finally:
                rec.current = current

        return wrapper

    with ExitStack() as stack:
        for method in _METHODS:
            stack.enter_context(mock.patch.object(toml.Table, method, wrap(method)))
        stack.enter_context(mock.patch.object(impact_case, "beam_problem", quiet(impact_case.beam_problem)))
        stack.enter_context(mock.patch.object(impact_case, "plate_problem", quiet(impact_case.plate_problem)))
        yield


def _data(name: str) -> dict:
    from softimpact.input.toml import builtin_cases, load_toml

    return load_toml(builtin_cases()[name])


def _set(data: dict, **dotted) -> dict:
    """A deep copy of ``data`` with dotted keys (``bar__end_cap`` for ``bar.end_cap``) set; None deletes."""
    out = copy.deepcopy(data)
    for key, value in dotted.items():
        *head, last = key.split("__")
        d = out
        for part in head:
            d = d.setdefault(part, {})
        if value is None:
            d.pop(last, None)
        else:
            d[last] = value
    return out


_INLINE_MATERIAL = {"name": "aluminium", "youngs_modulus": "10e6 psi", "poisson_ratio": 0.33, "density": "0.0975 lb/in^3", "source": "handbook"}
_INLINE_PLY = {
    "name": "ply",
    **{k: "10 GPa" for k in ("E1", "E2", "E3", "G12", "G13", "G23")},
    **{k: 0.3 for k in ("nu12", "nu13", "nu23")},
    "density": "1600 kg/m^3",
    "thickness": "0.1 mm",
    "source": "test",
    **{k: "100 MPa" for k in ("Xt", "Xc", "Yt", "Yc", "S", "S23")},  # strengths: the damage outputs need them
    "G_IIc": "500 J/m^2",
}


def _variants() -> dict[str, list]:
    """Per format: (reader arguments) that together take every branch of its reader."""
    from pathlib import Path as P

    bar = _data("paper-calibration")
    beam = _data("paper-long-beam")
    plate = _data("plate-ss-8in")
    impact = _data("paper-long-beam-impact")
    pimpact = _data("plate-ss-8in-impact")
    contact_laws = [
        {"law": "hertz-unloading", "critical_indentation": "0.1 mm", "target_modulus": "8 GPa"},
        {"law": "hunt-crossley", "restitution": 0.8, "form": "hunt-crossley"},
        {"law": "identified", "law_file": "law.json"},
        {"law": "identified", "law_file": "law.json", "parameters": {"k_ref": 4.0}},
    ]
    # the crushing and hydrodynamic laws are the projectile's material's (ice, gelatin), their optional keys
    # replacing the material's constants; a hail threat in place of the sphere's material, diameter, velocity
    flow_laws = [
        ({"material": "ice"}, {"law": "crushing", "strength_coefficient": "10 MPa", "strength_exponent": 0.1}),
        ({"material": "gelatin"}, {"law": "hydrodynamic", "sound_speed": "1500 m/s", "hugoniot_slope": 2.0}),
    ]
    threat = {"threat": {"hail": "38.1 mm", "airspeed": "100 m/s"}, "velocity": "30 m/s", "mass": "20 g"}
    bird = {"threat": {"bird": "4 lb", "density": "938 kg/m^3"}, "velocity": "150 m/s"}  # a bird: the substitute of that mass, velocity required
    history = [
        {"shape": "skewed", "peak_force": "100 lbf", "time_of_peak": "50 us", "duration": "200 us"},
        {"shape": "table", "file": "force.csv"},
        {"shape": "empirical", "projectile": "rubber-1/2in", "constants": "silicone-1/2in", "velocity": "1166 in/s", **{f"alpha{i}": 1.0 for i in range(1, 5)}},
    ]
    row = {"velocity": "1166 in/s", "peak_force": "100 lbf", "time_of_peak": "50 us", "duration": "200 us", "contact_radius": "0.1 in"}
    return {
        "bar": [(bar,), (_set(bar, bar__file="bar.toml"),), (_set(bar, bar__material=_INLINE_MATERIAL, bar__end_cap={"material": "steel", "diameter": "1 in", "length": "0.25 in"}, output={"snapshots": ["10 us"]}),)]
        + [(_set(bar, contact=c),) for c in contact_laws]
        + [(_set(bar, projectile__material=m["material"], contact=c),) for m, c in flow_laws]
        + [(_set(bar, projectile={**threat, "velocity": "30 m/s"}),)]
        + [(_set(bar, projectile=bird, contact={"law": "hydrodynamic"}),)],
        "beam": [(beam,), (beam, P("."), 1)]
        + [(_set(beam, load__history=h, load__table=[row]), P("."), 1) for h in history]
        + [
            (_set(beam, beam__laminate={"ply": _INLINE_PLY, "fractions": {"0": 0.5, "90": 0.5}, "thickness": "1 mm", "model": "layered"}, beam__plane="stress", beam__mass="lumped", beam__damping={"ratio": 0.01, "frequencies": ["1 kHz", "10 kHz"]}),),
            (_set(beam, beam__laminate=None, beam__material={"material": "steel", "thickness": "1 mm"}),),
            (_set(beam, beam__laminate=None, beam__material={**{k: v for k, v in _INLINE_MATERIAL.items() if k != "source"}, "thickness": "1 mm"}),),
        ],
        "plate": [(plate,), (_set(plate, plate__element="mitc4", plate__model="fsdt", load__grow=False, gauges=[{"name": "g", "position": ["1 in", "1 in"], "surface": "top", "direction": 45, "length": "0.1 in"}]),), (_data("plate-ss-pressure-vk"),)]
        + [(_set(plate, plate__laminate=None, plate__material="Al 2024-T3", plate__thickness="2 mm", plate__plasticity=False),)]
        + [(_set(plate, plate__laminate=None, plate__material={"youngs_modulus": "70 GPa", "poisson_ratio": 0.33, "density": "2700 kg/m^3", "yield_stress": "300 MPa", **h}, plate__thickness="2 mm"),)
           for h in ({"hardening_modulus": "500 MPa"}, {"ultimate_strength": "400 MPa", "elongation": 0.1})],
        "impact": [(impact,), (pimpact,), (_set(impact, impactor__mass="1 g", gauges=[{"name": "g", "position": "1 in", "surface": "top", "length": "0.1 in"}]),)]
        + [(_set(impact, contact=c),) for c in contact_laws]
        + [(_set(impact, impactor__material=m["material"], contact=c),) for m, c in flow_laws]
        + [(_set(impact, impactor=threat),)]
        + [(_set(impact, impactor=bird, contact={"law": "hydrodynamic"}),)]
        + [(_set(impact, impactor={"striker": True, "material": "steel", "diameter": "16 mm", "mass": "5.5 kg", "energy": "30 J"}),)]
        + [(_data("plate-ss-8in-impact-cohesive"),)]
        + [(_set(_data("plate-ss-8in-impact-cohesive"), damage__cohesive="dissimilar", damage__near_field="20 mm", damage__element_size="2 mm", damage__turon=True),)]
        + [(_set(_data("plate-ss-8in-impact-cohesive"), damage__near_field="whole"),)],
        "series": [
            "paper-rubber-series",
            _set(_data("paper-rubber-series"), bar__dispersion="pochhammer-chree", gauge__bridge="quarter", gauge__gauge_factor=2.1, gauge__excitation="5 V", gauge__gain=100, gauge__polarity=-1, gauge__poisson_ratio=0.3, gauge__gauge_resistance_ohm=350, gauge__lead_resistance_ohm=0.4, gauge__shunt_resistance_ohm=100e3, gauge__shunt_step="-0.3 V"),
            _set(_data("paper-rubber-series"), gauge__second_position="27 in", test=[{"name": "t", "record": {"file": "a.tdms", "channel": "g", "unit": "mV"}, "second_record": "b.csv", "velocity": "1000 in/s", "diameter": "0.5 in", "mass": "1 g", "accept_flagged": True}]),
        ],
        "calibration": ["paper-long-calibration", _set(_data("paper-long-calibration"), projectile="rubber-1/2in", constants="scaling.json", test=[{"name": "t", "measured": "m.csv", "velocity": "1000 in/s", "contact_radius": "0.1 in", "contact_time": "10 us", "reference": {"peak_force": "1 lbf", "time_of_peak": "1 us", "duration": "2 us", "contact_radius": "0.1 in"}}])],
        "bar-calibration": [
            "lab-bar-calibration",
            _set(_data("lab-bar-calibration"), bar__material=_INLINE_MATERIAL, bar__length_uncertainty="0.2 mm", bar__diameter_uncertainty="0.01 mm", bar__density="7850 kg/m^3", bar__density_uncertainty="5 kg/m^3", bar__dispersion_unknown="radius",
                 shot=[{"name": "s", "record": {"file": "lab-bar-calibration/ball-1.csv", "channel": "gauge", "unit": "mV"}, "ball": {"mass": "2 g", "velocity": "3 m/s", "mass_uncertainty": "1 mg", "velocity_uncertainty": "0.01 m/s", "rebound_max": "3 m/s"}},
                       {"record": "lab-bar-calibration/ball-2.csv", "ball": {"mass": "2 g", "velocity": "3 m/s", "rebound": "2.8 m/s", "rebound_uncertainty": "0.03 m/s"}}]),
        ],
        "two-bar": [
            "ice-shpb-series",
            _set(_data("ice-shpb-series"), dispersion="pochhammer-chree", specimen__density="900 kg/m^3",
                 test=[{"name": "t", "incident": "a.csv", "transmitted": {"file": "a.csv", "channel": "t", "unit": "V"}, "specimen": {"length": "5 mm", "diameter": "12 mm", "density": "900 kg/m^3"}, "transmitted_delay": "1 us"}]),
            _set(_data("ice-shpb-series"), incident_bar={"file": "incident-bar.toml"}),
        ],
        "sweep": [
            ({"sweep": {"case": "paper-long-beam", "method": "monte-carlo", "runs": 10, "seed": 1, "chunk": 5, "outputs": ["peak_force_N"], "parameter": [
                {"key": "load.history", "value": {"shape": "skewed", "peak_force": "1 lbf", "time_of_peak": "1 us", "duration": "2 us"}},
                {"key": "load.history.peak_force", "values": ["1 lbf", "2 lbf"]},
                {"key": "load.history.duration", "range": ["1 us", "2 us", 3]},
                {"key": "load.history.time_of_peak", "distribution": {"uniform": ["1 us", "2 us"]}},
                {"key": "load.history.velocity", "from": "scaling.json", "group": "0.5 in"}]}},),
            ({"sweep": {"case": "paper-long-beam", "method": "grid", "outputs": ["peak_force_N", "damage.max_strain"], "threshold_against": "load.history.peak_force",
                        "limits": {"damage.max_strain": 0.8}, "onset": [], "parameter": [{"key": "load.history.peak_force", "values": ["1 lbf", "2 lbf"]}]}},),
        ],
    }  # fmt: skip


def record() -> dict[str, dict[str, Key]]:
    """Run every reader over its variants and return the keys asked for, per format."""
    from softimpact.input import bar_calibration, bar_case, beam_case, impact_case, plate_case, series, shpb_series, sweep_spec, toml

    rec = Recorder()
    readers = {
        "bar": bar_case.bar_problem,
        "beam": beam_case.beam_problem,
        "plate": plate_case.plate_problem,
        "impact": impact_case.impact_problem,
        "sweep": lambda data: sweep_spec.read_sweep_spec(data, Path(".")),
    }
    with _recording(rec):
        for fmt, variants in _variants().items():
            for variant in variants:
                rec.current = fmt
                try:
                    if fmt in readers:
                        readers[fmt](*variant)
                    elif fmt in ("bar-calibration", "two-bar"):  # read by name: hand the reader the variant's data
                        module, reader, name = {
                            "bar-calibration": (bar_calibration, bar_calibration.load_calibration_file, "lab-bar-calibration"),
                            "two-bar": (shpb_series, shpb_series.load_shpb_series, "ice-shpb-series"),
                        }[fmt]
                        data = toml.load_toml(toml.locate(name)) if isinstance(variant, str) else variant
                        with mock.patch.object(module, "load_toml", lambda path, data=data: data):
                            reader(name)
                    else:  # the series readers take a name: hand them the variant's data
                        name = variant if isinstance(variant, str) else {"series": "paper-rubber-series", "calibration": "paper-long-calibration"}[fmt]
                        data = toml.load_toml(toml.locate(name)) if isinstance(variant, str) else variant
                        with mock.patch.object(series, "load_toml", lambda path, data=data: data):
                            (series.load_series if fmt == "series" else series.load_calibration_series)(name)
                except Exception:  # noqa: BLE001 - a variant may stop at a file it names; what it read before counts
                    pass
                finally:
                    rec.current = None
    return rec.keys


def _cell(text: str) -> str:
    return str(text).replace("|", "\\|")


# What a key read whole (``Table.raw``) holds: the reader checks its shape itself. Matched on the end
# of the key's path; tests/test_docs.py fails when a raw key has no line here.
RAW_VALUES = {
    "material": "a catalogue name (text) or an inline table (`youngs_modulus`, `poisson_ratio`, `density`, optional `name`, `source`)",
    "plate.material": "a catalogue metal (`Al 2024-T3`, `Al 7075-T6`, `Al 6061-T6`, `steel S355`, `Ti-6Al-4V`) or an inline table "
    "(`youngs_modulus`, `poisson_ratio`, `density`, `yield_stress` and `hardening_modulus` or `ultimate_strength` with `elongation`); "
    "with `thickness`, in place of `[plate.laminate]`",
    "turon": "true or false: the interface strengths lowered to Turon et al. 2007's for the near field's node spacing (eq. 12), so a coarser mesh resolves the process zone; every run that uses it says so",
    "near_field": 'a length (the half-width of the stacked square about the impact point) or `"whole"` (the whole plate stacked on its own mesh)',
    "plasticity": "true or false: a metal plate's section elastic-plastic (J2 through the thickness; the default) or elastic (checked against yield)",
    "ply": "a catalogue ply name (text) or an inline table (`E1`…`G23`, `nu12`…`nu23`, `density`, `thickness`)",
    "snapshots": "a list of times (quantities) within the run",
    "beam.elements": "`[along the length, through the thickness]`, two integers ≥ 1",
    "plate.elements": "`[along x, along y]`, two integers ≥ 2",
    "fractions": "a table of angle (degrees, as the key) = volume fraction",
    "frequencies": "two frequencies (quantities) at which the Rayleigh damping equals `ratio`",
    "support": 'one support for all four edges (`"simply-supported"`) or a table `{ x0 = …, x1 = …, y0 = …, y1 = … }` of edge supports',
    "position": "`[x, y]`, two lengths",
    "grow": "true or false: the contact disc grows with the force by eq (10)",
    "direction": '`"x"`, `"y"` or an angle in degrees from x',
    "record": "a path (relative to the series file) or a table `{ file, channel, unit }`",
    "second_record": "as `record`: the second gauge's record",
    "incident": "a path (relative to the series file) or a table `{ file, channel, unit }`: the incident bar's record",
    "gauge": "a table: the gauge's `position` and bridge keys (below); with `bar.file` its keys replace the bar file's `[gauge]`",
    "incident_gauge": "a table: the incident gauge's `position` (from the struck end) and bridge keys, as a series' `[gauge]`",
    "transmitted_gauge": "a table: the transmitted gauge's `position` (from the specimen) and bridge keys, as a series' `[gauge]`",
    "transmitted": "as `incident`: the transmitted bar's record, on the same clock",
    "channel": "a channel name (`group/channel` or a unique `channel`) or an index",
    "accept_flagged": "true or false: fit this test even if flagged",
    "striker": "true or false: a drop weight's hemispherical striker of `diameter` on a carriage of `mass` (required), named by its `velocity` or its `energy` (v = sqrt(2E/m)); no solid-sphere mass check",
    "constants": "a scaling.json path (of `softimpact fit`) or a preset name",
    "outputs": "a list of output keys (`peak_force_N`, `strain_<g>.peak`, `damage.<index>`, …)",
    "value": "any value the key takes (a whole table replaces the table)",
    "parameters": "a table of the identified law's parameters by name (`k_ref`, `p`, `kappa_ref`, …): numbers used in place of law.json's (a sweep draws them)",
    "values": "a list of levels (quantities or values)",
    "threshold_against": "the dotted case key of a level of quantities (`impactor.energy`, `impactor.diameter`, `impactor.threat.hail`): thresholds and onsets are found against it (default: the velocity level)",
    "limits": 'a table of output = limit in the output\'s unit (`"damage.dent_depth_m" = "0.25 mm"`, `"peak_force_N" = "5 kN"`; a plain number for an index): the threshold where the output first reaches it',
    "onset": "a list of outputs whose onset (first positive level, extrapolated to zero) is reported (default: every `damage.*` size in m, m², m³)",
    "range": "`[low, high, n]`: n levels evenly spaced",
    "between": "`[k, k + 1]`: two consecutive ply numbers (1 = the top ply), the interface between them tied by the cohesive law",
    "distribution": "`{ uniform = [lo, hi] }`, `{ normal = [mean, sd] }` or `{ lognormal = [median, sigma of ln] }`",
}


def raw_value(path: str) -> str | None:
    """The description of a raw key's value (longest matching end of its path), or None."""
    for suffix in sorted(RAW_VALUES, key=len, reverse=True):
        if path == suffix or path.endswith("." + suffix) or path.endswith("]." + suffix):
            return RAW_VALUES[suffix]
    return None


# Defaults that come from elsewhere in the file (the reader computes them): said in words
# (keyed by path, or by "format:path" where only one format's reader computes it).
_CONTEXT_DEFAULTS = {
    **{f"load.history.alpha{i}": f"the `constants` preset's α{i}" for i in range(1, 5)},
    "series:title": "the file's name",
    "calibration:title": "the file's name",
    "bar-calibration:title": "the file's name",
    "two-bar:title": "the file's name",
    "bar-calibration:shot[].name": "the record's file name",
    "two-bar:test[].name": "the incident record's file name",
    "bar.density": "the material's",
    "specimen.density": "the specimen material's",
    "test[].specimen.length": "`specimen.length`",
    "test[].specimen.diameter": "`specimen.diameter`",
    "test[].specimen.density": "`specimen.density`",
    "series:test[].name": "the record's file name",
    "calibration:test[].name": "the measured file's name",
    "gauge.poisson_ratio": "the bar material's",
    "incident_gauge.poisson_ratio": "the bar material's",
    "transmitted_gauge.poisson_ratio": "the bar material's",
    "load.table[].contact_radius": "`load.contact_radius`",
    "contact.target_modulus": "the ply's through-thickness modulus",
    "projectile.mass": "from density and diameter",
    "impactor.mass": "from density and diameter",
    "contact.strength_coefficient": "the projectile material's (ice: Jones 1997, 8.9 MPa)",
    "contact.strength_exponent": "the projectile material's (ice: Jones 1997, 0.15)",
    "contact.sound_speed": "the projectile material's (gelatin: Wilbeck, 1482.9 m/s)",
    "contact.hugoniot_slope": "the projectile material's (gelatin: Wilbeck, 2)",
    "projectile.threat.airspeed": "none: the hail falls at its terminal velocity",
    "impactor.threat.airspeed": "none: the hail falls at its terminal velocity",
    "damage.normal_strength": "the ply's transverse tensile strength Y_t",
    "damage.shear_strength": "the ply's in-plane shear strength S12",
    "damage.G_IIc": "the ply's G_IIc",
}


# What a choice means where its name does not say it all (keyed by path, or by "format:path"): rendered
# after the key's choices.
_KEY_NOTES = {
    "beam.kinematics": '`"von-karman"`: large deflection; for the plane beam it selects the total Lagrangian form '
    "(Green–Lagrange strain, St Venant–Kirchhoff with the same layered D), which contains von Kármán's beam as its "
    "moderate-rotation limit; stepped directly (no response engine, no contact kernels); an impact case's beam target takes it from its beam case",
}


def _note(k: Key) -> str:
    """A key's note (:data:`_KEY_NOTES`), or ''."""
    return _KEY_NOTES.get(f"{k.fmt}:{k.path}", _KEY_NOTES.get(k.path, ""))


# Keys of which one or the other is required (each "required" where its reader gets to it): said so in the default
# column, keyed by "format:path".
_STATIC = '`solver.analysis = "static"`'
_EITHER_OR = {
    "plate:load.pressure": f"required with {_STATIC} (a uniform pressure); else `load.history`",
    "plate:load.history": f"required unless {_STATIC} (then `load.pressure`)",
    "plate:load.position": f"required unless {_STATIC}",
    "plate:load.contact_radius": f"required unless {_STATIC}",
    "plate:solver.time_step": f"required unless {_STATIC}",
    "plate:solver.duration": f"required unless {_STATIC}",
    "beam:beam.laminate": "one of `beam.laminate` and `beam.material`",
    "beam:beam.material": "one of `beam.laminate` and `beam.material`",
    "bar:projectile.material": "required unless `projectile.threat`",
    "bar:projectile.diameter": "required unless `projectile.threat`",
    "bar:projectile.velocity": "required unless a hail `projectile.threat` (then its velocity); required with a bird threat (a bird has no speed of its own)",
    "impact:impactor.material": "required unless `impactor.threat`",
    "impact:impactor.diameter": "required unless `impactor.threat`",
    "impact:impactor.velocity": "required unless a hail `impactor.threat` (then its velocity) or a striker's `impactor.energy`; "
    "required with a bird threat (a bird has no speed of its own)",
    "bar:projectile.threat.hail": "one of `projectile.threat.hail` (a hailstone's diameter) and `projectile.threat.bird`",
    "bar:projectile.threat.bird": "one of `projectile.threat.hail` and `projectile.threat.bird` (a bird's mass: its gelatin substitute, "
    "a hemispherical-ended cylinder of L/D = 2)",
    "impact:impactor.threat.hail": "one of `impactor.threat.hail` (a hailstone's diameter) and `impactor.threat.bird`",
    "impact:impactor.threat.bird": "one of `impactor.threat.hail` and `impactor.threat.bird` (a bird's mass: its gelatin substitute, "
    "a hemispherical-ended cylinder of L/D = 2)",
    "impact:impactor.energy": "a striker's (`impactor.striker = true`) velocity as its kinetic energy, in place of `impactor.velocity`",
    "impact:impactor.mass": "from density and diameter; required for a striker (`impactor.striker = true`); refused with a bird threat (the bird is the mass)",
}


def _default(k: Key) -> str:
    from softimpact import units

    either = _EITHER_OR.get(f"{k.fmt}:{k.path}")
    if either:
        return either
    context = _CONTEXT_DEFAULTS.get(f"{k.fmt}:{k.path}", _CONTEXT_DEFAULTS.get(k.path))
    if context and not k.required:
        return context

    if k.method in ("table", "tables"):
        return "required" if k.required else "optional"
    if k.required:
        return "required"
    if k.default is None:
        return "optional"
    if k.method == "quantity" and isinstance(k.default, (int, float)):
        return f"`{k.default:.6g} {units.SI_UNITS[k.kind]}`"
    return f"`{k.default!r}`"


def _type(k: Key) -> str:
    from softimpact import units

    if k.method == "quantity":
        return f"{k.kind} [{units.SI_UNITS[k.kind]}]"
    if k.method == "raw":
        return raw_value(k.path) or "value"
    return {"number": "number", "integer": "integer", "string": "text", "table": "table", "tables": "array of tables"}[k.method]


def markdown(keys: dict[str, dict[str, Key]]) -> str:
    """The reference page: one table per file format, keys in the order the reader asks for them."""
    lines = [
        "# Case-file reference",
        "",
        "Generated at build time from the readers themselves (`docs/_ext/casekeys.py` runs every reader of",
        "`softimpact.input` over the built-in cases and variants that take each branch, and records what it asks",
        "for), so it lists exactly the keys the readers accept. A quantity is a string with its unit",
        '(`"0.5 in"`, `"62.1 in/s"`, `"0.5 us"`); its SI unit is given, any unit of the same dimension is accepted.',
        "Rows of an array of tables are shown as `name[]`. Unknown keys are refused. *Required* means required where",
        'the reader gets to it: `load.history.peak_force` with `shape = "skewed"`, `contact.restitution` with',
        '`law = "hunt-crossley"`, one of `beam.laminate` and `beam.material`, and so on.',
        "",
    ]
    for fmt, title in FORMATS.items():
        lines += [f"## {title}", "", "| key | type [SI unit] | default | limits |", "|---|---|---|---|"]
        tops = list(dict.fromkeys(path.split(".")[0].split("[")[0] for path in keys[fmt]))
        for k in sorted(keys[fmt].values(), key=lambda k: (tops.index(k.path.split(".")[0].split("[")[0]), k.path)):
            limits = ", ".join(f"`{c}`" for c in k.choices) if k.choices else k.limit
            limits = f"{limits}: {_note(k)}" if _note(k) else limits
            lines.append(f"| `{_cell(k.path)}` | {_cell(_type(k))} | {_cell(_default(k))} | {_cell(limits)} |")
        lines.append("")
    return "\n".join(lines)


def _write(app) -> None:
    out = Path(app.srcdir) / "_generated"
    out.mkdir(exist_ok=True)
    text = markdown(record())
    target = out / "case-files.md"
    if not target.exists() or target.read_text() != text:
        target.write_text(text)


def setup(app):
    app.connect("builder-inited", _write)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
