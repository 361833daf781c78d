"""The response engine: a linear, time-invariant model as a discrete convolution.

A Newmark-discretised linear model started from rest is a linear recursion
s_{k+1} = A·s_k + B·f_{k+1} on its state s = (u, v, a), so any output
y_k = O·u_k is the discrete convolution of the load history with the model's
impulse response, h_i = O·A^(i−1)·B. Computing h once per (model, dt, loaded
DOFs, outputs) costs one Newmark run with the unit loads as right-hand sides;
after that any load history costs an FFT convolution: milliseconds, and equal
to direct stepping to round-off. Calibration, sweeps and the contact loop of
the bar use it.

Shapes: loads F of shape (p, n_steps + 1) on p load patterns (columns of B,
shape (n, p)); outputs y of shape (q, n_steps + 1) for q output rows (O of shape
(q, n)); the kernel h has shape (q, p, n_steps).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse

from .newmark import NewmarkStepper

__all__ = ["ImpulseResponse"]


class ImpulseResponse:
    """Impulse responses of outputs O·u (and optionally O_v·v) to loads on patterns B.

    ``kernel[q, p, i]`` is output q at step i + 1 for a unit load on pattern p at
    step 1 only (zero elsewhere), the model at rest before. A load at step 0
    (t = 0) also sets the initial acceleration, so it has its own kernel,
    computed only when a history with F(0) ≠ 0 is given.
    """

    def __init__(self, stepper: NewmarkStepper, patterns, steps: int, outputs=None, velocity_outputs=None):
        B = patterns.toarray() if scipy.sparse.issparse(patterns) else np.asarray(patterns, dtype=float)
        if B.ndim == 1:
            B = B[:, None]
        self.stepper, self.B, self.steps = stepper, B, steps
        self.O = outputs
        self.Ov = velocity_outputs
        self.kernel, self.velocity_kernel = self._run(first_step=1)
        self._start = None

    @classmethod
    def reciprocal(cls, stepper: NewmarkStepper, patterns, steps: int, outputs) -> ImpulseResponse:
        """The same kernel, computed with loads and outputs swapped (Maxwell–Betti).

        For symmetric M, C, K the Newmark response matrix after k steps is
        symmetric (it is Φ·diag(r_k(ω))·Φᵀ in the M-orthonormal modes), so the
        response of outputs O to loads on patterns B equals, transposed, the
        response at Bᵀ to loads shaped like the output rows Oᵀ. With few outputs
        (gauges) and many loaded DOFs (a contact patch) this needs q, not p,
        right-hand sides per step.
        """
        O = outputs.toarray() if scipy.sparse.issparse(outputs) else np.asarray(outputs, float)
        B = patterns.toarray() if scipy.sparse.issparse(patterns) else np.asarray(patterns, float)
        swapped = cls(stepper, O.T, steps, outputs=B.T)
        swapped.kernel = np.ascontiguousarray(np.swapaxes(swapped.kernel, 0, 1))
        swapped.B, swapped.O = B, O
        swapped._start = None
        swapped._reciprocal = True
        return swapped

    def _observe(self, O, x):
        return x if O is None else O @ x

    @staticmethod
    def _sparse_if_sparse(O):
        """Output rows as CSR when they are mostly zeros (a patch's selection of DOFs):
        one product per step then costs its nonzeros, not q × n."""
        if O is None or O is True or scipy.sparse.issparse(O):
            return O
        O = np.asarray(O, float)
        return scipy.sparse.csr_matrix(O) if np.count_nonzero(O) < 0.1 * O.size else O

    def _run(self, first_step: int):
        st, B, N = self.stepper, self.B, self.steps
        n, p = B.shape
        u = np.zeros((n, p))
        v = np.zeros((n, p))
        if first_step == 0:
            a = st.initial_acceleration(u, v, B)
        else:
            a = np.zeros((n, p))
        q = n if self.O is None else self.O.shape[0]
        h = np.empty((q, p, N))
        hv = None if self.Ov is None else np.empty((n if self.Ov is True else self.Ov.shape[0], p, N))
        if first_step == 1:  # the unit load acts at step 1 only
            u1 = st.solve(B + st.predictor(u, v, a))
            v, a = st.correct(u1, u, v, a)
            u = u1
        else:
            u, v, a = st.free_step(u, v, a)
        if st.dense:
            # Small systems: march the whole state with one product per step, observe after.
            T = st.transition_operator()
            states = np.empty((N, 3 * n, p))
            states[0] = np.concatenate((u, v, a))
            for k in range(1, N):
                states[k] = T @ states[k - 1]
            us = states[:, :n, :]
            h[:] = np.moveaxis(us if self.O is None else np.einsum("qn,knp->kqp", self.O, us), 0, -1)
            if hv is not None:
                vs = states[:, n : 2 * n, :]
                hv[:] = np.moveaxis(vs if self.Ov is True else np.einsum("qn,knp->kqp", self.Ov, vs), 0, -1)
            return h, hv
        O = self._sparse_if_sparse(self.O)
        for k in range(N):
            if k:
                u, v, a = st.free_step(u, v, a)
            h[:, :, k] = self._observe(O, u)
            if hv is not None:
                hv[:, :, k] = v if self.Ov is True else self.Ov @ v
        return h, hv

    def _start_kernels(self):
        if getattr(self, "_reciprocal", False):
            raise ValueError("a reciprocal engine needs loads that start from zero (F(0) = 0)")
        if self._start is None:
            self._start = self._run(first_step=0)
        return self._start

    def _spectrum(self, velocity: bool = False):
        """The kernel's real FFT, zero-padded to a fast length ≥ 2·n_steps − 1 (no wrap-around), cached."""
        from scipy.fft import next_fast_len

        key = "velocity" if velocity else "displacement"
        cache = self.__dict__.setdefault("_spectra", {})
        if key not in cache:
            h = self.velocity_kernel if velocity else self.kernel
            nfft = next_fast_len(2 * self.steps - 1, real=True)
            cache[key] = (np.fft.rfft(h, nfft, axis=-1), nfft)
        return cache[key]

    def respond(self, loads: np.ndarray, velocity: bool = False) -> np.ndarray:
        """Outputs for load histories ``loads`` of shape (p, n_steps + 1) (or (n_steps + 1,) if p = 1).

        Returns shape (q, n_steps + 1); with ``velocity`` the velocity outputs.
        """
        F = np.asarray(loads, dtype=float)
        if F.ndim == 1:
            F = F[None, :]
        N = self.steps
        if F.shape != (self.B.shape[1], N + 1):
            raise ValueError(f"loads must have shape {(self.B.shape[1], N + 1)}, got {F.shape}")
        h = self.velocity_kernel if velocity else self.kernel
        if h is None:
            raise ValueError("no velocity outputs were requested for this engine")
        y = np.zeros((h.shape[0], N + 1))
        # y[k] = Σ_j h[k − j] F[j] (j ≥ 1), summed over the load patterns: a product of
        # spectra, the kernel's computed once per engine (it does not change).
        Hk, nfft = self._spectrum(velocity)
        Fk = np.fft.rfft(F[:, 1:], nfft, axis=-1)
        y[:, 1:] = np.fft.irfft(np.einsum("qpk,pk->qk", Hk, Fk), nfft, axis=-1)[:, :N]
        if np.any(F[:, 0] != 0.0):
            h0 = self._start_kernels()[1 if velocity else 0]
            y[:, 1:] += np.einsum("qpk,p->qk", h0, F[:, 0])
        return y

    def respond_pattern(self, pattern: np.ndarray, history: np.ndarray) -> np.ndarray:
        """:meth:`respond` for the loads ``np.outer(pattern, history)`` (one spatial pattern scaled
        by one history, F(0) = 0) in one convolution per output: the kernel's spectrum is combined
        over the pattern once (cached for the last pattern), so a new history no longer costs a
        transform per loaded DOF."""
        pattern = np.asarray(pattern, dtype=float)
        F = np.asarray(history, dtype=float)
        N = self.steps
        if pattern.shape != (self.B.shape[1],) or F.shape != (N + 1,):
            raise ValueError(f"pattern must have shape {(self.B.shape[1],)} and history {(N + 1,)}, got {pattern.shape}, {F.shape}")
        if F[0] != 0.0:
            return self.respond(np.outer(pattern, F))
        Hk, nfft = self._spectrum()
        last = self.__dict__.get("_pattern")
        if last is None or last[0].shape != pattern.shape or not np.array_equal(last[0], pattern):
            last = self._pattern = (pattern.copy(), np.einsum("qpk,p->qk", Hk, pattern))
        y = np.zeros((Hk.shape[0], N + 1))
        y[:, 1:] = np.fft.irfft(last[1] * np.fft.rfft(F[1:], nfft), nfft, axis=-1)[:, :N]
        return y

    def convolve(self, loads: np.ndarray) -> np.ndarray:
        """:meth:`respond` for histories that start from zero (F(0) = 0): a product of spectra,
        the kernel's computed once per engine (sweeps run many histories on one model)."""
        F = np.asarray(loads, dtype=float)
        if np.any((F[None, :] if F.ndim == 1 else F)[:, 0] != 0.0):
            raise ValueError("convolve needs loads that start from zero (F(0) = 0); use respond")
        return self.respond(F)
