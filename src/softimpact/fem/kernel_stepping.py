"""Stepping through contact kernels: the structure as its discrete impulse responses
(:class:`softimpact.fem.kernels.ContactKernels`), one implementation of :class:`CoupledStepper`.

The free response at step k + 1 is the convolution w̃_{k+1} = Σ_{j≤k} g_{k+1−j}·q_j of the loads so far: the
earlier contacts' as one precomputed "old" response, the current contact's as one contiguous dot product
(its loads newest first). When a contact ends, the response to its loads is one FFT product with the
kernels' cached spectra, kept for the outputs (one inverse transform at the end). While apart, no load is
added and the next contact is found by one vectorised test (:meth:`KernelStepper.flight`). The structure's
own energies need its state and are NaN.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from .impact import ContactStructure, ImpactHistory
from .kernels import ContactKernels
from .newmark import NewmarkParameters
from .stepping import CoupledStepper

__all__ = ["KernelStepper"]


class KernelStepper(CoupledStepper):
    """:class:`CoupledStepper` on contact kernels ``engine`` (a :class:`ContactKernels` built for this time
    step and run length; None: built here for ``structure``). ``structure``: the kernels' own, or the same
    target struck at the same point with a smaller contact reach (another impactor diameter,
    :meth:`ContactKernels.compliance_for`). No structure energies or snapshots (``energy`` must be False).
    """

    TAKE_TOP = True

    def __init__(
        self,
        structure: ContactStructure | None,
        law,
        mass: float,
        velocity: float,
        time_step: float,
        steps: int,
        newmark: NewmarkParameters = NewmarkParameters(),
        *,
        engine: ContactKernels | None = None,
        stop_after: float | None = None,
        energy: bool = False,
        snapshots=(),
    ):
        if energy or len(snapshots):
            raise InputError("contact kernels give no structure energies or snapshots: pass energy=False and no snapshots, or step directly")
        kernels = engine or ContactKernels(structure, time_step, steps, newmark)
        if kernels.steps != steps or not math.isclose(kernels.dt, float(time_step), rel_tol=1e-12):
            raise InputError(f"kernels: built for {kernels.steps} steps of {kernels.dt:.6g} s, the run is {steps} of {float(time_step):.6g} s")
        super().__init__(law, mass, velocity, kernels.dt, kernels.steps, stop_after)
        self.kernels, self.params = kernels, kernels.newmark
        self.compliance = kernels.compliance_for(structure)
        self.load = self.compliance.load
        self.lagged = kernels.lagged  # (steps, p): row i is g_i

    def _begin(self) -> None:
        super()._begin()
        N, p = self.steps, self.lagged.shape[1]
        self.p = p
        self.Qr = np.zeros((N + 1, p))  # Qr[N − j] = q_j = F_j·s_j: a contact's loads newest first, contiguous
        self.Qflat, self.gflat = self.Qr.ravel(), self.lagged.ravel()  # the same, as one run of lags × nodes each (views)
        self.old = [0.0] * (N + 1)  # response to the loads of the earlier contacts
        self.start = None  # first step of the current contact
        self.total = None  # the spectrum of the response to the loads of the contacts ended so far

    def free_approach(self, k: int) -> float:
        start = self.start
        if start is None:
            return self.old[k + 1]
        L, p, N = k + 1 - start, self.p, self.steps  # the current contact's loads, lags 1 … k + 1 − start: one dot product
        return self.old[k + 1] + float(np.dot(self.gflat[p : (L + 1) * p], self.Qflat[(N - k) * p : (N - k + L) * p]))

    def apply(self, k: int, f: float, r: float) -> None:
        """The step's loads f·s(r) into the contact's; when a contact ends, the free response to its loads, once."""
        if f != 0.0:
            self.load(r, f, self.Qr[self.steps - k - 1])
            if self.start is None:
                self.start = k + 1
        elif self.start is not None:
            self._close(k)

    def _close(self, upto: int) -> None:
        """The contact of steps ``start`` … ``upto`` ended: its response spectrum kept, its approach response added to ``old``."""
        spectrum = self.kernels.contact_spectrum(self.Qr, self.start, upto)
        self.total = spectrum if self.total is None else self.total + spectrum
        self.old = (np.asarray(self.old) + self.kernels.response(spectrum[:1])[0]).tolist()
        self.start = None

    def flight(self, k: int) -> tuple[list, list]:
        """The ballistic impactor against the structure's free response: every step up to the first whose
        predicted approach is positive, in one vectorised test."""
        N, dt, v = self.steps, self.dt, self.xv[k]
        ks = np.arange(k, N)
        pred = self.x[k] + (ks - k + 1) * (dt * v)
        tgt = pred - np.asarray(self.old[k + 1 : N + 1])
        hit = np.flatnonzero(tgt > 0.0)
        n = int(hit[0]) if hit.size else N - k
        return pred[:n].tolist(), tgt[:n].tolist()

    def history(self, last: int) -> ImpactHistory:
        N = self.steps
        if self.start is not None:  # in contact at the end
            spectrum = self.kernels.contact_spectrum(self.Qr, self.start, N)
            self.total = spectrum if self.total is None else self.total + spectrum
        y = self.kernels.response(self.total)  # (1 + q, N + 1): approach row, then the outputs
        sl = slice(0, last + 1)
        nan = np.full(last + 1, np.nan)
        t = np.arange(N + 1) * self.dt

        def arr(v):
            return np.array(v[: last + 1])

        return ImpactHistory(
            time=t[sl],
            force=arr(self.F),
            approach=arr(self.al),
            approach_rate=arr(self.ald),
            contact_radius=arr(self.rad),
            impactor_displacement=arr(self.x),
            impactor_velocity=arr(self.xv),
            target_displacement=y[0, sl],
            strain=y[1:, sl],
            structure_kinetic=nan,
            structure_strain=nan.copy(),
            structure_work=nan.copy(),
            contact_work=arr(self.cwork),
            contact_energy=arr(self.cen),
            surface_mismatch=nan.copy(),
            newton_iterations=self.newton_iterations,
            solves=0,
        )
