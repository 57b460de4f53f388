"""Speed of spdfit.nearest_correlation (issue 16): against one symmetric eigendecomposition of the
same size (numpy.linalg.eigh: the Newton method's unit of work) and against R's
Matrix::nearPD(corr = TRUE) (alternating projections) on the same matrices, best of `repeats`
runs each (nearPD: one run).

The test matrices (the generator, seeded): symmetric, unit diagonal, off-diagonal entries
(M + M^T)/2 with M uniform on [-1, 1] from numpy.random.default_rng(1); n = 100, 500, 1000,
3000. Both are asked for the plain nearest correlation matrix (spdfit: min_eig=0; nearPD:
posd.tol's final clip off with do2eigen = FALSE, its default tolerances otherwise), and the
distances ||X - C||_F are compared: nearPD stops at a relative change of 1e-6 (conv.tol), so
its answer is a little farther.

R is a benchmark dependency, not a test one: `apt-get install r-base-core r-cran-matrix`; without
Rscript the nearPD columns say so. nearPD runs at n <= `r_max_n` (default 1000: at 3000 it takes
minutes).

    PYTHONPATH=build/python /usr/bin/python3 bench/nearest_correlation_speed.py [repeats] [r_max_n]
"""
import os
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

import spdfit

from machine import cpu_model

SIZES = (100, 500, 1000, 3000)

# Times nearPD on the matrix in argv[1] (binary float64, n x n), best of argv[3] runs; writes the
# answer (binary) to argv[2] and prints "seconds iterations".
R_SCRIPT = r"""
args <- commandArgs(trailingOnly = TRUE)
suppressPackageStartupMessages(library(Matrix))
n <- as.integer(args[4])
C <- matrix(readBin(args[1], "double", n * n), n, n)
best <- Inf
for (k in seq_len(as.integer(args[3]))) {
  t <- system.time(r <- nearPD(C, corr = TRUE, do2eigen = FALSE, maxit = 1000))[["elapsed"]]
  best <- min(best, t)
}
writeBin(as.vector(as.matrix(r$mat)), args[2])
cat(best, r$iterations, "\n")
"""


def best(fn, repeats):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        value = fn()
        times.append(time.perf_counter() - start)
    return min(times), value


def test_matrix(n):
    M = np.random.default_rng(1).uniform(-1, 1, (n, n))
    C = (M + M.T) / 2
    np.fill_diagonal(C, 1.0)
    return C


def near_pd(C, repeats, workdir):
    """(seconds, iterations, answer) of R's nearPD(C, corr = TRUE), or None without Rscript."""
    if shutil.which("Rscript") is None:
        return None
    n = C.shape[0]
    source, answer, script = (os.path.join(workdir, name) for name in ("C.bin", "X.bin", "near.R"))
    np.asfortranarray(C).T.tofile(source)  # column-major, as R reads it
    with open(script, "w") as f:
        f.write(R_SCRIPT)
    out = subprocess.run(["Rscript", script, source, answer, str(repeats), str(n)], capture_output=True, text=True,
                         check=True).stdout.split()
    X = np.fromfile(answer).reshape(n, n).T
    return float(out[0]), int(out[1]), X


def main():
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    r_max_n = int(sys.argv[2]) if len(sys.argv) > 2 else 1000
    cpu = cpu_model()
    print(f"# nearest_correlation speed: {time.strftime('%Y-%m-%d')}, {cpu}, {os.cpu_count()} cores\n")
    print(f"`PYTHONPATH=build/python /usr/bin/python3 bench/nearest_correlation_speed.py {repeats} {r_max_n}`; "
          f"OPENBLAS_CORETYPE={os.environ.get('OPENBLAS_CORETYPE', '(unset)')}; spdfit and R both on Debian's "
          "OpenBLAS\n")
    print("| n | spdfit (s) | Newton iterations | numpy eigh (s) | spdfit / eigh | R nearPD (s) | nearPD iterations "
          "| nearPD / spdfit | distance: spdfit | distance: nearPD |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as workdir:
        for n in SIZES:
            C = test_matrix(n)
            seconds, result = best(lambda: spdfit.nearest_correlation(C, min_eig=0, full_output=True), repeats)
            eigh, _ = best(lambda: np.linalg.eigh(C), repeats)
            assert result.converged
            cells = [str(n), f"{seconds:.3f}", str(result.iterations), f"{eigh:.3f}", f"{seconds / eigh:.1f}"]
            r = near_pd(C, 1, workdir) if n <= r_max_n else None
            if r is None:
                reason = "(no Rscript)" if shutil.which("Rscript") is None else f"(not run above n = {r_max_n})"
                cells += [reason, "", "", f"{result.distance:.6f}", ""]
            else:
                r_seconds, r_iterations, X = r
                cells += [f"{r_seconds:.2f}", str(r_iterations), f"{r_seconds / seconds:.0f}", f"{result.distance:.6f}",
                          f"{np.linalg.norm(X - C):.6f}"]
            print("| " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
