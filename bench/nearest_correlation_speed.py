"""Speed and memory of spdfit.nearest_correlation: against one symmetric eigendecomposition of the
same size (numpy.linalg.eigh, LAPACK's dsyevd on the same OpenBLAS: the Newton method's unit of
work) and against R's Matrix::nearPD(corr = TRUE) (alternating projections) on the same
matrices, best of `repeats` runs each (from n = 5000 one; eigh's best of the runs before and after
spdfit's; nearPD: one run, stopped after `r_timeout` seconds). Wall time, and the CPU time of the
process (every thread: the steadier measure on a shared machine, where the wall time includes
waiting for a core).

The test matrices (the generator, seeded): symmetric, unit diagonal, off-diagonal entries
(M + M^T)/2 with M uniform on [-1, 1] from numpy.random.default_rng(1). Both are asked for the
plain nearest correlation matrix (spdfit: min_eig=0; nearPD: posd.tol's final clip off with
do2eigen = FALSE, its default tolerances otherwise), and the distances ||X - C||_F are
compared: nearPD stops at a relative change of 1e-6 (conv.tol), so its answer is a little
farther.

Memory: the peak resident set of this process during the call (/proc/self/status sampled every
10 ms), less the resident set just before it (C itself and the interpreter), in units of n^2
doubles: spdfit's working memory including the Python binding's column-major copy of C, and
eigh's for comparison (its output and dsyevd's workspace). nearPD's: the peak resident set of
the R process (getrusage of the child), less R's own start (measured once, n = 10), in n^2
doubles (C is one of them).

R is a benchmark dependency, not a test one: `apt-get install r-base-core r-cran-matrix`; without
Rscript the nearPD columns say so. nearPD runs at n <= `r_max_n`.

    PYTHONPATH=build/python /usr/bin/python3 bench/nearest_correlation_speed.py [repeats] [r_max_n] [sizes] [r_timeout]

sizes: comma-separated (default 100,500,1000,3000); r_timeout in seconds (default 600).
"""
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import threading
import time

import numpy as np

import spdfit

from machine import cpu_model

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


def resident_bytes():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) * 1024
    return 0


def measured(fn, repeats):
    """(best wall seconds, best CPU seconds of this process (every thread), peak resident increase
    in bytes over all runs, the last value)."""
    times, cpu_times, peak_increase = [], [], 0
    value = None
    for _ in range(repeats):
        value = None  # the previous answer freed first
        before = resident_bytes()
        peak = [before]
        done = threading.Event()

        def sample():
            while not done.wait(0.01):
                peak[0] = max(peak[0], resident_bytes())

        sampler = threading.Thread(target=sample)
        sampler.start()
        start, cpu_start = time.perf_counter(), time.process_time()
        value = fn()
        times.append(time.perf_counter() - start)
        cpu_times.append(time.process_time() - cpu_start)
        done.set()
        sampler.join()
        peak_increase = max(peak_increase, max(peak[0], resident_bytes()) - before)
    return min(times), min(cpu_times), peak_increase, value


def openblas_environment():
    """The OPENBLAS_* variables set (OPENBLAS_CORETYPE chooses the kernels: see performance.md)."""
    names = sorted(name for name in os.environ if name.startswith("OPENBLAS_"))
    return ", ".join(f"{name}={os.environ[name]}" for name in names) or "none set"


def test_matrix(n):
    M = np.random.default_rng(1).uniform(-1, 1, (n, n))
    C = (M + M.T) / 2
    np.fill_diagonal(C, 1.0)
    return C


def near_pd(C, repeats, workdir, timeout):
    """(seconds, iterations, answer, peak resident bytes of R) of R's nearPD(C, corr = TRUE), the
    string "timeout" when it did not finish in `timeout` seconds, or None without Rscript."""
    if shutil.which("Rscript") is None:
        return None
    n = C.shape[0]
    source, answer, script = (os.path.join(workdir, name) for name in ("C.bin", "X.bin", "near.R"))
    np.asfortranarray(C).T.tofile(source)  # column-major, as R reads it
    with open(script, "w") as f:
        f.write(R_SCRIPT)
    # Run in a child of a child, so that getrusage(RUSAGE_CHILDREN) of that middle process is R's
    # peak alone (this process's children's maximum would include every earlier R run).
    probe = ("import resource, subprocess, sys; "
             "out = subprocess.run(sys.argv[1:], capture_output=True, text=True, check=True, timeout=%d).stdout; "
             "print(out.strip(), resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)" % timeout)
    try:
        out = subprocess.run([sys.executable, "-c", probe, "Rscript", script, source, answer, str(repeats), str(n)],
                             capture_output=True, text=True, check=True).stdout.split()
    except subprocess.CalledProcessError as error:
        if "TimeoutExpired" in error.stderr:
            return "timeout"
        raise
    X = np.fromfile(answer).reshape(n, n).T
    return float(out[0]), int(out[1]), X, int(out[2]) * 1024


def main():
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    r_max_n = int(sys.argv[2]) if len(sys.argv) > 2 else 1000
    sizes = tuple(int(v) for v in sys.argv[3].split(",")) if len(sys.argv) > 3 else (100, 500, 1000, 3000)
    r_timeout = int(sys.argv[4]) if len(sys.argv) > 4 else 600
    cpu = cpu_model()
    print(f"# nearest_correlation speed: {time.strftime('%Y-%m-%d')}, {cpu}, {os.cpu_count()} cores\n")
    print(f"`PYTHONPATH=build/python /usr/bin/python3 bench/nearest_correlation_speed.py {repeats} {r_max_n} "
          f"{','.join(map(str, sizes))} {r_timeout}`; OpenBLAS's environment: {openblas_environment()}; spdfit "
          f"and R both on Debian's OpenBLAS; load average at the start {os.getloadavg()[0]:.1f}\n")
    print("| n | spdfit (s) | spdfit CPU (s) | Newton iterations | spdfit memory (n² doubles) | numpy eigh (s) "
          "| eigh CPU (s) | eigh memory (n² doubles) | spdfit / eigh | CPU: spdfit / eigh | R nearPD (s) "
          "| nearPD iterations | nearPD memory (n² doubles) | nearPD / spdfit | distance: spdfit | distance: nearPD |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as workdir:
        r_start = None
        for n in sizes:
            C = test_matrix(n)
            unit = 8.0 * n * n
            runs = repeats if n < 5000 else 1
            # eigh before and after spdfit, the best of both: the machine's load can change in between.
            eigh, eigh_cpu, eigh_memory, _ = measured(lambda: np.linalg.eigh(C), runs)
            seconds, cpu, memory, result = measured(lambda: spdfit.nearest_correlation(C, min_eig=0, full_output=True),
                                                    runs)
            assert result.converged
            distance, iterations = result.distance, result.iterations
            del result
            after, after_cpu, _, _ = measured(lambda: np.linalg.eigh(C), runs)
            eigh, eigh_cpu = min(eigh, after), min(eigh_cpu, after_cpu)
            cells = [str(n), f"{seconds:.3f}", f"{cpu:.3f}", str(iterations), f"{memory / unit:.2f}", f"{eigh:.3f}",
                     f"{eigh_cpu:.3f}", f"{eigh_memory / unit:.2f}", f"{seconds / eigh:.1f}", f"{cpu / eigh_cpu:.1f}"]
            r = None
            if n <= r_max_n and shutil.which("Rscript") is not None:
                if r_start is None:  # R's own resident set (interpreter, Matrix), from a tiny run
                    r_start = near_pd(test_matrix(10), 1, workdir, r_timeout)[3]
                r = near_pd(C, 1, workdir, r_timeout)
            if r is None:
                reason = "(no Rscript)" if shutil.which("Rscript") is None else f"(not run above n = {r_max_n})"
                cells += [reason, "", "", "", f"{distance:.6f}", ""]
            elif r == "timeout":
                cells += [f"> {r_timeout} (stopped)", "", "", "", f"{distance:.6f}", ""]
            else:
                r_seconds, r_iterations, X, r_peak = r
                cells += [f"{r_seconds:.2f}", str(r_iterations), f"{(r_peak - r_start) / unit:.2f}",
                          f"{r_seconds / seconds:.0f}", f"{distance:.6f}", f"{np.linalg.norm(X - C):.6f}"]
            print("| " + " | ".join(cells) + " |", flush=True)
    print(f"\nLoad average at the end {os.getloadavg()[0]:.1f}.")


if __name__ == "__main__":
    main()
