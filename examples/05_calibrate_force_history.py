"""
Calibrate a force history from measured strains
===============================================

The paper's inverse problem (Tables II, III; Figs 23–25): find the eq-(15) force history
(F0, t_F0, T) that makes the long beam's computed gauge strains match measured ones.
The built-in series ``paper-long-calibration`` holds strains measured on the long beam
at four impact velocities (synthetic: computed by a finer model from the Table II
histories, with 1.5 % noise and gauge offsets).

Checked against the paper: at 1166 in/s Table II gives F0 = 44 lbf; the calibration
recovers it within 2 %.
"""

# %%
# ``si.calibrate`` is ``softimpact calibrate paper-long-calibration``: the result holds the
# command's files by name (``res.write("out")`` writes them with manifest.json).
import matplotlib.pyplot as plt

import softimpact as si

# sphinx_gallery_thumbnail_path = "_static/thumbnails/05_calibrate_force_history.png"
res = si.calibrate("paper-long-calibration", figures=False)
print(res.line)

# %%
# ``tables.csv``: the calibrated history of each test, SI (Table III's layout), as a DataFrame.
tables = res.table("tables.csv")
for _, r in tables.iterrows():
    print(r["test"], f"F0 = {r['peak_force_N'] / 4.4482216:.1f} lbf", f"T = {r['duration_s'] * 1e6:.0f} us")

# %%
# The calibrated history at 1166 in/s, and the computed gauge strain against the measured one.
h = res.table("history-long-V1166.csv")
fig, (top, bottom) = plt.subplots(2, 1, sharex=True)
top.plot(h["time_s"] * 1e6, h["force_N"], label="calibrated (eq 15)")
top.plot(h["time_s"] * 1e6, h["deconvolved_force_N"], lw=0.8, label="deconvolved")
top.set_ylabel("force [N]")
top.legend()
bottom.plot(h["time_s"] * 1e6, h["measured_g1"] * 1e6, lw=0.8, label="measured g1")
bottom.plot(h["time_s"] * 1e6, h["computed_g1"] * 1e6, label="computed g1")
bottom.set_xlabel("time [µs]")
bottom.set_ylabel("strain [µε]")
bottom.legend()

# %%
# One number: F0 at 1166 in/s against Table II (44 lbf).
F0 = tables["peak_force_N"].iloc[0] / 4.4482216152605  # N → lbf
assert abs(F0 / 44 - 1) < 0.02, F0
