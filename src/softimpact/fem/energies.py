"""One energy record for every run of a linear structure: direct stepping and coupled impact.

Newmark average acceleration conserves energy exactly when the work of the loads is
summed as Σ½(f_k + f_{k+1})·(u_{k+1} − u_k): then kinetic + strain = work to round-off
(undamped). A coupled impact adds the impactor's kinetic energy and the contact's work
∫F dα (stored part ``contact_energy``, the rest lost), and ``surface_mismatch``, the work
of the force on the loaded surface nodes minus on the mid-surface point of the approach.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Energies"]


@dataclass(frozen=True)
class Energies:
    """Energy histories [J] of a run, each of shape (n_samples,), sampled at the steps ``step``.

    ``kinetic`` ½vᵀMv, ``strain`` ½uᵀKu (a nonlinear structure's: its recoverable energy plus what it dissipated,
    plastic work and fracture energy), ``work`` of the loads on the structure. A coupled run
    also has ``impactor_kinetic``, ``contact_work`` (∫F dα), ``contact_energy`` (its recoverable
    part) and ``surface_mismatch``; they are None for a prescribed-force run.
    """

    step: np.ndarray  # step indices of the samples
    kinetic: np.ndarray
    strain: np.ndarray
    work: np.ndarray
    impactor_kinetic: np.ndarray | None = None
    contact_work: np.ndarray | None = None
    contact_energy: np.ndarray | None = None
    surface_mismatch: np.ndarray | None = None

    @property
    def balance_error(self) -> np.ndarray:
        """Kinetic + strain − work [J]: zero to round-off for average acceleration, undamped."""
        return self.kinetic + self.strain - self.work

    @property
    def contact_loss(self) -> np.ndarray:
        """Energy lost in the contact [J]: its work less what it stores."""
        return self.contact_work - self.contact_energy

    @property
    def total(self) -> np.ndarray:
        """A coupled run: impactor KE + structure KE + strain energy + contact work [J]
        (= the initial KE + the surface mismatch)."""
        return self.impactor_kinetic + self.kinetic + self.strain + self.contact_work

    @property
    def mechanical(self) -> np.ndarray:
        """A coupled run: impactor KE + structure KE + strain energy + the contact's stored energy [J]:
        constant for an elastic contact (Hertz), falling by what a lossy law dissipates."""
        return self.impactor_kinetic + self.kinetic + self.strain + self.contact_energy
