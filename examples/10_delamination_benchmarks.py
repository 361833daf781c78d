"""
Delamination benchmarks on the stacked plate
============================================

Krueger's NASA double cantilever beam (NASA/TM-2008-215123, 2008): a [0]24 T300/1076 strip 150 mm long, 25 mm wide and
3 mm thick, pre-cracked over 30 mm at its mid-plane, its arms pulled apart at the cracked end. Modelled with what an
impact run's cohesive plate is made of (``softimpact.fem.cohesive_plate``): two FSDT sublaminates tied by the bilinear
cohesive law with nodal integration, the pre-crack as damage 1, half the width by symmetry. The quasi-static path
(``softimpact.fem.quasistatic``, opening controlled, the damage converged with the equilibrium in every increment) goes
through the peak and on into propagation; the load against the opening is drawn with the benchmark's critical points
(δ_crit, P_crit) in the opening's range, which lie on its propagation branch, and the crack-closure load at mid-width (linear
fracture mechanics through the same interface: the benchmark's own definition).

Checked: the cohesive peak at a0 = 30 mm against the benchmark's 60.7 N (Krueger 2008, as digitised, ±1 N), within 3 %.
No command line does this: the specimens verify the plate's interface from Python (``benchmarks/krueger.py`` prints
the whole DCB and MMB comparison, docs/delamination.md).
"""

# %%
# The laminate and the law: the penalty K = 50·E33/t of Turon et al. 2007 (Eq. 7, t the arm), a strength of 30 MPa whose
# process zone (about 1.2 mm) spans five 0.25-mm elements, G_Ic = 170.3 J/m².
import math

import matplotlib.pyplot as plt
import numpy as np

import softimpact as si
from softimpact.fem.plate_specimens import critical_load, dcb, release_rates
from softimpact.models.cohesive import BilinearCohesive
from softimpact.models.krueger import DCB_CRITICAL, DCB_OPENING, DCB_SPECIMEN

spec = DCB_SPECIMEN
laminate = si.Laminate(spec.ply, "[0]24")
print(f"{spec.ply.name}: [0]24, {laminate.stack.thickness * 1e3:.2f} mm")
law = BilinearCohesive(K=50 * spec.ply.E3 / spec.arm, N=30e6, S=30e6, GIc=spec.GIc, GIIc=spec.GIc, eta=spec.eta)


def specimen(a0, fine):
    return dcb(spec.ply, plies_per_arm=12, width=spec.width, length=spec.length, a0=a0, law=law, element=0.25e-3, fine=fine, coarse=12e-3)


# %%
# The path: to the elastic limit in one increment, on to 85 % of beam theory's estimate, then 2 % steps through the peak
# and on to an opening of 1.6 mm, past the benchmark's critical point at a = 31 mm.
EI = spec.ply.E1 * spec.width * spec.arm**3 / 12
estimate = math.sqrt(spec.width * EI * spec.GIc) / (spec.a0 + 3e-3)
model = specimen(spec.a0, (spec.a0, spec.a0 + 4e-3))
peak = critical_load(model, near=0.85 * estimate, step=0.02, until=1.60e-3)
opening, force = peak.path.displacement / model.share, peak.path.force
print(f"peak {peak.load:.2f} N at {peak.displacement * 1e3:.3f} mm; process zone {peak.zone * 1e3:.2f} mm at mid-width")

# %%
# Linear fracture mechanics through the same interface: the crack grown by 1 mm about 30 mm, G at mid-width by crack closure.
closure = release_rates(specimen(spec.a0 - 0.5e-3, (spec.a0 - 1e-3, spec.a0 + 1e-3)), 1e-3)
lefm = closure.critical_load(spec.GIc, spec.GIc, spec.eta, "middle")
print(f"crack closure at mid-width: {lefm:.2f} N")

# %%
# The load against the opening, with the benchmark's critical points (the opening twice the arm's δ_crit/2, as digitised).
near = [a for a in DCB_OPENING if DCB_OPENING[a] <= 1.05 * opening[-1]]
fig, ax = plt.subplots()
ax.plot(np.concatenate(([0.0], opening)) * 1e3, np.concatenate(([0.0], force)), "-", label="cohesive plate (fem.cohesive_plate)")
ax.plot([DCB_OPENING[a] * 1e3 for a in near], [DCB_CRITICAL[a] for a in near], "o", label="Krueger 2008, critical points")
ax.axhline(lefm, ls=":", color="grey", label="crack closure at mid-width, a = 30 mm")
ax.set_xlim(left=0)
ax.set_ylim(bottom=0)
ax.set_xlabel("load-point opening δ [mm]")
ax.set_ylabel("load P [N]")
ax.legend()

# %%
# One number: the cohesive peak at a0 = 30 mm against the benchmark's 60.7 N.
assert abs(peak.load / DCB_CRITICAL[30e-3] - 1) < 0.03, peak.load
