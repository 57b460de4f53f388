"""Whether single precision would make the nearest-correlation Newton method's eigendecompositions
cheaper: NumPy's eigh (LAPACK's dsyevd / ssyevd from Debian's OpenBLAS, as spdfit links) of the
same random symmetric n x n matrix in float64 and float32, alternating, wall and CPU seconds.

    /usr/bin/python3 bench/eigh_precision.py N
"""
import resource
import sys
import time

import numpy as np


def cpu_seconds():
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def main(n):
    rng = np.random.default_rng(1)
    A = rng.standard_normal((n, n))
    S = (A + A.T) / 2
    for _ in range(2):
        for dtype in (np.float64, np.float32):
            M = S.astype(dtype)
            cpu, wall = cpu_seconds(), time.time()
            np.linalg.eigh(M)
            print(f"{dtype.__name__}: wall {time.time() - wall:.2f} s, CPU {cpu_seconds() - cpu:.2f} s", flush=True)


if __name__ == "__main__":
    main(int(sys.argv[1]))
