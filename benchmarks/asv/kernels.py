"""Contact kernels against direct coupled stepping, as asv benchmarks (the cases of bench_kernels.py).

Two targets (the long beam 200 × 6 of paper-long-beam-impact and the 8-in plate at MITC9 16 × 16;
2000 steps of 0.5 µs each): one direct coupled run (energies off, as a sweep runs it), the kernel
build, and kernel runs of the steel ball through Hertz's law and of the 1/2-in silicone-rubber ball at
2000 in/s through the identified law (tests/data/law-v-main.json). The 48² plate and the Monte Carlo
stay in bench_kernels.py (tens of seconds a sample). Run: ``asv run --python=same --quick`` (this
environment, one sample each) or ``asv run`` over commits (BENCHMARKS.md).
"""

import shutil
import sys
import tempfile
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))  # benchmarks/: bench_kernels' cases

import bench_kernels as bk  # noqa: E402

from softimpact.input.impact_case import impact_problem, load_impact_case  # noqa: E402
from softimpact.input.toml import load_toml, locate  # noqa: E402
from softimpact.workflows.coupled import impact_kernels, impact_model, run_impact  # noqa: E402

TARGETS = ["long-beam", "plate-16"]


def _problems(target: str, folder: Path):
    """(steel-ball problem, rubber-ball problem) of a target, as bench_kernels builds them."""
    shutil.copy(bk.LAW, folder / "law.json")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if target == "long-beam":
            steel, _ = load_impact_case("paper-long-beam-impact")
            return steel, bk._rubber(folder, "paper-long-beam")
        case = bk._plate_case(folder, 16)
        data = load_toml(locate("plate-ss-8in-impact"))
        data["target"]["case"] = case
        return impact_problem(data, folder)[0], bk._rubber(folder, case)


class CoupledImpact:
    """Direct coupled run, kernel build and kernel runs on one target (``params``)."""

    params = TARGETS
    param_names = ["target"]
    number = 1
    repeat = (3, 10, 30.0)
    timeout = 600

    def setup(self, target):
        self._tmp = tempfile.TemporaryDirectory()
        self.steel, self.rubber = _problems(target, Path(self._tmp.name))
        self.model = impact_model(self.steel)
        self.kernels = impact_kernels(self.steel, self.model)
        for problem in (self.steel, self.rubber):  # warm: a plate's disc tabulates its compliance on first reach
            self.kernels.run(problem.law, problem.impactor.mass, problem.impactor.velocity)

    def teardown(self, target):
        self._tmp.cleanup()

    def time_direct_run(self, target):
        """One direct coupled run (the reference the build is compared with)."""
        run_impact(self.steel, self.model, energy=False, method="direct")

    def time_kernel_build(self, target):
        """The kernel build (issue 21: at most twice one direct run)."""
        impact_kernels(self.steel, self.model)

    def time_kernel_run_hertz(self, target):
        """A kernel run of the steel ball through Hertz's law."""
        imp = self.steel.impactor
        self.kernels.run(self.steel.law, imp.mass, imp.velocity)

    def time_kernel_run_identified(self, target):
        """A kernel run of the rubber ball through the identified law with its Maxwell arm (issue 21: ≤ 10 ms on the long beam)."""
        imp = self.rubber.impactor
        self.kernels.run(self.rubber.law, imp.mass, imp.velocity)

    def track_build_over_direct(self, target):
        """Kernel build over one direct run (a ratio: the machine's speed cancels)."""
        import time

        t0 = time.perf_counter()
        run_impact(self.steel, self.model, energy=False, method="direct")
        t1 = time.perf_counter()
        impact_kernels(self.steel, self.model)
        return (time.perf_counter() - t1) / (t1 - t0)

    track_build_over_direct.unit = "ratio"
