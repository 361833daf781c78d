"""
A dent in a metal skin: an impulse far past elastic
===================================================

A bay of Al 2024-T3 skin (the catalogue's metal), 2 mm thick, between two stiff frames 200 mm apart and long in the
other direction: a strip in cylindrical bending, its edges clamped and held in their plane. An impulse sets all of it
moving at 120 m/s (a blast's, or a broad soft slab's, delivered faster than the skin can respond). The kinetic energy
is some twenty times what the skin's membrane can hold elastically, and the deflection grows to fifteen thicknesses:
the skin no longer bends, it stretches, as a plastic string.

Checked against that string (rigid-perfectly-plastic, derived in ``tests/_support/rigid_plastic.py``): hinges run in
from the frames at c = √(N_0/(ρh)), N_0 = (2/√3)·σ_y·h the plane-strain yield force, the middle flies flat at the
impulse's speed until they meet at t_f = L/(2c), where the whole strip stops as a triangle of depth W_f = V_0·L/(2c).
The catalogue's metal hardens (its linear hardening an engineering estimate), so the string is bracketed: W_f with the
initial yield stress above, W_f with the flow stress at the string's strain ½(2W/L)² below, less half a thickness for
the bending the string leaves out. N. Jones's closed forms for impulsively loaded plates (*Structural Impact*), the
published check, were sought and not retrieved; the string is not them. ``tests/test_rigid_plastic_limit.py`` makes the
same check with a perfectly plastic metal, with a struck mass, and against an independent elastic–plastic code.

The API's structures take a laminate and a force history; this example steps the plastic plate of the layer below
(``softimpact.fem``) from an initial velocity, as its tests do.
"""

# %%
# The metal as the catalogue holds it (``softimpact catalogue``; its values and sources in the metals table).
import math

import matplotlib.pyplot as plt
import numpy as np

import softimpact as si
from softimpact.fem.nonlinear import NonlinearNewmark
from softimpact.fem.plate import Plate, W
from softimpact.fem.plate_plastic import PlasticPlate
from softimpact.models.metals import metal
from softimpact.models.plate_laminate import isotropic_section

# sphinx_gallery_thumbnail_path = "_static/thumbnails/12_dent_in_a_metal_skin.png"
row = next(r for r in si.catalogue().metals.rows if r[0] == "Al 2024-T3")
print(row[0], "|", row[-1])
al = metal("Al 2024-T3")
E, nu, rho = al.youngs_modulus, al.poisson_ratio, al.density
sy, H = al.yield_stress, al.hardening.modulus  # Pa: initial yield, linear hardening

# %%
# The strip: half its span (mid-span a symmetry edge, the frame clamped), one MITC9 element across a 5-mm width
# with symmetry edges (plane strain), twelve along; von Kármán kinematics, edges immovable in their plane; the
# section integrated through the thickness. Every free transverse DOF starts at 120 m/s; 2-µs steps to three
# times the string's stop time.
span, h, width, v0 = 0.2, 2e-3, 0.005, 120.0  # m, m, m, m/s
plate = Plate(span / 2, width, 12, 1, isotropic_section(E, nu, rho, h), ("symmetry", "clamped", "symmetry", "symmetry"), element="mitc9")
skin = PlasticPlate(plate, al.plasticity(), kinematics="von-karman", in_plane="immovable")
full = np.zeros(skin.fe.basis.N)
full[skin.fe.basis.nodal_dofs[W]] = v0
N0 = 2 / math.sqrt(3) * sy * h  # N/m
c = math.sqrt(N0 / (rho * h))
t_f = span / (2 * c)
xs = np.linspace(0.0, span / 2, 25)
rows = np.array([skin.deflection(x, 0.0) for x in xs])  # the profile; rows[0] the centre
dt = 2e-6
run = NonlinearNewmark(skin, dt, rtol=1e-8, max_iterations=40).run(None, int(round(3 * t_f / dt)), rows=rows, v0=full[skin.free])
centre = run.outputs[0]
peak = int(np.argmax(centre))

# %%
# The string's bracket and the one number: the peak centre deflection.
W_f = v0 * span / (2 * c)  # initial yield stress
strain = 0.5 * (2 * W_f / span) ** 2  # the string's membrane strain, uniform along it
N_flow = 2 / math.sqrt(3) * (sy + H * 2 / math.sqrt(3) * strain) * h  # its plastic strain (2/√3)·ε, all of it
W_flow = v0 * span / 2 * math.sqrt(rho * h / N_flow)
low, high = W_flow - h / 2, W_f
print(
    f"peak centre deflection {centre[peak] * 1e3:.1f} mm at {run.t[peak] / t_f:.2f} t_f; the string: {W_flow * 1e3:.1f} to {W_f * 1e3:.1f} mm at t_f = {t_f * 1e6:.0f} us"
)
print(f"then it rings elastically about {centre[run.t > run.t[-1] - t_f].mean() * 1e3:.1f} mm, near the dent it comes to rest in")
assert low <= centre[peak] <= high, (low, centre[peak], high)

# %%
# The centre against the string's (flat, at V_0, until the hinges meet), and the shape at the peak against its
# triangle: the elastic–plastic skin rounds the hinges the string has, then rings elastically about its dent.
fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
left.plot(run.t * 1e6, centre * 1e3, label="plastic plate (Al 2024-T3)")
t = np.linspace(0.0, run.t[-1], 200)
left.plot(t * 1e6, np.minimum(v0 * t, W_f) * 1e3, "--", label="rigid-plastic string (σ_y)")
left.axhspan(low * 1e3, high * 1e3, color="0.85", label="string's bracket (hardening, bending)")
left.set_xlabel("time [µs]")
left.set_ylabel("centre deflection [mm]")
left.legend(loc="lower right")
right.plot(
    np.concatenate([-xs[::-1], xs]) * 1e3,
    np.concatenate([run.outputs[::-1, peak], run.outputs[:, peak]]) * 1e3,
    label=f"at the peak, {run.t[peak] * 1e6:.0f} µs",
)
right.plot([-span / 2 * 1e3, 0.0, span / 2 * 1e3], [0.0, W_f * 1e3, 0.0], "--", label="the string's triangle")
right.set_xlabel("x [mm]")
right.set_ylabel("deflection [mm]")
right.legend(loc="lower center")
fig.suptitle("120 m/s on a 2-mm Al 2024-T3 skin bay, 200 mm between frames")
fig.tight_layout()
