"""Can bar records identify a gelatin sphere's Hugoniot (c0, k)? How much its force history moves when they change.

The hydrodynamic law (models/hydrodynamic_law.py) carries the Hugoniot only in the shock phase, over a crushed
depth s_c = d·V²/(4·U_s²) (a few hundredths to a few tenths of a per cent of d at 50-150 m/s) and its release; the
rest of the pulse is the steady flow ρ·ṡ²·A, which has no free parameter. This script integrates the law on a
rigid target (``rigid_target_pulse``) for a 50.8-mm sphere at 50 and 105 m/s and a 150-mm one at 150 m/s, changes
c0 and k by 10 % each, and prints the change of the force history (its peak, and its L2 norm relative to the
pulse's), raw and after a 5-µs moving average (a bar record's bandwidth). The synthetic series' noise is about 1 % of
its peak. Usage: ``python benchmarks/gelatin_identifiability.py``.
"""

import dataclasses
import math
import warnings

import numpy as np

from softimpact.models.crushing_law import rigid_target_pulse
from softimpact.models.hydrodynamic_law import HydrodynamicLaw
from softimpact.models.projectiles import LinearHugoniot, projectile_material

CASES = ((0.0508, 50.0), (0.0508, 105.0), (0.15, 150.0))  # (d [m], V [m/s])
SAMPLES = 20001


def main() -> None:
    warnings.simplefilter("ignore")
    gel = projectile_material("gelatin")
    for d, V in CASES:
        m = gel.density * math.pi / 6.0 * d**3
        base = HydrodynamicLaw.of(gel, d, m, V)
        t = np.linspace(0.0, 1.2 * d / V, SAMPLES)

        def history(law, m=m, V=V, t=t):
            p = rigid_target_pulse(law, m, V, samples=SAMPLES)
            return np.interp(t, p.time, p.force, right=0.0)

        f0 = history(base)
        width = max(int(5e-6 / (t[1] - t[0])), 1)
        kernel = np.ones(width) / width
        h = base.hugoniot
        us = h.c0 + h.k * V
        print(f"{d * 1e3:.1f} mm at {V:g} m/s: shock depth s_c = {V**2 / (4 * us**2) * 100:.3f} % of d, flow peak {f0.max() / 1e3:.2f} kN")
        for name, hug in (("c0 + 10 %", LinearHugoniot(1.1 * h.c0, h.k)), ("k + 10 %", LinearHugoniot(h.c0, 1.1 * h.k))):
            f1 = history(dataclasses.replace(base, hugoniot=hug))
            a, b = np.convolve(f0, kernel, "same"), np.convolve(f1, kernel, "same")
            print(
                f"   {name}: peak {f1.max() / f0.max() - 1:+.3%}, L2 {np.linalg.norm(f1 - f0) / np.linalg.norm(f0):.1e}; "
                f"after 5 us: peak {b.max() / a.max() - 1:+.3%}, L2 {np.linalg.norm(b - a) / np.linalg.norm(a):.1e}"
            )


if __name__ == "__main__":
    main()
