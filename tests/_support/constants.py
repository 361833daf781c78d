"""Inch-pound conversion factors, written here from their definitions, independently of ``softimpact.units``."""

INCH = 0.0254  # m, exact by definition
LBF = 4.4482216152605  # N: 1 lbf = 0.45359237 kg × 9.80665 m/s², exact by definition
PSI = LBF / INCH**2  # Pa: 1 lbf / in²
LB_PER_IN3 = 0.45359237 / INCH**3  # kg/m³
