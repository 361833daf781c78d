"""Record the output contract of every command on the built-in cases into tests/data/contract.json.

The commands, the fingerprint of their output folders and the comparison live in
``tests/_support/contract.py`` (``tests/test_contract.py`` uses them); this script only writes
the record. Re-record a command only for an intended change, and say so in that module's docstring:
name the commands to re-record after the file (the others keep their record); with none, all are recorded.

    .venv/bin/python tools/make_contract.py tests/data/contract.json calibrate
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from _support.contract import COMMANDS, contract  # noqa: E402

if __name__ == "__main__":
    path, names = Path(sys.argv[1]), sys.argv[2:]
    unknown = sorted(set(names) - {n for n, _ in COMMANDS})
    if unknown:
        sys.exit(f"unknown command(s) {', '.join(unknown)}; the contract's are {', '.join(n for n, _ in COMMANDS)}")
    record = json.loads(path.read_text(encoding="utf-8")) if names and path.exists() else {}
    record.update(contract(names or None))
    path.write_text(json.dumps(record, indent=1) + "\n", encoding="utf-8")
