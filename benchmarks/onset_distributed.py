"""Delamination onset under a load spread over a disc (crushed hail): F_c/F_d against a/h and the loaded radius r/h.

The computation of tests/test_onset_distributed.py (its module docstring says what and why): the stacked cohesive
plate of tests/test_delamination_onset.py with the central point load replaced by the cosine contact pressure over a
disc of radius r on the top sublaminate, the work-conjugate compliance differenced as the delaminated disc grows by
one element, F_c = sqrt(2·G_IIc/(dC/dA)) against Olsson's point-load F_d. Prints a table (rows a/h, columns r/h) for a
quarter of the simply supported 200-mm plate (16 × 16 MITC9), then r/h = 0 and 2 on 24 × 24 as a mesh check. Entries
with a < r (the delamination inside the loaded disc) are marked *. Takes about seven minutes on a 2-core machine.

Usage: python benchmarks/onset_distributed.py
"""

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parents[1] / "tests"))

from test_onset_distributed import H, distributed_onset  # noqa: E402  (the test's own computation)

R_OVER_H = (0.0, 0.5, 1.0, 2.0, 3.0, 5.0)


def table(n: int, r_over_h, discs: int) -> None:
    start = time.perf_counter()
    runs = [distributed_onset(rh * H, half=0.1, n=n, discs=discs) for rh in r_over_h]
    a_over_h = runs[0][0]
    print(f"plate 200 mm, quarter {n} x {n} MITC9: F_c/F_d (* where a < r)  [{time.perf_counter() - start:.0f} s]")
    print("   a/h  " + "".join(f"  r/h {rh:<4g}" for rh in r_over_h))
    for i, a in enumerate(a_over_h):
        print(f"{a:6.2f}  " + "".join(f"  {run[1][i]:7.3f}{'*' if a < rh else ' '}  " for rh, run in zip(r_over_h, runs)))


def main():
    table(16, R_OVER_H, 12)
    table(24, (0.0, 2.0), 14)


if __name__ == "__main__":
    main()
