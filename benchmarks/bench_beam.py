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
from timing import best

from softimpact.input.beam_case import load_beam_case
from softimpact.models.pulses import SkewedPulse
from softimpact.workflows.beam_impact import BeamModel


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
    except (ImportError, RuntimeError):
        print("  openseespy not importable: reference figure from the issue, about 5 s")
        return
    t_ops, eps_ops = opensees_run(model, F)
    lumped = BeamModel(problem.__class__(**{**problem.__dict__, "beam": problem.beam.__class__(**{**problem.beam.__dict__, "lumped": True})}))
    ours = lumped.direct(energy=False).strain[0]
    diff = np.max(np.abs(eps_ops - ours)) / np.max(np.abs(ours))
    print(f"  OpenSeesPy, same mesh, lumped mass:    {t_ops:.3f} s  (gauge g1 differs from softimpact's lumped-mass run by {diff:.1e} of its peak)")


def opensees_run(model, F):
    """The same problem in OpenSeesPy: quad PlaneStrain elements, ElasticOrthotropic, Newmark, BandGeneral."""
    import openseespy.opensees as ops

    from softimpact.models.laminate import engineering_constants

    p, pm = model.problem, model.plane
    ec = engineering_constants(p.beam.stack.effective())
    t = p.solver.times()
    loads = model.nodal_loads(F)
    t0 = time.perf_counter()
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 2)
    # OpenSees's plane is x (axis) and y: our z (thickness) is its y, our width direction its z (plane strain).
    xs, zs = pm.node_x, pm.node_z
    for i in range(xs.size):
        ops.node(i + 1, float(xs[i]), float(zs[i]))
    for i in np.flatnonzero(np.isclose(xs, 0.0)):
        ops.fix(int(i) + 1, 1, 1)
    # Its axes 1, 2, 3 are our 1 (axis), 3 (thickness), 2 (width): ν23 there is our ν32 = ν23·E3/E2.
    nu32 = ec["nu23"] * ec["E3"] / ec["E2"]
    ops.nDMaterial("ElasticOrthotropic", 1, ec["E1"], ec["E3"], ec["E2"], ec["nu13"], nu32, ec["nu12"], ec["G13"], ec["G23"], ec["G12"], p.beam.density)
    ops.nDMaterial("PlaneStrain", 2, 1)  # the 3-D material reduced to plane strain
    cells = pm.basis.mesh.t
    for e in range(cells.shape[1]):
        ops.element("quad", e + 1, *[int(n) + 1 for n in cells[::-1, e]], p.beam.width, "PlaneStrain", 2)  # counter-clockwise
    for j, node in enumerate(pm.top_nodes[model.patch.nodes]):
        ops.timeSeries("Path", j + 1, "-dt", p.solver.time_step, "-values", *(-loads[j]).tolist())
        ops.pattern("Plain", j + 1, j + 1)
        ops.load(int(node) + 1, 0.0, 1.0)
    g = p.gauges[0]
    a = pm.bottom_nodes[np.argmin(np.abs(xs[pm.bottom_nodes] - (g.position - g.length / 2)))]
    b = pm.bottom_nodes[np.argmin(np.abs(xs[pm.bottom_nodes] - (g.position + g.length / 2)))]
    ops.constraints("Plain")
    ops.numberer("RCM")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-12, 10)
    ops.algorithm("Linear")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")
    eps = np.zeros(t.size)
    for k in range(1, t.size):
        ops.analyze(1, p.solver.time_step)
        eps[k] = (ops.nodeDisp(int(b) + 1, 1) - ops.nodeDisp(int(a) + 1, 1)) / (xs[b] - xs[a])
    return time.perf_counter() - t0, eps


if __name__ == "__main__":
    main()
