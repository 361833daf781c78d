"""Two small case files shared by the field-output and API tests: a 40 × 4 Q4 beam and an 8 × 8 MITC9 plate
(T300/934 [90/0]5s, the paper's laminate), each under a prescribed eq-15 pulse."""

BEAM = """units = "in-lbf-s"
[beam]
length = "6 in"
width = "1 in"
elements = [40, 4]
[beam.laminate]
ply = "T300/934"
layup = "[90/0]5s"
[load]
position = "3 in"
contact_radius = "0.25 in"
history = { shape = "skewed", peak_force = "44 lbf", time_of_peak = "30 us", duration = "355 us" }
[solver]
time_step = "1 us"
duration = "450 us"
[[gauges]]
name = "g1"
position = "2 in"
"""

PLATE = """units = "in-lbf-s"
[plate]
length = "8 in"
width = "8 in"
elements = [8, 8]
support = { x0 = "simply-supported", x1 = "simply-supported", y0 = "simply-supported", y1 = "simply-supported" }
[plate.laminate]
ply = "T300/934"
layup = "[90/0]5s"
[load]
position = ["4 in", "4 in"]
contact_radius = "0.25 in"
grow = false
history = { shape = "skewed", peak_force = "100 lbf", time_of_peak = "20 us", duration = "250 us" }
[solver]
time_step = "1 us"
duration = "300 us"
"""
