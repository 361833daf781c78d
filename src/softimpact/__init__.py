"""softimpact: the impact of soft projectiles on structures.

Implements the method of J.E. Grady, "Contact Force History and Dynamic Response
Due to the Impact of a Soft Projectile" (NASA Lewis).

For notebooks and scripts, ``import softimpact as si`` gives the object-first API
(:mod:`softimpact.api`); quantities are unit strings (``"0.5 in"``) or pint
quantities, converted to SI once::

    import softimpact as si
    beam = si.Beam(length="6 in", width="1 in", laminate=si.Laminate("T300/934", "[90/0]5s"), elements=(200, 6))
    res = si.impact(beam, at="3 in", impactor=si.Sphere("steel", "0.5 in", velocity="100 in/s"),
                    law="hertz", time_step="0.5 us", duration="400 us", gauges={"g1": "2 in", "g2": "0.5 in"})
    res.peak_force, res.strain["g1"]; res.plot(); res.write("out/")

Structures and impactors: :class:`Beam`, :class:`Plate`, :class:`Laminate`, :class:`Sphere`, :func:`bird`.
Runs: :func:`impact`, :func:`press` (a static uniform pressure on a plate), :func:`load` and :func:`run` (any case
file or built-in name).
The chain of the paper: :func:`reduce`, :func:`fit`, :func:`predict`, :func:`identify`,
:func:`calibrate`, :func:`converge`, :func:`sweep`; lab records: :func:`read_record`; a lab's own bars:
:func:`calibrate_bar` and :func:`shpb` (two-bar tests); the named
materials, plies, projectiles, contact laws and cases: :func:`catalogue`.

The names are imported on first use (PEP 562), so ``import softimpact`` imports
no numpy, scipy, scikit-fem, pint or matplotlib. The layers below, imported
explicitly:

- :mod:`softimpact.models` — materials, Hertz contact (eqs 1–3), pulses (eq 15),
  the empirical soft-projectile model (eqs 4–7), laminates.
- :mod:`softimpact.fem` — Hermite rod, plane-strain and plate matrices (scikit-fem),
  Newmark time stepping, the one coupled stepper.
- :mod:`softimpact.workflows` — bar impact, record reduction, scaling fit,
  beam and plate impact, coupled impact, calibration.
- :mod:`softimpact.input` (case, series and record files),
  :mod:`softimpact.output` (the file contract, figures, the HTML report),
  :mod:`softimpact.app` (one function per command) and :mod:`softimpact.cli`
  (click only) — the edges. Imports point down only.

Everything inside is SI; units are parsed at the edges (:mod:`softimpact.units`).
"""

__version__ = "0.1.0"

# name → the module (relative to this package) that defines it; imported on first access.
_LAZY = {
    "Beam": "api",
    "Plate": "api",
    "Bar": "api",
    "Laminate": "api",
    "Sphere": "api",
    "bird": "api",
    "impact": "api",
    "press": "api",
    "load": "api",
    "run": "api",
    "reduce": "api",
    "fit": "api",
    "predict": "api",
    "identify": "api",
    "calibrate": "api",
    "converge": "api",
    "sweep": "api",
    "read_record": "api",
    "catalogue": "api",
    "calibrate_bar": "api",
    "shpb": "api",
    "Case": "api",
    "ImpactResult": "api",
    "BeamResult": "api",
    "PlateResult": "api",
    "StaticPlateResult": "api",
    "BarResult": "api",
    "CommandResult": "api",
    "Record": "api",
}

__all__ = ["__version__", *_LAZY]


def __getattr__(name: str):
    """The public names of :mod:`softimpact.api`, imported on first use (PEP 562)."""
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'softimpact' has no attribute {name!r}")
    import importlib

    value = getattr(importlib.import_module(f".{module}", __name__), name)
    globals()[name] = value  # later accesses skip this function
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))
