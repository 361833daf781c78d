"""The stacked cohesive plate's quasi-static delamination onset against Olsson's F_d, on two meshes and two plate sizes.

The computation of tests/test_delamination_onset.py (its module docstring says what and why): an isotropic plate
(E 70 GPa, ν 0.3, h 4 mm) split at its mid-plane, the interface fully damaged over a disc about a central point load,
the compliance differenced as the disc grows by one element, F_c = sqrt(2·G_IIc/(dC/dA)) against F_d. Prints a/h and
F_c/F_d for a quarter of a simply supported plate of side 200 mm (16 × 16 and 24 × 24 MITC9) and 400 mm (24 × 24).
Takes a few minutes on a 2-core machine (the 24 × 24 runs).

Usage: python benchmarks/onset_olsson.py
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parents[1] / "tests"))

from test_delamination_onset import onset_ratios  # noqa: E402  (the test's own computation)


def main():
    for side, n in ((0.2, 16), (0.2, 24), (0.4, 24)):
        a_over_h, ratio = onset_ratios(half=side / 2, n=n, discs=14 if n == 24 else 8)
        print(f"plate {side * 1e3:.0f} mm, quarter {n} x {n} MITC9:")
        for a, r in zip(a_over_h, ratio):
            print(f"   a/h {a:6.2f}   F_c/F_d {r:.3f}")


if __name__ == "__main__":
    main()
