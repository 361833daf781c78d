"""asv (airspeed velocity) benchmarks: the cases of benchmarks/bench_kernels.py, timed per commit."""
