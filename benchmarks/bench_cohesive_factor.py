"""The sparse factorisations of a cohesive stack's Newmark matrix, measured side by side.

    python benchmarks/bench_cohesive_factor.py [case] [--superlu]

Builds the built-in ``case`` (default ``d7136-drop-weight``: 14 cohesive interfaces, 15 sublaminates in a
40 × 40 mm near field, 85 863 DOF), its Jacobian K_T + M/(β·Δt²) at rest, and factors it with MKL PARDISO
(pypardiso, SPD, nested dissection) and, with ``--superlu``, SciPy's SuperLU (minimum degree on Aᵀ + A,
symmetric mode: minutes on this case). Prints each one's wall and CPU time, the factor's entries and a solve's
time and residual. Record the figures in BENCHMARKS.md with the machine and the date."""

import sys
import time

import numpy as np
import scipy.sparse as sp


def main(argv):
    from softimpact.input.impact_case import load_impact_case

    case = next((a for a in argv if not a.startswith("--")), "d7136-drop-weight")
    problem, _ = load_impact_case(case)
    target = problem.target
    model = target.model()
    st, dt = model.stack, target.solver.time_step
    A = sp.csr_matrix(st.tangent(np.zeros(st.n)) + st.M / (0.25 * dt * dt))
    A = ((A + A.T) * 0.5).tocsr()
    b = np.random.default_rng(0).standard_normal(A.shape[0])
    print(f"{case}: {A.shape[0]} DOF, {A.nnz} entries, {len(target.splits)} interfaces")

    def report(name, build):
        w, c = time.perf_counter(), time.process_time()
        f = build()
        wall, cpu = time.perf_counter() - w, time.process_time() - c
        w = time.perf_counter()
        x = f.solve(b)
        solve = time.perf_counter() - w
        res = np.linalg.norm(A @ x - b) / np.linalg.norm(b)
        print(f"{name:28s} factor {wall:8.2f} s wall {cpu:8.2f} s CPU, {f.stored / 1e6:8.1f} M entries, solve {solve:.3f} s, residual {res:.1e}")

    from softimpact.fem.newmark import MinimumDegreeLU, PardisoCholesky

    try:
        report("PARDISO (pypardiso)", lambda: PardisoCholesky(A))
    except ImportError:
        print("PARDISO: pypardiso not installed (pip install 'softimpact[fast]')")
    if "--superlu" in argv:
        report("SuperLU, MMD(AᵀA+A), symmetric", lambda: MinimumDegreeLU(A))


if __name__ == "__main__":
    main(sys.argv[1:])
