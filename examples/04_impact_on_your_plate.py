"""
Coupled impact on your own plate
================================

Describe your own plate and strike it: a 1/2-in steel ball at 100 in/s on the centre of a
clamped 6 × 6 in [0/90]4s T300/934 plate, coupled through Hertz's law (Sun's laminate
form). The force is not prescribed: the stepper finds it from the ball, the contact law
and the plate together.

Checked against conservation of momentum: the impulse the plate gave the ball equals the
ball's change of momentum, m·(V − v_rebound), with the mass of a steel sphere
ρ·πd³/6 written out here (the catalogue's steel, ρ = 0.283 lb/in³), to 0.1 %.
"""

# %%
# The plate and the ball as objects, units in the values. The same run from files is a
# plate case (``[plate]``, ``[plate.laminate]``, ``[load] position``) and an impact case whose
# ``[target] case`` names it: ``si.run(si.load("my-impact.toml"))``, or
# ``softimpact impact my-impact.toml --out out``.
import math

import softimpact as si

plate = si.Plate(
    length="6 in",
    width="6 in",
    laminate=si.Laminate("T300/934", "[0/90]4s"),
    elements=(12, 12),
    support="clamped",  # or one per edge: {"x0": "clamped", "x1": "free", "y0": ..., "y1": ...}
)
ball = si.Sphere("steel", "0.5 in", velocity="100 in/s")
res = si.impact(
    plate,
    at=("3 in", "3 in"),
    impactor=ball,
    law="hertz",
    time_step="0.5 us",
    duration="300 us",
    gauges={"centre": ("3.5 in", "3 in")},
    units="SI",  # the display units of its plots and files' figures, as printed below (default: lbf, in, µs)
)
print(f"peak force {res.peak_force:.1f} N, contact {res.contact_duration * 1e6:.1f} us, impulse {res.impulse:.3e} N s")

# %%
# The contact force, in N as printed above (``units="SI"``); ``res.write("out")`` would
# write history.csv, summary.json, the figures and manifest.json as ``softimpact impact`` does,
# and ``res.write_fields("out/plate.xdmf")`` the deflection over time for ParaView.
ax = res.plot()

# %%
# One number: the impulse of the first contact against m·(V − v_rebound). The rebound
# velocity is a number of the coupled result (``res.result``; summary.json's
# ``rebound_velocity_m_s``).
d, V = 0.5 * 0.0254, 100 * 0.0254
rho = 0.283 * 0.45359237 / 0.0254**3  # lb/in³ → kg/m³
m = rho * math.pi * d**3 / 6
expected = m * (V - res.result.rebound_velocity)
assert abs(res.impulse / expected - 1) < 0.001, (res.impulse, expected)
