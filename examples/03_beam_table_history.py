"""
A beam under a Table II force history
=====================================

The long laminated cantilever of the paper (``paper-long-beam``, Figs 18–22) loaded by the
second row of Table II: the eq-(15) history of peak F0 and duration T.

Checked against a closed form: eq (15) is a half-sine in a skewed time, so its impulse is
2·F0·T/π whatever the time of peak; the force column of ``history.csv`` integrates to it.
"""

# %%
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from click.testing import CliRunner

from softimpact.cli import main
from softimpact.input.beam_case import table_rows

out = Path(tempfile.mkdtemp()) / "beam"
run = CliRunner().invoke(main, ["beam", "paper-long-beam", "--history", "2", "--out", str(out), "--no-figures"])
assert run.exit_code == 0, run.output
print(run.output)

# %%
# ``history.csv``: time, force (compression +), gauge strains (tension +), deflection (up +).
data = np.genfromtxt(out / "history.csv", delimiter=",", names=True)
fig, ax = plt.subplots()
for name in data.dtype.names:
    if name.startswith("strain_"):
        ax.plot(data["time_s"] * 1e6, data[name] * 1e6, label=name)
ax.set_xlabel("time [µs]")
ax.set_ylabel("strain [µε]")
ax.legend()

# %%
# One number: the impulse of the applied force against 2·F0·T/π (eq 15, Table II row 2).
row = table_rows("paper-long-beam")[1]
expected = 2 * row["peak_force"] * row["duration"] / np.pi
impulse = np.trapezoid(data["force_N"], data["time_s"])
assert abs(impulse / expected - 1) < 0.01, (impulse, expected)
