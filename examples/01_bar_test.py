"""
The bar test of the paper (Figs 4–6)
====================================

A 5/8-in steel ball at 62.1 in/s strikes the end of the instrumented 36-in aluminium bar of
the paper (the built-in case ``paper-calibration`` without its end cap); the gauge at
mid-length records the compressive wave.

Checked against one-dimensional wave theory: far from the ends, the strain of a wave in a
bar is ε = −F/(EA), so the gauge's peak strain equals the peak contact force over EA
(within 3 %: the Hermite rod's dispersion).
"""

# %%
# The bar, the ball and the run, from objects (``import softimpact as si``); quantities carry
# their units and are converted to SI once. ``si.run(si.load("paper-calibration"))`` runs the
# built-in case, end cap included (``softimpact bar paper-calibration``).

import softimpact as si

bar = si.Bar("Al 6061-T6", length="36 in", diameter="0.5 in", elements=39)
ball = si.Sphere("steel", "0.625 in", velocity="62.1 in/s")
res = si.impact(bar, impactor=ball, law="hertz", time_step="0.5 us", duration="400 us", gauges={"midpoint": "18 in"})
print(f"peak force {res.peak_force:.1f} N at {res.time_of_peak * 1e6:.1f} us, contact {res.contact_duration * 1e6:.1f} us")

# %%
# The gauge strain (tension positive) against the contact force (compression positive);
# ``res.problem`` holds every input in SI.
E, A = res.problem.bar.material.youngs_modulus, res.problem.bar.area
strain = res.strain["midpoint"]
ax = res.plot()  # the contact force [N] against time [µs]
ax.lines[0].set_label("contact force [N]")
ax.plot(res.time * 1e6, -strain * E * A, "--", label="−EA·ε at midpoint [N]")
ax.legend()

# %%
# One number: the gauge's peak strain against −F_peak/(EA).
expected = -res.peak_force / (E * A)
assert abs(strain.min() / expected - 1) < 0.03, (strain.min(), expected)
