"""The report's hail map of Olsson's onset on von Kármán panels, two ways, in one process: on the reduced plate at the
linear map's meshes (8 × 8 at 2 µs, coarse 4 × 4 at 4 µs; ``nonlinear_stepping="von-karman-rom"``) and, as the report
does, on the full plate at 6 × 6 at 3 µs (coarse 3 × 3 at 6 µs). Prints each map's CPU time and each row's V* side by side.
The linear map (the guesses of both) is computed first. Takes a few minutes on a 2-core machine.

Usage: python benchmarks/bench_hail_rom_map.py
"""

import time
import warnings

from softimpact.app.paper import hail as H
from softimpact.studies.hail import CatalogueIce, hail_map
from softimpact.studies.thresholds import ONSET


def main():
    warnings.simplefilter("ignore")  # the rows' validity flags (w/h, the strength's extrapolation): in the rows, not the point here
    t0 = time.process_time()
    lin = H._rows()
    t1 = time.process_time()
    print("linear map CPU", t1 - t0, flush=True)
    rom = hail_map(
        CatalogueIce(),
        H.panel_target,
        meshes=H.HAIL_MESHES,
        duration=H.HAIL_DURATION,
        lo=H.HAIL_RANGE[0],
        hi=H.HAIL_RANGE[1],
        indices=(ONSET,),
        kinematics="von-karman",
        guesses=lin,
        nonlinear_stepping="von-karman-rom",
    )
    t2 = time.process_time()
    print("ROM VK map on the linear mesh CPU", t2 - t1, flush=True)
    full = H._vk_rows()
    t3 = time.process_time()
    print("full VK map (6x6) CPU", t3 - t2, flush=True)
    for r, f in zip(rom, full):
        print(
            f"h {r.thickness * 1e3:.2f} D {r.diameter * 1e3:.1f}: ROM(8x8) V* {r.velocity:.3f}  full(6x6) V* {f.velocity:.3f}  ratio {r.velocity / f.velocity:.4f}"
        )


if __name__ == "__main__":
    main()
