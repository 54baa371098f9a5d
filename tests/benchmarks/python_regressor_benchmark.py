"""idbench.regressor from Python on 100 000 PUMA 560 samples (Fv, Fc: 48 base
parameters), the problem of ident_benchmark's BM_StackBaseRegressorPuma560:
numpy arrays in, the stacked W out. Prints the median of the repetitions.

PYTHONPATH=build/workbench/python /usr/bin/python3 tests/benchmarks/python_regressor_benchmark.py
"""
import statistics
import time

import numpy as np

import idbench

N, REPETITIONS = 100_000, 10
rng = np.random.default_rng(2)
q, qd, qdd = (rng.uniform(-2.0, 2.0, (N, 6)) for _ in range(3))
robot = idbench.Robot("puma560")
friction = ["viscous", "coulomb"]
base = idbench.base_parameters(robot, friction)
times = []
for _ in range(REPETITIONS):
    start = time.perf_counter()
    W = idbench.regressor(robot, q, qd, qdd, friction, base=base)
    times.append(time.perf_counter() - start)
assert W.shape == (6 * N, base.n_base)
print(f"idbench.regressor, {N} samples, W {W.shape[0]} x {W.shape[1]}: "
      f"median {1e3 * statistics.median(times):.1f} ms over {REPETITIONS} (min {1e3 * min(times):.1f} ms)")
