"""How the hail map's FTE trend in h/D depends on the panel's size and supports (which were not retrieved).

The report's hail map (``softimpact.app.paper.hail``) runs Rhymer's three thicknesses on a 300-mm simply supported
panel, a choice. This script runs the same map (the catalogue's ice, Olsson's onset, the report's meshes and
velocity range) on other panels, changing only the side and the supports of the base case, and prints per panel the
R² of FTE's linear fit in h/D, the FTE of each row and its deflection over thickness at V*. Usage:

    python benchmarks/hail_panel_sensitivity.py                    # the linear panels of the table in docs/validation-hail.md
    python benchmarks/hail_panel_sensitivity.py 150 clamped vk     # one panel, von Karman (the full plate), from its linear map
    python benchmarks/hail_panel_sensitivity.py 300 simply-supported linear sun2015   # the report's panel, Sun-fitted strength

About 20-40 s of CPU a linear panel.
"""

import functools
import math
import sys
import warnings

from softimpact.app.paper import hail as H
from softimpact.models.projectiles import PowerLawStrength, projectile_material
from softimpact.studies.hail import ONSET, CatalogueIce, fte_fit, hail_map

LO = 1.0  # m/s: below the report's 5 m/s floor, which the stiff panels' thinnest rows reach (their thresholds would be flagged there)
# the strength fitted to Sun et al. 2015's peaks (benchmarks/ice_vs_sun2015.py), on the catalogue's envelope
SUN2015_FIT = PowerLawStrength(0.619e6, 0.359, projectile_material("ice").strength.rate_range, 1.0, "fitted to Sun et al. 2015 (ice_vs_sun2015.py)")
PANELS = ((300, "simply-supported"), (300, "clamped"), (200, "clamped"), (150, "simply-supported"), (150, "clamped"))


def target_of(side_mm: float, support: str):
    """The report's ``panel_target`` with the panel's side [mm] and its four edges' support changed."""
    return functools.partial(H.panel_target, side=side_mm * 1e-3, support=support)


def run(side: float, support: str, kinematics: str = "linear", strength: str = "catalogue") -> None:
    common = dict(duration=H.HAIL_DURATION, lo=LO, hi=H.HAIL_RANGE[1], indices=(ONSET,))
    ice = CatalogueIce(strength=SUN2015_FIT if strength == "sun2015" else None)
    rows = hail_map(ice, target_of(side, support), meshes=H.HAIL_MESHES, **common)
    if kinematics == "vk":  # the report's von Karman meshes, the full plate stepped (its secant steps from the linear V*)
        rows = hail_map(ice, target_of(side, support), meshes=H.VK_MESHES, kinematics="von-karman", guesses=rows, **common)
    fit = fte_fit(rows)
    print(f"{side:g} mm, {support}, {'von Karman' if kinematics == 'vk' else 'linear'}: R2 = {fit.r2:.3f}, FTE = {fit.slope:.1f}*h/D + {fit.intercept:.2f} J")
    for r in rows:
        w_h = r.validity.get("deflection_over_thickness", math.nan)
        radius = r.validity.get("contact_radius_over_projectile_radius", math.nan) * r.diameter / 2
        print(
            f"   h {r.thickness * 1e3:.2f} mm, D {r.diameter * 1e3:.1f} mm: V* {r.velocity:6.2f} m/s, FTE {r.fte:6.2f} J, w/h {w_h:.2f}, "
            f"GCI {r.gci / r.velocity:.1%}, largest crushed radius {radius * 1e3:.2f} mm"
        )


def main() -> None:
    warnings.simplefilter("ignore")  # the validity warnings: each row's flags are in its validity
    if len(sys.argv) > 1:
        run(float(sys.argv[1]), sys.argv[2], *sys.argv[3:5])
        return
    for side, support in PANELS:
        run(side, support)


if __name__ == "__main__":
    main()
