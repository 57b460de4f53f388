"""Coverage of auto's bootstrap intervals with a noise model from rest rows, on data where the
likelihood's infimum is often on the boundary (issue 42, item 6).

The data are the issue's reproduction: n = 3, a true X = Q diag(1, 1e-3, 1e-6) Q^T (condition 1e6;
Q fixed), full non-diagonal noise covariances Sigma_A and Sigma_B (fixed) of total standard deviation
`noise` per entry against a signal of standard deviation 1, m rows, and `rest` rows recorded at rest
(A's true values zero, B's a constant load) from which auto takes its noise model
(spdfit.NoiseModel.from_rest). Each trial draws new data and rest rows and runs
spdfit.fit(A, B, "auto", noise=..., bootstrap=R, interval=...) for each of the bootstrap's interval
types (`--types`, default percentile, basic and normal; also auto, and `default`, which passes no
`interval` at all: the same replicates, seed k + 1, for every type); an entry is covered when its interval contains the truth. Printed per set-up and build: the fraction of trials on the boundary (auto's
reason "boundary"), the method auto ran there, and the mean coverage over the six distinct entries
of X (lowest-highest entry), over all trials and over the boundary trials alone, with binomial
standard errors; and the mean error ||X - X_true||_F.

Each build (a directory holding the spdfit package, as PYTHONPATH takes it) runs in its own Python
process on the same draws, so that two builds are compared in one run:

    /usr/bin/python3 bench/boundary_coverage.py --trials 400 --replicates 200 \
        --builds build/python /path/to/other/build/python

(A build from before the interval types, 2026-12-02, runs with `--types default` only: its
default was the percentile interval.)
"""
import argparse
import json
import os
import pathlib
import subprocess
import sys
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
N = 3
SETUPS = [  # (m, noise std per entry, rest rows)
    (40, 0.3, 2000),
    (100, 0.3, 2000),
]


# X's eigenvalues: the near-singular X by default; `--eigenvalues 1 0.6 0.3` gives a
# well-conditioned X for comparison (the boundary then is rarely or never hit).
EIGENVALUES = [1.0, 1e-3, 1e-6]


def truth_and_covariances(noise):
    rng = np.random.default_rng(42)
    Q, _ = np.linalg.qr(rng.standard_normal((N, N)))
    X = Q @ np.diag(EIGENVALUES) @ Q.T
    covs = []
    for _ in range(2):
        G = rng.standard_normal((N, N))
        C = G @ G.T + 0.3 * np.eye(N)
        covs.append(noise ** 2 * N * C / np.trace(C))
    return 0.5 * (X + X.T), covs[0], covs[1]


def draw(k, m, noise, rest):
    X, cov_a, cov_b = truth_and_covariances(noise)
    rng = np.random.default_rng(1000 + k)
    A0 = rng.standard_normal((m, N))
    A = A0 + rng.multivariate_normal(np.zeros(N), cov_a, m)
    B = A0 @ X + rng.multivariate_normal(np.zeros(N), cov_b, m)
    rest_A = rng.multivariate_normal(np.zeros(N), cov_a, rest)
    rest_B = np.array([0.5, -1.0, 2.0]) + rng.multivariate_normal(np.zeros(N), cov_b, rest)
    return A, B, rest_A, rest_B, X


def child(trials, replicates, kind):
    """In the build's process: every set-up's trials with one interval type, as JSON on stdout."""
    import warnings
    import spdfit
    warnings.simplefilter("ignore", spdfit.SpdfitWarning)
    upper = np.triu_indices(N)
    extra = {} if kind == "default" else {"interval": kind}  # builds without the option: `default`
    out = []
    for m, noise, rest in SETUPS:
        rows = []
        start = time.process_time()
        for k in range(trials):
            A, B, rest_A, rest_B, X = draw(k, m, noise, rest)
            r = spdfit.fit(A, B, "auto", noise=spdfit.NoiseModel.from_rest(rest_A, rest_B), bootstrap=replicates,
                           seed=k + 1, **extra)
            reason = r.diagnostics.reason.code if r.diagnostics.reason else ""
            if not r.ok or r.interval is None:
                rows.append({"ok": False, "reason": reason, "method": r.method})
                continue
            covered = (r.interval.lower <= X) & (X <= r.interval.upper)
            rows.append({"ok": True, "reason": reason, "method": r.method,
                         "covered": covered[upper].astype(int).tolist(),
                         "width": float(np.mean((r.interval.upper - r.interval.lower)[upper])),
                         "error": float(np.linalg.norm(r.X - X))})
        out.append({"m": m, "noise": noise, "rest": rest, "rows": rows, "cpu": time.process_time() - start})
    print(json.dumps(out))


def summary(rows):
    kept = [r for r in rows if r["ok"]]
    if not kept:
        return "-", "-"
    hits = np.array([r["covered"] for r in kept], float)
    per_entry = hits.mean(axis=0)
    mean = per_entry.mean()
    se = np.sqrt(mean * (1 - mean) / len(kept))
    return f"{100 * mean:.1f} ± {100 * se:.1f} ({100 * per_entry.min():.0f}-{100 * per_entry.max():.0f})", len(kept)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=400)
    parser.add_argument("--replicates", type=int, default=200)
    parser.add_argument("--builds", nargs="+", default=["build/python"])
    parser.add_argument("--types", nargs="+", default=["percentile", "basic", "normal"],
                        help="the bootstrap's interval types to measure")
    parser.add_argument("--eigenvalues", nargs=3, type=float, default=EIGENVALUES,
                        help="X's eigenvalues (default 1 1e-3 1e-6: condition 1e6)")
    parser.add_argument("--child", help=argparse.SUPPRESS)
    args = parser.parse_args()
    EIGENVALUES[:] = args.eigenvalues
    if args.child:
        child(args.trials, args.replicates, args.child)
        return

    sys.path.insert(0, str(HERE))
    from machine import cpu_model
    results = {}
    for build in args.builds:
        env = dict(os.environ, PYTHONPATH=str(pathlib.Path(build).resolve()))
        for kind in args.types:
            text = subprocess.run([sys.executable, __file__, "--child", kind, "--trials", str(args.trials),
                                   "--replicates", str(args.replicates), "--eigenvalues",
                                   *map(repr, args.eigenvalues)], env=env, check=True, capture_output=True,
                                  text=True).stdout
            results[(build, kind)] = json.loads(text)

    print(f"# auto's bootstrap coverage on the boundary: {time.strftime('%Y-%m-%d')}, {cpu_model()}\n")
    print(f"`/usr/bin/python3 bench/boundary_coverage.py --trials {args.trials} --replicates {args.replicates} "
          f"--builds {' '.join(args.builds)} --types {' '.join(args.types)} --eigenvalues "
          f"{' '.join(map(repr, args.eigenvalues))}`: n = {N}, X = Q diag({', '.join(map(repr, args.eigenvalues))}) "
          f"Q^T, full Sigma_A and Sigma_B, auto with the noise model of the rest rows and {args.replicates} "
          f"bootstrap replicates per trial, nominal level 95%. Coverage: mean over X's six distinct entries ± its "
          f"binomial standard error (lowest-highest entry); width: the intervals' mean width over those entries.\n")
    print("| build | interval | m | noise std | on the boundary | auto ran there | coverage, all trials | coverage, "
          "boundary trials | coverage, interior trials | mean width | mean error ‖X − X_true‖_F | CPU seconds |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for (build, kind), setups in results.items():
        for s in setups:
            rows = s["rows"]
            on = [r for r in rows if r["reason"] == "boundary"]
            off = [r for r in rows if r["reason"] != "boundary"]
            ran = sorted({r["method"] for r in on})
            errors = [r["error"] for r in rows if r["ok"]]
            all_cov, _ = summary(rows)
            on_cov, _ = summary(on)
            off_cov, _ = summary(off)
            widths = [r["width"] for r in rows if r["ok"] and "width" in r]
            width = f"{np.mean(widths):.4f}" if widths else "-"
            print(f"| {build} | {kind} | {s['m']} | {s['noise']} | {len(on)} of {len(rows)} "
                  f"({100 * len(on) / len(rows):.0f}%) | {', '.join(ran) or '-'} | {all_cov} | {on_cov} | {off_cov} "
                  f"| {width} | {np.mean(errors):.4g} | {s['cpu']:.0f} |")


if __name__ == "__main__":
    main()
