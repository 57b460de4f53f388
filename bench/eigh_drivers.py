"""LAPACK's symmetric eigensolvers with eigenvectors on the same OpenBLAS: dsyevd (divide and
conquer, what numpy.linalg.eigh and spdfit's symmetric_eigen use; workspace 2 n^2 doubles besides
the matrix it overwrites) against dsyevr (MRRR; no n x n workspace, but its eigenvectors go to a
second n x n array), and ssyevd (divide and conquer in single precision: whether the nearest
correlation's early Newton steps could save time in it), through scipy.linalg.eigh(driver=...),
alternating, best of `repeats`, wall and CPU time (the CPU time of both threads when OpenBLAS runs
two). The choice behind src/repair/correlation_newton.cpp's in-place dsyevd.

    /usr/bin/python3 bench/eigh_drivers.py [sizes] [repeats]

sizes comma-separated (default 1000,3000).
"""
import os
import sys
import time

import numpy as np
import scipy.linalg

from machine import cpu_model


def main():
    sizes = tuple(int(v) for v in sys.argv[1].split(",")) if len(sys.argv) > 1 else (1000, 3000)
    repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 3
    names = sorted(name for name in os.environ if name.startswith("OPENBLAS_"))
    environment = ", ".join(f"{name}={os.environ[name]}" for name in names) or "none set"
    print(f"# dsyevd against dsyevr and ssyevd: {time.strftime('%Y-%m-%d')}, {cpu_model()}, {os.cpu_count()} cores\n")
    print(f"`/usr/bin/python3 bench/eigh_drivers.py {','.join(map(str, sizes))} {repeats}`; OpenBLAS's environment: "
          f"{environment}; load average at the start {os.getloadavg()[0]:.1f}\n")
    print("| n | dsyevd wall (s) | dsyevd CPU (s) | dsyevr wall (s) | dsyevr CPU (s) | ssyevd wall (s) | ssyevd CPU (s) |")
    print("|---|---|---|---|---|---|---|")
    for n in sizes:
        M = np.random.default_rng(1).uniform(-1, 1, (n, n))
        C = (M + M.T) / 2
        best = {}
        for _ in range(repeats):
            for name, driver, dtype in (("evd", "evd", np.float64), ("evr", "evr", np.float64),
                                        ("sevd", "evd", np.float32)):
                A = np.asfortranarray(C, dtype=dtype)
                wall, cpu = time.perf_counter(), time.process_time()
                scipy.linalg.eigh(A, driver=driver, overwrite_a=True, check_finite=False)
                wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
                old = best.get(name, (float("inf"), float("inf")))
                best[name] = (min(old[0], wall), min(old[1], cpu))
        cells = " | ".join(f"{best[name][0]:.2f} | {best[name][1]:.2f}" for name in ("evd", "evr", "sevd"))
        print(f"| {n} | {cells} |", flush=True)
    print(f"\nLoad average at the end {os.getloadavg()[0]:.1f}.")


if __name__ == "__main__":
    main()
