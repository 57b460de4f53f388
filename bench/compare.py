"""Speed of spdfit (through its Python module) against plain NumPy/SciPy code for the same estimators.

What is compared, and why: someone who could write each estimator in a few lines of NumPy
wants to know what spdfit costs or saves. The NumPy side below is the straightforward
textbook code, written for this script from the formulas of the source documents:

    ls          np.linalg.lstsq(A, B)
    procrustes  scipy.linalg.solve_continuous_lyapunov(P, C), P = AᵀA, C = AᵀB + BᵀA (thesis eq. 3.15)
    tls         X = -V12 V22⁻¹ from np.linalg.svd([A B]) (thesis eq. 4.37)
    tls-sym     (X_tls + X_tlsᵀ) / 2
    tls-psd     X_tls-sym with its negative eigenvalues set to zero (Higham)
    spde        X = P^-1/2 (P^1/2 Q P^1/2)^1/2 P^-1/2, P = AᵀA, Q = BᵀB, square roots by eigh
                (Chen & McInroy, Theorem III.3)

spdfit does more per call than these lines: it works from the Householder QR of [A B] instead
of the Gram matrices (for accuracy on ill-conditioned A), and every result carries diagnostics
(ranks and condition numbers of A and B, residual, definiteness, area criterion). The timings
are of the public calls as a user makes them, so that work is included.

Both sides run on the same inputs in one process; repetitions alternate between spdfit and
NumPy (in alternating order) so that a change in machine load hits both alike, and the table
shows medians. Before timing, the script checks that both give the same X on these
well-conditioned data (max |X_spdfit - X_numpy| / max |X_numpy|), so that like is compared
with like.

It also times the Monte Carlo experiments of the Python module (spdfit.experiment.paper_2x2
and thesis) and, for comparison, a vectorized NumPy batch of the paper's 2x2 example (60,000
trials, closed forms on stacked arrays).

    /usr/bin/python3 bench/compare.py [--repeats 21] [--large] [--clock cpu] [--out bench/results/FILE.md]

On a machine busy with other work, --clock cpu times by this process's CPU time instead of
wall time (the Monte Carlo runs always show both).

Without an installed spdfit, the module is taken from build/python when that exists.
"""
import argparse
import datetime
import gc
import os
import pathlib
import platform
import statistics
import subprocess
import sys
import time
import warnings

import numpy as np
import scipy
import scipy.linalg

from machine import cpu_model

try:
    import spdfit
except ImportError:
    _BUILT = pathlib.Path(__file__).resolve().parents[1] / "build" / "python"
    if not _BUILT.is_dir():
        raise
    sys.path.insert(0, str(_BUILT))
    import spdfit

SIZES = [(4, 2), (12, 6), (24, 12), (400, 100)]
LARGE_SIZE = (4000, 1000)
METHODS = ("ls", "procrustes", "tls", "tls-sym", "tls-psd", "spde")
TOLERANCE = 1e-8  # loose: the two sides use different algorithms (QR vs Gram matrices)


# ---- The NumPy/SciPy estimators --------------------------------------------------------------

def numpy_ls(A, B):
    return np.linalg.lstsq(A, B, rcond=None)[0]


def numpy_procrustes(A, B):
    P = A.T @ A
    C = A.T @ B + B.T @ A
    return scipy.linalg.solve_continuous_lyapunov(P, C)  # P X + X P = C


def numpy_tls(A, B):
    n = A.shape[1]
    V = np.linalg.svd(np.hstack([A, B]), full_matrices=False)[2].T
    V12, V22 = V[:n, n:], V[n:, n:]
    return -np.linalg.solve(V22.T, V12.T).T  # -V12 V22^-1


def numpy_tls_sym(A, B):
    X = numpy_tls(A, B)
    return (X + X.T) / 2


def numpy_tls_psd(A, B):
    w, V = np.linalg.eigh(numpy_tls_sym(A, B))
    return (V * np.maximum(w, 0.0)) @ V.T


def numpy_spde(A, B):
    w, V = np.linalg.eigh(A.T @ A)
    root = np.sqrt(w)
    P_half = (V * root) @ V.T
    P_minus_half = (V / root) @ V.T
    mu, W = np.linalg.eigh(P_half @ (B.T @ B) @ P_half)
    M_half = (W * np.sqrt(np.maximum(mu, 0.0))) @ W.T
    return P_minus_half @ M_half @ P_minus_half


NUMPY = {"ls": numpy_ls, "procrustes": numpy_procrustes, "tls": numpy_tls, "tls-sym": numpy_tls_sym,
         "tls-psd": numpy_tls_psd, "spde": numpy_spde}


# ---- The paper's 2x2 example as one vectorized NumPy batch -----------------------------------

PAPER_X = np.array([[3.0, 1.0], [1.0, 1.0]])
PAPER_A0 = np.array([[5.0, 2.0], [-3.0, 1.0], [1.0, -2.0], [-1.0, 1.0]])


def batch_data(rng, trials, std_a, std_b=1.0):
    """A, B of shape (trials, 4, 2): the paper's A0 and A0 X plus Gaussian noise."""
    A = PAPER_A0 + std_a * rng.standard_normal((trials, 4, 2))
    B = PAPER_A0 @ PAPER_X + std_b * rng.standard_normal((trials, 4, 2))
    return A, B


def transpose(S):
    return np.swapaxes(S, -1, -2)


def batch_spde(A, B):
    """SPDE of every trial at once: the Gram formula with stacked eigh."""
    w, V = np.linalg.eigh(transpose(A) @ A)
    root = np.sqrt(w)[..., None, :]
    P_half = (V * root) @ transpose(V)
    P_minus_half = (V / root) @ transpose(V)
    mu, W = np.linalg.eigh(P_half @ (transpose(B) @ B) @ P_half)
    M_half = (W * np.sqrt(np.maximum(mu, 0.0))[..., None, :]) @ transpose(W)
    return P_minus_half @ M_half @ P_minus_half


def batch_procrustes(A, B):
    """P X + X P = C for symmetric P = V diag(l) Vᵀ: X = V [(VᵀCV)_ij / (l_i + l_j)] Vᵀ."""
    l, V = np.linalg.eigh(transpose(A) @ A)
    AtB = transpose(A) @ B
    C = AtB + transpose(AtB)
    return V @ ((transpose(V) @ C @ V) / (l[..., :, None] + l[..., None, :])) @ transpose(V)


def batch_tls(A, B):
    n = A.shape[-1]
    V = transpose(np.linalg.svd(np.concatenate([A, B], axis=-1))[2])
    return -transpose(np.linalg.solve(transpose(V[..., n:, n:]), transpose(V[..., :n, n:])))


def batch_all(A, B):
    """What spdfit's paper_2x2 reports: procrustes, tls and spde per trial."""
    return batch_procrustes(A, B), batch_tls(A, B), batch_spde(A, B)


def entry_mae(X):
    """Mean absolute error of x11, x12, x22 over the trials (the paper's Figure 3)."""
    E = np.abs(X - PAPER_X)
    return np.array([E[:, 0, 0].mean(), E[:, 0, 1].mean(), E[:, 1, 1].mean()])


# ---- Timing ----------------------------------------------------------------------------------

# The clock of the estimator timings: wall time, or with --clock cpu this process's CPU time,
# which leaves out the time the process waits while other programs run on a busy machine. spdfit's
# estimators run on one thread; with a multithreaded BLAS under NumPy the CPU clock would add up
# its threads' time, so use the wall clock there.
CLOCKS = {"wall": time.perf_counter, "cpu": time.process_time}
clock = CLOCKS["wall"]


def _time(fn, number):
    start = clock()
    for _ in range(number):
        fn()
    return (clock() - start) / number


def _calibrate(fn, target):
    """Calls per sample so that one sample takes about `target` seconds (at least one call).

    Returns (number, seconds per call of the last calibration sample)."""
    number = 1
    while True:
        seconds = _time(fn, number)
        if seconds * number >= target:
            return number, seconds
        number = max(number * 2, int(number * target / max(seconds * number, 1e-9) * 1.2))


def time_pair(first, second, repeats, target):
    """Median seconds per call of two functions, samples alternating between them.

    Calls slower than 0.5 s are not repeated for warm-up: their calibration call is a sample."""
    gc_was_enabled = gc.isenabled()
    gc.disable()
    try:
        plans = [_calibrate(fn, target) for fn in (first, second)]
        samples = [[seconds] if seconds >= 0.5 else [] for _, seconds in plans]
        for r in range(repeats):
            order = (0, 1) if r % 2 == 0 else (1, 0)
            for i in order:
                if len(samples[i]) < repeats:
                    samples[i].append(_time((first, second)[i], plans[i][0]))
    finally:
        if gc_was_enabled:
            gc.enable()
    return statistics.median(samples[0]), statistics.median(samples[1])


def time_once(fn):
    """(wall seconds, CPU seconds of this process, result) of one call."""
    wall, cpu = time.perf_counter(), time.process_time()
    result = fn()
    return time.perf_counter() - wall, time.process_time() - cpu, result


def fmt_time(seconds):
    if seconds < 1e-3:
        return f"{seconds * 1e6:.1f} µs"
    if seconds < 1.0:
        return f"{seconds * 1e3:.2f} ms"
    return f"{seconds:.2f} s"


# ---- The report ------------------------------------------------------------------------------

def linear_algebra_libraries():
    """The BLAS/LAPACK files NumPy has loaded (reference BLAS and OpenBLAS differ tenfold)."""
    found = set()
    try:
        with open("/proc/self/maps") as f:
            for line in f:
                path = line.split()[-1] if len(line.split()) >= 6 else ""
                name = os.path.basename(path).lower()
                if name.startswith("lib") and any(key in name for key in ("blas", "lapack", "mkl")):
                    found.add(os.path.realpath(path))
    except OSError:
        pass
    return ", ".join(sorted(found)) or "unknown"


def source_revision():
    """The commit of the checkout this script is in (the build being timed may differ)."""
    try:
        out = subprocess.run(["git", "-C", str(pathlib.Path(__file__).resolve().parent), "describe", "--always",
                              "--dirty"], capture_output=True, text=True, timeout=10)
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    return out.stdout.strip() if out.returncode == 0 else "unknown"


def load_average():
    try:
        return " ".join(f"{x:.2f}" for x in os.getloadavg())
    except OSError:
        return "unknown"


def make_data(rng, m, n):
    """As bench_estimators.cpp: uniform entries in [-5, 5], X = W Wᵀ + n I, noise 0.3 in A and B."""
    W = rng.uniform(-5, 5, (n, n))
    X = W @ W.T + n * np.eye(n)
    A0 = rng.uniform(-5, 5, (m, n))
    return A0 + 0.3 * rng.uniform(-5, 5, (m, n)), A0 @ X + 0.3 * rng.uniform(-5, 5, (m, n))


def compare_estimators(sizes, repeats, target, emit):
    emit("## Estimators: median time per call")
    emit("")
    emit("| m × n | method | spdfit | NumPy/SciPy | NumPy / spdfit | max rel. diff. of X |")
    emit("|---|---|---:|---:|---:|---:|")
    rng = np.random.default_rng(42)
    mismatches = []
    for m, n in sizes:
        A, B = make_data(rng, m, n)
        for method in METHODS:
            ours = lambda: spdfit.fit(A, B, method=method)  # noqa: E731
            theirs = lambda: NUMPY[method](A, B)  # noqa: E731
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                X_ours = ours().X
            X_theirs = theirs()
            diff = np.max(np.abs(X_ours - X_theirs)) / np.max(np.abs(X_theirs))
            if not diff <= TOLERANCE or caught:
                mismatches.append(f"{m}×{n} {method}: rel. diff. {diff:.1e}"
                                  + "".join(f"; warning: {w.message}" for w in caught))
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                t_ours, t_theirs = time_pair(ours, theirs, repeats, target)
            emit(f"| {m} × {n} | {method} | {fmt_time(t_ours)} | {fmt_time(t_theirs)} "
                 f"| {t_theirs / t_ours:.2f} | {diff:.1e} |")
    emit("")
    if mismatches:
        emit(f"**Not the same X to {TOLERANCE:g}, or spdfit warned:** " + "; ".join(mismatches))
    else:
        emit(f"Every X agrees to {TOLERANCE:g} (relative to its largest entry) and spdfit warned about nothing.")
    emit("")


def call_overhead(repeats, target, emit):
    """What the Python layer of spdfit.fit (argument checks, warnings) adds to the binding."""
    A, B = make_data(np.random.default_rng(7), 4, 2)
    core = spdfit._spdfit.fit
    t_public, t_core = time_pair(lambda: spdfit.fit(A, B, method="spde"), lambda: core(A, B, "spde", None),
                                 repeats, target)
    emit(f"Call overhead at 4 × 2 (spde): spdfit.fit {fmt_time(t_public)}, the binding "
         f"spdfit._spdfit.fit alone {fmt_time(t_core)}.")
    emit("")


def compare_experiments(emit):
    trials, std_a = 60000, 1.0
    emit(f"## Monte Carlo: the paper's 2×2 example, {trials:,} trials at std_a = {std_a}, std_b = 1 (one run each)")
    emit("")
    emit("spdfit's experiment computes procrustes, tls and spde for each trial from one shared reduction"
         " of [A B] (QR, SVD of R11, factor of B); the NumPy batch computes only what it names.")
    emit("")
    emit("| what | wall time | per trial | CPU time | MAE of x11, x12, x22 (spde) |")
    emit("|---|---:|---:|---:|---|")
    rows = []
    for threads in (1, 0):
        wall, cpu, result = time_once(
            lambda: spdfit.experiment.paper_2x2(std_a, trials=trials, threads=threads))
        spde_stats = next(s for s in result.methods if s.method == "spde")
        label = "1 thread" if threads == 1 else f"all cores ({os.cpu_count()})"
        rows.append((f"spdfit.experiment.paper_2x2, {label}", wall, cpu, np.asarray(spde_stats.mae)))
    rng = np.random.default_rng(1)
    wall, cpu, (A, B) = time_once(lambda: batch_data(rng, trials, std_a))
    rows.append(("NumPy: draw the data", wall, cpu, None))
    wall, cpu, X = time_once(lambda: batch_spde(A, B))
    rows.append(("NumPy batch: spde (Gram formula, stacked eigh)", wall, cpu, entry_mae(X)))
    wall, cpu, (_, _, X) = time_once(lambda: batch_all(A, B))
    rows.append(("NumPy batch: procrustes + tls + spde", wall, cpu, entry_mae(X)))
    for label, wall, cpu, mae in rows:
        mae_text = "" if mae is None else ", ".join(f"{v:.4f}" for v in mae)
        emit(f"| {label} | {fmt_time(wall)} | {fmt_time(wall / trials)} | {fmt_time(cpu)} | {mae_text} |")
    emit("")
    emit("The MAEs differ only by Monte Carlo error (different random numbers).")
    emit("")

    emit("## Monte Carlo: the thesis' experiment 2 (V = 0.86, m = 12, n = 6), 2,000 trials (one run each)")
    emit("")
    emit("| what | wall time | per trial | CPU time |")
    emit("|---|---:|---:|---:|")
    for threads in (1, 0):
        wall, cpu, _ = time_once(lambda: spdfit.experiment.thesis(0.86, trials=2000, threads=threads))
        label = "1 thread" if threads == 1 else f"all cores ({os.cpu_count()})"
        emit(f"| spdfit.experiment.thesis, {label} | {fmt_time(wall)} | {fmt_time(wall / 2000)} | {fmt_time(cpu)} |")
    emit("")


def parse_size(text):
    m, n = (int(v) for v in text.lower().split("x"))
    return m, n


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeats", type=int, default=21, help="timed samples per side (default 21)")
    parser.add_argument("--large", action="store_true", help=f"also {LARGE_SIZE[0]} × {LARGE_SIZE[1]} (slow)")
    parser.add_argument("--sizes", nargs="+", type=parse_size, metavar="MxN",
                        help="only these sizes, e.g. --sizes 4000x1000 (overrides the defaults and --large)")
    parser.add_argument("--no-experiments", action="store_true", help="skip the Monte Carlo timings")
    parser.add_argument("--target", type=float, default=0.005,
                        help="seconds one sample should last; fast calls are looped (default 0.005)")
    parser.add_argument("--clock", choices=sorted(CLOCKS), default="wall",
                        help="time the estimators by wall time (default) or by this process's CPU time")
    parser.add_argument("--out", type=pathlib.Path, help="also write the report as Markdown to this file")
    args = parser.parse_args()
    sizes = args.sizes or SIZES + ([LARGE_SIZE] if args.large else [])
    global clock
    clock = CLOCKS[args.clock]

    lines = []

    def emit(line):
        print(line, flush=True)
        lines.append(line)

    emit("# spdfit against NumPy/SciPy")
    emit("")
    emit(f"- CPU: {cpu_model()} ({os.cpu_count()} logical CPUs)")
    emit(f"- date: {datetime.datetime.now().astimezone().strftime('%Y-%m-%d %H:%M %Z')}")
    emit(f"- spdfit {spdfit.__version__} ({pathlib.Path(spdfit.__file__).parent}), NumPy {np.__version__}, "
         f"SciPy {scipy.__version__}, Python {platform.python_version()}")
    emit(f"- source checkout: {source_revision()}")
    emit(f"- NumPy's BLAS/LAPACK: {linear_algebra_libraries()}")
    emit(f"- load average at start: {load_average()}")
    emit(f"- medians of {args.repeats} samples per side, {args.clock} clock; "
         "NumPy / spdfit > 1 means spdfit is faster")
    emit("")
    compare_estimators(sizes, args.repeats, args.target, emit)
    call_overhead(args.repeats, args.target, emit)
    if not args.no_experiments:
        compare_experiments(emit)
    emit(f"Load average at end: {load_average()}")
    if args.out:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
