"""
The bar test of the paper (Figs 4–6)
====================================

A steel ball strikes the end of the instrumented aluminium bar (the built-in case
``paper-calibration``); the gauge at mid-length records the compressive wave.

Checked against one-dimensional wave theory: far from the ends, the strain of a wave in a
bar is ε = −F/(EA), so the gauge's peak strain equals the peak contact force over EA
(within 3 %: the Hermite rod's dispersion and the end cap's inertia).
"""

# %%
# Read the built-in case, take the end cap off, and run it (the Python layers the ``bar``
# command uses).
import matplotlib.pyplot as plt

from softimpact.input.bar_case import load_bar_case
from softimpact.workflows.bar_impact import simulate_impact, without_end_cap

problem, path = load_bar_case("paper-calibration")
problem = without_end_cap(problem)
result = simulate_impact(problem)
print(f"peak force {result.peak_force:.1f} N at {result.time_of_peak * 1e6:.1f} us, contact {result.contact_duration * 1e6:.1f} us")

# %%
# The gauge strain (tension positive) against the contact force (compression positive).
fig, ax = plt.subplots()
ax.plot(result.time * 1e6, result.force, label="contact force [N]")
ax.plot(result.time * 1e6, -result.strain[0] * problem.bar.material.youngs_modulus * problem.bar.area, "--", label=f"−EA·ε at {result.strain_names[0]} [N]")
ax.set_xlabel("time [µs]")
ax.legend()

# %%
# One number: the gauge's peak strain against −F_peak/(EA).
E, A = problem.bar.material.youngs_modulus, problem.bar.area
expected = -result.peak_force / (E * A)
assert abs(result.strain[0].min() / expected - 1) < 0.03, (result.strain[0].min(), expected)
