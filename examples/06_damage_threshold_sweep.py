"""
A damage-threshold sweep
========================

How fast may a 1/2-in rubber ball hit the long laminated beam before a ply fails? A sweep
runs the beam case ``paper-long-beam`` under the paper's empirical force history
(eqs 4–7, Table I constants) at impact velocities from 1000 to 5000 in/s, reads the
Tsai–Wu and maximum-strain indices of every ply, and interpolates the velocity at which
each index reaches 1 (``thresholds.csv``). All runs share one model and its impulse
responses: each costs milliseconds.

Checked against the paper's closed form: at 5000 in/s the peak force is eq (4),
F0 = α1·m·V²/(2d) with α1 = 4.25 (Table I, 1/2-in ball), within 1 % (the force is
sampled at the time step).
"""

# %%
import csv
import json
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
from click.testing import CliRunner

from softimpact.cli import main
from softimpact.models.empirical import PROJECTILES

work = Path(tempfile.mkdtemp())
(work / "spec.toml").write_text("""
[sweep]
case = "paper-long-beam"
method = "grid"
outputs = ["peak_force_N", "damage.tsai_wu", "damage.max_strain"]
[[sweep.parameter]]
key = "load.history"
value = { shape = "empirical", projectile = "rubber-1/2in", velocity = "1000 in/s" }
[[sweep.parameter]]
key = "load.history.velocity"
range = ["1000 in/s", "5000 in/s", 9]
""")
out = work / "out"
run = CliRunner().invoke(main, ["sweep", str(work / "spec.toml"), "--workers", "0", "--out", str(out), "--no-figures"])
assert run.exit_code == 0, run.output
print(run.output)

# %%
# The threshold velocities, one per damage index.
thresholds = {row["index"]: float(row["threshold_velocity_median_m_s"]) / 0.0254 for row in csv.DictReader((out / "thresholds.csv").open())}
print({k: f"{v:.0f} in/s" for k, v in thresholds.items()})
fig, ax = plt.subplots()
ax.barh(list(thresholds), list(thresholds.values()))
ax.set_xlabel("threshold impact velocity [in/s]")

# %%
# One number: the largest peak force (at 5000 in/s) against eq (4).
summary = json.loads((out / "summary.json").read_text())
ball = PROJECTILES["rubber-1/2in"]
V = 5000 * 0.0254
expected = 4.25 * ball.mass * V**2 / (2 * ball.diameter)
peak = summary["statistics"]["peak_force_N"]["max"]
assert abs(peak / expected - 1) < 0.01, (peak, expected)
