"""The frozen results of the notebook API: what a run or a command made, with ``.plot``, ``.write``,
``.summary``, ``.to_frame`` and (beam, plate, impact) ``.write_fields``.

Why pandas and not xarray for the tabular view: every history here has one dimension,
time, so a DataFrame indexed by time holds it exactly; pandas is what users of lab
data already know, and the CSV files of the contract read back into the same frame.

Split by concern: :mod:`._written` (what every result offers: write, summary, to_frame's frame), :mod:`.runs` (a coupled
impact and a bar run), :mod:`.prescribed` (a beam or plate under a prescribed load, and the static plate),
:mod:`.command` (what a chain command made, and a lab record).
"""

from .command import CommandResult, Record
from .prescribed import BeamResult, PlateResult, StaticPlateResult
from .runs import BarResult, ImpactResult

__all__ = ["ImpactResult", "BeamResult", "PlateResult", "StaticPlateResult", "BarResult", "CommandResult", "Record"]
