"""Speed of spdfit.nearest_correlation (issue 16) against one symmetric eigendecomposition of the
same size (numpy.linalg.eigh), best of `repeats` runs each.

The test matrices: symmetric, unit diagonal, off-diagonal entries (M + M^T)/2 with M uniform on
[-1, 1] from numpy.random.default_rng(1), n = 100, 500, 1000.

    PYTHONPATH=build/python /usr/bin/python3 bench/nearest_correlation_speed.py [repeats]
"""
import os
import sys
import time

import numpy as np

import spdfit

from machine import cpu_model


def best(fn, repeats):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        value = fn()
        times.append(time.perf_counter() - start)
    return min(times), value


def main():
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    cpu = cpu_model()
    print(f"# nearest_correlation speed: {time.strftime('%Y-%m-%d')}, {cpu}, {os.cpu_count()} cores\n")
    print(f"`PYTHONPATH=build/python /usr/bin/python3 bench/nearest_correlation_speed.py {repeats}`; "
          f"OPENBLAS_CORETYPE={os.environ.get('OPENBLAS_CORETYPE', '(unset)')}\n")
    print("| n | nearest_correlation (s) | Newton iterations | numpy eigh (s) | ratio |")
    print("|---|---|---|---|---|")
    for n in (100, 500, 1000):
        M = np.random.default_rng(1).uniform(-1, 1, (n, n))
        C = (M + M.T) / 2
        np.fill_diagonal(C, 1.0)
        seconds, result = best(lambda: spdfit.nearest_correlation(C, full_output=True), repeats)
        eigh, _ = best(lambda: np.linalg.eigh(C), repeats)
        assert result.converged
        print(f"| {n} | {seconds:.3f} | {result.iterations} | {eigh:.3f} | {seconds / eigh:.0f} |", flush=True)


if __name__ == "__main__":
    main()
