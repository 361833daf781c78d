"""softimpact: the impact of soft projectiles on structures.

Implements the method of J.E. Grady, "Contact Force History and Dynamic Response
Due to the Impact of a Soft Projectile" (NASA Lewis):

- :mod:`softimpact.models` — materials, Hertz contact (eqs 1–3), pulses (eq 15),
  the empirical soft-projectile model (eqs 4–7), laminates.
- :mod:`softimpact.fem` — Hermite rod and plane-strain matrices (scikit-fem),
  Newmark time stepping.
- :mod:`softimpact.workflows` — bar impact, record reduction, scaling fit,
  beam impact, calibration.
- :mod:`softimpact.input` (case, series and record files),
  :mod:`softimpact.output` (the file contract, figures, the HTML report),
  :mod:`softimpact.app` (one function per command) and :mod:`softimpact.cli`
  (click only) — the edges. Imports point down only.

Everything inside is SI; units are parsed at the edges (:mod:`softimpact.units`).
"""

__version__ = "0.1.0"

__all__ = ["__version__"]
