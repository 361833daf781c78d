"""
Coupled impact on your own plate
================================

Write your own plate case and an impact case that strikes it: a 1/2-in steel ball at
100 in/s on the centre of a clamped 6 × 6 in [0/90]4s T300/934 plate, coupled through
Hertz's law (Sun's laminate form). The force is not prescribed: the stepper finds it
from the ball, the contact law and the plate together.

Checked against conservation of momentum: the impulse the plate gave the ball equals the
ball's change of momentum, m·(V − v_rebound), with the mass of a steel sphere
ρ·πd³/6 written out here (the catalogue's steel, ρ = 0.283 lb/in³), to 0.1 %.
"""

# %%
# The two case files, as a user would write them (units in the values).
import json
import math
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from click.testing import CliRunner

from softimpact.cli import main

work = Path(tempfile.mkdtemp())
(work / "my-plate.toml").write_text("""
title = "Clamped 6 x 6 in [0/90]4s plate"
[plate]
length = "6 in"
width = "6 in"
elements = [12, 12]
support = { x0 = "clamped", x1 = "clamped", y0 = "clamped", y1 = "clamped" }
[plate.laminate]
ply = "T300/934"
layup = "[0/90]4s"
[load]                      # the impact point; the history is ignored by an impact case
position = ["3 in", "3 in"]
contact_radius = "0.1 in"
history = { shape = "skewed", peak_force = "1 lbf", time_of_peak = "10 us", duration = "100 us" }
[solver]
time_step = "0.5 us"
duration = "300 us"
[[gauges]]
name = "centre"
position = ["3.5 in", "3 in"]
""")
(work / "my-impact.toml").write_text("""
title = "Steel ball on my plate"
[target]
case = "my-plate.toml"
[impactor]
material = "steel"
diameter = "0.5 in"
velocity = "100 in/s"
[contact]
law = "hertz"
[solver]
time_step = "0.5 us"
duration = "300 us"
""")

# %%
# Run it (``softimpact impact my-impact.toml --out ...``).
out = work / "out"
run = CliRunner().invoke(main, ["impact", str(work / "my-impact.toml"), "--out", str(out), "--no-figures"])
assert run.exit_code == 0, run.output
print(run.output)
summary = json.loads((out / "summary.json").read_text())
data = np.genfromtxt(out / "history.csv", delimiter=",", names=True)

fig, ax = plt.subplots()
ax.plot(data["time_s"] * 1e6, data["contact_force_N"])
ax.set_xlabel("time [µs]")
ax.set_ylabel("contact force [N]")

# %%
# One number: the impulse of the first contact against m·(V − v_rebound).
d, V = 0.5 * 0.0254, 100 * 0.0254
rho = 0.283 * 0.45359237 / 0.0254**3  # lb/in³ → kg/m³
m = rho * math.pi * d**3 / 6
expected = m * (V - summary["rebound_velocity_m_s"])
assert abs(summary["impulse_N_s"] / expected - 1) < 0.001, (summary["impulse_N_s"], expected)
