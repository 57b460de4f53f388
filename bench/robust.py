"""Issue 42 item 3's goals for the robust fit and the outlier warning, measured through spdfit's
Python module (prints a Markdown report; bench/results/robust-*.md keeps one):

- gross errors: 2% of the rows of B shifted by +-50 sigma; --robust huber's mean error against the
  same estimator's on the clean rows (goal <= 1.3x; the plain fit about 10x worse);
- wrong rows of A: 2% of the rows of A replaced by other values (leverage points); --robust tukey's
  mean error against the clean rows' (goal <= 1.5x);
- efficiency on clean Gaussian data: least squares' mean squared error over Huber's (goal >= 0.93);
- the outlier warning's false positives on clean data with strong leverage (a few rows 30 times
  larger): goal <= 1% of 1000 data sets;
- speed at m = 1e5: the robust fit's time over the plain fit's (goal <= 3x), median of 5 runs.

    PYTHONPATH=build/python /usr/bin/python3 bench/robust.py [--trials 200]
"""
import argparse
import datetime
import pathlib
import sys
import time
import warnings

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from machine import cpu_model  # noqa: E402

import spdfit  # noqa: E402

X_TRUE = np.array([[4.0, 1.0, 0.5], [1.0, 3.0, 0.2], [0.5, 0.2, 2.0]])
SIGMA = 0.05


def quiet(*args, **kwargs):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = spdfit.fit(*args, **kwargs)
    return r, [str(w.message) for w in caught]


def draw(rng, m):
    A0 = rng.standard_normal((m, 3))
    return A0 + SIGMA * rng.standard_normal((m, 3)), A0 @ X_TRUE + SIGMA * rng.standard_normal((m, 3))


def gross_b(rng, A, B):
    bad = rng.choice(len(B), len(B) // 50, replace=False)
    B = B.copy()
    B[bad] += 50 * SIGMA * rng.choice([-1.0, 1.0], (len(bad), 3))
    return A, B


def wrong_a(rng, A, B):
    bad = rng.choice(len(A), len(A) // 50, replace=False)
    A = A.copy()
    A[bad] = 10 * rng.standard_normal((len(bad), 3))
    return A, B


def error_ratios(method, m, trials, seed):
    rng = np.random.default_rng(seed)
    e = {k: [] for k in ("clean", "plain_b", "huber_b", "plain_a", "tukey_a")}
    for _ in range(trials):
        A, B = draw(rng, m)
        err = lambda r: np.linalg.norm(r[0].X - X_TRUE)  # noqa: E731
        e["clean"].append(err(quiet(A, B, method)))
        Ab, Bb = gross_b(rng, A, B)
        e["plain_b"].append(err(quiet(Ab, Bb, method)))
        e["huber_b"].append(err(quiet(Ab, Bb, method, robust="huber")))
        Aa, Ba = wrong_a(rng, A, B)
        e["plain_a"].append(err(quiet(Aa, Ba, method)))
        e["tukey_a"].append(err(quiet(Aa, Ba, method, robust="tukey")))
    return {k: float(np.mean(v)) for k, v in e.items()}


def gross_b_ratios(method, m, trials, seed):
    """Huber's and Tukey's mean errors on gross errors in B over the clean rows' (the data of
    error_ratios with the same seed: the same draws, so its Huber column is reproduced)."""
    rng = np.random.default_rng(seed)
    e = {k: [] for k in ("clean", "huber_b", "tukey_b")}
    for _ in range(trials):
        A, B = draw(rng, m)
        err = lambda r: np.linalg.norm(r[0].X - X_TRUE)  # noqa: E731
        e["clean"].append(err(quiet(A, B, method)))
        Ab, Bb = gross_b(rng, A, B)
        e["huber_b"].append(err(quiet(Ab, Bb, method, robust="huber")))
        e["tukey_b"].append(err(quiet(Ab, Bb, method, robust="tukey")))
        wrong_a(rng, A, B)  # error_ratios' draws, in its order
    clean = float(np.mean(e["clean"]))
    return {k: float(np.mean(v)) / clean for k, v in e.items() if k != "clean"}


def efficiency(trials, seed):
    rng = np.random.default_rng(seed)
    p, h = [], []
    for _ in range(trials):
        A = rng.standard_normal((200, 3))
        B = A @ X_TRUE + SIGMA * rng.standard_normal((200, 3))
        p.append(np.sum((quiet(A, B, "ls")[0].X - X_TRUE) ** 2))
        h.append(np.sum((quiet(A, B, "ls", robust="huber")[0].X - X_TRUE) ** 2))
    p, h = np.array(p), np.array(h)
    g = np.array([1 / h.mean(), -p.mean() / h.mean() ** 2])
    return p.mean() / h.mean(), float(np.sqrt(g @ np.cov(np.vstack([p, h])) @ g / trials))


def false_positives(sets, seed):
    rng = np.random.default_rng(seed)
    flagged = 0
    for _ in range(sets):
        A = rng.standard_normal((200, 3))
        A[:4] *= 30
        B = A @ X_TRUE + SIGMA * rng.standard_normal((200, 3))
        flagged += any("dominate" in w for w in quiet(A, B, "ls")[1])
    return flagged


def speed(method, m, loss, repeats=5, clock=time.perf_counter):
    """Median times of the plain and the robust fit, run alternately (`clock`: wall by default;
    time.process_time for CPU time, steadier on a shared machine)."""
    rng = np.random.default_rng(9)
    A, B = gross_b(rng, *draw(rng, m))
    options = {"plain": {}, loss: {"robust": loss}}
    quiet(A, B, method, **options[loss])  # the loss's constants, computed once per process
    runs = {name: [] for name in options}
    for _ in range(repeats):
        for name, kw in options.items():
            t = clock()
            quiet(A, B, method, **kw)
            runs[name].append(clock() - t)
    return {name: float(np.median(r)) for name, r in runs.items()}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=200)
    parser.add_argument("--speed-only", action="store_true",
                        help="only the speed table, in CPU time, 41 alternating runs of each")
    parser.add_argument("--gross-b-only", action="store_true",
                        help="only Huber and Tukey on gross errors in B, over the clean rows' error")
    args = parser.parse_args()
    if args.gross_b_only:
        print(f"`PYTHONPATH=build/python /usr/bin/python3 bench/robust.py --gross-b-only --trials {args.trials}`; "
              f"{cpu_model()}; {datetime.date.today()}\n")
        print("| method | m | trials | huber / clean | tukey / clean |")
        print("|---|---|---|---|---|")
        for method in ("ls", "spd-tls"):
            for m in (500, 10000):
                trials = args.trials if m == 500 else max(args.trials // 4, 20)
                e = gross_b_ratios(method, m, trials, 1)
                print(f"| {method} | {m} | {trials} | {e['huber_b']:.3f} | {e['tukey_b']:.3f} |")
        return
    if args.speed_only:
        print(f"`PYTHONPATH=build/python /usr/bin/python3 bench/robust.py --speed-only`; {cpu_model()}; "
              f"{datetime.date.today()}; CPU time (process_time), median of 41 alternating runs\n")
        print("| method | m | plain (s) | robust (s) | ratio (goal <= 3) |")
        print("|---|---|---|---|---|")
        for method, loss in (("ls", "huber"), ("spd-tls", "huber"), ("spd-tls", "tukey")):
            t = speed(method, 100000, loss, repeats=41, clock=time.process_time)
            print(f"| {method} {loss} | 100000 | {t['plain']:.4f} | {t[loss]:.4f} | {t[loss] / t['plain']:.2f} |")
        return
    print(f"# Robust fit and outlier warning (issue 42 item 3)\n")
    print(f"`PYTHONPATH=build/python /usr/bin/python3 bench/robust.py --trials {args.trials}`; "
          f"{cpu_model()}; {datetime.date.today()}\n")
    print("| method | m | clean | plain, 2% gross B | huber | ratio (goal <= 1.3) | plain, 2% wrong A | tukey | "
          "ratio (goal <= 1.5) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for method in ("ls", "spd-tls"):
        for m in (500, 10000):
            e = error_ratios(method, m, args.trials if m == 500 else max(args.trials // 4, 20), 1)
            print(f"| {method} | {m} | {e['clean']:.3g} | {e['plain_b']:.3g} | {e['huber_b']:.3g} | "
                  f"{e['huber_b'] / e['clean']:.3f} | {e['plain_a']:.3g} | {e['tukey_a']:.3g} | "
                  f"{e['tukey_a'] / e['clean']:.3f} |")
    eff, se = efficiency(1000, 2)
    print(f"\nHuber's efficiency on clean Gaussian data (ls, m = 200, 1000 trials): {eff:.4f} +- {se:.4f} "
          "(goal >= 0.93)\n")
    fp = false_positives(1000, 3)
    print(f"Outlier warning on 1000 clean data sets with 4 rows 30 times larger (m = 200): {fp} flagged "
          f"({fp / 10:.1f}%, goal <= 1%)\n")
    print("| method | m | plain (s) | robust (s) | ratio (goal <= 3) |")
    print("|---|---|---|---|---|")
    for method, loss in (("ls", "huber"), ("spd-tls", "huber"), ("spd-tls", "tukey")):
        t = speed(method, 100000, loss)
        print(f"| {method} {loss} | 100000 | {t['plain']:.4f} | {t[loss]:.4f} | {t[loss] / t['plain']:.2f} |")


if __name__ == "__main__":
    main()
