"""LAPACK's symmetric eigensolvers with eigenvectors on the same OpenBLAS: dsyevd (divide and
conquer, what numpy.linalg.eigh and spdfit's symmetric_eigen use; workspace 2 n^2 doubles besides
the matrix it overwrites) against dsyevr (MRRR; no n x n workspace, but its eigenvectors go to a
second n x n array), through scipy.linalg.eigh(driver=...), alternating, best of `repeats`, wall
and CPU time (the CPU time of both threads when OpenBLAS runs two). The choice behind
src/repair/correlation_newton.cpp's in-place dsyevd.

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
    print(f"# dsyevd against dsyevr: {time.strftime('%Y-%m-%d')}, {cpu_model()}, {os.cpu_count()} cores\n")
    print(f"`/usr/bin/python3 bench/eigh_drivers.py {','.join(map(str, sizes))} {repeats}`; OpenBLAS's environment: "
          f"{environment}; load average at the start {os.getloadavg()[0]:.1f}\n")
    print("| n | dsyevd wall (s) | dsyevd CPU (s) | dsyevr wall (s) | dsyevr CPU (s) |")
    print("|---|---|---|---|---|")
    for n in sizes:
        M = np.random.default_rng(1).uniform(-1, 1, (n, n))
        C = (M + M.T) / 2
        best = {}
        for _ in range(repeats):
            for driver in ("evd", "evr"):
                A = np.asfortranarray(C)
                wall, cpu = time.perf_counter(), time.process_time()
                scipy.linalg.eigh(A, driver=driver, overwrite_a=True, check_finite=False)
                wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
                old = best.get(driver, (float("inf"), float("inf")))
                best[driver] = (min(old[0], wall), min(old[1], cpu))
        print(f"| {n} | {best['evd'][0]:.2f} | {best['evd'][1]:.2f} | {best['evr'][0]:.2f} | {best['evr'][1]:.2f} |",
              flush=True)
    print(f"\nLoad average at the end {os.getloadavg()[0]:.1f}.")


if __name__ == "__main__":
    main()
