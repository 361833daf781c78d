"""
Reduce a lab-file series and fit the scaling law
================================================

The built-in series ``paper-rubber-series`` holds bar strain records of rubber balls
(synthetic: made by the bar FE from the paper's Table I constants, with noise). ``si.fit``
reduces each record to a force history (incident wave separated from its reflections) and
fits the scaling constants α1–α4 of eqs (4)–(7) (``softimpact fit paper-rubber-series``).

Checked against the paper: α1 of the 3/8-in ball is 4.00 in Table I; the fit recovers it
within 2 %.
"""

# %%
import matplotlib.pyplot as plt

import softimpact as si

# sphinx_gallery_thumbnail_path = "_static/thumbnails/02_reduce_and_fit.png"
res = si.fit("paper-rubber-series", figures=False)
print(res.line)

# %%
# ``scaling.json`` holds the constants per ball size and pooled, with 95 % intervals; the
# result reads the command's files without writing them (``res.write(dir)`` does).
scaling = res.json("scaling.json")
for group, fit in scaling["groups"].items():
    print(group, {a: round(fit[a]["value"], 3) for a in ("alpha1", "alpha2", "alpha3", "alpha4")})

# %%
# Eq (4): each test's F0 against mV²/(2d), and the fitted line of slope α1 per ball size.
# ``res.table("tests.csv")`` is the per-test table as a pandas DataFrame (SI columns).
tests = res.table("tests.csv")
tests = tests[tests["status"] == "ok"]
fig, ax = plt.subplots()
for group, fit in scaling["groups"].items():
    rows = tests[abs(tests["diameter_m"] / 0.0254 - float(group.split()[0])) < 1e-6]
    x = rows["mass_kg"] * rows["velocity_m_s"] ** 2 / (2 * rows["diameter_m"])
    ax.plot(x, rows["peak_force_N"], "o", label=f"{group} ball")
    ax.plot([0, x.max()], [0, fit["alpha1"]["value"] * x.max()], "-", color=ax.lines[-1].get_color())
ax.set_xlabel("mV²/(2d) [N]")
ax.set_ylabel("F0 [N]")
ax.legend()

# %%
# One number: α1 of the 3/8-in ball against Table I.
alpha1 = scaling["groups"]["0.375 in"]["alpha1"]["value"]
assert abs(alpha1 / 4.00 - 1) < 0.02, alpha1
