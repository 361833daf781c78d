"""Record the output contract of every command on the built-in cases into tests/data/contract.json.

The commands, the fingerprint of their output folders and the comparison live in
``tests/_support/contract.py`` (``tests/test_contract.py`` uses them); this script only writes
the record. Re-record a command only for an intended change, and say so in that module's docstring.

    .venv/bin/python tools/make_contract.py tests/data/contract.json
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from _support.contract import contract  # noqa: E402

if __name__ == "__main__":
    Path(sys.argv[1]).write_text(json.dumps(contract(), indent=1) + "\n", encoding="utf-8")
