"""The paper's 8 × 8 in plate problem, shared by the plate tests; its exact solution is
:mod:`_support.plate_navier` (FSDT Navier series), as scipy's ``test_ivp.py`` pairs problems with exact solutions."""

from softimpact.models.laminate import PLIES, Stack, parse_layup
from softimpact.models.plate_laminate import plate_section
from softimpact.models.pulses import SkewedPulse

from .constants import INCH, LBF

PLY = PLIES["T300/934"]
STACK = Stack(PLY, parse_layup("[90/0]5s"))  # the paper's beams' layup, 20 plies, 0.110 in
SECTION = plate_section(STACK)
A = 8 * INCH  # m: side of the square plate
PAPER_PULSE = SkewedPulse(100 * LBF, 20e-6, 250e-6)  # eq (15), the pulse
SMOOTH_PULSE = SkewedPulse(100 * LBF, 125e-6, 250e-6)  # a half sine: fewer short waves, for fast checks
