"""
Hail and a bird substitute on a plate
=====================================

Soft projectiles that do not bounce: a 38.1-mm hailstone falling at its terminal velocity and a
25-mm gelatin sphere (the bird substitute) at 50 m/s, each on the centre of a clamped
200 × 200 mm quasi-isotropic [45/0/-45/90]4s IM7/8552 plate (4.19 mm, within the 1.56-4.66 mm
panels of Rhymer's hail tests). Ice crushes (``law="crushing"``: the crushed section times the
crushing strength plus the momentum flux of the crushed ice); gelatin flows (``law="hydrodynamic"``:
Wilbeck's shock, release and steady flow). Both laws come from the sphere's material.

Checked against Wilbeck's hydrodynamic impact (Wilbeck 1978, AFML-TR-77-134): a fluid-like
projectile is brought to rest on a rigid target, so the impulse is its whole momentum m·V, with
the mass ρ·πd³/6 of a sphere of Wilbeck's density ρ = 950 kg/m³ written out here. The plate gives
a little (the flowed gelatin keeps a little of the plate's velocity): within 3 %.
"""

# %%
# The plate and the two spheres. The same runs from files: the built-in impact cases
# ``hail-plate-38mm`` (its ``[impactor] threat = { hail = "38.1 mm" }`` sets the size, the ice
# mass and the terminal velocity) and ``gelatin-plate``, ``softimpact impact hail-plate-38mm --out out``.
import math
import warnings

import softimpact as si
from softimpact.models.threats import hail_terminal_velocity

plate = si.Plate(length="200 mm", width="200 mm", laminate=si.Laminate("IM7/8552", "[45/0/-45/90]4s"), elements=(12, 12), support="clamped")
centre = ("100 mm", "100 mm")
hail = si.Sphere("ice", "38.1 mm", velocity=f"{hail_terminal_velocity(0.0381):.4f} m/s")
gel = si.Sphere("gelatin", "25 mm", velocity="50 m/s")

# %%
# The hailstone. Jones's (1997) strength law of ice was measured at 0.1-10 1/s; the crush runs at
# V/d ≈ 700 1/s, and the run says so (a warning, and in the result's validity).
with warnings.catch_warnings():
    warnings.simplefilter("ignore")  # the strength's extrapolation, said above
    ice = si.impact(plate, at=centre, impactor=hail, law="crushing", time_step="1 us", duration="800 us", units="SI")
print(f"hail: peak force {ice.peak_force:.0f} N at {ice.time_of_peak * 1e6:.0f} us, impulse/(mV) {ice.impulse / (hail.mass * hail.velocity):.3f}")

# %%
# The gelatin sphere: its force rises with the flowed section, peaks near half the transit time
# d/V and ends near d/V.
res = si.impact(plate, at=centre, impactor=gel, law="hydrodynamic", time_step="1 us", duration="800 us", units="SI")
print(f"gelatin: peak force {res.peak_force:.0f} N, contact {res.contact_duration * 1e6:.0f} us (d/V = {0.025 / 50 * 1e6:.0f} us)")
ax = res.plot()

# %%
# One number: the gelatin's impulse over its momentum m·V, m = ρ·πd³/6 (Wilbeck's ρ).
m = 950.0 * math.pi * 0.025**3 / 6
ratio = res.impulse / (m * 50.0)
print(f"impulse/(mV) = {ratio:.4f}")
assert abs(ratio - 1) < 0.03, ratio
