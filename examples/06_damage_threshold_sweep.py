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
# A sweep is described by a spec file: the API takes its path, as ``softimpact sweep spec.toml
# --workers 0 --out out`` does (there is no dict form of a spec). ``out`` holds the
# checkpoints, so the same call resumes.
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt

import softimpact as si

# sphinx_gallery_thumbnail_path = "_static/thumbnails/06_damage_threshold_sweep.png"
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
res = si.sweep(work / "spec.toml", out=work / "out", workers=0, figures=False)
print(res.line)

# %%
# The answer in one figure: each damage index against the impact velocity (``runs.parquet``, one
# row per run), the line where it reaches 1, and the threshold velocity the sweep interpolates
# there (``thresholds.csv``). Open markers: runs outside the models' validity (``validity_flags``;
# here the beam deflects past w/h = 0.5, where linear theory stiffens too little).
import io  # noqa: E402

import pandas as pd  # noqa: E402

runs = pd.read_parquet(io.BytesIO(res.outcome.files["runs.parquet"])).sort_values("load.history.velocity")
thresholds = res.table("thresholds.csv").set_index("index")["threshold_velocity_median_m_s"] / 0.0254
print({k: f"{v:.0f} in/s" for k, v in thresholds.items()})
v = runs["load.history.velocity"] / 0.0254
outside = runs["validity_flags"].astype(str).str.len() > 0
fig, ax = plt.subplots()
for k, (index, label) in enumerate((("tsai_wu", "Tsai-Wu"), ("max_strain", "maximum strain"))):
    y = runs[f"damage.{index}"]
    ax.plot(v, y, "-", color=f"C{k}", label=f"{label}: threshold {thresholds[index]:.0f} in/s")
    ax.plot(v[~outside], y[~outside], "o", color=f"C{k}")
    ax.plot(v[outside], y[outside], "o", mfc="none", color=f"C{k}")
    ax.axvline(thresholds[index], color=f"C{k}", ls=":", lw=1)
ax.axhline(1.0, color="k", lw=0.8)
ax.set_xlabel("impact velocity [in/s]")
ax.set_ylabel("damage index (1: first-ply failure)")
ax.set_title("1/2-in rubber ball on the long beam: where each index reaches 1")
ax.legend()

# %%
# One number: the largest peak force (at 5000 in/s) against eq (4). The ball's mass and
# diameter come from the projectile catalogue (the API has no catalogue view: the model layer).
from softimpact.models.empirical import PROJECTILES  # noqa: E402

ball = PROJECTILES["rubber-1/2in"]
V = 5000 * 0.0254
expected = 4.25 * ball.mass * V**2 / (2 * ball.diameter)
peak = res.summary()["statistics"]["peak_force_N"]["max"]
assert abs(peak / expected - 1) < 0.01, (peak, expected)
