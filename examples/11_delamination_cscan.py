"""
A C-scan of a struck quasi-isotropic plate
==========================================

A 1/4-in steel ball at 50 m/s on a small simply supported IM7/8552 [45/0/-45/90]s plate (60 × 60 mm, 1.05 mm),
the three interfaces of the lower half (90/-45, -45/0, 0/45: where the bending shear of the plate peaks and
impact delaminations grow largest) cohesive, in a 25 × 25 mm near field of 2.5-mm MITC9 elements with Turon's
strengths for that size; one plate of the laminate beyond. What an ultrasonic C-scan would show: each interface's
delaminated region (damage 1) seen from the struck face, its area, the major axis of the ellipse with its second
moments and that axis's angle beside the fibres of the ply below the interface, and the projected envelope
(``softimpact impact`` writes the same as summary.json's ``damage.delamination_shapes`` and
delamination-cscan.png).

The classic observation these shapes are read against: an impact delamination is elongated along the fibres of the
ply below its interface (Aymerich, Dore & Priolo 2009, Compos. Sci. Technol. 69:1383). This model does not reproduce
it on this case: one interface of three delaminates, elongated across the fibres below it, and the run is not converged
in its 1-µs step (docs/delamination.md; the slow test ``tests/test_cscan_shape.py``). The example shows the outputs;
the shape it draws is not a validated prediction.

Checked: the interface code these runs are made of, against Krueger's NASA double cantilever beam
(NASA/TM-2008-215123: [0]24 T300/1076, a0 = 30 mm, critical load 60.7 N): the crack-closure load at mid-width
through the plate's own interface within 3 % (the measured +1.4 % is the benchmark's digitising and the plate's
width average, docs/delamination.md).
"""

# %%
# The plate, the ball and the interfaces, from Python objects: the package's plate problem split below plies 5, 6
# and 7 into four sublaminates tied by the bilinear law of the ply (Y_t, S12, G_IIc of the catalogue's IM7/8552; G_Ic
# 277 J/m², B-K's η 1.634 and the penalty 1.5e15 N/m³ as the built-in d7136-drop-weight case takes them).
import time

import matplotlib.pyplot as plt

import softimpact as si
from softimpact.fem.newmark import SolverSpec
from softimpact.models.cohesive import BilinearCohesive
from softimpact.models.contact_laws import HertzLaw
from softimpact.output.delamination_plots import draw_cscan
from softimpact.units import display
from softimpact.workflows.coupled import ImpactProblem
from softimpact.workflows.plate import PlateLoad, PlateProblem
from softimpact.workflows.plate.cohesive import CohesivePlateProblem

# sphinx_gallery_thumbnail_path = "_static/thumbnails/11_delamination_cscan.png"
L = 60e-3
laminate = si.Laminate("IM7/8552", "[45/0/-45/90]s")
plate = si.Plate(length="60 mm", width="60 mm", laminate=laminate, elements=(6, 6))
ball = si.Sphere("steel", "0.25 in", velocity="50 m/s")
ply = laminate.stack.ply
law = BilinearCohesive(K=1.5e15, N=ply.strength.Yt, S=ply.strength.S12, GIc=277.0, GIIc=ply.strength.GIIc, eta=1.634)
target = PlateProblem(plate.spec, PlateLoad((L / 2, L / 2), ball.diameter / 2, None), SolverSpec(1e-6, 100e-6), title="QI plate")
target = CohesivePlateProblem.of(target, (5, 6, 7), law, near_field=12.5e-3, element_size=2.5e-3, turon=True)
hertz = HertzLaw.sphere_on_laminate(ball.diameter / 2, ball.material, ply.E3)
problem = ImpactProblem(target, "(Python)", ball.impactor, ball.material, "hertz", hertz, "1/4-in ball on a QI plate")
print(f"Turon's strengths for 1.25-mm node spacing: {target.run_law().N / 1e6:.1f} MPa normal, {target.run_law().S / 1e6:.1f} MPa shear")

# %%
# The coupled run (100 steps of 1 µs; about 3 minutes of one core), then what a C-scan of it shows: on this run one
# interface of the three delaminates, elongated but not along the fibres of the ply below (docs/delamination.md).
start = time.process_time()
res = si.run(problem, figures=False, units="SI")
damage = res.run_summary["damage"]
print(f"{time.process_time() - start:.0f} s CPU; peak force {res.peak_force:.0f} N, {damage['peak_over_olsson']:.2f} × Olsson's F_d")
scan = res.model.cscan()
for i in scan.interfaces:
    if i.area > 0:
        print(
            f"{i.words}: {i.area * 1e6:6.1f} mm², {i.major_axis * 1e3:.1f} × {i.minor_axis * 1e3:.1f} mm, major axis at {i.orientation_deg:.0f}°, lower ply {i.lower_ply_deg:g}°"
        )
    else:
        print(f"{i.words}: no delamination (lower ply {i.lower_ply_deg:g}°)")
print(f"projected: {scan.projected_area * 1e6:.1f} mm²")

# %%
# The C-scan figure of the package (delamination-cscan.png of ``softimpact impact``), drawn on the near field.
c, h = L / 2, 15e-3
fig = draw_cscan(scan, display("SI", "length"), window=(c - h, c + h, c - h, c + h))

# %%
# One number: the interface these delaminations grow through, on Krueger's DCB. Two [0]12 arms of FSDT plates tied by
# the same bilinear law at the nodes (``softimpact.fem.plate_specimens``, half the width), the crack grown by 1 mm about
# a0 = 30 mm, the energy released at mid-width by crack closure (linear fracture mechanics through the plate's
# interface: the benchmark's own definition; half a second).
from softimpact.fem.plate_specimens import dcb, release_rates  # noqa: E402 - the check's own imports
from softimpact.models.krueger import DCB_CRITICAL, DCB_SPECIMEN  # noqa: E402

spec = DCB_SPECIMEN
dcb_law = BilinearCohesive(K=50 * spec.ply.E3 / spec.arm, N=30e6, S=30e6, GIc=spec.GIc, GIIc=spec.GIc, eta=spec.eta)
specimen = dcb(
    spec.ply,
    plies_per_arm=12,
    width=spec.width,
    length=spec.length,
    a0=spec.a0 - 0.5e-3,
    law=dcb_law,
    element=0.25e-3,
    fine=(spec.a0 - 1e-3, spec.a0 + 1e-3),
    coarse=12e-3,
)
P = release_rates(specimen, 1e-3).critical_load(spec.GIc, spec.GIc, spec.eta, "middle")
print(f"DCB, a = 30 mm: crack closure at mid-width {P:.2f} N against Krueger's {DCB_CRITICAL[30e-3]} N")
assert abs(P / DCB_CRITICAL[30e-3] - 1) < 0.03, P
plt.show()
