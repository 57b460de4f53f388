"""The singular values of an upper-triangular N x N factor (what the noise estimate needs, N = 2n)
by LAPACK's dgesdd without vectors, against the eigenvalues of the symmetric [0 R; R^T 0] by the
two-stage dsyevd_2stage (LAPACKE, through ctypes): a route with the same absolute accuracy
(eps * sigma_max) whose reduction is matrix-matrix work. Prints the times (best of two) and the
largest difference between the two sets of singular values relative to sigma_max.

    /usr/bin/python3 bench/singular_values_routes.py [N ...]     (default 1000 2000)"""
import ctypes
import sys
import time

import numpy as np
import scipy.linalg as sl

LAPACK_COL_MAJOR = 102


def best_of_two(run):
    best = float("inf")
    for _ in range(2):
        start = time.perf_counter()
        out = run()
        best = min(best, time.perf_counter() - start)
    return best, out


def main():
    sizes = [int(a) for a in sys.argv[1:]] or [1000, 2000]
    lapacke = ctypes.CDLL("liblapacke.so.3")
    syevd = lapacke.LAPACKE_dsyevd_2stage
    syevd.argtypes = [ctypes.c_int, ctypes.c_char, ctypes.c_char, ctypes.c_int, ctypes.c_void_p, ctypes.c_int,
                      ctypes.c_void_p]
    syevd.restype = ctypes.c_int
    rng = np.random.default_rng(1)
    for N in sizes:
        R = np.linalg.qr(rng.standard_normal((2 * N, N)), mode="r")
        R[:, N // 2:] *= 1e-7  # half the singular values small, as noise beside signal
        H = np.zeros((2 * N, 2 * N), order="F")
        H[:N, N:] = R
        H[N:, :N] = R.T
        w = np.empty(2 * N)

        def augmented():
            work = np.asfortranarray(H.copy())
            if syevd(LAPACK_COL_MAJOR, b"N", b"L", 2 * N, work.ctypes.data, 2 * N, w.ctypes.data) != 0:
                raise RuntimeError("dsyevd_2stage failed")
            return np.sort(np.abs(np.sort(w)[::-1][:N]))[::-1]

        t_aug, s_aug = best_of_two(augmented)
        t_svd, s_svd = best_of_two(lambda: sl.svd(R, compute_uv=False, lapack_driver="gesdd"))
        print(f"N = {N}: dgesdd (values) {t_svd:.3f} s, dsyevd_2stage on [0 R; R^T 0] {t_aug:.3f} s, "
              f"max |difference| / sigma_max {np.max(np.abs(s_aug - s_svd)) / s_svd[0]:.1e}")


if __name__ == "__main__":
    main()
