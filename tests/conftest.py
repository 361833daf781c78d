"""Shared problems for the tests (inch units converted here, independently of the package)."""

import os
import tempfile

os.environ.setdefault("MPLBACKEND", "Agg")
# The unit-factor cache of softimpact.units goes to a folder of this test session,
# not the user's ~/.cache (subprocesses of the CLI tests inherit it).
os.environ["SOFTIMPACT_CACHE_DIR"] = tempfile.mkdtemp(prefix="softimpact-cache-")

INCH = 0.0254  # m, exact by definition
PSI = 4.4482216152605 / INCH**2  # Pa: 1 lbf / in²
LB_PER_IN3 = 0.45359237 / INCH**3  # kg/m³
