"""Coverage of calibrate's uncertainties (issues 9 and 22): do the 95 % intervals of F0, t_F0
and T hold the truth 95 % of the time, without being several times too wide?

Twelve force histories (eq 15), six on each beam: the four of Table II (long beam) or Table III
(short beam) and two more, so that t_F0 runs from 5 to 35 µs. For each, the "measured" strains
are made once by a model 8× finer than the case in mesh and in time step (level 3 of the
calibration ladder: 1600 × 48 elements, 0.125 µs; the stand-in for the real structure, computed
through its response engine, which equals direct stepping to round-off) and cached. Each of N
realisations adds independent noise (1.5 % of each gauge's peak, white) and a gauge offset, and is
calibrated with the defaults through the command's path (:func:`studies.calibration.calibrate_tests`'s
steps: the model checked and refined within the default budget, then the parameters' own
convergence over three levels with the one-factor refinements).

Printed per parameter: the fraction of realisations whose 95 % interval (±1.96 SE) holds the
true value, the RMS of error/SE, the mean and largest relative error; then per history.

Usage: python benchmarks/bench_coverage.py [realisations per history, default 17] [workers, default 2]
Cache: benchmarks/.cache/coverage (truth strains, one JSON line per calibration); delete it to start over.
"""

from __future__ import annotations

import json
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

LBF, INCH = 4.4482216152605, 0.0254
CACHE = Path(__file__).parent / ".cache" / "coverage"
TRUTH_LEVEL = 3  # 2**3 = 8× the case in mesh (both directions) and in time step
NOISE, OFFSET = 0.015, 30e-6  # noise σ as a fraction of each gauge's peak; gauge offset σ (strain)
# (case, V [in/s], F0 [lbf], t_F0 [µs], T [µs], r0 [in]): Tables II and III, and two more per beam
HISTORIES = [
    ("paper-long-beam", 1000, 36, 35, 400, 0.25),
    ("paper-long-beam", 1166, 44, 30, 355, 0.25),
    ("paper-long-beam", 1932, 90, 21, 250, 0.25),
    ("paper-long-beam", 3058, 215, 13, 158, 0.30),
    ("paper-long-beam", 4026, 325, 10, 120, 0.35),
    ("paper-long-beam", 4800, 420, 5, 100, 0.35),
    ("paper-short-beam", 1000, 33, 35, 470, 0.25),
    ("paper-short-beam", 1166, 42, 35, 415, 0.25),
    ("paper-short-beam", 1981, 84, 20, 310, 0.25),
    ("paper-short-beam", 2994, 170, 13, 205, 0.30),
    ("paper-short-beam", 4049, 245, 10, 155, 0.35),
    ("paper-short-beam", 4800, 300, 6, 130, 0.35),
]
NAMES = ("peak_force", "time_of_peak", "duration")


def _pulse(h):
    from softimpact.models.pulses import SkewedPulse

    return SkewedPulse(h[2] * LBF, h[3] * 1e-6, h[4] * 1e-6)


def _ladder(case):
    from softimpact.input.beam_case import load_beam_case
    from softimpact.studies.calibration import ModelLadder

    problem, _ = load_beam_case(case)
    return ModelLadder(problem, sorted({h[5] * INCH for h in HISTORIES if h[0] == case}))


def truth(case: str) -> None:
    """The clean strains of every history of ``case`` on the level-3 model, cached (npz per history)."""
    todo = [(i, h) for i, h in enumerate(HISTORIES) if h[0] == case and not (CACHE / f"truth-{i}.npz").exists()]
    if not todo:
        return
    ladder = _ladder(case)
    t0 = time.perf_counter()
    model = ladder(TRUTH_LEVEL)
    b = model.problem.beam
    print(f"{case}: truth model {b.nx} × {b.nz}, {model.problem.solver.time_step * 1e6:g} µs", file=sys.stderr, flush=True)
    for i, h in todo:
        r = model.respond(_pulse(h), h[5] * INCH)
        np.savez(CACHE / f"truth-{i}.npz", time=r.time, strain=r.strain, names=[g.name for g in model.problem.gauges])
        print(f"  history {i} (V {h[1]}): {time.perf_counter() - t0:.0f} s", file=sys.stderr, flush=True)


def _record(conv) -> dict:
    return {"status": conv.status, "order": float(conv.order), "safety": float(conv.safety_factor), "extrapolated": float(conv.extrapolated)}


def calibrate_realisations(i: int, seeds: list[int]) -> list[dict]:
    """Calibrate realisations ``seeds`` of history ``i``; one dict of components per calibration."""
    from softimpact.input.scaling_constants import start_pulse
    from softimpact.studies.calibration import DEFAULT_BUDGET, parameter_convergence, with_parameter_convergence
    from softimpact.workflows.calibration import Measured, calibrate_checked

    h = HISTORIES[i]
    data = np.load(CACHE / f"truth-{i}.npz")
    ladder = _ladder(h[0])
    max_level = ladder.affordable(DEFAULT_BUDGET)
    start = start_pulse("rubber-1/2in", None, min(max(h[1], 1000), 4000) * INCH)
    t = np.arange(-100e-6, data["time"][-1], 1e-6)
    out = []
    for seed in seeds:
        rng = np.random.default_rng([20261125, i, seed])
        strains = {}
        for name, eps in zip(data["names"], data["strain"]):
            y = np.interp(t, data["time"], eps, left=0.0)
            strains[str(name)] = y + NOISE * np.max(np.abs(eps)) * rng.standard_normal(t.size) + rng.normal(0, OFFSET)
        measured = Measured(f"h{i}-{seed}", t + 100e-6, strains)
        c0 = time.process_time()
        cal = calibrate_checked(ladder, measured, start, radius=h[5] * INCH, max_level=max_level)
        conv = parameter_convergence(ladder, measured, start, cal, None, False)
        final = with_parameter_convergence(ladder, measured, start, cal, None, False)
        out.append(
            {
                "history": i,
                "seed": seed,
                "cpu": time.process_time() - c0,
                "level": cal.check.level,
                "value": {n: getattr(cal, n) for n in NAMES},
                "se": {n: final.standard_errors[n] for n in NAMES},
                "noise_se": {n: cal.check.noise_errors[n] for n in NAMES},
                "shift": {n: cal.check.shifts.get(n, 0.0) for n in NAMES},
                "u": {n: conv[n][0] for n in NAMES} if conv else {},  # discretisation standard uncertainty (k = 1)
                "conv": {n: _record(conv[n][1]) for n in NAMES} if conv else {},
                "level_fits": {str(k): v for k, v in cal.check.level_fits.items()},
            }
        )
    return out


def _truth_values(i):
    p = _pulse(HISTORIES[i])
    return {"peak_force": p.peak_force, "time_of_peak": p.time_of_peak, "duration": p.duration}


def summarise(rows: list[dict], se_of=lambda r, n: r["se"][n]) -> None:
    """Print coverage, RMS z and errors per parameter, then per history."""
    print(f"{len(rows)} calibrations of {len({r['history'] for r in rows})} histories; median CPU {np.median([r['cpu'] for r in rows]):.1f} s per calibration")
    print(f"{'parameter':14s} {'95 % coverage':>14s} {'RMS error/SE':>13s} {'(by history)':>14s} {'mean error':>11s} {'largest |error|':>16s}")
    histories = sorted({r["history"] for r in rows})
    rng = np.random.default_rng(1)
    for n in NAMES:
        z = np.array([(r["value"][n] - _truth_values(r["history"])[n]) / se_of(r, n) for r in rows])
        e = np.array([r["value"][n] / _truth_values(r["history"])[n] - 1 for r in rows])
        # 95 % interval of the RMS z by a bootstrap over histories (a history's realisations share its discretisation error)
        by = {i: z[[r["history"] == i for r in rows]] for i in histories}
        boot = [np.sqrt(np.mean(np.concatenate([by[i] for i in rng.choice(histories, len(histories))]) ** 2)) for _ in range(2000)]
        lo, hi = np.percentile(boot, [2.5, 97.5])
        rms = np.sqrt(np.mean(z**2))
        print(f"{n:14s} {np.mean(np.abs(z) <= 1.96):14.1%} {rms:13.3f} {f'{lo:.2f}-{hi:.2f}':>14s} {np.mean(e):+11.2%} {np.max(np.abs(e)):16.2%}")
    print("per history: coverage (RMS z) of F0, t_F0, T; mean error of t_F0")
    for i in sorted({r["history"] for r in rows}):
        h, rs = HISTORIES[i], [r for r in rows if r["history"] == i]
        cells = []
        for n in NAMES:
            z = np.array([(r["value"][n] - _truth_values(i)[n]) / se_of(r, n) for r in rs])
            cells.append(f"{np.mean(np.abs(z) <= 1.96):4.0%} ({np.sqrt(np.mean(z**2)):.2f})")
        e = np.mean([r["value"]["time_of_peak"] / _truth_values(i)["time_of_peak"] - 1 for r in rs])
        print(f"  {h[0][6:]:11s} V {h[1]:4d} t_F0 {h[3]:2d} µs: " + "  ".join(cells) + f"  t_F0 {e:+.1%}")


def main(n: int = 17, workers: int = 2) -> None:
    CACHE.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    with ProcessPoolExecutor(workers) as pool:
        list(pool.map(truth, sorted({h[0] for h in HISTORIES})))
    print(f"truth strains: {time.perf_counter() - t0:.0f} s", file=sys.stderr, flush=True)
    done = CACHE / "calibrations.jsonl"
    rows = [json.loads(line) for line in done.read_text().splitlines()] if done.exists() else []
    have = {(r["history"], r["seed"]) for r in rows}
    tasks = [(i, [s for s in range(n) if (i, s) not in have]) for i in range(len(HISTORIES))]
    tasks = [(i, s[k : k + 3]) for i, s in tasks for k in range(0, len(s), 3) if s]
    with ProcessPoolExecutor(workers) as pool, done.open("a") as f:
        for batch in pool.map(calibrate_realisations, *zip(*tasks)) if tasks else []:
            for r in batch:
                f.write(json.dumps(r) + "\n")
                rows.append(r)
            f.flush()
            print(f"{len(rows)} calibrations, {time.perf_counter() - t0:.0f} s", file=sys.stderr, flush=True)
    if n:
        summarise([r for r in rows if r["seed"] < n])


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:3]))
