"""The notebook edge of softimpact: objects in, frozen results out (``import softimpact as si``).

Quantities are given as unit strings (``"6 in"``, ``"0.5 us"``, ``"100 in/s"``) or pint
quantities, and converted to SI floats ONCE, here, by :func:`softimpact.units.parse`
(the same conversion a case file's keys go through, so a run from objects and the
same run from a case file agree to the last bit). Everything below this package is SI.
A plain number is refused where a unit is needed: ``6`` could be inches or metres.

The index (every name is also ``si.NAME``):

- structures and the impactor (:mod:`softimpact.api.structures`): :class:`Laminate`, :class:`Beam`,
  :class:`Plate`, :class:`Bar`, :class:`Sphere`; :func:`bird` (a bird threat as its gelatin substitute, a :class:`Sphere`);
- runs (:mod:`softimpact.api.commands`): :func:`impact` (the one coupled stepper,
  :func:`softimpact.workflows.coupled.run_impact`), :func:`load` (a :class:`Case`) and :func:`run`
  for any case file or built-in name (through :data:`softimpact.cases.KINDS`);
- the chain of the paper (:mod:`softimpact.api.chain`), wrapping the commands' own functions
  (:mod:`softimpact.app`) with the options of the same table the command line reads
  (:mod:`softimpact.app.options`): :func:`reduce`, :func:`fit`, :func:`predict`, :func:`identify`,
  :func:`calibrate`, :func:`converge`, :func:`sweep`; :func:`read_record` reads one channel of a lab record;
  a lab's own bars: :func:`calibrate_bar` (a bar file from its records) and :func:`shpb` (two-bar tests);
  :func:`catalogue` lists the named materials, plies, projectiles, contact laws and built-in cases;
- the frozen results (:mod:`softimpact.api.results`): :class:`ImpactResult`, :class:`BeamResult`,
  :class:`PlateResult`, :class:`BarResult`, :class:`CommandResult`, :class:`Record`.

Results are frozen, their arrays read-only; they carry their inputs in SI (``res.problem``) and offer
``.plot(ax=None)``, ``.write(dir)`` (the command's files and manifest.json, written
atomically as the command line writes them), ``.summary()`` (summary.json's numbers)
and ``.to_frame()`` (a pandas DataFrame; the ``table`` extra).

Errors are :class:`~softimpact.errors.InputError` s naming the keyword argument (``measured``, not
the command line's ``--measured``), raised before anything is computed where the arguments alone
show the fault. Warnings: what the command line shows as ``softimpact: warning:`` lines (a model
past its validity envelope, a law used outside what it was identified on) the API warns as
:class:`~softimpact.errors.SoftimpactWarning` s pointing at the user's call, raised by the same
functions; the result keeps them (``res.warnings``) and ``write`` lists them in manifest.json,
with the files read (a law.json with its SHA-256), as the command line does.

Importing this package imports no numpy: every heavy module is imported inside the function that
needs it. Not re-exported here: the layers below (:mod:`softimpact.models`, :mod:`softimpact.workflows`, …),
imported explicitly.
"""

from .chain import calibrate, calibrate_bar, catalogue, converge, fit, identify, predict, read_record, reduce, shpb, sweep
from .commands import Case, impact, load, press, run
from .results import BarResult, BeamResult, CommandResult, ImpactResult, PlateResult, Record, StaticPlateResult
from .structures import Bar, Beam, Laminate, Plate, Sphere, bird

__all__ = [
    "Laminate",
    "Beam",
    "Plate",
    "Bar",
    "Sphere",
    "bird",
    "impact",
    "press",
    "load",
    "run",
    "Case",
    "ImpactResult",
    "BeamResult",
    "PlateResult",
    "StaticPlateResult",
    "BarResult",
    "CommandResult",
    "Record",
    "reduce",
    "fit",
    "predict",
    "identify",
    "calibrate",
    "converge",
    "sweep",
    "read_record",
    "catalogue",
    "calibrate_bar",
    "shpb",
]
