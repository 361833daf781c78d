"""Benchmark: transverse impact of the 8 × 8 in SS [90/0]5s plate (eq-15 pulse, 0.25-in cosine patch).

Per mesh: softimpact's direct stepping (1000 steps of 1 µs, MITC9 FSDT by default,
K_eff factored by ``softimpact.fem.newmark.spd_factor``) against a plain Newmark loop on the same K, M
factored by scipy's ``splu`` (COLAMD); then the response engine: building the
impulse responses at two gauges and the centre deflection (reciprocity), and one
new force history through it. The gauge strains of the two loops are compared.

Whole process (``--whole``): ``softimpact plate`` on the built-in plate-ss-8in case
with the mesh set to n × n (interpreter start, imports, case, assembly, factor,
1000 steps with the energy balance, five natural frequencies for the summary,
history.csv and summary.json) against ``benchmarks/plain_plate.py`` (the same
matrices stepped with ``splu``, a CSV written), alternated, best of ``REPEATS``.

Run: ``python benchmarks/bench_plate.py [--element mitc9|mitc4] [--whole] [nx ...]``
(MITC9 by default, the element of ``softimpact plate``).
"""

import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import scipy.sparse.linalg as spl

from softimpact.fem.newmark import SolverSpec
from softimpact.models.laminate import PLIES, Stack, parse_layup
from softimpact.models.pulses import SkewedPulse
from softimpact.workflows.plate_impact import PlateGauge, PlateLoad, PlateModel, PlateProblem, PlateSpec

IN, LBF = 0.0254, 4.4482216152605


ELEMENT = "mitc9"


def problem(n):
    return PlateProblem(
        PlateSpec(8 * IN, 8 * IN, (n, n), Stack(PLIES["T300/934"], parse_layup("[90/0]5s")), element=ELEMENT),
        PlateLoad((4 * IN, 4 * IN), 0.25 * IN, SkewedPulse(100 * LBF, 20e-6, 250e-6)),
        SolverSpec(1e-6, 1000e-6),
        (PlateGauge("x1", (5 * IN, 4 * IN), "bottom", "x"), PlateGauge("y2", (4 * IN, 6 * IN), "bottom", "y")),
    )


def plain_newmark(model):
    """Average-acceleration Newmark, K_eff factored by splu: what one writes with scikit-fem + scipy."""
    K, M, dt, N = model.fe.K, model.fe.M, model.problem.solver.time_step, model.steps
    a0, a2, a3 = 4 / dt**2, 4 / dt, 1.0
    lu = spl.splu((K + a0 * M).tocsc())
    f = np.zeros((N + 1, model.fe.n))
    f[:, model.load_dofs] = -model.nodal_loads(model.force_samples()).T
    u, v, a = np.zeros(model.fe.n), np.zeros(model.fe.n), np.zeros(model.fe.n)
    out = np.zeros((model.O.shape[0], N + 1))
    for k in range(N):
        u1 = lu.solve(f[k + 1] + M @ (a0 * u + a2 * v + a3 * a))
        a1 = a0 * (u1 - u) - a2 * v - a3 * a
        v = v + dt / 2 * (a + a1)
        u, a = u1, a1
        out[:, k + 1] = model.O @ u
    return out


def main(meshes):
    print(f"{'mesh':>7} {'DOFs':>6} {'build s':>8} {'direct s':>9} {'splu loop s':>12} {'speed-up':>9} {'engine s':>9} {'respond ms':>11} {'|Δε|/ε':>9}")
    for n in meshes:
        t = time.perf_counter()
        model = PlateModel(problem(n))
        build = time.perf_counter() - t
        t = time.perf_counter()
        r = model.direct(energy=False)
        direct = time.perf_counter() - t
        t = time.perf_counter()
        y = plain_newmark(model)
        plain = time.perf_counter() - t
        diff = np.max(np.abs(y[:2] - r.strain)) / np.max(np.abs(r.strain))
        t = time.perf_counter()
        model.engine()
        engine = time.perf_counter() - t
        new = SkewedPulse(80 * LBF, 25e-6, 300e-6)
        model.respond(new)  # warm the FFT plan and the patch table
        reps = 20
        t = time.perf_counter()
        for _ in range(reps):
            model.respond(SkewedPulse(80 * LBF, 25e-6, 300e-6 + 1e-6 * _))
        respond = (time.perf_counter() - t) / reps
        print(
            f"{n:>3}×{n:<3} {model.fe.n:>6} {build:>8.2f} {direct:>9.2f} {plain:>12.2f} {plain / direct:>8.1f}× {engine:>9.2f} {respond * 1e3:>11.1f} {diff:>9.1e}"
        )


HERE = Path(__file__).resolve().parent
REPEATS = 3


def whole(meshes):
    from softimpact.input.toml import locate

    base = locate("plate-ss-8in").read_text()
    print(f"{'mesh':>7} {'softimpact plate s':>19} {'plain script s':>15} {'speed-up':>9}")
    with tempfile.TemporaryDirectory() as tmp:
        for n in meshes:
            case = Path(tmp) / f"plate{n}.toml"
            case.write_text(base.replace("elements = [48, 48]", f'elements = [{n}, {n}]\nelement = "{ELEMENT}"'))
            cmds = {
                "softimpact": [str(Path(sys.executable).parent / "softimpact"), "plate", str(case), "--no-figures", "--out", str(Path(tmp) / f"out{n}")],
                "plain": [sys.executable, str(HERE / "plain_plate.py"), str(n), str(Path(tmp) / f"plain{n}.csv"), "--element", ELEMENT],
            }
            times = {k: [] for k in cmds}
            for _ in range(REPEATS):
                for k, cmd in cmds.items():
                    t0 = time.perf_counter()
                    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                    times[k].append(time.perf_counter() - t0)
            a, b = min(times["softimpact"]), min(times["plain"])
            print(f"{n:>3}×{n:<3} {a:>19.2f} {b:>15.2f} {b / a:>8.1f}×", flush=True)


if __name__ == "__main__":
    args = sys.argv[1:]
    if "--element" in args:
        i = args.index("--element")
        ELEMENT = args[i + 1]
        del args[i : i + 2]
    if args and args[0] == "--whole":
        whole([int(a) for a in args[1:]] or [24, 48])
    else:
        main([int(a) for a in args] or [16, 24, 32, 48])
