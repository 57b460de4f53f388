"""Coverage of the bootstrap's 95% intervals, every method, by Monte Carlo (issue 15).

For each set-up, `trials` independent data sets are drawn; each is identified by every estimator
with `spdfit.hexapod.identify(..., bootstrap=N)` (all methods share the resamples), and a method's
coverage of an entry is the fraction of trials whose interval contains the true value. Printed
per method: the mean coverage over the entries, and the lowest and highest entry.

Set-ups:
- the thesis model (M_p of eq. 6.1, n = 6, accelerations of variance 25/3) with equal Gaussian
  noise of variance 0.86 in A and B, m = 12, 100, 1000 (spdfit.hexapod.simulate);
- the paper's 2x2 design (X = [3 1; 1 1]), its 4 rows repeated to m = 4 and 100, A exact,
  noise of std 1 in B only.

    PYTHONPATH=build/python /usr/bin/python3 bench/bootstrap_coverage.py [trials] [replicates]
"""
import sys
import time
import warnings

import numpy as np

import spdfit
import spdfit.hexapod as hx

from machine import cpu_model

warnings.simplefilter("ignore", spdfit.SpdfitWarning)
METHODS = ["ls", "procrustes", "tls", "tls-sym", "tls-psd", "spde", "spd-tls", "psd-ls"]
X_PAPER = np.array([[3.0, 1.0], [1.0, 1.0]])
A_PAPER = np.array([[5.0, 2.0], [-3.0, 1.0], [1.0, -2.0], [-1.0, 1.0]])


def coverage(draw, trials, replicates):
    hits = {m: 0.0 for m in METHODS}
    failed = {m: 0 for m in METHODS}
    for k in range(trials):
        A, B, truth = draw(k)
        results = hx.identify(A, B, bootstrap=replicates, seed=k + 1)
        for m in METHODS:
            r = results[m].result
            if not r.ok or r.interval is None or not np.all(np.isfinite(r.interval.lower)):
                failed[m] += 1
                continue
            hits[m] = hits[m] + ((r.interval.lower <= truth) & (truth <= r.interval.upper))
    return {m: (None if failed[m] == trials else hits[m] / (trials - failed[m]), failed[m]) for m in METHODS}


def thesis(m):
    def draw(k):
        s = hx.simulate(m, 0.86, seed=k + 1, distribution="gaussian")
        return s.A, s.B, s.truth
    return draw


def paper(m):
    A = np.tile(A_PAPER, (m // 4, 1))

    def draw(k):
        B = A @ X_PAPER + np.random.default_rng(1000 + k).standard_normal(A.shape)
        return A, B, X_PAPER
    return draw


def main():
    trials = int(sys.argv[1]) if len(sys.argv) > 1 else 400
    replicates = int(sys.argv[2]) if len(sys.argv) > 2 else 500
    cpu = cpu_model()
    print(f"# Bootstrap coverage: {time.strftime('%Y-%m-%d')}, {cpu}\n")
    print(f"`PYTHONPATH=build/python /usr/bin/python3 bench/bootstrap_coverage.py {trials} {replicates}`: "
          f"{trials} trials per set-up, {replicates} bootstrap replicates per trial, nominal level 95%. "
          f"Cells: mean coverage over the entries (lowest-highest entry); a well-calibrated interval gives "
          f"95% +- {300 * np.sqrt(0.95 * 0.05 / trials):.1f}% (three binomial standard errors).\n")
    print("| set-up | m | " + " | ".join(METHODS) + " | seconds |")
    print("|---|---|" + "---|" * len(METHODS) + "---|")
    setups = [("thesis, noise var 0.86 in A and B", m, thesis(m)) for m in (12, 100, 1000)]
    setups += [("paper 2x2, A exact, std 1 in B", m, paper(m)) for m in (4, 100)]
    for name, m, draw in setups:
        start = time.time()
        result = coverage(draw, trials, replicates)
        cells = []
        for method in METHODS:
            rate, failed = result[method]
            if rate is None:
                cells.append("-")
                continue
            cell = f"{100 * rate.mean():.1f} ({100 * rate.min():.0f}-{100 * rate.max():.0f})"
            cells.append(cell + (f" [{failed} failed]" if failed else ""))
        print(f"| {name} | {m} | " + " | ".join(cells) + f" | {time.time() - start:.0f} |", flush=True)


if __name__ == "__main__":
    main()
