"""The structured repairs (spdfit nearest --fixed, --h-weights, --rank, --factors) against their
references, and their speed:

1. optimality: --fixed, --h-weights and both (unit diagonal, --min-eig 0) on `problems` random
   problems n = 5..30 against the semidefinite QP solved by CVXOPT (tolerances 1e-10): the largest
   relative difference of the objective ||H o (X - C)||_F, whether every kept entry is C's to the
   last bit, and spdfit's own certificate (distance - lower_bound);
2. --rank K: against the best of the local methods of tests/support/repair_reference.py
   (Pietersz-Groenen majorization and L-BFGS, each from modified PCA and 3 random starts), with
   spdfit's gap to the convex lower bound;
3. --factors K: against statsmodels' corr_nearest_factor on the matrices of its own tests
   (statsmodels/stats/tests/test_corrpsd.py: sinusoidal loadings, d = 100 and 200);
4. NAG's published examples of g02aj, g02ak, g02ae (and g02aa, g02ab, which the unit tests check);
5. speed at n = `speed_n` (default 1000): plain --corr, --fixed (a kept block of n/10 variables
   plus 1% of the other pairs) and --h-weights (the overlap counts of data with missing values,
   scaled to max 1) on a pairwise-deletion correlation matrix (the realistic input), and on the
   uniform random matrix of bench/nearest_correlation_speed.py (the hard one: half its eigenvalues
   negative), each with its kept block floored at 1e-3 (nearly singular) and at 0.05, interleaved,
   `repeats` runs each, median and spread of wall and CPU time (with SPDFIT_BASE_CLI, another
   build's command beside it);
6. --factors 10 at n = `factor_n` (default 10000) from .npy: the library's time without the read
   (Python, C already in memory), and the command's peak resident set with --factors-only (C is
   n^2 doubles; nothing else of that size).

    PYTHONPATH=build/python /usr/bin/python3 bench/structured_repair.py [problems] [repeats] [speed_n] [factor_n]
"""
import json
import os
import pathlib
import resource
import statistics
import subprocess
import sys
import tempfile
import time
import warnings

import numpy as np

import spdfit

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "support"))
sys.path.insert(0, str(ROOT / "bench"))

import repair_reference as ref  # noqa: E402
from machine import cpu_model  # noqa: E402


def quiet(function, *args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", spdfit.SpdfitWarning)
        return function(*args, **kwargs)


def optimality(problems):
    rng = np.random.default_rng(2024)
    cases = []
    for k in range(problems):
        n = int(rng.integers(5, 31))
        C = ref.random_problem(rng, n)
        kind = ("fixed", "h", "both")[k % 3]
        fixed = None
        if kind in ("fixed", "both"):
            size = max(2, n // 4)
            block = rng.choice(n, size=size, replace=False)
            Z = rng.standard_normal((size, 2 * size))
            B = np.corrcoef(Z)
            C[np.ix_(block, block)] = (B + B.T) / 2  # exactly symmetric: the kept entries are C's
            np.fill_diagonal(C, 1.0)
            fixed = np.zeros((n, n), bool)
            fixed[np.ix_(block, block)] = True
        H = None
        if kind in ("h", "both"):
            H = rng.uniform(0.1, 1.0, (n, n))
            H = (H + H.T) / 2
            H[rng.uniform(size=(n, n)) < 0.05] = 0.0
            H = np.minimum(H, H.T)
        cases.append(dict(C=C, H=H, fixed=fixed, diagonal="unit", kind=kind, n=n))
    started = time.perf_counter()
    answers = ref.cvxopt_in_subprocess([dict(C=c["C"], H=c["H"], fixed=c["fixed"], diagonal="unit") for c in cases])
    cvx_seconds = time.perf_counter() - started
    worst, worst_absolute, worst_gap, exact, ours_seconds = 0.0, 0.0, 0.0, True, 0.0
    rows = []
    for case, (_, theirs) in zip(cases, answers):
        options = dict(min_eig=0, full_output=True)
        if case["fixed"] is not None:
            options["fixed"] = case["fixed"].astype(float)
        if case["H"] is not None:
            options["h_weights"] = case["H"]
        started = time.perf_counter()
        r = quiet(spdfit.nearest_correlation, case["C"], **options)
        ours_seconds += time.perf_counter() - started
        H = np.ones_like(case["C"]) if case["H"] is None else case["H"]
        ours = np.linalg.norm(H * (r.X - case["C"]))
        # Relative to the objective; where the objective is (nearly) 0 (C itself admissible but for
        # weight-0 entries) CVXOPT's answer is 0 only to its tolerance, so those are compared by
        # their absolute difference.
        floor = 1e-6 * np.linalg.norm(case["C"])
        relative = (ours - theirs) / max(theirs, floor)
        if theirs > floor:
            worst = max(worst, abs(relative))
        else:
            worst_absolute = max(worst_absolute, abs(ours - theirs))
        worst_gap = max(worst_gap, (r.distance - r.lower_bound) / max(r.distance, floor))
        if case["fixed"] is not None:
            exact = exact and np.array_equal(r.X[case["fixed"]], case["C"][case["fixed"]])
        rows.append((case["kind"], case["n"], ours, theirs, relative, r.iterations, r.method))
    print(f"## 1. Optimality against CVXOPT ({problems} problems, n = 5..30, unit diagonal, --min-eig 0)\n")
    print("| kind | n | spdfit ||H o (X - C)|| | CVXOPT | relative difference | iterations |")
    print("|---|---|---|---|---|---|")
    for kind, n, ours, theirs, relative, iterations, _ in rows:
        print(f"| {kind} | {n} | {ours:.12f} | {theirs:.12f} | {relative:+.1e} | {iterations} |")
    print(f"\nLargest |relative difference|: {worst:.1e} (goal 1e-6); where the objective is below 1e-6 ||C||, "
          f"the largest absolute difference {worst_absolute:.1e}; kept entries C's to the last bit: {exact}; "
          f"largest relative certificate gap (distance - lower_bound) / distance: {worst_gap:.1e}. "
          f"Time: spdfit {ours_seconds:.2f} s in all, CVXOPT {cvx_seconds:.1f} s (one thread).\n")


def rank_comparison():
    print("## 2. --rank K against the best local method (majorization, L-BFGS; modified PCA and 3 random starts)\n")
    print("| n | K | spdfit | best reference | spdfit / best | convex lower bound | gap | residual | spdfit (s) | reference (s) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    rng = np.random.default_rng(7)
    worst = 0.0
    for n, K in ((20, 2), (30, 3), (40, 5), (60, 4), (80, 6)):
        C = ref.random_problem(rng, n)
        started = time.perf_counter()
        r = quiet(spdfit.nearest_correlation, C, rank=K, full_output=True)
        ours_seconds = time.perf_counter() - started
        started = time.perf_counter()
        best = ref.best_local_rank(C, K, random_starts=3, seed=n)
        their_seconds = time.perf_counter() - started
        worst = max(worst, r.distance / best)
        print(f"| {n} | {K} | {r.distance:.8f} | {best:.8f} | {r.distance / best:.6f} | {r.lower_bound:.6f} | "
              f"{r.distance - r.lower_bound:.4f} | {r.optimality_residual:.1e} | {ours_seconds:.2f} | {their_seconds:.1f} |")
    print(f"\nLargest ratio spdfit / best reference: {worst:.6f} (goal <= 1.001).\n")


def factor_comparison():
    from statsmodels.stats.correlation_tools import _project_correlation_factors, corr_nearest_factor
    print("## 3. --factors K against statsmodels' corr_nearest_factor (its test matrices)\n")
    print("| matrix | K | spdfit ||X - C|| | statsmodels | spdfit (s) | statsmodels (s) |")
    print("|---|---|---|---|---|---|")
    for d, noise, threshold in ((100, 1e-10, None), (200, 1.0, 0.35)):
        for dm in (1, 2):
            X = np.zeros((d, dm))
            x = np.linspace(0, 2 * np.pi, d)
            rs = np.random.RandomState(10)
            if noise < 1e-5:
                np.random.seed(10)
            for j in range(dm):
                X[:, j] = np.sin(x * (j + 1)) + noise * (np.random.randn(d) if noise < 1e-5 else rs.randn(d))
            _project_correlation_factors(X)
            X *= 0.7
            mat = X @ X.T
            np.fill_diagonal(mat, 1.0)
            if threshold is not None:
                mat.flat[np.abs(mat.flat) < threshold] = 0.0
            started = time.perf_counter()
            r = quiet(spdfit.nearest_correlation, mat, factors=dm, full_output=True)
            ours_seconds = time.perf_counter() - started
            started = time.perf_counter()
            theirs = corr_nearest_factor(mat, dm, maxiter=10000).corr.to_matrix()
            their_seconds = time.perf_counter() - started
            name = f"d = {d}" + (f", thresholded at {threshold}" if threshold else "")
            print(f"| {name} | {dm} | {np.linalg.norm(r.X - mat):.10f} | {np.linalg.norm(theirs - mat):.10f} | "
                  f"{ours_seconds:.3f} | {their_seconds:.3f} |")
    print()


def nag_examples():
    G = np.array([[2.0, -1, 0, 0], [-1, 2, -1, 0], [0, -1, 2, -1], [0, 0, -1, 2]])
    Gu = G.copy()
    np.fill_diagonal(Gu, 1.0)
    H = np.array([[0.0, 10, 0, 0], [10, 0, 1.5, 1.5], [0, 1.5, 0, 0], [0, 1.5, 0, 0]])
    aj = quiet(spdfit.nearest_correlation, G, h_weights=H, alpha=0.04, full_output=True)
    ak = quiet(spdfit.nearest_correlation, G, rank=2, full_output=True)
    ae = quiet(spdfit.nearest_correlation, G, factors=2, full_output=True)
    nag_ae = np.array([[1.0, -0.8934, 0.2418, 0.1939], [-0.8934, 1.0, -0.6384, 0.2418],
                       [0.2418, -0.6384, 1.0, -0.8934], [0.1939, 0.2418, -0.8934, 1.0]])
    print("## 4. NAG's published examples (G = tridiag(-1, 2, -1), n = 4)\n")
    print("| routine | NAG prints | spdfit |")
    print("|---|---|---|")
    print(f"| g02aj (H weights, alpha 0.04) | ||H o (G - X)||_F = 0.0572 (H scaled to max 1) | "
          f"{np.linalg.norm(H / 10 * (aj.X - Gu)):.6f} |")
    print(f"| g02ak (rank 2) | ||X - G||_F^2 / 2 = 3.082e-01 (G's diagonal set to 1; its printed X: 0.3082058) | "
          f"{0.5 * np.linalg.norm(ak.X - Gu) ** 2:.7f} |")
    print(f"| g02ae (2 factors) | X to 4 decimals: ||X - G||_F = {np.linalg.norm(nag_ae - G):.6f} | "
          f"{np.linalg.norm(ae.X - G):.6f} |")
    print()


def pairwise_correlation(n, rows, rng):
    """A pairwise-deletion correlation matrix (df.corr() of data with 30% of its values missing)
    and the overlap counts behind each entry, scaled to max 1."""
    factors = rng.standard_normal((rows, max(1, n // 20)))
    data = factors @ rng.standard_normal((factors.shape[1], n)) + rng.standard_normal((rows, n))
    missing = rng.uniform(size=data.shape) < 0.3
    seen = (~missing).astype(float)
    data = np.where(missing, 0.0, data)
    counts = seen.T @ seen
    sums = data.T @ seen
    means = sums / counts
    squares = (data ** 2).T @ seen
    cross = data.T @ data
    cov = cross / counts - means * means.T
    var_i = squares / counts - means ** 2
    C = cov / np.sqrt(var_i * var_i.T)
    C = (C + C.T) / 2
    np.fill_diagonal(C, 1.0)
    return C, counts / counts.max()


def speed(n, repeats, workdir):
    """Section 5. With SPDFIT_BASE_CLI set (another build's `spdfit`), every run is made with both
    commands, interleaved, and the table gains the baseline's CPU time."""
    rng = np.random.default_rng(5)
    matrices = {"pairwise deletion": pairwise_correlation(n, n // 2, rng)}
    M = np.random.default_rng(1).uniform(-1, 1, (n, n))
    U = (M + M.T) / 2
    np.fill_diagonal(U, 1.0)
    matrices["uniform random"] = (U, matrices["pairwise deletion"][1])
    cli = os.environ.get("SPDFIT_CLI", str(ROOT / "build" / "apps" / "spdfit"))
    base = os.environ.get("SPDFIT_BASE_CLI")
    commands = {"": cli, **({"base": base} if base else {})}
    print(f"## 5. Speed at n = {n} (the command line, {repeats} interleaved runs each; median [min, max])\n")
    print("The kept block (n/10 variables) is the data's own correlation of those variables, repaired with an "
          "eigenvalue floor where it is not positive definite: a floor of 1e-3 leaves a block whose smallest "
          "eigenvalues are all 1e-3 (nearly singular: the hard case), a floor of 0.05 a well-conditioned one.\n")
    header = "| matrix | block floor | negative eigenvalues | run | wall (s) | CPU (s) | CPU / plain --corr | iterations |"
    if base:
        header += " baseline CPU (s) | baseline iterations |"
    print(header)
    print("|" + "---|" * (header.count("|") - 1))
    for name, (C0, H) in matrices.items():
        mask = np.zeros((n, n))
        block = rng.choice(n, size=n // 10, replace=False)
        mask[np.ix_(block, block)] = 1
        extra = rng.uniform(size=(n, n)) < 0.005
        if name == "pairwise deletion":
            # Scattered pairs too; those of the uniform random matrix would admit no completion
            # (its entries are not correlations of anything: `nearest` says so, exit 1).
            mask[extra | extra.T] = 1
        np.save(os.path.join(workdir, "mask.npy"), mask)
        np.save(os.path.join(workdir, "H.npy"), H)
        for floor in (1e-3, 0.05):
            # The kept block must be semidefinite, and positive definite for Newton's method to
            # converge fast (a singular kept block makes every completion singular: the dual then
            # has no minimizer, and the warning says so).
            C = C0.copy()
            sub = np.linalg.eigvalsh(C[np.ix_(block, block)])
            if sub[0] < floor:
                C[np.ix_(block, block)] = quiet(spdfit.nearest_correlation, C[np.ix_(block, block)], min_eig=floor)
            path = os.path.join(workdir, "C.npy")
            np.save(path, C)
            runs = {"--corr": ["--corr"], "--corr --fixed": ["--corr", "--fixed", os.path.join(workdir, "mask.npy")]}
            if floor == 1e-3:  # the weights do not involve the block
                runs["--corr --h-weights"] = ["--corr", "--h-weights", os.path.join(workdir, "H.npy")]
            times = {(k, c): [] for k in runs for c in commands}
            iterations = {}
            for _ in range(repeats):
                for label, args in runs.items():
                    for which, command in commands.items():
                        before = resource.getrusage(resource.RUSAGE_CHILDREN)
                        started = time.perf_counter()
                        done = subprocess.run([command, "nearest", *args, "--json", "-q", path], capture_output=True,
                                              text=True)
                        wall = time.perf_counter() - started
                        after = resource.getrusage(resource.RUSAGE_CHILDREN)
                        assert done.returncode == 0, done.stderr
                        result = json.loads(done.stdout)
                        assert result["converged"], (label, which)
                        iterations[label, which] = result["iterations"]
                        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
                        times[label, which].append((wall, cpu))
            plain_cpu = statistics.median(c for _, c in times["--corr", ""])
            negative = int(np.sum(np.linalg.eigvalsh(C) < 0))
            for label in runs:
                walls = [w for w, _ in times[label, ""]]
                cpus = [c for _, c in times[label, ""]]
                row = (f"| {name} | {floor:g} | {negative} | {label} | {statistics.median(walls):.2f} "
                       f"[{min(walls):.2f}, {max(walls):.2f}] | {statistics.median(cpus):.2f} [{min(cpus):.2f}, "
                       f"{max(cpus):.2f}] | {statistics.median(cpus) / plain_cpu:.1f} | {iterations[label, '']} |")
                if base:
                    base_cpus = [c for _, c in times[label, "base"]]
                    row += (f" {statistics.median(base_cpus):.2f} [{min(base_cpus):.2f}, {max(base_cpus):.2f}] | "
                            f"{iterations[label, 'base']} |")
                print(row)
    print()


def factors_at_scale(n, workdir):
    rng = np.random.default_rng(9)
    k = 10
    F = rng.standard_normal((n, k)) / np.sqrt(k) * 0.8
    C = F @ F.T + 0.1 * rng.standard_normal((n, n)) / np.sqrt(n)
    C = (C + C.T) / 2
    np.fill_diagonal(C, 1.0)
    path = os.path.join(workdir, "C.npy")
    np.save(path, C)
    started, cpu_started = time.perf_counter(), time.process_time()
    r = quiet(spdfit.nearest_correlation, C, factors=k, factors_only=True, full_output=True)
    seconds, cpu = time.perf_counter() - started, time.process_time() - cpu_started
    del C
    cli = os.environ.get("SPDFIT_CLI", str(ROOT / "build" / "apps" / "spdfit"))
    probe = ("import resource, subprocess, sys; subprocess.run(sys.argv[1:], check=True, capture_output=True); "
             "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)")
    started = time.perf_counter()
    peak = int(subprocess.run([sys.executable, "-c", probe, cli, "nearest", "--corr", "--factors", str(k),
                               "--factors-only", "-q", "-o", os.path.join(workdir, "F.npy"), path],
                              capture_output=True, text=True, check=True).stdout) * 1024
    command_seconds = time.perf_counter() - started
    print(f"## 6. --factors {k} at n = {n} from .npy\n")
    print(f"Library (Python, C in memory, the binding's copy included): {seconds:.1f} s wall, {cpu:.1f} s CPU, "
          f"{r.iterations} iterations, converged {r.converged}, stationarity residual {r.optimality_residual:.1e}, "
          f"distance {r.distance:.6f}. The command `spdfit nearest --corr --factors {k} --factors-only -o F.npy C.npy`: "
          f"{command_seconds:.1f} s wall with the read; peak resident set {peak / 2**20:.0f} MiB = "
          f"{peak / (8.0 * n * n):.2f} n^2 doubles (C itself is 1).\n")


def main():
    problems = int(sys.argv[1]) if len(sys.argv) > 1 else 50
    repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 3
    speed_n = int(sys.argv[3]) if len(sys.argv) > 3 else 1000
    factor_n = int(sys.argv[4]) if len(sys.argv) > 4 else 10000
    print(f"# Structured repairs: {time.strftime('%Y-%m-%d')}, {cpu_model()}, {os.cpu_count()} cores\n")
    print(f"`PYTHONPATH=build/python /usr/bin/python3 bench/structured_repair.py {problems} {repeats} {speed_n} "
          f"{factor_n}`; load average at the start {os.getloadavg()[0]:.1f}\n")
    optimality(problems)
    rank_comparison()
    factor_comparison()
    nag_examples()
    with tempfile.TemporaryDirectory() as workdir:
        if speed_n > 0:
            speed(speed_n, repeats, workdir)
        if factor_n > 0:
            factors_at_scale(factor_n, workdir)
    print(f"Load average at the end {os.getloadavg()[0]:.1f}.")


if __name__ == "__main__":
    main()
