"""Krueger's NASA delamination benchmarks: the specimens, their plies and the published critical points, SI.

Both reports define a benchmark by the virtual crack closure technique (VCCT, linear elastic fracture
mechanics) on models solved at a set of crack lengths: the critical load is where the energy release rate
reaches the toughness. Neither report could be read here; every number below is as quoted and digitised by
the ``saullocastro/panels`` validation notebooks (``notebooks/krueger2008_dcb.ipynb``,
``notebooks/krueger2012_mmb_benchmark.ipynb``), summarised with their caveats in the project's research notes
on issue 39.

- DCB (Krueger 2008, NASA/TM-2008-215123, "An approach to assess delamination propagation simulation
  capabilities in commercial finite element codes"): [0]24 T300/1076, B = 25 mm, 2h = 3 mm, 150 mm long,
  a0 = 30 mm, G_Ic = 170.3 J/m² (of T300/914C, the report's Fig. 2a). Critical loads at a = 30–40 mm from 3-D
  C3D8I models (0.25 mm at the front), read by eye from the report's Figs. 11 and 13, ±5 J/m² and ±1 N; they
  are the onset at **mid-width** (y/B = 0), where G is highest: a width-averaged model (a plate, a beam) is
  expected about sqrt(G_mid/Ḡ) = 1.026 above them (panels' estimate).
- MMB (Krueger 2012, NASA/CR-2012-217562, "Development and application of benchmark examples for mixed-mode
  I/II quasi-static delamination propagation predictions"): [0]24 IM7/8552, b = 25.4 mm, 2h = 4.5 mm,
  a0 = 25.4 mm, G_Ic = 0.212, G_IIc = 0.774 N/mm, B–K η = 2.1; 2-D plane-strain VCCT; lever lengths c for
  G_II/G_T = 0.2, 0.5, 0.8 and the critical points (w, P) "given in the text and exact". The half-span is
  quoted only as ``L2 = 100.8`` mm, unexplained (the research notes: "check against the report before use");
  :data:`MMB_HALF_SPAN` reads it as the span 2L, which the benchmark's own numbers corroborate
  (docs/delamination.md).

The plies carry no density in the reports: the values here are typical (unused by quasi-static runs).
"""

from __future__ import annotations

from dataclasses import dataclass

from .laminate import Ply

__all__ = ["DCB_SPECIMEN", "MMB_SPECIMEN", "MMB_HALF_SPAN", "T300_1076", "IM7_8552_MMB", "DCB_CRITICAL", "DCB_OPENING", "MMB_CRITICAL", "Specimen"]

T300_1076 = Ply(
    "T300/1076 (Krueger 2008)",
    139.4e9,
    10.16e9,
    10.16e9,
    4.6e9,
    4.6e9,
    3.54e9,
    0.30,
    0.30,
    0.436,
    1600.0,
    3.0e-3 / 24,
    "Krueger 2008, NASA/TM-2008-215123, Table I (via saullocastro/panels); ply thickness 2h/24; density typical, unverified, unused quasi-statically",
)

IM7_8552_MMB = Ply(
    "IM7/8552 (Krueger 2012)",
    161e9,
    11.38e9,
    11.38e9,
    5.2e9,
    5.2e9,
    3.9e9,
    0.32,
    0.32,
    0.45,
    1570.0,
    4.5e-3 / 24,
    "Krueger 2012, NASA/CR-2012-217562 (via saullocastro/panels); ply thickness 2h/24; density Hexcel's nominal, unused quasi-statically",
)


@dataclass(frozen=True)
class Specimen:
    """A split-beam specimen: ``ply``, plies per arm, ``width`` b [m], ``length`` [m] (the span 2L for the MMB),
    pre-crack ``a0`` [m] from the loaded end, toughnesses ``GIc``, ``GIIc`` [J/m²], B–K exponent ``eta``."""

    ply: Ply
    plies_per_arm: int
    width: float
    length: float
    a0: float
    GIc: float
    GIIc: float
    eta: float

    @property
    def arm(self) -> float:
        """An arm's thickness h [m]."""
        return self.plies_per_arm * self.ply.thickness


# G_IIc and η do not enter the mode-I DCB benchmark; the mode-II values of the MMB's material are not the DCB's:
# the DCB's law takes G_IIc = G_Ic (a mode-I specimen: the sliding at its front is nil by symmetry).
DCB_SPECIMEN = Specimen(T300_1076, 12, 25.0e-3, 150.0e-3, 30.0e-3, 170.3, 170.3, 2.1)

MMB_HALF_SPAN = 50.4e-3
"""The MMB's half-span L [m]: the notebook's unexplained ``L2 = 100.8`` mm read as the span 2L. Corroborated by the
benchmark's own elastic compliance: the plate model's w/P at 2L = 100.8 mm is within 0.65 % of w_crit/P_crit at all
three mode ratios (given to three digits: ±0.3 %), against up to 1.0 % at 2L = 101.6 mm (4 in)."""

MMB_SPECIMEN = Specimen(IM7_8552_MMB, 12, 25.4e-3, 2 * MMB_HALF_SPAN, 25.4e-3, 212.0, 774.0, 2.1)

DCB_CRITICAL = {
    30e-3: 60.7,
    31e-3: 58.8,
    32e-3: 57.3,
    33e-3: 55.6,
    34e-3: 54.2,
    35e-3: 52.5,
    40e-3: 46.7,
}
"""Krueger 2008's DCB critical loads [N] (mid-width onset, ±1 N as digitised) against the crack length a [m]."""

DCB_OPENING = {
    30e-3: 1.500e-3,
    31e-3: 1.588e-3,
    32e-3: 1.684e-3,
    33e-3: 1.780e-3,
    34e-3: 1.884e-3,
    35e-3: 2.002e-3,
    40e-3: 2.548e-3,
}
"""Krueger 2008's DCB load-point openings at the critical points [m]: twice the per-arm δ_crit/2 the report plots
(0.750 mm at a0 = 30 mm, stated in its Section 5.2.1), against the crack length a [m]."""

MMB_CRITICAL = {
    0.2: (92.9e-3, 1.64e-3, 128.5),
    0.5: (41.3e-3, 1.34e-3, 385.0),
    0.8: (27.3e-3, 1.65e-3, 751.0),
}
"""Krueger 2012's MMB benchmark per mode ratio G_II/G_T: (lever c [m], critical lever displacement w [m],
critical load P [N])."""
